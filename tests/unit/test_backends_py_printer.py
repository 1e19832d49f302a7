"""linkgen.backends.py.printer: every primitive printed as a standard-library Python function at each
order, exec'd in a namespace like the generated program's, gives the DSL's own values bit for bit
(tests/dsl_walk.py), always as (status, sigma, ...) where it can fail."""

from __future__ import annotations

import math
import re
import sys

import pytest
from dsl_walk import evaluate, rows, same

from linkgen.backends.py.printer import inline_lines, python_function
from linkgen.primitives import PRIMITIVES
from linkgen.primitives.dsl import Primitive, record_fields

ORDERS = (0, 1, 2)
ROWS = 40
ATAN2_ULPS = 4


def _args(prim: Primitive, order: int, row: dict) -> list:
    return [tuple(row[f"{p.name}_{f}"] for f in record_fields(p.kind, order)) if p.is_record else row[p.name]
            for p in prim.params]


def _program_namespace() -> dict:
    """What the generated NAME.py gives its runtime functions."""
    return {"sqrt": math.sqrt, "atan2": math.atan2, "cos": math.cos, "sin": math.sin, "EPS": sys.float_info.epsilon,
            "NAN": math.nan, "PI": math.pi}


@pytest.mark.parametrize("order", ORDERS)
@pytest.mark.parametrize("name", list(PRIMITIVES))
def test_the_python_function_computes_what_the_dsl_says_bit_for_bit(name: str, order: int):
    prim = PRIMITIVES[name]
    space = _program_namespace()
    exec(python_function(prim, order), space)
    function = space[name]
    for row in rows(name, ROWS):
        st, sigma, fields = evaluate(prim, order, row)
        res = function(*_args(prim, order, row))
        head = [x for x in (st, sigma) if x is not None]
        if prim.status is None:
            res = (res,) if len(prim.outputs) == 1 else res
        else:
            assert all(same(a, b) for a, b in zip(res, head)), row
            res = res[len(head):]
        got = [x for record in res for x in record]
        assert len(got) == len(fields) and all(same(a, b) for a, b in zip(got, fields)), (row, got, fields)


def test_a_record_whose_fields_are_unread_is_not_unpacked():
    """At order 0 coupler_point reads only the displacement of j0 and phi: the rates are not named."""
    text = python_function(PRIMITIVES["coupler_point"], 0)
    assert "    j0_x, j0_y = j0\n" in text and "    phi_the, = phi\n" in text
    assert "_dx" not in text and "dthe" not in text
    assert text.splitlines()[1] == f'    """{PRIMITIVES["coupler_point"].doc}"""'


def test_a_function_that_can_fail_returns_its_status_and_sigma_first():
    text = python_function(PRIMITIVES["RRR_links"], 2)
    assert "    if st == 1:\n        return st, sigma, (NAN, NAN, NAN, NAN, NAN, NAN)\n" in text
    singular = re.search(r"    if st == 3:\n        return st, sigma, \(([^()]*), ([^()]*), NAN, NAN, NAN, NAN\)\n",
                         text)
    assert singular is not None and "NAN" not in singular[1] + singular[2]  # the position, no rates
    assert python_function(PRIMITIVES["offset_angle"], 0).rstrip().endswith("return (th,)")


def _inlined(prim: Primitive, order: int, row: dict, literal: bool) -> str:
    """A function whose body is the primitive's call inlined (inline_lines) as NAME.py's steps have it:
    records read from its parameters or, with ``literal``, the first record and the scalars given as
    literals in place (constant records and flags in NAME.py); returns (st, sigma, outputs...)."""
    args: list[str | list[str]] = []
    for p in prim.params:
        values = [row[f"{p.name}_{f}"] for f in record_fields(p.kind, order)] if p.is_record else [row[p.name]]
        given = literal and all(math.isfinite(x) for x in values) and (not p.is_record or p is prim.params[0])
        args.append([repr(x) for x in values] if given and p.is_record else repr(values[0]) if given else p.name)
    outs = [f"out{k}" for k in range(len(prim.outputs))]
    done = f"return st, sigma_out, {', '.join(outs)},"
    lines = inline_lines(prim, order, args, outs, "sigma_out", [done])
    params = ", ".join(p.name for p in prim.params)
    return "\n".join([f"def inlined({params}):", "    st = sigma_out = None", *(f"    {line}" for line in lines),
                      f"    {done}"]) + "\n"


@pytest.mark.parametrize("literal", (False, True), ids=("unpacked", "literals"))
@pytest.mark.parametrize("order", ORDERS)
@pytest.mark.parametrize("name", list(PRIMITIVES))
def test_the_inlined_call_computes_what_the_dsl_says_bit_for_bit(name: str, order: int, literal: bool):
    """The statements NAME.py runs in place of a call: the same values, status and conditioning, every field a
    failing or singular chain masks nan, whether its arguments are unpacked or read as literals."""
    prim = PRIMITIVES[name]
    for row in rows(name, ROWS):
        space = _program_namespace()
        exec(_inlined(prim, order, row, literal), space)
        st, sigma, *res = space["inlined"](*_args(prim, order, row))
        want_st, want_sigma, fields = evaluate(prim, order, row)
        assert same(st, want_st) if want_st is not None else st is None, row
        assert same(sigma, want_sigma) if want_sigma is not None else sigma is None, row
        got = [x for record in res for x in record]
        assert len(got) == len(fields) and all(same(a, b) for a, b in zip(got, fields)), (row, got, fields)


def test_an_inlined_call_names_its_locals_with_an_underscore():
    """No name of the calling function's own (w, a, st, ...) is taken: every local the body sets has a leading
    underscore, a literal scalar stands in place, a one-field record keeps its comma."""
    lines = inline_lines(PRIMITIVES["RRR_links"], 0, ["w.p_A", "p_O2", ["78.1"], "w.l", "-1"], ["w.p_B"], "s", ["x"])
    assigned = {line.split(" = ")[0] for line in lines if " = " in line and not line.startswith(" ")}
    assert all(name.startswith(("_", "st", "s", "w.p_B")) for name in assigned), assigned
    assert "_l1_v" not in "\n".join(lines) and "78.1" in "\n".join(lines) and "(-1) * _idd2" in "\n".join(lines)
    assert "_l2_v, = w.l" in lines
