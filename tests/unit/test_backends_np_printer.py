"""linkgen.backends.np.printer: every primitive printed as a numpy function gives the DSL's own values
(tests/dsl_walk.py) over a whole column of rows at once (numpy's arctan2 within a few ulps of the
platform's atan2, as tests/test_primitives.py measures), always as (status, sigma, ...); what the DSL
computes twice is computed once."""

from __future__ import annotations

import math

import numpy as np
import pytest
from dsl_walk import evaluate, rows, same

from linkgen.backends.np.printer import numpy_function
from linkgen.backends.py.printer import python_function
from linkgen.primitives import PRIMITIVES
from linkgen.primitives.dsl import Primitive, record_fields

ORDERS = (0, 1, 2)
ROWS = 40
ATAN2_ULPS = 4


def _args(prim: Primitive, order: int, row: dict) -> list:
    return [tuple(row[f"{p.name}_{f}"] for f in record_fields(p.kind, order)) if p.is_record else row[p.name]
            for p in prim.params]


@pytest.mark.parametrize("order", ORDERS)
@pytest.mark.parametrize("name", list(PRIMITIVES))
def test_the_numpy_twin_computes_a_column_of_rows_at_once(name: str, order: int):
    prim = PRIMITIVES[name]
    space = {"np": np, "EPS": float(np.finfo(float).eps), "NAN": np.nan, "PI": np.pi}
    exec(numpy_function(prim, order), space)
    table = rows(name, ROWS)
    columns = {k: np.array([r[k] for r in table]) for k in table[0]}
    with np.errstate(all="ignore"):
        st, sigma, *outs = space[name](*_args(prim, order, columns))
    angles = {(o.name, "the") for o in prim.outputs if o.kind == "ANGLE"}
    for i, row in enumerate(table):
        want_st, want_sigma, fields = evaluate(prim, order, row)
        assert np.broadcast_to(st, (len(table),))[i] == (want_st or 0)  # 0 where the function cannot fail
        assert same(float(np.broadcast_to(sigma, (len(table),))[i]), 1.0 if want_sigma is None else want_sigma)
        names = [(o.name, f) for o in prim.outputs for f in record_fields(o.kind, order)]
        got = [float(np.broadcast_to(column, (len(table),))[i]) for out in outs for column in out]
        for (o, f), a, b in zip(names, got, fields, strict=True):
            if (o, f) in angles and "atan2" in python_function(prim, order) and math.isfinite(b):
                assert abs(a - b) <= ATAN2_ULPS * math.ulp(b), (row, o, f)
            else:
                assert same(a, b), (row, o, f, a, b)


@pytest.mark.parametrize("order", ORDERS)
def test_the_angle_wrap_takes_one_arctan2(order: int):
    """link_angle's wrap reads atan2(dy, dx) + off once (the DSL names it th0), in numpy as in Python."""
    text = numpy_function(PRIMITIVES["link_angle"], order)
    assert text.count("np.arctan2(") == 1
    assert python_function(PRIMITIVES["link_angle"], order).count("atan2(") == 1
