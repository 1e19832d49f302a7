"""A resolver group as the row solver (linkgen.rowsolver) runs it, each part compiled once as one function:
a block's pass (the generated programs' _group_N: its steps' calls on the records at Add-link lengths, rates
and accelerations), the states of all the group's blocks read off a solved configuration (_lengths_N), and
the branches the blocks' states give the group's chains.

A resolver solves a row in a few dozen passes; a pass as a loop over the steps, each call made by a compiled
runner, its result unpacked and stored through a helper, took half again the time of the calls themselves.
The steps outside the groups are compiled likewise (steps_pass).
The compiled pass makes the same calls with the same arguments in the same order, stores the same records
and reports the same (status, sigma) per step; the compiled states compute the same expressions (a measure
several blocks share once: the same operands, the same bits).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Mapping, Sequence
from types import CodeType
from typing import Any

from .primitives import PRIMITIVES
from .status import CANNOT_CLOSE
from .steplog import BranchSign, ResolverGroup, Step

BRANCH = "branch"  # env key (with a step number) of a chain's branch where it is not the sketch's
Env = dict[Any, Any]  # variable -> record, (BRANCH, step) -> branch
Report = dict[int, tuple[Any, Any]]  # step -> (status, sigma), in the order the steps ran
Pass = Callable[[list[float], list[float], list[float], bool], tuple[int, Any]]
MakePass = Callable[[Env, Report, Env, list[float]], Pass]  # (env, last, before, chains) -> the block's pass
Measure = Callable[[Env, list[float]], list[tuple[float, ...]]]  # (env, old state) -> a loop block's state records
States = Callable[[Env, list[list[float]], list[list[float]]], None]  # (env, a, ad): every block's state and rates


def _function(source: str, scope: dict[str, Any], name: str) -> Any:
    """The function ``name`` the source defines, its names read from scope."""
    exec(_code(source, name), scope)
    return scope[name]


@functools.cache
def _code(source: str, name: str) -> CodeType:
    """A generated function's module code, compiled once (a build makes a few row solvers of one mechanism;
    their blocks' texts are the same, the constants they name bound in each one's scope) and kept per user
    across processes (kernel.compiled: compiling a resolver mechanism's blocks took 15-20 ms of its build)."""
    from .kernel import compiled  # the kernel renders through the backends, which the row solver's callers import

    return compiled(source, f"<linkgen block {name}>")


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
    keys = [(s(name), 2 if kind == "POINT" else 1) for name, kind in reads]  # a record's values: a point's x, y
    live = ", ".join(f"{k}: before[{k}]" for k, _ in keys)
    still = ", ".join(f"{k}: tuple(before[{k}][:{n}]) + (0.0,) * (len(before[{k}]) - {n})" for k, n in keys)
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


def _call(step: Step, fns: Mapping[str, Any], s: _Scope, j: int, sigmas: dict[int, str], report: str = "last",
          check: str = "fails += {r}[0] == FAIL", indent: str = "        ", name: str = "") -> list[str]:
    """One step's call in a compiled pass (the function of fns named ``name`` where given, else the step's; a
    record read as ``env[name]``, a chain's branch as the env's, else the step's, a number in place); its
    (status, sigma) into the dict
    ``report``, its outputs into env, then ``check`` (formatted with the result's name r) where it has a status."""
    prim = PRIMITIVES[step.function]
    args = []
    for a in step.args:
        if a.kind == "var":
            args.append(f"env[{s(a.var)}]")
        elif a.kind == "int" and a.label == "minv":
            args.append(f"env.get({s((BRANCH, step.number))}, {s(int(a.value))})")
        else:
            args.append(s(int(a.value) if a.kind == "int" else float(a.value)))
    call, r = f"{s(fns[name or step.function])}({', '.join(args)})", f"r{j}"
    n = s(step.number)
    checks = []
    if prim.status is None:
        lines = [f"{r} = {call}", f"{report}[{n}] = (0, 1.0)"]
        outs = [r] if len(prim.outputs) == 1 else [f"{r}[{k}]" for k in range(len(prim.outputs))]
        sigmas[step.number] = "1.0"
    else:
        first = 2 if prim.sigma is not None else 1
        sigma = f"{r}[1]" if prim.sigma is not None else "1.0"
        lines = [f"{r} = {call}", f"{report}[{n}] = ({r}[0], {sigma})"]
        checks = check.format(r=r).splitlines()
        outs = [f"{r}[{first + k}]" for k in range(len(prim.outputs))]
        sigmas[step.number] = sigma
    lines += [f"env[{s(name)}] = {out}" for name, out in zip(step.outputs, outs)] + checks
    return [indent + line for line in lines]


def steps_pass(steps: Sequence[Step], fns: Mapping[str, Any],
               callee: Mapping[int, str]) -> Callable[[Env, Report], bool]:
    """run(env, report): steps outside the resolver groups called in order (each step's function of fns named
    by ``callee``: the variant the programs call, backends/still.py), each step's (status, sigma) into report,
    its outputs into env, up to the first that cannot close: False there, else True."""
    s = _Scope()
    body = [line for j, step in enumerate(steps)
            for line in _call(step, fns, s, j, {}, "report", "if {r}[0] == FAIL:\n    return False", "    ",
                              callee[step.number])]
    made: Callable[[Env, Report], bool] = _function("\n".join(["def run(env, report):", *body, "    return True", ""]),
                                                    {**s.names, "FAIL": CANNOT_CLOSE}, "run")
    return made


def group_states(blocks: Sequence[ResolverGroup], first: int, pos: Mapping[str, str], residual: Any,
                 zero: tuple[float, ...], measures: Sequence[Measure | None]) -> States:
    """The states and rates of a group's blocks off a solved configuration, states(env, a, ad): block k's
    (a[first + k], ad[first + k]) its Add-link lengths (each pair's link_residual at a zero length; the block's
    ``measures`` instead where given: a loop block's arc), its chains' sign measures and rates (the predictor moves
    them: a chain passing its fold changes branch; a zero keeps the old one, rate 0), then its orientation (0).
    A pair or a chain's measure that several blocks share is computed once."""
    s = _Scope()
    s.names.update(residual=residual, zero=zero, cos=math.cos, sin=math.sin)
    body: list[str] = []
    done: dict[Any, str] = {}  # a pair's or a chain's measure -> its local name
    for k, (b, measure) in enumerate(zip(blocks, measures)):
        body.append(f"    old = a[{first + k}]")
        if measure is None:
            fs = []
            for p, q in b.pairs:
                if (pos[p], pos[q]) not in done:
                    v = done[pos[p], pos[q]] = f"v{len(done)}"
                    body.append(f"    {v} = residual(env[{s(pos[p])}], env[{s(pos[q])}], zero)")
                fs.append(done[pos[p], pos[q]])
            values, rates = [f"{f}[0]" for f in fs], [f"{f}[1]" for f in fs]
        else:
            body.append(f"    f = {s(measure)}(env, old)")
            values, rates = ["*[r[0] for r in f]"], ["*[r[1] for r in f]"]
        n = len(b.pairs)
        for j, bs in enumerate(b.branches):
            if (bs.kind, bs.points, bs.angle) not in done:
                m = done[bs.kind, bs.points, bs.angle] = f"v{len(done)}"
                body += _sign(bs, s, m)
            m = done[bs.kind, bs.points, bs.angle]
            values.append(f"{m} if {m} != 0 else old[{n + j}]")
            rates.append(f"d{m} if {m} != 0 else 0.0")
        body.append(f"    a[{first + k}], ad[{first + k}] = [{', '.join([*values, '0.0'])}], "
                    f"[{', '.join([*rates, '0.0'])}]")
    made: States = _function("\n".join(["def states(env, a, ad):", *body, ""]), s.names, "states")
    return made


def group_signs(blocks: Sequence[ResolverGroup], first: int) -> Callable[[Env, list[list[float]]], None]:
    """signs(env, a): the branch of every chain of the group's blocks as their states a hold it (a sign measure
    below zero: -1, else 1)."""
    s = _Scope()
    body = [f"    env[{s((BRANCH, bs.step))}] = -1 if a[{first + k}][{len(b.add_links) + i}] < 0 else 1"
            for k, b in enumerate(blocks) for i, bs in enumerate(b.branches)]
    made: Callable[[Env, list[list[float]]], None] = _function("\n".join(["def signs(env, a):", *body, "    return",
                                                                          ""]), s.names, "signs")
    return made


def _sign(bs: BranchSign, s: _Scope, m: str) -> list[str]:
    """A chain's sign measure m and its rate dm: b - a against c - a (side), or against the direction of an
    angle record; each difference as the generated programs have it."""
    q0, q1 = (s(p) for p in bs.points[:2])
    lines = [f"    q0, q1 = env[{q0}], env[{q1}]", "    ux, uy = q1[0] - q0[0], q1[1] - q0[1]"]
    if bs.kind == "side":
        return lines + [f"    q2 = env[{s(bs.points[2])}]", "    vx, vy = q2[0] - q0[0], q2[1] - q0[1]",
                        f"    {m} = ux * vy - uy * vx",
                        f"    d{m} = (q1[2] - q0[2]) * vy + ux * (q2[3] - q0[3]) - (q1[3] - q0[3]) * vx"
                        " - uy * (q2[2] - q0[2])"]
    return lines + [f"    angle = env[{s(bs.angle)}]", "    c, s, dt = cos(angle[0]), sin(angle[0]), angle[1]",
                    f"    {m} = ux * c + uy * s",
                    f"    d{m} = (q1[2] - q0[2]) * c + (q1[3] - q0[3]) * s + (uy * c - ux * s) * dt"]
