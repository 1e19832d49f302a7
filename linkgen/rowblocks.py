"""A resolver block as the row solver (linkgen.rowsolver) runs it, each part compiled once as one function:
its pass (the generated programs' _group_N: its steps' calls on the records at Add-link lengths, rates and
accelerations) and its state read off a solved configuration (_lengths_N).

A resolver solves a row in a few dozen passes; a pass as a loop over the steps' runners (linkgen.runners),
each call's result unpacked and stored through a helper, took half again the time of the calls themselves.
The compiled pass makes the same calls with the same arguments in the same order, stores the same records
and reports the same (status, sigma) per step; the compiled state computes the same expressions.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Mapping, Sequence
from types import CodeType
from typing import Any

from .primitives import PRIMITIVES
from .runners import BRANCH, Env
from .status import CANNOT_CLOSE
from .steplog import BranchSign, ResolverGroup, Step

Report = dict[int, tuple[Any, Any]]  # step -> (status, sigma), in the order the steps ran
Pass = Callable[[list[float], list[float], list[float], bool], tuple[int, Any]]
MakePass = Callable[[Env, Report, Env, list[float]], Pass]  # (env, last, before, chains) -> the block's pass
State = Callable[[Env, list[float]], tuple[list[float], list[float]]]


def _still(rec: tuple[float, ...], kind: str) -> tuple[float, ...]:
    """A record with its derivatives zero."""
    width = 2 if kind == "POINT" else 1
    return tuple(rec[:width]) + (0.0,) * (len(rec) - width)


def _function(source: str, scope: dict[str, Any], name: str) -> Any:
    """The function ``name`` the source defines, its names read from scope."""
    exec(_code(source, name), scope)
    return scope[name]


@functools.cache
def _code(source: str, name: str) -> CodeType:
    """A generated function's module code, compiled once (a build makes a few row solvers of one mechanism;
    their blocks' texts are the same, the constants they name bound in each one's scope)."""
    return compile(source, f"<linkgen block {name}>", "exec")


class _Scope:
    """The names a generated function reads: each constant bound once under a short name."""

    def __init__(self) -> None:
        self.names: dict[str, Any] = {}

    def __call__(self, value: Any) -> str:
        name = f"c{len(self.names)}"
        self.names[name] = value
        return name


def block_pass(b: ResolverGroup, steps: Sequence[Step], fns: Mapping[str, Any], reads: Sequence[tuple[str, str]],
               sigma_steps: Sequence[int], width: int) -> MakePass:
    """The block's pass, made per resolver step as ``make(env, last, before, chains)``: pass(x, dx, ddx, live) sets
    the records the block reads to ``before``'s (live False: their rates zero) and the Add-links to the records
    (x, dx, ddx)[:width], runs every step's call (each step's (status, sigma) into ``last``, cleared first, its
    outputs into env) and returns (1, None) where a call failed to close, else (0, the residual records), the worst
    conditioning of the pass's chains, from the block's lever down, in chains[0].  ``steps``: the block's steps
    that call a function, in order; ``reads``: (record, kind) of what it reads from before the group."""
    s = _Scope()
    s.names["still"] = _still
    keys = [(s(name), s(kind)) for name, kind in reads]
    live = ", ".join(f"{k}: before[{k}]" for k, _ in keys)
    still = ", ".join(f"{k}: still(before[{k}], {kind})" for k, kind in keys)
    body = ["        if not seen:  # the records as the group found them (a block's pass leaves its reads still)",
            f"            seen.append({{{live}}})", f"            seen.append({{{still}}})",
            "        env.update(seen[0] if live else seen[1])"]
    fields = ("x", "dx", "ddx")[:width]
    body += [f"        env[{s(name)}] = ({', '.join(f'{f}[{k}]' for f in fields)},)"
             for k, name in enumerate(b.add_links)]
    body += ["        last.clear()", "        fails = 0"]
    sigmas: dict[int, str] = {}
    for j, step in enumerate(steps):
        body += _call(step, fns, s, j, sigmas)
    body += ["        if fails:", "            return 1, None",
             f"        chains[0] = min([{s(b.lever)}{''.join(', ' + sigmas[n] for n in sigma_steps)}])",
             f"        return 0, [{', '.join(f'env[{s(f)}]' for f in b.residuals)}]"]
    source = "\n".join(["def make(env, last, before, chains):", "    seen = []",
                        "    def group(x, dx, ddx, live):", *body, "    return group", ""])
    made: MakePass = _function(source, {**s.names, "FAIL": CANNOT_CLOSE}, "make")
    return made


def _call(step: Step, fns: Mapping[str, Any], s: _Scope, j: int, sigmas: dict[int, str]) -> list[str]:
    """One step's call in a block's pass: as linkgen.runners.runner makes it, and what rowsolver._run does
    with its result."""
    prim = PRIMITIVES[step.function]
    args = []
    for a in step.args:
        if a.kind == "var":
            args.append(f"env[{s(a.var)}]")
        elif a.kind == "int" and a.label == "minv":
            args.append(f"env.get({s((BRANCH, step.number))}, {s(int(a.value))})")
        else:
            args.append(s(int(a.value) if a.kind == "int" else float(a.value)))
    call, r = f"{s(fns[step.function])}({', '.join(args)})", f"r{j}"
    n = s(step.number)
    if prim.status is None:
        lines = [f"        {r} = {call}", f"        last[{n}] = (0, 1.0)"]
        outs = [r] if len(prim.outputs) == 1 else [f"{r}[{k}]" for k in range(len(prim.outputs))]
        sigmas[step.number] = "1.0"
    else:
        first = 2 if prim.sigma is not None else 1
        sigma = f"{r}[1]" if prim.sigma is not None else "1.0"
        lines = [f"        {r} = {call}", f"        last[{n}] = ({r}[0], {sigma})",
                 f"        fails += {r}[0] == FAIL"]
        outs = [f"{r}[{first + k}]" for k in range(len(prim.outputs))]
        sigmas[step.number] = sigma
    return lines + [f"        env[{s(name)}] = {out}" for name, out in zip(step.outputs, outs)]


def block_state(b: ResolverGroup, pos: Mapping[str, str], residual: Any, zero: tuple[float, ...],
                measure: Callable[[Env, list[float]], list[tuple[float, ...]]] | None) -> State:
    """The block's state and rates off a solved configuration, state(env, old): its Add-link lengths (each pair's
    link_residual at a zero length; ``measure`` instead where given: a loop block's arc), its chains' sign
    measures and rates (the predictor moves them: a chain passing its fold changes branch; a zero keeps the old
    one, rate 0), then its orientation (0)."""
    s = _Scope()
    s.names.update(residual=residual, zero=zero, measure=measure, cos=math.cos, sin=math.sin)
    if measure is None:
        body = [f"    f{k} = residual(env[{s(pos[p])}], env[{s(pos[q])}], zero)" for k, (p, q) in enumerate(b.pairs)]
        values, rates = [f"f{k}[0]" for k in range(len(b.pairs))], [f"f{k}[1]" for k in range(len(b.pairs))]
    else:
        body, values, rates = ["    f = measure(env, old)"], ["*[r[0] for r in f]"], ["*[r[1] for r in f]"]
    n = len(b.pairs)
    for j, bs in enumerate(b.branches):
        body += _sign(bs, s, j)
        values.append(f"m{j} if m{j} != 0 else old[{n + j}]")
        rates.append(f"dm{j} if m{j} != 0 else 0.0")
    body.append(f"    return [{', '.join([*values, '0.0'])}], [{', '.join([*rates, '0.0'])}]")
    made: State = _function("\n".join(["def state(env, old):", *body, ""]), s.names, "state")
    return made


def _sign(bs: BranchSign, s: _Scope, j: int) -> list[str]:
    """A chain's sign measure m{j} and its rate dm{j}: b - a against c - a (side), or against the direction of an
    angle record; each difference as the generated programs have it."""
    q0, q1 = (s(p) for p in bs.points[:2])
    lines = [f"    q0, q1 = env[{q0}], env[{q1}]", "    ux, uy = q1[0] - q0[0], q1[1] - q0[1]"]
    if bs.kind == "side":
        return lines + [f"    q2 = env[{s(bs.points[2])}]", "    vx, vy = q2[0] - q0[0], q2[1] - q0[1]",
                        f"    m{j} = ux * vy - uy * vx",
                        f"    dm{j} = (q1[2] - q0[2]) * vy + ux * (q2[3] - q0[3]) - (q1[3] - q0[3]) * vx"
                        " - uy * (q2[2] - q0[2])"]
    return lines + [f"    angle = env[{s(bs.angle)}]", "    c, s, dt = cos(angle[0]), sin(angle[0]), angle[1]",
                    f"    m{j} = ux * c + uy * s",
                    f"    dm{j} = (q1[2] - q0[2]) * c + (q1[3] - q0[3]) * s + (uy * c - ux * s) * dt"]
