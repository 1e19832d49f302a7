"""linkgen.backends.np.printer: every primitive printed as a numpy function gives the DSL's own values
(tests/dsl_walk.py) over a whole column of rows at once (numpy's arctan2 within a few ulps of the
platform's atan2, as tests/test_primitives.py measures; a cosine and a sine of one angle from one
half-angle tangent, within COS_SIN_EPS eps of the size of what they scale), always as (status, sigma,
...); what the DSL computes twice is computed once; with a suffix, at a lower order, it takes the
records of a higher one; a record held still (its rates 0) gives the bits it gives with its rates 0."""

from __future__ import annotations

import math

import numpy as np
import pytest
from dsl_walk import evaluate, rows, same

from linkgen.backends.np.printer import numpy_function
from linkgen.backends.py.printer import python_function
from linkgen.backends.still import held_still
from linkgen.primitives import PRIMITIVES
from linkgen.primitives.dsl import Primitive, field_order, record_fields

ORDERS = (0, 1, 2)
ROWS = 40
ATAN2_ULPS = 4
COS_SIN_EPS = 8  # measured at most 0.77 over 2000 rows each (size: the largest magnitude to the field's order + 2)
EPS = float(np.finfo(float).eps)


def _space() -> dict:
    from linkgen.backends.np import RUNTIME

    space = {"np": np, "REAL": np.float64, "EPS": EPS, "NAN": np.nan, "PI": np.pi}
    exec(RUNTIME.source("trig"), space)
    return space


def _args(prim: Primitive, order: int, row: dict) -> list:
    return [tuple(row[f"{p.name}_{f}"] for f in record_fields(p.kind, order)) if p.is_record else row[p.name]
            for p in prim.params]


@pytest.mark.parametrize("order", ORDERS)
@pytest.mark.parametrize("name", list(PRIMITIVES))
def test_the_numpy_twin_computes_a_column_of_rows_at_once(name: str, order: int):
    prim = PRIMITIVES[name]
    space = _space()
    text = numpy_function(prim, order)
    exec(text, space)
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
            elif (name, f) == ("loop_residual", "v") and math.isfinite(b):  # l times an angle off atan2
                assert abs(a - b) <= ATAN2_ULPS * math.ulp(math.pi) * abs(row["l_v"]), (row, o, f)
            elif "cos_sin(" in text and math.isfinite(b):
                size = max([1.0, abs(b)] + [abs(v) for v in row.values()]) ** (field_order(o_kind(prim, o), f) + 2)
                assert abs(a - b) <= COS_SIN_EPS * EPS * size, (row, o, f, a, b)
            else:
                assert same(a, b), (row, o, f, a, b)


@pytest.mark.parametrize("order", ORDERS)
def test_the_angle_wrap_takes_one_arctan2(order: int):
    """link_angle's wrap reads atan2(dy, dx) + off once (the DSL names it th0), in numpy as in Python."""
    text = numpy_function(PRIMITIVES["link_angle"], order)
    assert text.count("np.arctan2(") == 1
    assert python_function(PRIMITIVES["link_angle"], order).count("atan2(") == 1


def o_kind(prim: Primitive, name: str) -> str:
    return next(o.kind for o in prim.outputs if o.name == name)


@pytest.mark.parametrize("name", ["crank_input", "coupler_point", "slider_input"])
def test_a_cosine_and_a_sine_of_one_angle_take_one_tangent(name: str):
    text = numpy_function(PRIMITIVES[name], 2)
    assert text.count("cos_sin(") == 1 and "np.cos(" not in text and "np.sin(" not in text


def test_a_chain_that_decides_a_status_on_an_angle_keeps_the_library_cosine():
    text = numpy_function(PRIMITIVES["PRR_links"], 2)
    assert "cos_sin(" not in text and "np.cos(" in text


def test_the_suffixed_function_takes_records_of_a_higher_order():
    """RRR_links at order 1 named RRR_links_1 gives order 2's positions and rates from order-2 records."""
    space = _space()
    exec(numpy_function(PRIMITIVES["RRR_links"], 1, "_1") + numpy_function(PRIMITIVES["RRR_links"], 2), space)
    j1, j2 = (0.0, 0.0, 0.5, -0.25, 3.0, 1.0), (3.0, 1.0, -1.0, 0.5, 2.0, -2.0)
    l1, l2 = (2.0, 0.1, 0.3), (2.5, -0.2, 0.1)
    low = space["RRR_links_1"](j1, j2, l1, l2, 1)
    high = space["RRR_links"](j1, j2, l1, l2, 1)
    assert low[:2] == high[:2] and low[2] == high[2][:4]


@pytest.mark.parametrize("order", (1, 2))
@pytest.mark.parametrize("name", list(PRIMITIVES))
def test_a_record_held_still_gives_the_values_of_its_rates_at_zero(name: str, order: int):
    """held_still(prim, (p,)): each record parameter held still (what its zero rates add, subtract or
    multiply left out) gives what the primitive gives with that record's rates 0.0, nan where it gives
    nan, on the DSL's rows (tests/dsl_walk.py) of finite numbers (the programs refuse others) with a -0.0
    in every field: the same numbers, a zero's sign aside (0.0 + -0.0 is 0.0, the fold's x is -0.0)."""
    prim = PRIMITIVES[name]
    table = rows(name, ROWS)
    columns = {k: np.array([r[k] for r in table], dtype=float) for k in table[0]}
    for i, k in enumerate(sorted(columns)):
        columns[k][i % len(table)] = -0.0
    for p in (p for p in prim.params if p.is_record and p.kind != "CENTRE"):
        held, saved = held_still(prim, (p.name,))
        space = _space()
        exec(numpy_function(prim, order) + numpy_function(held, order, name="held"), space)
        still = dict(columns)
        for f in record_fields(p.kind, order):
            if field_order(p.kind, f) > 0:
                still[f"{p.name}_{f}"] = np.zeros(len(table))
        with np.errstate(all="ignore"):
            want = space[name](*_args(prim, order, still))
            got = space["held"](*_args(prim, order, still))
        for a, b in zip(_columns(want, len(table)), _columns(got, len(table)), strict=True):
            assert all(float(x) == float(y) or (math.isnan(x) and math.isnan(y)) for x, y in zip(a, b)), (p.name, saved)


def _columns(result: tuple, n: int) -> list[np.ndarray]:
    """A primitive's (status, sigma, records...) as columns of n rows."""
    return [np.broadcast_to(x, (n,)) for x in (result[0], result[1], *(f for record in result[2:] for f in record))]
