"""Every assembly of a mechanism at one input: the procedure's steps walked as a tree.

A two-link chain with two branches splits the walk in two; a chain that cannot close on a
branch ends that subtree.  A resolver group splits it into one subtree per real root of its
characteristic polynomial (``polynomial``), the group's records written from the polished
root.  Every other step runs as the programs run it (the Python runtime's primitives, at
order 0).  Each leaf is one assembly; its link lengths are checked against the sketch, and
the assembly the programs follow from the sketch (the evaluator's) is marked.
"""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, cast

import numpy as np

from .. import status
from ..evaluate import evaluate
from ..primitives import PRIMITIVES, python_backend
from ..primitives.dsl import record_fields
from ..primitives.interpret import constant_record
from ..steplog import ResolverGroup, Step, StepLog, held
from .bodies import TwoBodies, two_bodies_of
from .pivots import Pivoted, pivoted_of
from .roots import Root, Solution, solve  # kept across processes: python-flint and mpmath imported where not
from .triad import NotReducible, Triad, grid, snap, triad_of

CHAINS = ("RRR_links", "PRR_links", "RPR_links", "PRP_links", "PPR_links")
CHECK = 1e-9  # an assembly whose link lengths are off by more (relative to L) breaks a constraint the procedure skips
MATCH = 1e-6  # the programs' configuration is an assembly this close (see distance)

if TYPE_CHECKING:
    from .resultant import Assembled, Count

Env = dict[str, tuple[float, ...]]


@dataclass(frozen=True)
class Choice:
    """How an assembly passes one step: a chain's branch, or a group's root."""

    step: int
    target: str  # the chain's pair, or "group N"
    value: int  # chain: the branch (+1 / -1); group: the root's number (1 = smallest turn)
    of: int  # chain: 2 (1 at a toggle, where both branches are one); group: its real roots
    theta: float = 0.0  # group: the ternary's turn from the sketch (radians)


@dataclass(frozen=True)
class GroupCount:
    """One solve of a resolver group (for one position of its bases)."""

    group: int
    triad: str  # what the group is, in words
    degree: int
    real_roots: int
    at_pi: bool
    thetas: tuple[float, ...]
    coefficients: tuple[float, ...]
    multiple: tuple[tuple[float, int], ...] = ()  # (theta, multiplicity) of its multiple roots: singular positions
    factors: tuple[int, ...] = ()  # class IV: the degrees of the eliminant's irreducible factors
    rejected: int = 0  # class IV: real roots of the eliminant that no assembly has (back-substitution)


@dataclass(frozen=True)
class Assembly:
    number: int
    sketch: bool  # the assembly the programs follow from the sketch
    choices: tuple[Choice, ...]
    values: dict[str, float]  # the CSV's columns at order 0: inputs, positions, link angles, slides
    error: float  # the worst link length error, over the length scale


@dataclass
class Census:
    """Every assembly at one input, and what was found on the way."""

    inputs: tuple[float, ...]  # radians or length units
    assemblies: list[Assembly] = field(default_factory=list)
    solves: list[GroupCount] = field(default_factory=list)
    cannot_close: dict[int, int] = field(default_factory=dict)  # step -> subtrees it ends
    toggles: list[int] = field(default_factory=list)  # chains at a toggle (their branches are one)
    broken: list[tuple[str, float]] = field(default_factory=list)  # leaves dropped: (link, error / L)
    sketch_note: str = ""  # why no assembly is marked as the sketch's
    at: tuple[float, ...] = ()  # the input values in the file's units, as given (empty: from ``inputs``)


def census(log: StepLog, values: Sequence[float]) -> Census:
    """Every assembly of the log's mechanism at the input values (radians, length units)."""
    walk = _Walk(log, tuple(float(v) for v in values))
    walk.run(0, dict(walk.start), ())
    out = walk.out
    out.cannot_close = dict(sorted(walk.closed.items()))
    leaves = []
    for v, choices in walk.leaves:
        error, link = _length_error(log, v)
        if error > CHECK:
            out.broken.append((link, error))
        else:
            leaves.append((v, choices, error))
    marked = _programs_assembly(log, out.inputs)
    index = _nearest(log, marked, [v for v, _, _ in leaves]) if isinstance(marked, dict) else None
    if index is None:
        out.sketch_note = marked if isinstance(marked, str) else \
            "the programs' configuration here is none of the assemblies found"
    out.assemblies = [Assembly(k + 1, k == index, choices, v, error) for k, (v, choices, error) in enumerate(leaves)]
    return out


class _Walk:
    def __init__(self, log: StepLog, values: tuple[float, ...]):
        self.log = log
        self.fns = python_backend(0)
        self.triads = {g.number: shape_of(log, g) for g in log.groups}
        self.groups = {g.step: g for g in log.groups}
        inside = {n for g in log.groups for b in (g, *g.variants) for n in b.steps}
        self.steps = [s for s in log.steps
                      if s.action == "resolve" or (s.function and s.number not in inside and not s.variant)]
        self.start: Env = {v.name: constant_record(v, 0, log.origin) for v in log.variables if v.constant}
        self.start.update((i.variable, (x,)) for i, x in zip(log.inputs, values))
        self.pos = {c.name[:-2]: c.variable for c in log.columns if c.name.endswith(".x")}
        self.solutions: dict[Any, Solution | Count] = {}
        self.closed: Counter[int] = Counter()
        self.out = Census(values)
        self.leaves: list[tuple[dict[str, float], tuple[Choice, ...]]] = []

    def call(self, step: Step, env: Env, branch: int = 0) -> tuple[int, float, tuple[Any, ...]]:
        """(status, sigma, outputs) of one step, its branch flag replaced by ``branch`` when given."""
        args: list[Any] = []
        for a in step.args:
            if a.kind == "var":
                args.append(env[a.var])
            elif a.kind == "int":
                args.append(branch if branch and a.label == "minv" else int(a.value))
            else:
                args.append(float(a.value))
        prim = PRIMITIVES[step.function]
        res = self.fns[step.function](*args)
        if prim.status is None:
            return 0, 1.0, ((res,) if len(prim.outputs) == 1 else res)
        if prim.sigma is None:
            return int(res[0]), 1.0, res[1:]
        return int(res[0]), float(res[1]), res[2:]

    def run(self, i: int, env: Env, choices: tuple[Choice, ...]) -> None:
        """Walk the steps from the i-th with the records ``env``."""
        while i < len(self.steps):
            s = self.steps[i]
            if s.action == "resolve":
                self._group(i, self.groups[s.number], env, choices)
                return
            if s.branch:
                self._split(i, s, env, choices)
                return
            st, _, outs = self.call(s, env)
            if st == status.CANNOT_CLOSE:
                self.closed[s.number] += 1
                return
            env.update(zip(s.outputs, outs))
            i += 1
        self.leaves.append((self._values(env), choices))

    def _split(self, i: int, s: Step, env: Env, choices: tuple[Choice, ...]) -> None:
        """Both branches of a chain (one at a toggle, where they are the same)."""
        for branch in (s.branch, -s.branch):
            st, sigma, outs = self.call(s, env, branch)
            if st == status.CANNOT_CLOSE:
                self.closed[s.number] += 1
                continue
            toggle = sigma == 0.0
            if toggle and s.number not in self.out.toggles:
                self.out.toggles.append(s.number)
            branch_env = dict(env)
            branch_env.update(zip(s.outputs, outs))
            self.run(i + 1, branch_env, (*choices, Choice(s.number, s.target, branch, 1 if toggle else 2)))
            if toggle:
                return

    def _group(self, i: int, g: ResolverGroup, env: Env, choices: tuple[Choice, ...]) -> None:
        """One subtree per real root of the group's polynomial."""
        triad = self.triads[g.number]
        solution = self._solve(triad, env)
        roots: tuple[Root | Assembled, ...] = solution.roots
        for k, root in enumerate(roots):
            root_env = dict(env)
            placed = dict(zip(triad.pairs, root.positions))
            axes = triad.axes(cast("Assembled", root).angles) if isinstance(triad, Pivoted) else {}
            for s in (self.log.step(n) for n in g.steps):
                if s.function in CHAINS:
                    entity = self.log.variable(s.outputs[-1]).entity
                    if entity not in placed:
                        raise NotReducible(f"resolver group {g.number}: step {s.number} is not a chain of the triad")
                    if len(s.outputs) == 1:
                        root_env[s.outputs[0]] = placed[entity]
                    else:  # a block's chain: its slide and slider point too
                        root_env.update(zip(s.outputs, self._slider(s, g, root_env, placed, axes.get(entity))))
                    continue
                st, _, outs = self.call(s, root_env)
                if st == status.CANNOT_CLOSE:
                    raise ArithmeticError(f"resolver group {g.number}: step {s.number} fails at a root")
                root_env.update(zip(s.outputs, outs))
            worst = max(abs(root_env[f][0]) for f in g.residuals) / self.log.length_scale
            if worst > CHECK:
                raise ArithmeticError(f"resolver group {g.number}: a root leaves a residual of {worst:.3g} L")
            self.run(i + 1, root_env, (*choices, Choice(g.step, f"group {g.number}", k + 1, len(solution.roots),
                                                        root.theta)))

    def _slider(self, s: Step, g: ResolverGroup, env: Env, placed: dict[str, tuple[float, float]],
                axis: float | None) -> tuple[Any, ...]:
        """A block's chain step run at the root: its Add-links' lengths from the placed pairs, the branch whose
        pair is the placed one (and whose slide's angle, its first output, is ``axis`` where the slide turns)."""
        for name, (a, b) in zip(g.add_links, g.pairs):
            if a in placed or b in placed:
                pa, pb = (placed[p] if p in placed else env[self.pos[p]] for p in (a, b))
                env[name] = (math.hypot(pa[0] - pb[0], pa[1] - pb[1]), *[0.0] * (len(record_fields(
                    self._kind(name), 0)) - 1))
        want = placed[self.log.variable(s.outputs[-1]).entity]
        best: tuple[float, tuple[Any, ...]] = (math.inf, ())
        for branch in (1, -1):
            st, _, outs = self.call(s, env, branch)
            if st != status.CANNOT_CLOSE:
                off = math.hypot(outs[-1][0] - want[0], outs[-1][1] - want[1])
                if axis is not None:
                    off += self.log.length_scale * abs(math.remainder(outs[0][0] - axis, 2 * math.pi))
                best = min(best, (off, outs), key=lambda b: b[0])
        if best[0] > CHECK * self.log.length_scale:
            raise ArithmeticError(f"resolver group {g.number}: step {s.number} does not reach the root")
        return best[1]

    def _solve(self, triad: Triad | TwoBodies | Pivoted, env: Env) -> Solution | Count:
        """The group's solution at the bases' positions in ``env`` (solved once per position)."""
        unit = grid(self.log.length_scale)
        if isinstance(triad, TwoBodies):
            return self._solve_bodies(triad, env, unit)
        if isinstance(triad, Pivoted):
            return self._solve_pivoted(triad, env, unit)
        if any(leg.line for leg in triad.legs):
            return self._solve_slides(triad, env, unit)
        bases = [tuple(snap(x, unit) for x in env[self.pos[leg.base]][:2]) for leg in triad.legs]
        lengths2 = [leg.length2 if leg.length2 is not None else snap(env[self.log.inputs[leg.input].variable][0], unit)
                    ** 2 for leg in triad.legs]
        key = (triad.group, tuple(bases), tuple(lengths2))
        if key not in self.solutions:
            sol = solve([(b[0], b[1]) for b in bases], list(triad.local), lengths2, self.log.length_scale)
            self.solutions[key] = sol
            self.out.solves.append(GroupCount(
                triad.group, triad.describe(), sol.degree, sol.real_roots, sol.at_pi, tuple(r.theta for r in sol.roots),
                sol.coefficients, tuple((r.theta, r.multiplicity) for r in sol.roots if r.multiplicity > 1)))
        return self.solutions[key]

    def _solve_slides(self, triad: Triad, env: Env, unit: Any) -> Solution:
        """The triad with blocks on fixed slides at its revolute legs' bases in ``env`` (``slides``)."""
        from . import slides

        holds: list[slides.Hold] = []
        for leg in triad.legs:
            if leg.line:
                holds.append((leg.line[0], leg.line[1], "slide"))
                continue
            base = (snap(env[self.pos[leg.base]][0], unit), snap(env[self.pos[leg.base]][1], unit))
            holds.append((base, leg.length2 if leg.length2 is not None else
                          snap(env[self.log.inputs[leg.input].variable][0], unit) ** 2))
        key = (triad.group, tuple(holds))
        if key not in self.solutions:
            sol = slides.solve(list(triad.local), holds, self.log.length_scale)
            self.solutions[key] = sol
            self.out.solves.append(GroupCount(
                triad.group, triad.describe(), sol.degree, sol.real_roots, sol.at_pi, tuple(r.theta for r in sol.roots),
                sol.coefficients, tuple((r.theta, r.multiplicity) for r in sol.roots if r.multiplicity > 1)))
        found = self.solutions[key]
        assert isinstance(found, Solution)
        return found

    def _solve_bodies(self, bodies: TwoBodies, env: Env, unit: Any) -> Count:
        """The class-IV group's solution at its legs' bases in ``env`` (``resultant``)."""
        from . import resultant

        names = [n for b in bodies.bodies for n in (b.base, b.base if b.line else b.other_base)]  # a slide: unused
        bases = [(snap(env[self.pos[n]][0], unit), snap(env[self.pos[n]][1], unit)) for n in names]
        key = (bodies.group, tuple(bases))
        if key not in self.solutions:
            sol = resultant.solve(bodies, tuple(bases), unit, self.log.length_scale)
            self.solutions[key] = sol
            self.out.solves.append(GroupCount(bodies.group, bodies.describe(), sol.degree, sol.real_roots, sol.at_pi,
                                              tuple(r.theta for r in sol.roots), (), (), sol.factors, sol.rejected))
        found = self.solutions[key]
        assert isinstance(found, resultant.Count)
        return found

    def _solve_pivoted(self, shape: Pivoted, env: Env, unit: Any) -> Count:
        """The group of two links on their own pivots at the pivots' positions in ``env`` (``pivoted``)."""
        from . import pivoted

        pivots = [(snap(env[self.pos[n]][0], unit), snap(env[self.pos[n]][1], unit)) for n in shape.pivots]
        key = (shape.group, tuple(pivots))
        if key not in self.solutions:
            sol = pivoted.solve(shape, pivots, unit, self.log.length_scale)
            self.solutions[key] = sol
            self.out.solves.append(GroupCount(shape.group, shape.describe(), sol.degree, sol.real_roots, sol.at_pi,
                                              tuple(r.theta for r in sol.roots), (), (), sol.factors, sol.rejected))
        return cast("Count", self.solutions[key])

    def _values(self, env: Env) -> dict[str, float]:
        return _columns(self.log, lambda name, field: env[name][record_fields(self._kind(name), 0).index(field)])

    def _kind(self, name: str) -> str:
        return self.log.variable(name).kind


def shape_of(log: StepLog, g: ResolverGroup) -> Triad | TwoBodies | Pivoted:
    """What the group is: a triad (one Add-link), two links on their own pivots tied by two links or
    slots (one Add-link, class IV: ``pivots``), or two bodies on four-bars tied by two couplers (two
    Add-links at once: class IV)."""
    if len(g.add_links) == 2:
        return two_bodies_of(log, g)
    try:
        return triad_of(log, g)
    except NotReducible as exc:
        try:
            return pivoted_of(log, g)
        except NotReducible as other:
            raise NotReducible(f"{exc}; nor is it {other.args[0].split(' is not ', 1)[-1]}") from None


def _columns(log: StepLog, get: Any) -> dict[str, float]:
    """The CSV's columns at order 0 (points in the file's coordinates) from ``get(variable, field)``."""
    out = {}
    for c in log.columns:
        if c.field in ("x", "y", "the", "v"):
            out[c.name] = float(get(c.variable, c.field)) + log.offset(c)
    return out


def _programs_assembly(log: StepLog, values: tuple[float, ...]) -> dict[str, float] | str:
    """The configuration the programs compute at the input, following the sketch's assembly
    (the evaluator), or why there is none."""
    rows = np.array([values])
    rates = np.array([[i.speed for i in log.inputs]])
    res = evaluate(log, rows, rates, np.zeros_like(rows), order=0)
    code = int(res.status[0])
    if status.failed(code):
        return (f"the sketch's assembly does not reach this input (the programs give status {code}: step "
                f"{status.step(code)} fails)")

    def get(name: str, fld: str) -> float:
        v = log.variable(name)
        k = record_fields(v.kind, 0).index(fld)
        return held(v, log.origin)[k] if v.constant else float(res.values[name][k][0])

    return _columns(log, get)


def distance(log: StepLog, a: dict[str, float], b: dict[str, float]) -> float:
    """How far apart two configurations are: the largest difference of a position or slide over the
    length scale, or of an angle (wrapped, in radians)."""
    worst = 0.0
    for c in log.columns[len(log.inputs):]:
        d = a[c.name] - b[c.name]
        if c.quantity == "angle":
            d = math.remainder(d, 2 * math.pi)
        else:
            d /= log.length_scale
        worst = max(worst, abs(d))
    return worst


def _nearest(log: StepLog, marked: dict[str, float], leaves: list[dict[str, float]]) -> int | None:
    """The leaf the programs' configuration is (within MATCH), if any."""
    best, index = MATCH, None
    for k, v in enumerate(leaves):
        d = distance(log, v, marked)
        if d <= best:
            best, index = d, k
    return index


def _length_error(log: StepLog, v: dict[str, float]) -> tuple[float, str]:
    """The worst error of the links' lengths (their truss members) over the length scale, and its
    link; a prismatic pair's position is its slider's copy, so it is measured on the slider only."""
    guides = {p.name: p.guide for p in log.pairs if p.kind == "prismatic"}
    worst, link = 0.0, ""
    for lk in log.links:
        for a, b, length in lk.lengths:
            if guides.get(a) == lk.name or guides.get(b) == lk.name:
                continue
            d = float(np.hypot(v[f"{a}.x"] - v[f"{b}.x"], v[f"{a}.y"] - v[f"{b}.y"]))
            if abs(d - length) / log.length_scale > worst:
                worst, link = abs(d - length) / log.length_scale, lk.name
    return worst, link
