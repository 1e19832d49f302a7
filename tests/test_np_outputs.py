"""The memory of NAME_np.solve's outputs (linkgen/backends/np/runtime/driver.py): a column of a
constant record is one number, returned as a read-only view of it where every row keeps it; the
arrays of a result nothing holds any longer are reused by the next call, those a caller holds
(even one slice of one column) never."""

from __future__ import annotations

import math

import numpy as np
from programs import ROOT

from linkgen.kernel import kernel
from linkgen.pipeline import build_log
from linkgen.rows import input_rows

FOURBAR = ROOT / "samples" / "fourbar" / "fourbar.yaml"


def _address(a: np.ndarray) -> int:
    return int(a.__array_interface__["data"][0])


def test_a_constant_records_column_is_its_number_and_nan_where_a_row_loses_it():
    module = kernel(build_log(str(FOURBAR)), 2)
    values, rates, accs = input_rows(build_log(str(FOURBAR)), 13)
    fine = module.solve(values, rates, accs)
    column = fine["O2.x"]
    assert column.shape == (13,) and not column.flags.writeable and column.strides == (0,)
    assert (column == module.PARAMS["O2.x"]).all() and (fine["O2.vx"] == 0.0).all()
    bad = values.copy()
    bad[4, 0] = math.nan
    lost = module.solve(bad, rates, accs)
    assert lost["O2.x"].flags.writeable and np.isnan(lost["O2.x"][4])
    assert (np.delete(lost["O2.x"], 4) == module.PARAMS["O2.x"]).all()
    again = module.solve(values, rates, accs, out=fine)  # its read-only columns are given anew
    for name, value in module.solve(values, rates, accs).items():
        assert np.array_equal(again[name], value), name


def test_a_later_call_reuses_a_dropped_results_arrays_and_never_a_held_ones():
    log = build_log(str(FOURBAR))
    module = kernel(log, 2)
    values, rates, accs = input_rows(log, 1000)
    first = module.solve(values, rates, accs)
    held = first["B.x"][10:20]
    kept = held.copy()
    addresses = {_address(first[name]) for name in ("B.x", "P.vx", "status")}
    del first
    second = module.solve(values + 0.5, rates, accs)  # the held slice's array stays the caller's
    assert np.array_equal(held, kept) and not np.array_equal(second["B.x"][10:20], kept)
    del held
    third = module.solve(values, rates, accs)
    assert np.array_equal(third["B.x"][10:20], kept)
    last = {_address(third[name]) for name in ("B.x", "P.vx", "status")}
    del third
    fourth = module.solve(values, rates, accs)
    assert {_address(fourth[name]) for name in ("B.x", "P.vx", "status")} <= last | addresses
