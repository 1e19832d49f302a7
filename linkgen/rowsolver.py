"""The row solver: a resolver mechanism's rows solved one at a time, as the generated programs solve them.

The Python runtime the generated programs carry (linkgen/backends/py/runtime: the row driver, the
resolver, branch_at, reach_at) runs here on the step log: ``RowSolver`` gives the driver one pass of
the procedure, whose calls the scalar primitives make (the steps between the groups, each block's pass
and the groups' state readers each compiled once as one function: linkgen.rowblocks).
"""

from __future__ import annotations

import functools
import math
from collections import OrderedDict
from collections.abc import Callable
from dataclasses import dataclass, replace
from importlib import resources
from types import SimpleNamespace
from typing import Any

from . import status
from .backends.still import held_params, scalar_variants, still_suffix
from .kernel import compiled
from .loopstate import lengths, loop_flags
from .options import runtime_policy
from .primitives import PRIMITIVES, python_backend
from .primitives.interpret import constant_record
from .render.closure import in_process
from .rowblocks import BRANCH, Env, MakePass, Measure, States, block_pass, group_signs, group_states, steps_pass
from .steplog import Reach, ResolverGroup, Step, StepLog

FAIL, NOT_CONVERGED, SINGULAR, NEAR = status.CANNOT_CLOSE, status.NOT_CONVERGED, status.SINGULAR, status.NEAR_SINGULAR
Report = dict[int, tuple[Any, Any]]  # step -> (status, sigma), in the order the steps ran
Call = Callable[[str, list[Any]], tuple[Any, Any, tuple[Any, ...]]]


@functools.cache
def runtime() -> dict[str, Any]:
    """The Python runtime's functions, as the generated module has them."""
    ns: dict[str, Any] = {"sqrt": math.sqrt, "floor": math.floor, "NAN": math.nan, "PI": math.pi}
    for name in ("status.py", "branch.py", "reach.py", "resolver.py", "closure.py", "driver.py"):
        source = resources.files("linkgen.backends.py").joinpath("runtime").joinpath(name).read_text(encoding="utf-8")
        exec(compiled(source, f"<linkgen runtime {name}>"), ns)  # compiled once per user (7 ms of a build)
    return ns


def _scalar_call(order: int) -> Call:
    fns = python_backend(order)

    def call(name: str, args: list[Any]) -> tuple[Any, Any, tuple[Any, ...]]:
        prim = PRIMITIVES[name]
        res = fns[name](*args)
        if prim.status is None:
            return 0, 1.0, ((res,) if len(prim.outputs) == 1 else res)
        if prim.sigma is None:
            return res[0], 1.0, res[1:]
        return res[0], res[1], res[2:]

    return call


def branches(log: StepLog, env: Env, theta: float) -> None:
    """The branch of every chain with change points at the first input's value theta (the
    Python runtime's branch_at)."""
    periodic = log.inputs[0].kind == "revolute" if log.inputs else False
    theta0 = log.inputs[0].sketch if log.inputs else 0.0
    for s in log.steps:
        if s.change_points:
            b0 = next(int(a.value) for a in s.args if a.label == "minv")
            env[BRANCH, s.number] = runtime()["branch_at"](theta, b0, theta0, s.change_points, periodic)


def bounds(reach: Reach) -> tuple[float, float]:
    low, high = (math.nan if x is None else x for x in (reach.low, reach.high))
    return low, high


def _runs(steps: list[Step]) -> list[list[Step]]:
    """The steps in order, each resolve step alone and the steps between them together."""
    out: list[list[Step]] = []
    for s in steps:
        if s.action == "resolve" or not out or out[-1][0].action == "resolve":
            out.append([s])
        else:
            out[-1].append(s)
    return out


def row_status(report: Report) -> int:
    """The programs' row status from the steps' reports in the order they ran: the first
    failure's code, else the first singular step's, else the first near-singular one's
    (negative)."""
    singular = near = 0
    for n, (st, _) in report.items():
        if st in (FAIL, NOT_CONVERGED, status.NOT_CONTRACTING):
            return int(status.code(n, st))
        if st == SINGULAR and not singular:
            singular = status.code(n, st)
        elif st == NEAR and not near:
            near = status.code(n, st)
    return int(singular or near)


def _input_env(log: StepLog, order: int, values: Any, rates: Any, accs: Any) -> Env:
    """The constant records and the input records at ``order`` (no inputs given: constants only)."""
    env: Env = {v.name: constant_record(v, order, log.origin) for v in log.variables if v.constant}
    for inp, x, r, c in zip(log.inputs, values, rates, accs):
        env[inp.variable] = (x, r, c)[: order + 1]
    return env


class _Fields:
    """The records of an Env as the fields of a generated program's work (the runtime's addlink_rates
    reads and bends a block's records by name): the env is the object's own namespace, so getattr
    and setattr read and write its records without a call of Python code."""

    def __init__(self, env: Env):
        self.__dict__ = env


@dataclass
class Row:
    """One row (or pass) as the row driver left it: the records, each step's (status, sigma)
    in the order the steps ran, the Newton steps per group and the row's status code."""

    env: Env
    report: Report
    iterations: dict[int, int]
    code: int

    @property
    def ok(self) -> bool:
        """Whether the row has outputs (a singular position has its positions)."""
        return not status.failed(self.code)


def mechanism(log: StepLog, one_way: bool = False) -> SimpleNamespace:
    """What the runtime's row driver needs of the mechanism (the generated programs' MECHANISM);
    ``one_way``: no input is taken as an angle, so the continuation goes the straight way only."""
    blocks = [b for g in log.groups for b in (g, *g.variants)]
    return SimpleNamespace(
        length_scale=log.length_scale, sketch_inputs=tuple(i.sketch for i in log.inputs),
        sketch_a=tuple(b.start() for b in blocks), sizes=tuple(len(b.add_links) for b in blocks),
        loops=loop_flags(log),
        limits=log.step_limits(), periodic=tuple(i.kind == "revolute" and not one_way for i in log.inputs),
        low=math.nan if log.reach is None or log.reach.low is None else log.reach.low, groups=len(log.groups),
        another=status.code(log.groups[0].step, NOT_CONVERGED) if log.groups else 0, not_converged=NOT_CONVERGED)


_recent: OrderedDict[tuple[int, int], RowSolver] = OrderedDict()
RECENT = 8  # logs whose row solvers are kept: the summary evaluates one log's rows a few at a time, often


def solver(log: StepLog, order: int) -> RowSolver:
    """The log's RowSolver at ``order``, made once for the last few logs (making one costs more than
    solving a row), reset: no warm start, the policy's halvings."""
    key = (id(log), order)
    found = _recent.get(key)
    if found is None or found.log is not log:
        found = _recent[key] = RowSolver(log, order)
        if len(_recent) > RECENT:
            _recent.popitem(last=False)
    _recent.move_to_end(key)
    found.warm, found.halvings, found.its, found.last = None, log.policy.max_halvings, [], None
    return found


class RowSolver:
    """The generated programs' solve(): the runtime's row driver, one row at a time with warm
    starts (``warm``: the driver's, None without one), on the step log.  ``halvings`` is the
    continuation's (the policy's unless set)."""

    def __init__(self, log: StepLog, order: int):
        self.log, self.order, self.width = log, order, max(order, 1)  # records carry rates: the Jacobian's
        self.call = _scalar_call(self.width)
        fns = {**python_backend(self.width), **scalar_variants(log, self.width)}  # the programs' calls (still.py)
        callee = {s.number: s.function + still_suffix(held_params(log, self.width, s)) for s in log.steps if s.function}
        self.warm: Any = None
        self.halvings = log.policy.max_halvings
        self.mech, self.straight = mechanism(log), mechanism(log, one_way=True)
        self.kinds = {v.name: v.kind for v in log.variables}
        self.pos = {v.entity: v.name for v in log.variables if v.role == "pair"}
        self.groups = {g.step: g for g in log.groups}
        self.slots = {g.number: k for k, g in enumerate(log.groups)}
        counts = [1 + len(g.variants) for g in log.groups]
        self.first = {g.number: sum(counts[:k]) for k, g in enumerate(log.groups)}
        self.constants, self.inputs = _input_env(log, self.width, (), (), ()), [i.variable for i in log.inputs]
        inside = {n for g in log.groups for b in (g, *g.variants) for n in b.steps}
        self.steps = [s for s in log.steps
                      if s.action == "resolve" or (s.function and s.number not in inside and not s.variant)]
        blocks = [b for g in log.groups for b in (g, *g.variants)]
        parts = {(b.number, b.variant): self._parts(b) for b in blocks}
        self.passes: dict[tuple[int, int], MakePass] = {
            key: block_pass(b, steps, fns, reads, sigma, self.width + 1)
            for key, (b, steps, reads, sigma) in parts.items()}
        self.group_reads = {g.number: list(dict.fromkeys(name for b in (g, *g.variants)
                                                         for name, _ in parts[b.number, b.variant][2]))
                            for g in log.groups}
        self.plan: list[tuple[ResolverGroup | None, Callable[[Env, Report], bool] | None]] = [
            (self.groups[k[0].number], None) if k[0].action == "resolve" else (None, steps_pass(k, fns, callee))
            for k in _runs(self.steps)]
        residual, zero = fns["link_residual"], (0.0,) * (self.width + 1)
        self.states: dict[int, States] = {
            g.number: group_states((g, *g.variants), self.first[g.number], self.pos, residual, zero,
                                   [self._arc(b) for b in (g, *g.variants)]) for g in log.groups}
        self.signs = {g.number: group_signs((g, *g.variants), self.first[g.number]) for g in log.groups}
        self.periodic = log.inputs[0].kind == "revolute" if log.inputs else False
        self.theta0 = log.inputs[0].sketch if log.inputs else 0.0
        self.change_points = [(s.number, next(int(a.value) for a in s.args if a.label == "minv"), s.change_points)
                              for s in log.steps if s.change_points]
        self.blocks = {g.number: [self.passes[b.number, b.variant] for b in (g, *g.variants)] for g in log.groups}
        self.its: list[int] = []
        self.last: Row | None = None
        self.sets = {g.number: [b.sets for b in (g, *g.variants)] for g in log.groups}
        self._policies: dict[int, SimpleNamespace] = {}

    def _policy(self, halvings: int) -> SimpleNamespace:
        """The runtime's policy with the continuation's halvings, made once for each number of them
        (the runtime reads it, never changes it)."""
        if halvings not in self._policies:
            self._policies[halvings] = runtime_policy(replace(self.log.policy, max_halvings=halvings),
                                                      self.log.options)
        return self._policies[halvings]

    def _parts(self, b: ResolverGroup) -> tuple[ResolverGroup, list[Step], list[tuple[str, str]], list[int]]:
        """A block, its steps that call a function, the records they read from before the group
        (with their kinds) and the steps whose conditioning its chains' is."""
        steps = [self.log.step(n) for n in b.steps]
        inner = set(b.writes) | set(b.add_links)
        reads = sorted({a.var for st in steps for a in st.args if a.kind == "var" and a.var not in inner})
        sigma = [s.number for s in steps if s.function and PRIMITIVES[s.function].sigma is not None]
        return b, [s for s in steps if s.function], [(name, self.kinds[name]) for name in reads], sigma

    def _arc(self, b: ResolverGroup) -> Measure | None:
        """A loop block's state records off a configuration (loopstate.lengths); None for an Add-link block
        (its pairs measured by link_residual)."""
        if self.log.step(b.steps[0]).function != "loop_point":
            return None
        return lambda env, old: lengths(self.call, env, self.pos, self.log, b, old, self.width)

    def solve(self, values: Any, rates: Any, accs: Any, one_way: bool = False) -> Row:
        """Solve one row (see the runtime's drive); ``one_way``: the continuation takes the
        straight path only, never the other way round (the build's search for limit positions)."""
        p = self._policy(self.halvings)
        x, d, dd = ([float(v) for v in seq] for seq in (values, rates, accs))
        self.its = [0] * len(self.log.groups)
        past = self._side(x) != 0
        code, self.warm = runtime()["drive"](self.run, self.warm, x, d, dd, self.order, past,
                                             self.straight if one_way else self.mech, p)
        row = self.last
        assert row is not None
        if code != row.code:  # solvable on another assembly only
            n = status.step(code)
            row.report[n], row.code = (status.reason(code), row.report[n][1]), code
        row.iterations = {g.number: its for g, its in zip(self.log.groups, self.its)}
        return row

    def run(self, inputs: list[float], rates: list[float], accs: list[float], order: int, a: list[list[float]],
            used: list[int], row: int) -> tuple[int, list[list[float]]]:
        """One pass of the procedure (the generated _run), each block started from its state
        in ``a``; a and used are updated as the resolvers leave them.  Returns (status code,
        the block states' rates)."""
        env = dict(self.constants)
        for name, x, r, c in zip(self.inputs, inputs, rates, accs):
            env[name] = (x, r, c)[: self.width + 1]
        theta, branch_at = float(inputs[0]) if inputs else 0.0, runtime()["branch_at"]
        for number, b0, points in self.change_points:  # the branch of every chain with change points (branches)
            env[BRANCH, number] = branch_at(theta, b0, self.theta0, points, self.periodic)
        report: Report = {}
        ad = [[0.0] * len(s) for s in a]
        its = self.its if row else [0] * len(self.log.groups)
        side, reach = self._side(inputs), self.log.reach
        if reach is not None and side:  # past a limit position: fails at once
            report[status.step(reach.codes()[side > 0])] = (FAIL, math.nan)
        for group, steps in self.plan if not side else ():
            done = (self._resolve(group, env, report, order, a, ad, used, its, row != 1) if group
                    else steps and steps(env, report))
            if not done:
                break
        code = row_status(report)
        if row:
            self.last = Row(env, report, {}, code)
        return code, ad

    def _side(self, inputs: list[float]) -> int:
        """The Python runtime's reach_at of the first input (0 without a reach)."""
        reach = self.log.reach
        return 0 if reach is None else int(runtime()["reach_at"](float(inputs[0]), *bounds(reach), reach.periodic))

    def _resolve(self, g: ResolverGroup, env: Env, report: Report, order: int, a: list[list[float]],
                 ad: list[list[float]], used: list[int], its: list[int], full: bool) -> bool:
        """The group's resolver step through the runtime's resolve_group (full: every block's state read
        off the solution, a continuation pass's; else the solving block's); the report gets the last pass of
        the block that solved, then the step's own status."""
        first, signs, states = self.first[g.number], self.signs[g.number], self.states[g.number]
        signs(env, a)  # each chain's branch as the blocks' states hold it
        last: Report = {}
        chains = [0.0]
        before = {name: env[name] for name in self.group_reads[g.number] if name in env}  # as the group found them
        fns = [make(env, last, before, chains) for make in self.blocks[g.number]]

        def lengths(a: list[list[float]], ad: list[list[float]]) -> None:
            states(env, a, ad)

        p = self.log.policy
        resolve = runtime()["resolve_group"]
        if g.closure is not None:  # the closure strategy: its equations first, the states read off the solution
            def adopt(states: list[list[float]]) -> None:
                lengths(states, [[]] * len(states))
                signs(env, states)

            resolve = functools.partial(runtime()["resolve_closure"], in_process(g.closure, env, adopt))
        ok, sigma = resolve(fns, lengths, a, ad, first, self.slots[g.number], used, its, order, lambda: chains[0],
                            self.mech, self._policy(p.max_halvings), (_Fields(env), self.sets[g.number]), full)
        if ok > 0:
            report.update(last)
        report[g.step] = ((SINGULAR if sigma < p.singular else NEAR if sigma < p.near_singular else 0) if ok > 0
                          else NOT_CONVERGED if ok == 0 else status.NOT_CONTRACTING, sigma)
        return bool(ok > 0)

    def _group(self, b: ResolverGroup, env: Env, before: Env, last: Report, chains: list[float]) -> Callable[..., Any]:
        """The runtime's view of a block (the generated _group_N, linkgen.rowblocks.block_pass): (status, residual
        records) of its steps at Add-link lengths, rates and accelerations; live=False zeroes the rates of what it
        reads from before the group (``before``: the records as the group found them).  ``chains[0]``: the worst
        conditioning of the last pass's chains, from the block's lever down."""
        return self.passes[b.number, b.variant](env, last, before, chains)
