"""The loops of the loop strategy at one input, per combination of the chains' branches: the map
g(theta) the forward loop of a class-III group iterates (extraction.loops), its fixed points and the
slope |g'| there (below 1 the forward loop contracts, above it the reverse one, whose slope is 1/g').

Each fixed point of one branch combination is an assembly of the group; over the 2^3 combinations
they are every assembly the group has at that input (linkgen assemblies counts them, certified).
A fixed point whose body is the mirror image of the drawn one (its six distances hold, the ternary
link turned over) is no assembly and is left out.  The map is scanned on a fine grid of the assumed
angle, refined towards each end of its domain (a chain at its fold), each change of sign of the
returning angle's mismatch bisected to the last bit; a double root (a tangency, a singular input)
can be missed, as between grid points any sampling can.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from .evaluate import evaluate
from .extraction.loops import side
from .steplog import ResolverGroup, StepLog

GRID = 7200  # assumed angles per turn the map is sampled at
Point = tuple[float, float]
Branches = tuple[int, ...]  # the forward loop's three chains' branches, in the order they run


@dataclass(frozen=True)
class FixedPoint:
    group: int
    branches: Branches
    theta: float  # the assumed angle of the loop's leg at the fixed point (radians)
    slope: float  # g'(theta): |slope| < 1 the forward loop contracts there, > 1 the reverse one
    pairs: dict[str, Point]  # the group's pairs, as drawn (the file's frame)


def _chain(a: Point, k: Point, la: float, lk: float, side: int) -> Point | None:
    """The point at la from a and lk from k on the side ``side`` of a -> k (None: the chain cannot close)."""
    dx, dy = k[0] - a[0], k[1] - a[1]
    d2 = dx * dx + dy * dy
    if d2 == 0.0:
        return None
    along = (la * la - lk * lk + d2) / (2 * d2)
    h2 = la * la / d2 - along * along
    if h2 < 0.0:
        return None
    h = side * math.sqrt(h2)
    return a[0] + along * dx - h * dy, a[1] + along * dy + h * dx


@dataclass(frozen=True)
class Loop:
    """One group's forward loop: the pairs it places (X1, X3, X2) from the legs' known ends at one input."""

    group: int
    names: tuple[str, str, str]  # X1, X2, X3 (extraction.loops' Triad order)
    ks: tuple[Point, Point, Point]
    legs: tuple[float, float, float]
    sides: tuple[float, float, float]  # |X1X2|, |X1X3|, |X2X3|
    turn: int  # the body's orientation in the sketch: the sign of (X2 - X1) x (X3 - X1)

    def around(self, theta: float, branches: Branches) -> tuple[float, dict[str, Point]] | None:
        """The angle that comes back from theta, and the pairs placed (None: a chain cannot close)."""
        (k1, k2, k3), (l1, l2, l3), (s12, s13, s23) = self.ks, self.legs, self.sides
        x1 = (k1[0] + l1 * math.cos(theta), k1[1] + l1 * math.sin(theta))
        x3 = _chain(x1, k3, s13, l3, branches[0])
        x2 = _chain(x3, k2, s23, l2, branches[1]) if x3 else None
        back = _chain(x2, k1, s12, l1, branches[2]) if x2 else None
        if back is None or x2 is None or x3 is None:
            return None
        if side(x1, x2, x3) != self.turn:  # the body's mirror image: its distances, not the body
            return math.nan, {}
        return math.atan2(back[1] - k1[1], back[0] - k1[0]), dict(zip(self.names, (x1, x2, x3)))

    def mismatch(self, theta: float, branches: Branches) -> float | None:
        got = self.around(theta, branches)
        return None if got is None or got[0] != got[0] else math.remainder(got[0] - theta, 2 * math.pi)


def loops(log: StepLog, values: list[float]) -> list[Loop]:
    """The forward loop of every looped group of a log built with strategy loop, at the inputs ``values``."""
    row = evaluate(log, np.array([values]), np.zeros((1, len(values))), np.zeros((1, len(values))), order=0)
    ox, oy = log.origin

    def at(var: str) -> Point:
        v = log.variable(var)
        return (v.value[0], v.value[1]) if v.constant else (float(row.values[var][0][0]) + ox,
                                                            float(row.values[var][1][0]) + oy)

    return [loop for g in log.groups if (loop := _loop(log, g, at)) is not None]


def _loop(log: StepLog, g: ResolverGroup, at: Callable[[str], Point]) -> Loop | None:
    """A group's forward loop (None: the group has none), its legs' known pairs placed by ``at``."""
    forward = next((b for b in g.variants if log.variable(b.add_links[0]).role == "loop"), None)
    if forward is None:
        return None
    steps = [log.step(n) for n in forward.steps]
    pos = {v.name: v.entity for v in log.variables if v.role == "pair"}

    def length(var: str) -> float:
        return log.variable(var).value[0]

    chains = steps[1:4]
    x1, x3, x2 = steps[0].outputs[0], chains[0].outputs[0], chains[1].outputs[0]
    ks = (at(steps[0].args[0].var), at(chains[1].args[1].var), at(chains[0].args[1].var))
    legs = (length(steps[0].args[1].var), length(chains[1].args[3].var), length(chains[0].args[3].var))
    sides = (length(chains[2].args[2].var), length(chains[0].args[2].var), length(chains[1].args[2].var))
    drawn = [log.variable(x).sketch for x in (x1, x2, x3)]
    turn = side(*((p[0], p[1]) for p in drawn))
    return Loop(g.number, (pos[x1], pos[x2], pos[x3]), ks, legs, sides, turn)


def sketch_slopes(log: StepLog) -> dict[int, float]:
    """|g'| of each loop block (by its index among the group's blocks' variants) at the sketch's pose: the
    forward loop's, and the reverse loop's its reciprocal."""
    out = {}
    for g in log.groups:
        loop = _loop(log, g, lambda var: (log.variable(var).sketch[0], log.variable(var).sketch[1]))
        if loop is None:
            continue
        forward, reverse = (b for b in g.variants if log.variable(b.add_links[0]).role == "loop")
        branches = tuple(log.step(n).branch for n in forward.steps[1:4])
        slope = abs(_slope(loop, forward.lengths[0] / loop.legs[0], branches))
        out[forward.variant], out[reverse.variant] = slope, 1.0 / slope
    return out


def _slope(loop: Loop, theta: float, branches: Branches, h: float = 1e-7) -> float:
    """g'(theta) = 1 + the mismatch's slope, by central differences (one-sided next to a fold; nan where the
    map is not defined on either side)."""
    up, down, here = (loop.mismatch(theta + d, branches) for d in (h, -h, 0.0))
    if up is not None and down is not None:
        return 1.0 + (up - down) / (2 * h)
    if here is None:
        return math.nan
    return 1.0 + (up - here if up is not None else here - down if down is not None else math.nan) / h


def _edge(loop: Loop, inside: float, outside: float, branches: Branches) -> list[float]:
    """Angles approaching the end of the map's domain (a chain at its fold) between a grid point inside
    and one outside, closer and closer (a fixed point next to a fold is found between two of them)."""
    for _ in range(60):
        mid = 0.5 * (inside + outside)
        inside, outside = (mid, outside) if loop.mismatch(mid, branches) is not None else (inside, mid)
    step = outside - inside
    return [inside - step * 2.0 ** k for k in range(53, -1, -1) if abs(step) * 2.0 ** k < 2 * math.pi / GRID]


def fixed_points(loop: Loop) -> list[FixedPoint]:
    """Every fixed point of the loop's map, per branch combination, with its slope."""
    out = []
    grid = [-math.pi + 2 * math.pi * i / GRID for i in range(GRID + 1)]
    for branches in itertools.product((1, -1), repeat=3):
        f = [loop.mismatch(t, branches) for t in grid]
        near = [x for a, b, fa, fb in zip(grid, grid[1:], f, f[1:]) if (fa is None) != (fb is None)
                for x in (_edge(loop, a, b, branches) if fb is None else _edge(loop, b, a, branches))]
        angles = sorted(set(grid + near))
        f = [loop.mismatch(x, branches) for x in angles]
        for a, b, fa, fb in zip(angles, angles[1:], f, f[1:]):
            if fa is None or fb is None or abs(fa - fb) > 1.0 or fa * fb > 0 or fb == 0.0:
                continue
            for _ in range(200 if fa else 0):  # bisection to the last bit (none where a is the root)
                mid = 0.5 * (a + b)
                fm = loop.mismatch(mid, branches)
                if fm is None or mid in (a, b):
                    break
                a, b, fa = (mid, b, fm) if (fm > 0) == (fa > 0) else (a, mid, fa)
            theta = 0.5 * (a + b) if fa else a
            got = loop.around(theta, branches)
            if got is not None and got[1]:
                out.append(FixedPoint(loop.group, branches, theta, _slope(loop, theta, branches), got[1]))
    return out


def text(log: StepLog, values: list[float]) -> str:
    """The listing: per looped group and branch combination, its fixed points with |g'| and which loop contracts."""
    lines = []
    for loop in loops(log, values):
        found = fixed_points(loop)
        lines.append(f"group {loop.group}: the forward loop assumes the angle of the leg at {loop.names[0]} and places "
                     f"{loop.names[2]}, {loop.names[1]}, then {loop.names[0]} again; {len(found)} fixed points")
        for p in found:
            where = ", ".join(f"{n} ({x:.6g}, {y:.6g})" for n, (x, y) in p.pairs.items())
            way = "forward" if abs(p.slope) < 1 else "reverse"
            lines.append(f"  branches {'/'.join(f'{b:+d}' for b in p.branches)}: theta {math.degrees(p.theta):.6g} "
                         f"deg, |g'| {abs(p.slope):.4g} ({way} loop contracts): {where}")
    return "\n".join(lines) + "\n"
