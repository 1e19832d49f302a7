"""linkgen.backends.py.spelling: the Python program's constants, input records and calls, exec'd for the
samples without a resolver, compute every record as linkgen.primitives.interpret does (tests/spelled.py),
bit for bit, and note a failing step's status (where it has one) with its own codes; the reach check, exec'd, ends a row
past the reach with the reach's codes."""

from __future__ import annotations

import dataclasses
import math
import sys
from importlib import resources

import pytest
from spelled import NAMES, ROOT, computed, reference, row, same, view

from linkgen import status
from linkgen.backends.py.spelling import Python
from linkgen.pipeline import build_log
from linkgen.primitives import PRIMITIVES, python_backend
from linkgen.primitives.dsl import record_fields
from linkgen.render.view import build_view


class Work:
    """The work record: the records as attributes, the conditioning per step, the notes taken."""

    def __init__(self, steps: int):
        self.sigma = [math.nan] * (steps + 1)
        self.notes: list[tuple[int, int, int]] = []

    def note(self, st: int, singular: int, near: int) -> None:
        self.notes.append((st, singular, near))


def run_one(step, env: dict, order: int) -> tuple:
    """A step's call on the reference records, straight to the runtime function."""
    args = [env[a.var] if a.kind == "var" else int(a.value) if a.kind == "int" else float(a.value) for a in step.args]
    return python_backend(order)[step.function](*args)


def program(name: str, spell: Python | None = None) -> str:
    v = view(name)
    spell = spell or Python(v)
    lines = [f"{c.name} = {spell.initializer(c)}" for c in v.constants]
    lines.append("def run(w, inputs, d_inputs, dd_inputs):")
    lines += [f"    {spell.input_record(var, k)}" for k, var in enumerate(v.inputs)]
    lines += [f"    {line}" for s in v.run if s.function for line in spell.call(s, None)]
    lines.append("    return 0")
    return "\n".join(lines) + "\n"


def namespace(order: int) -> dict:
    """What NAME.py gives its steps: the runtime functions and the math they inline."""
    return {**python_backend(order), "sqrt": math.sqrt, "atan2": math.atan2, "cos": math.cos, "sin": math.sin,
            "floor": math.floor, "EPS": sys.float_info.epsilon, "NAN": math.nan, "PI": math.pi}


@pytest.mark.parametrize("name", NAMES)
def test_the_spelled_procedure_computes_every_record(name: str):
    v = view(name)
    space = namespace(v.record_order)
    exec(program(name), space)
    w = Work(v.last_step)
    assert space["run"](w, *row(v)) == 0
    want = reference(v)
    kinds = {r.name: r.kind for r in v.records}
    for rec, f in computed(v):
        k = record_fields(kinds[rec], v.record_order).index(f)
        assert same(getattr(w, rec)[k], want[rec][k]), (rec, f)
    failing = [s for s in v.run if s.fails]
    assert w.notes == []  # a row near the sketch: every chain closes well conditioned, no step has a note
    text = program(name)  # a step with something to report notes it with its own codes
    for s in failing:
        codes = f"{status.code(s.number, status.SINGULAR)}, {status.code(s.number, status.NEAR_SINGULAR)}"
        assert f"    if st:\n        w.note(st, {codes})\n" in text, s.number
    for s in failing:  # each chain's conditioning lands in its step's place
        st, *rest = run_one(s, want, v.record_order)
        assert st == 0 and same(w.sigma[s.number], rest[0] if PRIMITIVES[s.function].sigma else math.nan)


def test_a_chain_that_cannot_close_ends_the_row_with_its_steps_code():
    v = view("fourbar")
    space = namespace(v.record_order)
    chain = next(s for s in v.run if s.function == "RRR_links")
    grounded = next(c for c in v.constants if c.role == "pair" and any(a.var == c.name for a in chain.args))
    spell = Python(v)  # the chain's known pair far away (the inlined call reads its literals): it cannot close
    spell.variables[grounded.name] = dataclasses.replace(grounded, value=(1e6, 1e6))
    exec(program("fourbar", spell), space)
    w = Work(v.last_step)
    assert space["run"](w, *row(v)) == status.code(chain.number, status.CANNOT_CLOSE)


def test_records_are_tuples_of_the_programs_order():
    v = view("jansen_foot")  # order 1
    spell = Python(v)
    assert v.record_order == 1 and spell.member("POINT", "dy") == "[3]" and spell.member("ANGLE", "dthe") == "[1]"
    angle = next(var for var in v.inputs)
    held = f"_{angle.name}_the, _{angle.name}_dthe = w.{angle.name}"  # _run's steps read the locals
    assert spell.input_record(angle, 0) == f"{held} = (inputs[0], d_inputs[0])"
    order0 = Python(dataclasses.replace(v, record_order=0))
    assert order0.input_record(angle, 0) == f"_{angle.name}_the, = w.{angle.name} = (inputs[0],)"
    length = next(c for c in v.constants if c.kind == "VARIABLE")
    assert eval(order0.initializer(length)) == (length.value[0],)  # a one-field tuple keeps its comma


def test_the_reach_check_ends_a_row_past_the_reach_with_its_codes():
    """A crank whose reach is an arc (low, high): past high by a little is nearer high's gap, below low by a
    little nearer low's (its step is another: the codes differ)."""
    log = build_log(str(ROOT / "tests" / "mechanisms" / "stephenson_circuit.yaml"), None, None, sweep=False)
    spell = Python(build_view(log))
    assert log.reach is not None and log.reach.low is not None and log.reach.high is not None
    low, high = log.reach.codes()
    assert low != high
    source = resources.files("linkgen.backends.py").joinpath("runtime", "reach.py").read_text(encoding="utf-8")
    space = {"floor": math.floor, "PI": math.pi, "NAN": math.nan}
    exec(source + "\ndef check(inputs):\n" + "".join(f"    {line}\n" for line in spell.reach_check())
         + "    return 0\n", space)
    probes = (log.reach.low - 0.1, (log.reach.low + log.reach.high) / 2, log.reach.high + 0.1)
    assert [space["check"]([x]) for x in probes] == [low, 0, high]
    assert (low, high) == (status.code(log.reach.low_step, 1), status.code(log.reach.high_step, 1))
