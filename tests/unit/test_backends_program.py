"""linkgen.backends.program, what the program backends build alike from the view: the derivative order of
each output quantity (the field's own, by the DSL), the primitives a procedure calls, the runtime sources a
program carries (each only where the procedure needs it), each resolver block's sketch state and the inputs'
lists, read back as numbers and compared with the step log."""

from __future__ import annotations

from functools import cache

import pytest
from spelled import ROOT

from linkgen.backends.c import RUNTIME as C_RUNTIME
from linkgen.backends.c.printer import c_function
from linkgen.backends.c.spelling import C
from linkgen.backends.program import (
    LEVEL,
    input_lists,
    program_primitive,
    runtime_sources,
    sketch_states,
    used_primitives,
)
from linkgen.backends.py import RUNTIME as PY_RUNTIME
from linkgen.backends.py.printer import python_function
from linkgen.backends.py.spelling import Python
from linkgen.backends.still import held_params, variant
from linkgen.pipeline import build_log
from linkgen.primitives import PRIMITIVES
from linkgen.primitives.dsl import Primitive, field_order
from linkgen.render.view import View, build_view

PATHS = {"fourbar": "samples/fourbar/fourbar.yaml", "parallelogram": "tests/mechanisms/parallelogram.yaml",
         "cylinder": "tests/mechanisms/cylinder_triad.yaml", "fallback": "tests/mechanisms/sixbar_fallback.yaml",
         "fivebar": "samples/fivebar/fivebar.yaml"}


@cache
def view(key: str) -> View:
    return build_view(build_log(str(ROOT / PATHS[key]), None, None, sweep=False))


@pytest.mark.parametrize("key", sorted(PATHS))
def test_the_level_of_a_quantity_is_its_fields_derivative_order(key: str):
    log = view(key).log
    for c in log.columns:
        assert LEVEL[c.quantity] == field_order(log.variable(c.variable).kind, c.field), c.name


@pytest.mark.parametrize("key", sorted(PATHS))
def test_the_used_primitives_are_the_steps_functions_in_the_librarys_order(key: str):
    v = view(key)
    used = used_primitives(v)
    expected = {s.function for s in v.log.steps if s.function} | ({"link_residual"} if v.log.groups else set())
    assert set(used) == expected
    assert used == [p for p in PRIMITIVES if p in expected]


@pytest.mark.parametrize("key, extra", [
    ("fourbar", []), ("parallelogram", ["branch"]), ("cylinder", ["reach", "resolver", "driver"]),
    ("fallback", ["reach", "resolver", "driver"]),
])
def test_a_program_carries_the_runtime_its_procedure_needs(key: str, extra: list[str]):
    v = view(key)
    for printer, runtime in ((python_function, PY_RUNTIME), (c_function, C_RUNTIME)):
        texts = runtime_sources(v, printer, runtime)
        want = [printer(p, v.record_order) for p in calls(v, v.measures)]
        want += [runtime.source(name) for name in ["status", *extra]]
        assert texts == want


def calls(v: View, checks: bool) -> list[Primitive]:
    """The primitives the steps call (with the checks or without): those a step calls as they are, then their
    variants with the sketch's records held still (still.held_params), each in the library's order."""
    found = {(s.function, held_params(v.log, v.record_order, s)) for s in v.log.steps if s.function}
    found |= {(p, ()) for p in used_primitives(v) if all(f != p for f, _ in found)}  # called by the runtime alone
    order = list(PRIMITIVES)
    ranked = sorted(found, key=lambda call: (bool(call[1]), order.index(call[0]), call[1]))
    return [variant(p, checks, still) for p, still in ranked]


@pytest.mark.parametrize("key", ["fourbar", "cylinder"])
def test_without_checks_the_primitives_drop_theirs_unless_a_resolver_needs_them(key: str):
    """options.checks off: the chains measure no conditioning, except where a resolver picks its block by it."""
    v = build_view(build_log(str(ROOT / PATHS[key]), None, None, sweep=False, options={"checks": False}))
    assert not v.checks and v.measures == bool(v.groups)
    for p in used_primitives(v):
        got = program_primitive(v, p)
        assert got is PRIMITIVES[p] if v.groups else got.sigma is None and got.codes() <= {1}
        assert program_primitive(view(key), p) is PRIMITIVES[p]  # with the checks (the default)
    texts = runtime_sources(v, c_function, C_RUNTIME, status=False)
    want = [c_function(p, v.record_order) for p in calls(v, v.measures)]
    assert texts[: len(want)] == want
    assert C_RUNTIME.source("status") not in texts


@pytest.mark.parametrize("key", ["cylinder", "fallback"])
def test_each_blocks_sketch_state_padded_to_the_largest(key: str):
    v = view(key)
    for spell in (Python(v), C(v)):
        states = [[float(x) for x in s.split(", ")] for s in sketch_states(v, spell)]
        assert len(states) == len(v.blocks)
        for state, b in zip(states, v.blocks):
            start = b.group.start()
            assert state == start + [0.0] * (v.nmax - len(start))
            assert state[: b.size] == list(b.group.lengths)  # the Add-links' sketch lengths come first


@pytest.mark.parametrize("key", ["fivebar", "cylinder"])
def test_the_input_lists_are_the_logs_numbers(key: str):
    v = view(key)
    log = v.log
    lists = input_lists(v, Python(v))
    for k in ("start", "stop", "speed", "sketch"):
        assert [float(x) for x in lists[k].split(", ")] == [getattr(i, k) for i in log.inputs], k
    limits = [float(x) for x in lists["limits"].split(", ")]
    p = log.policy
    assert limits == [p.step_angle if i.kind == "revolute" else p.step_length * log.length_scale for i in log.inputs]
    assert lists["periodic"].split(", ") == [str(i.kind == "revolute") for i in log.inputs]
    assert input_lists(v, C(v))["periodic"].split(", ") == [str(int(i.kind == "revolute")) for i in log.inputs]


def test_the_closure_strategy_carries_its_runtime_and_a_state_as_large_as_its_unknowns():
    """cylinder_triad by the closure strategy: the closure runtime after the resolver's, and every
    block's state at least as large as the group's four unknowns (its Jacobian is solved in the same
    arrays: here the blocks' own four entries)."""
    v = build_view(build_log(str(ROOT / PATHS["cylinder"]), sweep=False, options={"strategy": "closure"}))
    assert v.nmax == 4 == view("cylinder").nmax
    for printer, runtime in ((python_function, PY_RUNTIME), (c_function, C_RUNTIME)):
        assert runtime_sources(v, printer, runtime)[-4:] == [runtime.source(n)
                                                             for n in ("reach", "resolver", "closure", "driver")]
    states = [s.split(", ") for s in sketch_states(v, C(v))]
    assert {len(s) for s in states} == {4}
