"""linkgen.rowblocks: the compiled passes give what the generic calls give (the row solver's
_scalar_call: the primitive looked up by name, its arguments gathered from the step's), step by step:
the steps outside the groups on a chain mechanism and a resolver mechanism, with a chain's branch read
from the records where they hold one, else the step's own; and a resolver block's pass, its reads held
still or live, on every block of the resolver samples."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from linkgen.backends.still import held_params, scalar_variants, still_suffix
from linkgen.pipeline import build_log
from linkgen.primitives import PRIMITIVES, python_backend
from linkgen.primitives.interpret import constant_record
from linkgen.rowblocks import BRANCH, steps_pass
from linkgen.rowsolver import RowSolver, _scalar_call
from linkgen.status import CANNOT_CLOSE
from linkgen.steplog import Step, StepLog
from linkgen.sweepdata import file_rows

ROOT = Path(__file__).resolve().parents[2]
ORDER = 2


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


def _row(sample: str, row: int = 40) -> tuple[StepLog, dict[Any, Any]]:
    """A sample's log and the records of one row of its sweep (the calls' arguments), its constants too."""
    log = build_log(str(ROOT / "samples" / sample / f"{sample}.yaml"), sweep=False)
    result = file_rows(log)
    env: dict[Any, Any] = {name: tuple(float(x[row]) for x in result.values[name]) for name in result.values}
    env.update((v.name, constant_record(v, ORDER, log.origin)) for v in log.variables if v.constant)
    return log, env


def _generic(step: Step, env: dict[Any, Any]) -> tuple[Any, Any, list[Any]]:
    """(status, sigma, the outputs' records) of the generic call."""
    st, sigma, outs = _scalar_call(ORDER)(step.function, _arguments(step, env))
    return st, sigma, list(outs)[:len(step.outputs)]


@pytest.mark.parametrize("sample", ["jansen", "sixbar_fig14"])
def test_a_compiled_step_gives_the_generic_calls_result(sample: str):
    log, env = _row(sample)
    fns = python_backend(ORDER)
    steps = [s for s in log.steps if s.function and all(a.var in env for a in s.args if a.kind == "var")]
    assert len(steps) > 5
    for s in steps:  # compared as printed: every number to the bit, a nan (a fallback's record at this row) as nan
        mine, report = dict(env), {}
        done = steps_pass([s], fns, {s.number: s.function})(mine, report)
        st, sigma, outs = _generic(s, env)
        assert repr((report[s.number], [mine[o] for o in s.outputs])) == repr(((st, sigma), outs)), s.number
        assert done == (st != CANNOT_CLOSE)
    chain = next(s for s in steps if any(a.label == "minv" for a in s.args))
    flipped = {**env, (BRANCH, chain.number): -next(int(a.value) for a in chain.args if a.label == "minv")}
    ours: dict[Any, Any] = dict(flipped)
    steps_pass([chain], fns, {chain.number: chain.function})(ours, {})
    assert repr([ours[o] for o in chain.outputs]) == repr(_generic(chain, flipped)[2])
    assert [ours[o] for o in chain.outputs] != _generic(chain, env)[2]  # the other branch: another position


def test_a_step_calls_the_variant_it_is_named():
    """Where the programs call a primitive with records held still (backends/still.py), the compiled step calls
    that variant: its result is the variant's own on the step's arguments (here the four-bar's, at an order with
    rates, where the chains hold the frame's pairs still)."""
    log, env = _row("fourbar")
    fns = {**python_backend(ORDER), **scalar_variants(log, ORDER)}
    named = {s.number: s.function + still_suffix(held_params(log, ORDER, s)) for s in log.steps if s.function}
    held = [s for s in log.steps if s.function and named[s.number] != s.function]
    assert held  # the four-bar's crank and chain hold the frame's pairs still
    called: list[str] = []
    spied = {**fns, **{named[s.number]: _spy(fns[named[s.number]], named[s.number], called) for s in held}}
    for s in held:
        mine: dict[Any, Any] = dict(env)
        steps_pass([s], spied, named)(mine, {})
        assert called[-1:] == [named[s.number]]
        out = fns[named[s.number]](*_arguments(s, env))
        first = (1 if PRIMITIVES[s.function].status is not None else 0) + (PRIMITIVES[s.function].sigma is not None)
        want = [out] if len(PRIMITIVES[s.function].outputs) == 1 and first == 0 else list(out)[first:]
        assert repr([mine[o] for o in s.outputs]) == repr(want[:len(s.outputs)]), s.number


def _spy(fn: Any, name: str, called: list[str]) -> Any:
    """fn, noting its name in ``called`` at each call."""
    def spy(*args: Any) -> Any:
        called.append(name)
        return fn(*args)
    return spy


def _still(rec: tuple[float, ...], kind: str) -> tuple[float, ...]:
    keep = 2 if kind == "POINT" else 1
    return rec[:keep] + (0.0,) * (len(rec) - keep)


@pytest.mark.parametrize("sample", ["sixbar_fig14", "double_triad"])
@pytest.mark.parametrize("live", [True, False])
def test_a_blocks_compiled_pass_gives_the_generic_calls_results_step_by_step(sample: str, live: bool):
    log, env = _row(sample)
    solver = RowSolver(log, ORDER)
    kinds = {v.name: v.kind for v in log.variables}
    for b in (b for g in log.groups for b in (g, *g.variants)):
        x = [env[a][0] * 1.001 for a in b.add_links] if all(a in env for a in b.add_links) else list(b.lengths)
        dx, ddx = [0.5] * len(x), [0.25] * len(x)
        mine, last, chains = dict(env), {}, [0.0]
        st, residuals = solver._group(b, mine, dict(env), last, chains)(x, dx, ddx, live)
        theirs, report = dict(env), {}  # the block's steps called one by one on its reads and Add-links
        steps = [log.step(n) for n in b.steps if log.step(n).function]
        inner = set(b.writes) | set(b.add_links)
        for s in steps:
            for a in s.args:
                if a.kind == "var" and a.var not in inner and not live:
                    theirs[a.var] = _still(env[a.var], kinds[a.var])
        for name, v, r, c in zip(b.add_links, x, dx, ddx):
            theirs[name] = (v, r, c)
        for s in steps:
            code, sigma, outs = _generic(s, theirs)
            report[s.number] = (code, sigma)
            theirs.update(zip(s.outputs, outs))
        assert repr(last) == repr(report), (b.number, b.variant)
        if any(code == CANNOT_CLOSE for code, _ in report.values()):
            assert (st, residuals) == (1, None)
            continue
        worst = min([b.lever, *(report[s.number][1] for s in steps if PRIMITIVES[s.function].sigma is not None)])
        assert st == 0 and repr(residuals) == repr([theirs[f] for f in b.residuals]) and chains[0] == worst
        assert all(repr(mine[name]) == repr(theirs[name]) for name in b.writes), (b.number, b.variant)
