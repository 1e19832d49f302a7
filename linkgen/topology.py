"""Stage 3: the mechanism's structure and sketch geometry.

Multi-pair links become trusses of binary members (the paper's rule i), compound
hinges are one pair on several links (rule iii), each link gets the direction
that defines its angle, each input its sketch value; the length scale and the
origin the programs compute from are set, and the mobility is checked (``mobility``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from . import exact
from .errors import InputError
from .mobility import check_mobility
from .model import Input, Link, Mechanism
from .policy import LENGTH_SCALES


@dataclass(frozen=True)
class Member:
    """A binary link of the truss that replaces a link: two pairs at a fixed distance."""

    link: str
    a: str
    b: str
    length: float

    @property
    def label(self) -> str:
        return f"{self.link}:{self.a}-{self.b}"


@dataclass(frozen=True)
class Direction:
    """How a link's angle is measured: from pair/point ``origin`` towards ``target``,
    or along the axis of the prismatic pair ``axis_of`` when all its points coincide."""

    origin: str
    target: str
    axis_of: str
    angle: float  # in the sketch


@dataclass(frozen=True)
class Topology:
    """The mechanism with its truss members, link directions, sketch inputs, mobility counts
    and the length scale and origin the programs compute with."""

    mechanism: Mechanism
    length_scale: float
    origin: tuple[float, float]
    grubler: int
    mobility: int
    redundant: int
    members: tuple[Member, ...]
    directions: tuple[Direction, ...]  # per link, in links order
    sketch_inputs: tuple[float, ...]  # per input, in its units (radians or length)

    def position(self, name: str) -> tuple[float, float]:
        return sketch_position(self.mechanism, name)

    def direction(self, link: str) -> Direction:
        return self.directions[self.mechanism.link(link).index]


def sketch_position(m: Mechanism, name: str) -> tuple[float, float]:
    return m.positions[name]


def wrap_angle(a: float) -> float:
    """Angle in (-pi, pi]."""
    a = math.remainder(a, 2 * math.pi)
    return math.pi if a == -math.pi else a


def angle_between(m: Mechanism, origin: str, target: str) -> float:
    (x0, y0), (x1, y1) = sketch_position(m, origin), sketch_position(m, target)
    return exact.atan2(y1 - y0, x1 - x0)


def _carried(link: Link) -> list[str]:
    return list(link.joints) + [p.name for p in link.points]


def link_direction(m: Mechanism, link: Link) -> Direction:
    """The spec's link direction: first pair to the next pair (then point) elsewhere."""
    names = _carried(link)
    origin = names[0]
    for target in names[1:]:
        if sketch_position(m, target) != sketch_position(m, origin):
            return Direction(origin, target, "", angle_between(m, origin, target))
    prismatic = next(j for j in link.joints if not m.joint(j).revolute)
    return Direction(origin, "", prismatic, m.joint(prismatic).axis)


def input_direction(m: Mechanism, link: Link, joint: str) -> Direction:
    """A link's direction seen from an input pair: towards the next pair after it
    (cyclically), then its points, skipping any at the same sketch position."""
    pairs = list(link.joints)
    start = pairs.index(joint)
    order = pairs[start + 1:] + pairs[:start] + [p.name for p in link.points]
    here = sketch_position(m, joint)
    for target in order:
        if sketch_position(m, target) != here:
            return Direction(joint, target, "", angle_between(m, joint, target))
    raise InputError(f"every pair and point of link {link.name} lies at the input pair {joint}, so the input "
                     f"angle at {joint} has no direction on {link.name}; give {link.name} a point away from {joint} "
                     f"(points: {{NAME: [x, y]}})", m.path, link.where.line, link.where.key)


def truss(m: Mechanism, link: Link) -> list[Member]:
    """Rule (i): a link with k pairs becomes the binary members between all its pairs."""
    pairs = list(link.joints)
    if len(pairs) == 1:
        return [Member(link.name, pairs[0], "", 0.0)]
    out = []
    for i, a in enumerate(pairs):
        for b in pairs[i + 1:]:
            (xa, ya), (xb, yb) = sketch_position(m, a), sketch_position(m, b)
            out.append(Member(link.name, a, b, math.hypot(xb - xa, yb - ya)))
    return out


def _nearest_turn(value: float, start: float, stop: float) -> float:
    """The representative of an angle (mod 2 pi) nearest the range, preferring the start:
    among the turns next to either end of the range (inside it when one is), so a range of
    any width takes the same few steps."""
    lo, hi, turn = min(start, stop), max(start, stop), 2 * math.pi
    turns = {k + j for k in (math.floor((lo - value) / turn), math.floor((hi - value) / turn)) for j in (-1, 0, 1, 2)}
    return min((value + turn * k for k in turns), key=lambda c: (max(lo - c, c - hi, 0.0), abs(c - start)))


def reference_angle(m: Mechanism, inp: Input) -> float:
    """phi_F of a revolute input: 0 for the fixed link, else its direction seen from the pair."""
    ref = m.link(inp.relative_to)
    return 0.0 if ref.fixed else input_direction(m, ref, inp.joint).angle


def sketch_input(m: Mechanism, inp: Input) -> float:
    if inp.kind == "revolute":
        phi_l = input_direction(m, m.link(inp.link), inp.joint).angle
        return _nearest_turn(wrap_angle(phi_l - reference_angle(m, inp)), inp.start, inp.stop)
    if inp.kind == "prismatic":
        return 0.0
    (xa, ya), (xb, yb) = sketch_position(m, inp.between[0]), sketch_position(m, inp.between[1])
    return math.hypot(xb - xa, yb - ya)


def _farthest(m: Mechanism) -> tuple[str, str, float]:
    """The two pairs or points of the sketch farthest apart (the first such in declaration
    order), and their distance.

    Only the spots that can be an end of the farthest pair are compared pairwise: a spot's
    distance to any other is at most its distance to the farthest corner of the bounding box,
    and the farthest pair is at least as far apart as the spot with the largest such bound
    is from its farthest spot."""
    names = list(m.positions)
    spots = np.array([m.positions[n] for n in names])
    lo, hi = spots.min(axis=0), spots.max(axis=0)
    bound = np.hypot(*np.maximum(spots - lo, hi - spots).T)
    first = spots[int(np.argmax(bound))]
    least = np.hypot(*(spots - first).T).max()
    ends = np.flatnonzero(bound >= least * (1 - 1e-9))
    d = spots[ends][:, None, :] - spots[ends][None, :, :]
    dist = np.hypot(d[..., 0], d[..., 1])
    i, k = (int(ends[j]) for j in np.unravel_index(int(np.argmax(dist)), dist.shape))
    return names[min(i, k)], names[max(i, k)], float(np.hypot(*(spots[i] - spots[k])))


def _check_scale(m: Mechanism) -> float:
    """The length scale, refused outside the supported range (and when every pair is at one spot)."""
    a, b, scale = _farthest(m)
    if scale == 0:
        first = m.joints[0].where
        raise InputError("all pairs and points lie at one position; draw the mechanism as it is assembled, "
                         "with every pair at its place", m.path, first.line, "joints")
    low, high = LENGTH_SCALES
    if not low <= scale <= high:
        where = next(e.where for e in m.joints + m.points if e.name == b)
        size = f"{scale:.3g}".replace("e+", "e") + (f" {m.length_unit}" if m.length_unit else "")
        raise InputError(f"the sketch measures {size} (from {a} to {b}, the largest distance between two "
                         "pairs or points), but linkgen supports sketches from 1e-30 to 1e30 in the file's length "
                         f"unit; give the positions in a unit that makes their numbers "
                         f"{'larger' if scale < low else 'smaller'}", m.path, where.line, where.key)
    return scale


def sketch_origin(m: Mechanism, scale: float) -> tuple[float, float]:
    """The centre of the sketch's bounding box, rounded to a multiple of a sixteenth of the
    largest power of two not above the length scale (a short number).  The programs compute
    points relative to it, so their errors follow the mechanism's size wherever it is drawn;
    scaling the sketch by 2^k scales it exactly."""
    grid = math.ldexp(1.0, math.frexp(scale)[1] - 5)
    spots = [(j.x, j.y) for j in m.joints] + [(p.x, p.y) for p in m.points]
    x, y = ((min(c) + max(c)) / 2 for c in zip(*spots))
    return math.floor(x / grid + 0.5) * grid, math.floor(y / grid + 0.5) * grid


def analyse(m: Mechanism) -> Topology:
    """Build the topology and check that the inputs drive the mechanism exactly."""
    scale = _check_scale(m)
    count, mobility = check_mobility(m, scale)
    directions = tuple(link_direction(m, lk) for lk in m.links)
    members = tuple(mb for lk in m.links for mb in truss(m, lk))
    sketch = tuple(sketch_input(m, i) for i in m.inputs)
    return Topology(m, scale, sketch_origin(m, scale), count, mobility, mobility - count, members, directions, sketch)
