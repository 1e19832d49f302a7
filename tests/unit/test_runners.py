"""linkgen.runners: a step's compiled call gives what the generic call gives (the row solver's
_scalar_call: the primitive looked up by name, its arguments gathered from the step's), on every
step of a chain mechanism and of a resolver mechanism, with a chain's branch read from the records
where they hold one, else the step's own."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from linkgen.pipeline import build_log
from linkgen.primitives import python_backend
from linkgen.primitives.interpret import constant_record
from linkgen.rowsolver import _scalar_call
from linkgen.runners import BRANCH, runner
from linkgen.steplog import Step
from linkgen.sweepdata import file_rows

ROOT = Path(__file__).resolve().parents[2]


def _arguments(step: Step, env: dict[Any, Any]) -> list[Any]:
    """The step's arguments as the generic call takes them, gathered here one by one."""
    out: list[Any] = []
    for a in step.args:
        if a.kind == "var":
            out.append(env[a.var])
        elif a.kind == "int" and a.label == "minv":
            out.append(env.get((BRANCH, step.number), int(a.value)))
        else:
            out.append(int(a.value) if a.kind == "int" else float(a.value))
    return out


@pytest.mark.parametrize("sample", ["jansen", "sixbar_fig14"])
def test_a_compiled_call_gives_the_generic_calls_result(sample: str):
    log = build_log(str(ROOT / "samples" / sample / f"{sample}.yaml"), sweep=False)
    order = 2
    fns, call = python_backend(order), _scalar_call(order)
    result = file_rows(log)  # the records of a row the procedure reached: the calls' arguments
    row = 40
    env: dict[Any, Any] = {name: tuple(float(x[row]) for x in result.values[name]) for name in result.values}
    env.update((v.name, constant_record(v, order, log.origin)) for v in log.variables if v.constant)
    steps = [s for s in log.steps if s.function and all(a.var in env for a in s.args if a.kind == "var")]
    assert len(steps) > 5
    for s in steps:  # compared as printed: every number to the bit, a nan (a fallback's record at this row) as nan
        assert repr(runner(s, fns)(env)) == repr(call(s.function, _arguments(s, env))), s.number
    chain = next(s for s in steps if any(a.label == "minv" for a in s.args))
    flipped = {**env, (BRANCH, chain.number): -next(int(a.value) for a in chain.args if a.label == "minv")}
    ours = runner(chain, fns)(flipped)
    assert repr(ours) == repr(call(chain.function, _arguments(chain, flipped)))
    assert ours != runner(chain, fns)(env)  # the other branch: another position


def test_a_call_runs_the_function_named_where_a_name_is_given():
    """The row solver names a step's variant with records held still (linkgen.backends.still)."""
    log = build_log(str(ROOT / "samples" / "fourbar" / "fourbar.yaml"), sweep=False)
    step = next(s for s in log.steps if s.function == "crank_angle")
    seen: list[tuple[Any, ...]] = []
    fns = {**python_backend(2), "other": lambda *args: seen.append(args) or (1.0, 2.0, 3.0)}
    env = {v.name: constant_record(v, 2, log.origin) for v in log.variables if v.constant} | {"in1": (0.5, 1.0, 0.0)}
    assert runner(step, fns, "other")(env) == (0, 1.0, ((1.0, 2.0, 3.0),)) and len(seen) == 1
    assert runner(step, fns)(env) != runner(step, fns, "other")(env)
