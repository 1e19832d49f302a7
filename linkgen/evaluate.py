"""Stage 6: evaluate a step log in-process.

Mechanisms without Add-links are evaluated for all rows at once by the log's vectorised
kernel, the numpy backend's NAME_np.py run in-process (linkgen.kernel).
Mechanisms with Add-links are evaluated row by row by the Python runtime the generated
programs carry (linkgen/backends/py/runtime: the row driver, the resolver, branch_at, reach_at),
run here on the step log: ``RowSolver`` gives the driver one pass of the procedure, whose
calls the scalar primitives make, and the blocks' state reader.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, replace
from importlib import resources
from types import SimpleNamespace
from typing import Any

import numpy as np

from . import status
from .kernel import Records, column, kernel
from .kernel import runtime as numpy_runtime
from .loopstate import lengths, loop_flags
from .options import runtime_policy
from .primitives import PRIMITIVES, python_backend
from .primitives.dsl import record_fields
from .primitives.interpret import constant_record
from .render.closure import in_process
from .steplog import Reach, ResolverGroup, Step, StepLog

FAIL, NOT_CONVERGED, SINGULAR, NEAR = status.CANNOT_CLOSE, status.NOT_CONVERGED, status.SINGULAR, status.NEAR_SINGULAR
BRANCH = "branch"  # env key (with a step number) of a chain's branch where it is not the sketch's

Env = dict[Any, Any]  # variable -> record, (BRANCH, step) -> branch
Report = dict[int, tuple[Any, Any]]  # step -> (status, sigma), in the order the steps ran
Call = Callable[[str, list[Any]], tuple[Any, Any, tuple[Any, ...]]]


@functools.cache
def runtime() -> dict[str, Any]:
    """The Python runtime's functions, as the generated module has them."""
    ns: dict[str, Any] = {"sqrt": math.sqrt, "floor": math.floor, "NAN": math.nan, "PI": math.pi}
    for name in ("status.py", "branch.py", "reach.py", "resolver.py", "closure.py", "driver.py"):
        source = resources.files("linkgen.backends.py").joinpath("runtime").joinpath(name).read_text(encoding="utf-8")
        exec(compile(source, f"<linkgen runtime {name}>", "exec"), ns)
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


def _args(step: Step, env: Env) -> list[Any]:
    out: list[Any] = []
    for a in step.args:
        if a.kind == "var":
            out.append(env[a.var])
        elif a.kind == "int":
            out.append(env.get((BRANCH, step.number), int(a.value)) if a.label == "minv" else int(a.value))
        else:
            out.append(float(a.value))
    return out


def branches(log: StepLog, env: Env, theta: float) -> None:
    """The branch of every chain with change points at the first input's value theta (the
    Python runtime's branch_at)."""
    periodic = log.inputs[0].kind == "revolute" if log.inputs else False
    theta0 = log.inputs[0].sketch if log.inputs else 0.0
    for s in log.steps:
        if s.change_points:
            b0 = next(int(a.value) for a in s.args if a.label == "minv")
            env[BRANCH, s.number] = runtime()["branch_at"](theta, b0, theta0, s.change_points, periodic)


def _bounds(reach: Reach) -> tuple[float, float]:
    low, high = (math.nan if x is None else x for x in (reach.low, reach.high))
    return low, high


def reach_side(reach: Reach, theta: Any) -> Any:
    """The numpy runtime's reach_at at every input value of an array: 0 where it is reached
    from the sketch, -1 past the gap below, 1 past the gap above."""
    side = numpy_runtime()["reach_at"](np.asarray(theta, dtype=float), *_bounds(reach), reach.periodic)
    return np.asarray(side, dtype=int)


def execute(steps: list[Step] | tuple[Step, ...], env: Env, call: Call) -> Report:
    """Run runtime calls in order; returns {step number: (status, sigma)}."""
    report: Report = {}
    for step in steps:
        if not step.function:
            continue
        st, sigma, outs = call(step.function, _args(step, env))
        for name, rec in zip(step.outputs, outs):
            env[name] = rec
        report[step.number] = (st, sigma)
    return report


def row_status(report: Report) -> Any:
    """The programs' row status from the steps' reports in the order they ran: the first
    failure's code, else the first singular step's, else the first near-singular one's
    (negative).  Works on one row (ints) and on arrays of rows alike."""
    fail: Any = 0
    singular: Any = 0
    near: Any = 0
    for n, (st, _) in report.items():
        failed = (st == FAIL) | (st == NOT_CONVERGED) | (st == status.NOT_CONTRACTING)
        fail = fail + (fail == 0) * failed * status.code(n, st)
        singular = singular + (singular == 0) * (st == SINGULAR) * status.code(n, st)
        near = near + (near == 0) * (st == NEAR) * status.code(n, st)
    return fail + (fail == 0) * (singular + (singular == 0) * near)


@dataclass
class Result:
    inputs: np.ndarray  # rows x inputs
    values: Mapping[str, tuple[np.ndarray, ...]]  # variable -> its fields per row (points relative to the origin)
    status: np.ndarray
    sigma: dict[int, np.ndarray]  # step -> conditioning per row
    iterations: dict[int, np.ndarray] = field(default_factory=dict)  # group -> Newton steps per row
    warm: list[Any] = field(default_factory=list)  # resolver warm start after each row (None where it failed)


def _input_env(log: StepLog, order: int, values: Any, rates: Any, accs: Any) -> Env:
    """The constant records and the input records at ``order`` (no inputs given: constants only)."""
    env: Env = {v.name: constant_record(v, order, log.origin) for v in log.variables if v.constant}
    for inp, x, r, c in zip(log.inputs, values, rates, accs):
        env[inp.variable] = (x, r, c)[: order + 1]
    return env


def evaluate(log: StepLog, values: np.ndarray, rates: np.ndarray, accs: np.ndarray, order: int | None = None,
             warm: Any = None, stop: int = 0, line: int = 0) -> Result:
    """Evaluate the procedure at rows of input values, rates and accelerations.

    With resolvers the rows are solved in order, the first from ``warm`` (a previous
    result's warm start) when given, else from the sketch, and every ``line``-th row
    from the sketch again (line_length; 0: never); ``stop`` (a step number)
    leaves the rows after the first one that fails at or before that step unsolved (nan).
    """
    order = log.order if order is None else order
    if log.groups:
        return _evaluate_rows(log, values, rates, accs, order, warm, stop, line)
    module = kernel(log, order, outputs=False)
    with np.errstate(all="ignore"):
        w, code, sigma = module._run(list(values.T), list(rates.T), list(accs.T), dict(module.PARAMS))
    rows = values.shape[0]
    return Result(values, Records(vars(w), rows),
                  np.broadcast_to(np.asarray(code, dtype=int), (rows,)).copy(),
                  {s.number: column(sigma[s.number], rows) for s in log.steps if s.function})


class _Fields:
    """The records of an Env as the fields of a generated program's work (the runtime's addlink_rates
    reads and bends a block's records by name)."""

    def __init__(self, env: Env):
        object.__setattr__(self, "env", env)

    def __getattr__(self, name: str) -> Any:
        return self.env[name]

    def __setattr__(self, name: str, value: Any) -> None:
        self.env[name] = value


def _still(rec: tuple[float, ...], kind: str) -> tuple[float, ...]:
    """A record with its derivatives zero."""
    width = 2 if kind == "POINT" else 1
    return tuple(rec[:width]) + (0.0,) * (len(rec) - width)


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


class RowSolver:
    """The generated programs' solve(): the runtime's row driver, one row at a time with warm
    starts (``warm``: the driver's, None without one), on the step log.  ``halvings`` is the
    continuation's (the policy's unless set)."""

    def __init__(self, log: StepLog, order: int):
        self.log, self.order, self.width = log, order, max(order, 1)  # records carry rates: the Jacobian's
        self.call = _scalar_call(self.width)
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
        self.parts = {(b.number, b.variant): self._parts(b) for g in log.groups for b in (g, *g.variants)}
        self.its: list[int] = []
        self.last: Row | None = None

    def _parts(self, b: ResolverGroup) -> tuple[list[Step], list[tuple[str, str]], list[int]]:
        """A block's steps, the records they read from before the group (with their kinds)
        and the steps whose conditioning its chains' is."""
        steps = [self.log.step(n) for n in b.steps]
        inner = set(b.writes) | set(b.add_links)
        reads = sorted({a.var for st in steps for a in st.args if a.kind == "var" and a.var not in inner})
        sigma = [s.number for s in steps if s.function and PRIMITIVES[s.function].sigma is not None]
        return steps, [(name, self.kinds[name]) for name in reads], sigma

    def solve(self, values: Any, rates: Any, accs: Any, one_way: bool = False) -> Row:
        """Solve one row (see the runtime's drive); ``one_way``: the continuation takes the
        straight path only, never the other way round (the build's search for limit positions)."""
        p = runtime_policy(replace(self.log.policy, max_halvings=self.halvings), self.log.options)
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
            used: list[int], row: bool) -> tuple[int, list[list[float]]]:
        """One pass of the procedure (the generated _run), each block started from its state
        in ``a``; a and used are updated as the resolvers leave them.  Returns (status code,
        the block states' rates)."""
        env = dict(self.constants)
        for name, x, r, c in zip(self.inputs, inputs, rates, accs):
            env[name] = (x, r, c)[: self.width + 1]
        branches(self.log, env, float(inputs[0]) if inputs else 0.0)
        report: Report = {}
        ad = [[0.0] * len(s) for s in a]
        its = self.its if row else [0] * len(self.log.groups)
        side, reach = self._side(inputs), self.log.reach
        if reach is not None and side:  # past a limit position: fails at once
            report[status.step(reach.codes()[side > 0])] = (FAIL, math.nan)
        for step in self.steps if not side else ():
            if step.action == "resolve":
                if not self._resolve(self.groups[step.number], env, report, order, a, ad, used, its):
                    break
            else:
                report.update(execute([step], env, self.call))
                if report[step.number][0] == FAIL:
                    break
        code = int(row_status(report))
        if row:
            self.last = Row(env, report, {}, code)
        return code, ad

    def _side(self, inputs: list[float]) -> int:
        """The Python runtime's reach_at of the first input (0 without a reach)."""
        reach = self.log.reach
        return 0 if reach is None else int(runtime()["reach_at"](float(inputs[0]), *_bounds(reach), reach.periodic))

    def _resolve(self, g: ResolverGroup, env: Env, report: Report, order: int, a: list[list[float]],
                 ad: list[list[float]], used: list[int], its: list[int]) -> bool:
        """The group's resolver step through the runtime's resolve_group; the report gets the
        last pass of the block that solved, then the step's own status."""
        first, blocks = self.first[g.number], (g, *g.variants)

        def branches_of(a: list[list[float]]) -> None:
            for j, b in enumerate(blocks):
                for i, bs in enumerate(b.branches):
                    env[BRANCH, bs.step] = -1 if a[first + j][len(b.add_links) + i] < 0 else 1

        branches_of(a)
        last: Report = {}
        chains = [0.0]
        before = dict(env)
        fns = [self._group(b, env, before, last, chains) for b in blocks]

        def lengths(states: list[list[float]], rates: list[list[float]]) -> None:
            for j, b in enumerate(blocks):
                states[first + j], rates[first + j] = self._state(env, b, states[first + j])

        p = self.log.policy
        resolve = runtime()["resolve_group"]
        if g.closure is not None:  # the closure strategy: its equations first, the states read off the solution
            def adopt(states: list[list[float]]) -> None:
                lengths(states, [[]] * len(states))
                branches_of(states)

            resolve = functools.partial(runtime()["resolve_closure"], in_process(g.closure, env, adopt))
        ok, sigma = resolve(fns, lengths, a, ad, first, self.slots[g.number], used, its, order, lambda: chains[0],
                            self.mech, runtime_policy(p, self.log.options), (_Fields(env), [b.sets for b in blocks]))
        if ok > 0:
            report.update(last)
        report[g.step] = ((SINGULAR if sigma < p.singular else NEAR if sigma < p.near_singular else 0) if ok > 0
                          else NOT_CONVERGED if ok == 0 else status.NOT_CONTRACTING, sigma)
        return bool(ok > 0)

    def _group(self, b: ResolverGroup, env: Env, before: Env, last: Report, chains: list[float]) -> Callable[..., Any]:
        """The runtime's view of a block (the generated _group_N): (status, residual records)
        of its steps at Add-link lengths, rates and accelerations; live=False zeroes the rates
        of what it reads from before the group.  ``chains[0]``: the worst conditioning of the
        last pass's chains, from the block's lever down."""
        steps, reads, sigma_steps = self.parts[b.number, b.variant]
        width, call = self.width + 1, self.call
        seen: dict[bool, Env] = {}

        def group(x: list[float], dx: list[float], ddx: list[float], live: bool) -> tuple[int, Any]:
            if not seen:  # the records as the group found them (a block's pass leaves its reads still)
                seen[True] = {name: before[name] for name, _ in reads}
                seen[False] = {name: _still(before[name], kind) for name, kind in reads}
            env.update(seen[live])
            for name, v, r, c in zip(b.add_links, x, dx, ddx):
                env[name] = (v, r, c)[:width]
            last.clear()
            last.update(execute(steps, env, call))
            if any(st == FAIL for st, _ in last.values()):
                return 1, None
            chains[0] = min([b.lever, *(last[n][1] for n in sigma_steps)])
            return 0, [env[f] for f in b.residuals]

        return group

    def _state(self, env: Env, b: ResolverGroup, old: list[float]) -> tuple[list[float], list[float]]:
        """A block's state and rates off a solved configuration (the generated _lengths_N): its Add-link lengths
        or loop's arc (loopstate.lengths), its chains' sign measures and rates (the predictor moves them: a chain
        passing its fold changes branch; a zero keeps the old one, rate 0), then its orientation (0)."""
        f = lengths(self.call, env, self.pos, self.log, b, old, self.width)
        n, marks, turns = len(b.pairs), [], []
        for j, bs in enumerate(b.branches):
            q = [env[v] for v in bs.points]
            if bs.kind == "side":
                m = (q[1][0] - q[0][0]) * (q[2][1] - q[0][1]) - (q[1][1] - q[0][1]) * (q[2][0] - q[0][0])
                dm = ((q[1][2] - q[0][2]) * (q[2][1] - q[0][1]) + (q[1][0] - q[0][0]) * (q[2][3] - q[0][3])
                      - (q[1][3] - q[0][3]) * (q[2][0] - q[0][0]) - (q[1][1] - q[0][1]) * (q[2][2] - q[0][2]))
            else:
                c, s, dt = math.cos(env[bs.angle][0]), math.sin(env[bs.angle][0]), env[bs.angle][1]
                m = (q[1][0] - q[0][0]) * c + (q[1][1] - q[0][1]) * s
                dm = ((q[1][2] - q[0][2]) * c + (q[1][3] - q[0][3]) * s
                      + ((q[1][1] - q[0][1]) * c - (q[1][0] - q[0][0]) * s) * dt)
            marks.append(m if m != 0 else old[n + j])
            turns.append(dm if m != 0 else 0.0)
        return [r[0] for r in f] + marks + [0.0], [r[1] for r in f] + turns + [0.0]


def _evaluate_rows(log: StepLog, values: np.ndarray, rates: np.ndarray, accs: np.ndarray, order: int, warm: Any,
                   stop: int, line: int) -> Result:
    solver = RowSolver(log, max(order, 1))  # the resolver's rates start the next row at every order
    solver.warm = warm
    rows: list[Row] = []
    warms: list[Any] = []
    for r in range(values.shape[0]):
        if line and r and r % line == 0:
            solver.warm = None
        failed = {n: rep for n, rep in rows[-1].report.items() if rep[0] in status.FAILED} if rows else {}
        stopped = bool(stop) and any(n <= stop for n in failed)
        rows.append(Row({}, failed, {}, rows[-1].code) if stopped else solver.solve(values[r], rates[r], accs[r]))
        warms.append(None if stopped else solver.warm)
    nan = {v.name: (math.nan,) * len(record_fields(v.kind, order)) for v in log.variables}
    env = {name: tuple(np.array([row.env.get(name, nan[name])[i] for row in rows], dtype=float)
                       for i in range(len(nan[name])))
           for name in sorted(nan)}
    numbers = sorted({n for row in rows for n in row.report})
    sigma = {n: np.array([row.report.get(n, (0, math.nan))[1] for row in rows], dtype=float) for n in numbers}
    its = {g.number: np.array([row.iterations.get(g.number, 0) for row in rows], dtype=int) for g in log.groups}
    codes = np.array([row.code for row in rows], dtype=int)
    if not log.options.checks:  # as the programs built without checks: a failure's code or 0
        codes = np.where(status.failed(codes), codes, 0)
    return Result(values, env, codes, sigma, its, warms)
