"""Stage 6: evaluate a step log in-process.

Mechanisms without Add-links are evaluated for all rows at once with numpy.
Mechanisms with Add-links are evaluated row by row, exactly as the generated
programs do: the same scalar primitives, the same Newton resolver, warm-started
from the previous row and, from a cold start, continued from the sketch with
halved input steps where a direct step fails.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field
from importlib import resources

import numpy as np

from . import status
from .primitives import PRIMITIVES, numpy_backend, python_backend
from .primitives.dsl import record_fields
from .steplog import Reach, ResolverGroup, Step, StepLog, Variable, held

FAIL, NOT_CONVERGED, SINGULAR, NEAR = status.CANNOT_CLOSE, status.NOT_CONVERGED, status.SINGULAR, status.NEAR_SINGULAR


def _record(kind: str, order: int, value: float, rate: float = 0.0, acc: float = 0.0, y: float = 0.0) -> tuple:
    if kind == "POINT":
        return (value, y, 0.0, 0.0, 0.0, 0.0)[: 2 * (order + 1)]
    return (value, rate, acc)[: order + 1]


def constant_record(v: Variable, order: int, origin: tuple[float, float]) -> tuple:
    """A constant record as the programs hold it (points relative to ``origin``)."""
    value = held(v, origin)
    if v.kind == "POINT":
        return _record("POINT", order, value[0], y=value[1])
    return _record(v.kind, order, value[0])


@functools.cache
def _resolver_namespace() -> dict:
    """The Python runtime's resolver and branch functions, as the generated module has them."""
    ns: dict = {"sqrt": math.sqrt, "floor": math.floor, "NAN": math.nan, "PI": math.pi}
    for name in ("resolver.py", "branch.py"):
        source = resources.files("linkgen.backends.py").joinpath("runtime").joinpath(name).read_text(encoding="utf-8")
        exec(compile(source, f"<linkgen runtime {name}>", "exec"), ns)
    return ns


def _scalar_call(order: int):
    fns = python_backend(order)

    def call(name: str, args: list) -> tuple[int, float, tuple]:
        prim = PRIMITIVES[name]
        res = fns[name](*args)
        if prim.status is None:
            return 0, 1.0, ((res,) if len(prim.outputs) == 1 else res)
        if prim.sigma is None:
            return res[0], 1.0, res[1:]
        return res[0], res[1], res[2:]

    return call


def _numpy_call(order: int):
    fns = numpy_backend(order)

    def call(name: str, args: list) -> tuple:
        st, sigma, *outs = fns[name](*args)
        return st, sigma, tuple(outs)

    return call


def _args(step: Step, env: dict) -> list:
    out = []
    for a in step.args:
        if a.kind == "var":
            out.append(env[a.var])
        elif a.kind == "int":
            out.append(env.get((BRANCH, step.number), int(a.value)) if a.label == "minv" else int(a.value))
        else:
            out.append(float(a.value))
    return out


BRANCH = "branch"  # env key (with a step number) of a chain's branch where it is not the sketch's


def branches(log: StepLog, env: dict, theta, scalar: bool) -> None:
    """The branch of every chain with change points, at the first input's value(s) theta."""
    periodic = log.inputs[0].kind == "revolute" if log.inputs else False
    theta0 = log.inputs[0].sketch if log.inputs else 0.0
    for s in log.steps:
        if not s.change_points:
            continue
        b0 = next(int(a.value) for a in s.args if a.label == "minv")
        if scalar:
            env[BRANCH, s.number] = _resolver_namespace()["branch_at"](theta, b0, theta0, s.change_points, periodic)
            continue
        n = np.zeros_like(np.asarray(theta, dtype=float))
        for p in s.change_points:
            if periodic:
                n = n + np.floor((theta - p) / (2 * np.pi)) - np.floor((theta0 - p) / (2 * np.pi))
            else:
                n = n + (theta >= p).astype(float) - float(theta0 >= p)
        env[BRANCH, s.number] = np.where(n % 2 == 0, b0, -b0)


def execute(steps, env: dict, call) -> dict[int, tuple]:
    """Run runtime calls in order; returns {step number: (status, sigma)}."""
    report = {}
    for step in steps:
        if not step.function:
            continue
        st, sigma, outs = call(step.function, _args(step, env))
        for name, rec in zip(step.outputs, outs):
            env[name] = rec
        report[step.number] = (st, sigma)
    return report


class Codes:
    """Row status from step reports: first failure, else first singular, else first near-singular."""

    def __init__(self, rows: int):
        self.fail = np.zeros(rows, dtype=int)
        self.singular = np.zeros(rows, dtype=int)
        self.near = np.zeros(rows, dtype=int)

    def add(self, number: int, reported) -> None:
        st = np.asarray(reported)
        for target, codes in ((self.fail, (FAIL, NOT_CONVERGED)), (self.singular, (SINGULAR,)), (self.near, (NEAR,))):
            hit = np.isin(st, codes) & (target == 0)
            target[hit] = np.abs(status.code(number, st * np.ones_like(target)))[hit]

    def status(self) -> np.ndarray:
        return np.where(self.fail > 0, self.fail,
                        np.where(self.singular > 0, self.singular, -np.where(self.near > 0, self.near, 0)))


def input_rows(log: StepLog, samples: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    k = np.arange(samples, dtype=float)
    values = np.stack([i.start + k * (i.stop - i.start) / (samples - 1) for i in log.inputs], axis=1)
    rates = np.tile([i.speed for i in log.inputs], (samples, 1)).astype(float)
    return values, rates, np.zeros_like(values)


@dataclass
class Result:
    inputs: np.ndarray  # rows x inputs
    values: dict[str, tuple]  # variable -> tuple of arrays (rows), as computed: points relative to the origin
    status: np.ndarray
    sigma: dict[int, np.ndarray]  # step -> conditioning per row
    iterations: dict[int, np.ndarray] = field(default_factory=dict)  # group -> Newton steps per row
    warm: list = field(default_factory=list)  # resolver warm start after each row (None where it failed)


def _input_record(log: StepLog, i: int, order: int, value, rate, acc) -> tuple:
    kind = "ANGLE" if log.inputs[i].kind == "revolute" else "VARIABLE"
    return _record(kind, order, value, rate, acc)


def _base_env(log: StepLog, order: int) -> dict:
    return {v.name: constant_record(v, order, log.origin) for v in log.variables if v.constant}


def evaluate(log: StepLog, values: np.ndarray, rates: np.ndarray, accs: np.ndarray, order: int | None = None,
             warm=None, stop: int = 0) -> Result:
    """Evaluate the procedure at rows of input values, rates and accelerations.

    With resolvers the rows are solved in order, the first from ``warm`` (a previous
    result's warm start) when given, else from the sketch; ``stop`` (a step number)
    leaves the rows after the first one that fails at or before that step unsolved (nan).
    """
    order = log.order if order is None else order
    if log.groups:
        return _evaluate_rows(log, values, rates, accs, order, warm, stop)
    env = _base_env(log, order)
    for i, inp in enumerate(log.inputs):
        env[inp.variable] = _input_record(log, i, order, values[:, i], rates[:, i], accs[:, i])
    branches(log, env, values[:, 0] if log.inputs else 0.0, scalar=False)
    with np.errstate(all="ignore"):
        report = execute(log.steps, env, _numpy_call(order))
    result = _finish(log, values, env, report, order)
    if log.reach is not None:
        side = reach_side(log.reach, values[:, 0])
        result.status[side < 0], result.status[side > 0] = log.reach.codes()
    return result


def reach_side(reach: Reach, theta: np.ndarray) -> np.ndarray:
    """The runtime's reach_at for every row: 0 where the input value is reached from the
    sketch, -1 past the gap below, 1 past the gap above."""
    low = np.nan if reach.low is None else reach.low
    high = np.nan if reach.high is None else reach.high
    if reach.periodic:
        t = theta - 2 * np.pi * np.floor((theta - low) / (2 * np.pi))
        return np.where(t < high, 0, np.where(t - high <= low + 2 * np.pi - t, 1, -1))
    return np.where(theta <= low, -1, np.where(theta >= high, 1, 0))


def _finish(log: StepLog, values: np.ndarray, env: dict, report: dict, order: int,
            iterations: dict | None = None) -> Result:
    rows = values.shape[0]
    codes = Codes(rows)
    for number in sorted(report):
        codes.add(number, report[number][0])
    status = codes.status()
    out = {}
    for name, rec in env.items():
        out[name] = tuple(np.broadcast_to(np.asarray(x, dtype=float), (rows,)).copy() for x in rec)
    sigma = {n: np.broadcast_to(np.asarray(s, dtype=float), (rows,)).copy() for n, (_, s) in report.items()}
    return Result(values, out, status, sigma, iterations or {})


def _pad(rec: tuple, kind: str, order: int, live: bool) -> tuple:
    """A record at ``order``: missing derivative fields are zero, and all of them when not live."""
    width = 2 if kind == "POINT" else 1
    full = list(rec) + [0.0] * (width * (order + 1) - len(rec))
    return tuple(x if live or i < width else 0.0 for i, x in enumerate(full[: width * (order + 1)]))


@dataclass
class Pass:
    report: dict
    env: dict
    solutions: list  # per resolver block (a group or one of its variants): Add-link lengths
    rates: list  # their rates
    used: dict  # group -> the variant that solved it
    iterations: dict  # group -> Newton steps
    failed_group: int  # the group whose resolver failed (0: none)

    @property
    def ok(self) -> bool:
        return not self.failed_group and all(st != FAIL for st, _ in self.report.values())


def _block_state(env: dict, pos: dict[str, str], block: ResolverGroup, start: list, turn: int) -> tuple[list, list]:
    """A block's state read off a solved configuration, with its rates: the Add-link lengths
    (link_residual against a zero length, as the generated programs measure them), the
    branches of its chains (rate 0; a sign of zero keeps the branch of ``start``), then its
    orientation ``turn`` (the sign of its Jacobian's determinant where it solved, else 0)."""
    call = _scalar_call(1)
    a, ad = [], []
    for k, u in block.pairs:
        _, _, (f,) = call("link_residual", [env[pos[k]][:4], env[pos[u]][:4], (0.0, 0.0)])
        a.append(f[0])
        ad.append(f[1])
    n = len(block.pairs)
    for j, b in enumerate(block.branches):
        p = [env[v] for v in b.points]
        if b.kind == "side":
            m = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0])
        else:
            t = env[b.angle][0]
            m = (p[1][0] - p[0][0]) * math.cos(t) + (p[1][1] - p[0][1]) * math.sin(t)
        a.append(1.0 if m > 0 else -1.0 if m < 0 else start[n + j])
        ad.append(0.0)
    return a + [float(turn)], ad + [0.0]


class RowSolver:
    """The generated programs' solve(): one row at a time, with warm starts.

    Each resolver group has blocks: the chosen Add-link candidate and its fallbacks.
    The block that solved the previous row is tried first, then the others in rank
    order; every block's Add-link lengths are then measured on the solved pairs, so
    any of them can start the next row.
    """

    def __init__(self, log: StepLog, order: int):
        self.log = log
        self.order = order
        self.ns = _resolver_namespace()
        self.kinds = {v.name: v.kind for v in log.variables}
        self.pos = {v.entity: v.name for v in log.variables if v.role == "pair"}
        self.blocks = [b for g in log.groups for b in (g, *g.variants)]
        self.warm = None  # (inputs, rates, block states, their rates, used variants)
        self.sketch_in = tuple(i.sketch for i in log.inputs)
        self.sketch_a = [b.start() for b in self.blocks]
        self.halvings = log.policy.max_halvings
        self.sizes = [len(b.add_links) for b in self.blocks]
        self.slack = log.policy.path_slack * log.length_scale
        self.reach = log.policy.max_move * log.length_scale
        self.periodic = [i.kind == "revolute" for i in log.inputs]
        self.limits = list(log.step_limits())
        self.low = math.nan if log.reach is None or log.reach.low is None else log.reach.low

    def run(self, values, rates, accs, order: int, start: list, prefer: dict) -> Pass:
        """One pass of the whole procedure, each resolver block started from ``start``."""
        call = _scalar_call(order)
        env = _base_env(self.log, order)
        for i, inp in enumerate(self.log.inputs):
            env[inp.variable] = _input_record(self.log, i, order, values[i], rates[i], accs[i])
        branches(self.log, env, values[0] if len(values) else 0.0, scalar=True)
        n = len(self.blocks)
        out = Pass({}, env, [None] * n, [None] * n, {}, {}, 0)
        if self.log.reach is not None:
            side = int(reach_side(self.log.reach, np.array([values[0]]))[0])
            if side:  # past a limit position: fails at once
                code = self.log.reach.codes()[side > 0]
                out.report[status.step(code)] = (FAIL, math.nan)
                return out
        groups = {g.step: g for g in self.log.groups}
        inside = {n for b in self.blocks for n in b.steps}
        for step in self.log.steps:
            if step.action == "resolve":
                g = groups[step.number]
                if not self.resolve(g, out, order, start, prefer.get(g.number, 0)):
                    out.report[step.number] = (NOT_CONVERGED, 0.0)
                    out.failed_group = g.number
                    return out
            elif step.function and step.number not in inside and not step.variant:
                out.report.update(execute([step], env, call))
                if out.report[step.number][0] == FAIL:
                    return out
        return out

    def resolve(self, g: ResolverGroup, out: Pass, order: int, start: list, prefer: int) -> bool:
        """The group's blocks, the preferred one first: the first that converges with its chains
        conditioned at least the policy's ``min_chain_sigma`` is taken, else the best conditioned one that
        converges (a later one only when more than twice as well conditioned); then every
        block's state is read off the solved pairs."""
        first = self.blocks.index(g)
        count = 1 + len(g.variants)
        before = dict(out.env)

        def attempt(k: int):
            out.env.clear()
            out.env.update(before)
            return self._newton(self.blocks[first + k], out, order, start[first + k])

        def take(k: int, finish) -> bool:
            done = finish()
            if done is None:
                return False
            out.used[g.number] = k
            out.report[g.step], turn = done
            for j in range(count):
                b = self.blocks[first + j]
                out.solutions[first + j], out.rates[first + j] = _block_state(out.env, self.pos, b, start[first + j],
                                                                              turn if j == k else 0)
            return True

        best: tuple[float, int] | None = None  # the best of the converged blocks with poorly conditioned chains
        for k in [prefer] + [k for k in range(count) if k != prefer]:
            solved = attempt(k)
            if solved is None:
                continue
            if solved[0] < self.log.policy.min_chain_sigma:
                if best is None or solved[0] > 2 * best[0]:
                    best = (solved[0], k)
                continue
            if take(k, solved[1]):
                return True
        if best is None:
            return False
        solved = attempt(best[1])
        return solved is not None and take(best[1], solved[1])

    def _newton(self, g: ResolverGroup, out: Pass, order: int, a0: list[float]):
        """Newton on one block's Add-links from its state a0 (lengths, then branches), with
        the velocity channel at least, for the Jacobian.  None when it does not converge, else
        (the worst conditioning of the block's chains there, finish) where finish() computes
        the exact rates and returns the resolver's (status, sigma), or None when a chain fails."""
        env = out.env
        n = len(g.add_links)
        for j, b in enumerate(g.branches):
            env[BRANCH, b.step] = int(a0[n + j])
        inner = max(order, 1)
        call = _scalar_call(inner)
        steps = [self.log.step(n) for n in g.steps]
        inner_vars = set(g.writes) | set(g.add_links)
        reads = {a.var: env[a.var] for st in steps for a in st.args if a.kind == "var" and a.var not in inner_vars}
        last: dict[int, tuple] = {}

        padded = {live: {name: _pad(rec, self.kinds[name], inner, live) for name, rec in reads.items()}
                  for live in (False, True)}

        def group(a, live):
            env.update(padded[live])
            for name, rec in zip(g.add_links, a):
                env[name] = tuple(rec[: inner + 1])
            last.clear()
            last.update(execute(steps, env, call))
            bad = any(st == FAIL for st, _ in last.values())
            return (1 if bad else 0), [env[f] for f in g.residuals]

        scale = self.log.length_scale
        p = self.log.policy
        ok, a, its, jac = self.ns["newton"](group, list(a0[:n]), p.tolerance * scale, p.max_iterations,
                                            p.max_move * scale)
        out.iterations[g.number] = its
        if not ok:
            return None
        worst = min([g.lever, *(sigma for _, sigma in last.values())])

        def finish():
            st, sigma, turn = self.ns["addlink_rates"](group, a, jac, order)
            if st == FAIL:
                return None
            width = {"POINT": 2}
            for name in list(g.writes) + list(g.add_links) + list(reads):
                env[name] = env[name][: width.get(self.kinds[name], 1) * (order + 1)]
            out.report.update(last)
            return (SINGULAR if sigma < p.singular else NEAR if sigma < p.near_singular else 0, sigma), turn

        return worst, finish

    def solve(self, values, rates, accs, one_way: bool = False) -> Pass:
        """Solve one row on the sketch's assembly: from the previous row when it was solved and
        no input has moved farther than a continuation step (Taylor-predicted start), else by
        continuation from the previous row or, without one, from the sketch.  A row past the
        reach fails at once.  ``one_way``: the continuation takes the straight path only, never
        the other way round (the build's search for limit positions)."""
        if self.log.reach is not None and reach_side(self.log.reach, np.array([values[0]]))[0]:
            self.warm = None
            return self.run(values, rates, accs, self.order, self.sketch_a, {})
        if self.warm is not None:
            w_in, w_rates, a, ad, used = self.warm
            if self.ns["within"](values, w_in, self.limits):
                start = self.ns["predict"]((w_in, w_rates, a, ad), values, self.sizes)
                out = self.run(values, rates, accs, self.order, start, used)
                if out.ok and self.ns["on_path"](a, start, out.solutions, self.sizes, self.slack):
                    self._remember(values, rates, out)
                    return out
                if not out.ok and out.failed_group == 0:
                    self.warm = None
                    return out
            base, base_a, prefer = w_in, a, used
        else:
            base, base_a, prefer = self.sketch_in, self.sketch_a, {}
        path = lambda x, d, o, s: self._path_run(x, d, o, s, prefer)  # noqa: E731
        states = [list(b) for b in base_a]
        if one_way:
            a = self.ns["walk"](path, list(base), states, list(values), self.limits, self.halvings, self.sizes,
                                self.slack, self.reach)
        else:
            a = self.ns["continuation"](path, list(base), states, list(values), self.limits, self.periodic,
                                        self.halvings, self.sizes, self.slack, self.reach, self.low)
        if a is None:
            self.warm = None
            out = self.run(values, rates, accs, self.order, base_a, prefer)
            if out.ok:  # solvable only on another assembly: not the sketch's
                out.report[self.log.groups[0].step] = (NOT_CONVERGED, 0.0)
                out.failed_group = self.log.groups[0].number
            return out
        out = self.run(values, rates, accs, self.order, a, prefer)
        if out.ok:
            self._remember(values, rates, out)
        else:
            self.warm = None
        return out

    def _remember(self, values, rates, out: Pass) -> None:
        self.warm = (tuple(values), tuple(rates), out.solutions, out.rates, dict(out.used))

    def _path_run(self, inputs, rates, order, a, prefer):
        """The continuation's view of a pass: (ok, lengths, their rates along the path)."""
        out = self.run(inputs, rates, [0.0] * len(inputs), order, a, prefer)
        if not out.ok:
            return False, None, None
        return True, out.solutions, out.rates


def _evaluate_rows(log: StepLog, values, rates, accs, order: int, warm, stop: int) -> Result:
    solver = RowSolver(log, max(order, 1))  # the resolver's rates start the next row at every order
    solver.warm = warm
    rows = values.shape[0]
    envs, reports, warms, its = [], [], [], {g.number: np.zeros(rows, dtype=int) for g in log.groups}
    stopped, failed = False, {}
    for r in range(rows):
        if stopped:
            envs.append({})
            reports.append(failed)
            warms.append(None)
            continue
        row = solver.solve(values[r], rates[r], accs[r])
        envs.append(row.env)
        reports.append(row.report)
        warms.append(solver.warm)
        failed = {n: rep for n, rep in row.report.items() if rep[0] in (FAIL, NOT_CONVERGED)}
        stopped = bool(stop) and any(n <= stop for n in failed)
        for g, n in row.iterations.items():
            its[g][r] = n
    nan = {v.name: (math.nan,) * len(record_fields(v.kind, order)) for v in log.variables}
    env = {}
    for name in sorted(nan):
        recs = [e.get(name, nan[name]) for e in envs]
        env[name] = tuple(np.array([rec[i] for rec in recs], dtype=float) for i in range(len(nan[name])))
    numbers = {n for rep in reports for n in rep}
    report = {
        n: (np.array([rep.get(n, (0, math.nan))[0] for rep in reports]),
            np.array([rep.get(n, (0, math.nan))[1] for rep in reports], dtype=float))
        for n in sorted(numbers)
    }
    result = _finish(log, values, env, report, order, its)
    result.warm = warms
    return result


def residual_norm(variables: dict[str, Variable], steps: list[Step], inputs: list[str], values: tuple[float, ...],
                  residuals: list[str], origin: tuple[float, float]) -> float | None:
    """|f| with every Add-link at its sketch length (the paper's ranking of candidates)."""
    env = {v.name: constant_record(v, 0, origin) for v in variables.values() if v.constant}
    for name, value in zip(inputs, values):
        env[name] = (value,)
    for v in variables.values():
        if v.role == "addlink":
            env[v.name] = (v.sketch[0],)
    report = execute(steps, env, _scalar_call(0))
    if any(st == FAIL for st, _ in report.values()):
        return None
    return math.sqrt(sum(env[f][0] ** 2 for f in residuals))
