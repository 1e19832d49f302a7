"""Stage 3: the mechanism's structure and sketch geometry.

Multi-pair links become trusses of binary members (the paper's rule i), compound
hinges are one pair on several links (rule iii), each link gets the direction
that defines its angle, each input its sketch value, and the mobility is found
both by Grübler's count and by the rank of the constraint Jacobian at the sketch
(which sees redundant constraints such as an exactly drawn parallelogram).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from . import exact
from .errors import InputError, and_list
from .model import Input, Link, Mechanism
from .policy import LENGTH_SCALES

RANK_TOLERANCE = 1e-9  # relative, as the format specifies
OFF_LINE = 1e-3  # how far (relative to the length scale) a pair in line is moved to see if it causes a rank drop
Array = npt.NDArray[np.float64]


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
    if name in m.positions:
        return m.positions[name]
    raise KeyError(name)


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


class _Jacobian:
    """Velocity constraints at the sketch (or at the positions given), columns (vx, vy, omega * L)
    per moving link."""

    def __init__(self, m: Mechanism, scale: float, positions: dict[str, tuple[float, float]] | None = None):
        self.m = m
        self.scale = scale
        self.positions = positions or m.positions
        self.moving = [lk for lk in m.links if not lk.fixed]
        self.col = {lk.name: 3 * i for i, lk in enumerate(self.moving)}
        self.n = 3 * len(self.moving)

    def point_rows(self, link: str, name: str) -> Array:
        """d(velocity of a point on link)/d(unknowns): a 2 x n block."""
        block = np.zeros((2, self.n))
        if link not in self.col:
            return block
        c = self.col[link]
        ref = self.positions[self.m.link(link).joints[0]]
        x, y = self.positions[name]
        block[0, c], block[1, c + 1] = 1.0, 1.0
        block[0, c + 2] = -(y - ref[1]) / self.scale
        block[1, c + 2] = (x - ref[0]) / self.scale
        return block

    def turn_row(self, link: str) -> Array:
        row = np.zeros(self.n)
        if link in self.col:
            row[self.col[link] + 2] = 1.0
        return row

    def constraints(self) -> Array:
        rows: list[Array] = []
        for j in self.m.joints:
            on = [lk.name for lk in self.m.links_of(j.name)]
            if j.revolute:
                for other in on[1:]:
                    rows.extend(self.point_rows(on[0], j.name) - self.point_rows(other, j.name))
            else:
                p = self.m.prismatic_of(j.name)
                normal = np.array([-math.sin(j.axis), math.cos(j.axis)])
                rel = self.point_rows(p.slider, j.name) - self.point_rows(p.guide, j.name)
                rows.append(normal @ rel)
                rows.append(self.turn_row(p.slider) - self.turn_row(p.guide))
        return np.array(rows).reshape(-1, self.n)

    def input_row(self, inp: Input) -> Array:
        if inp.kind == "revolute":
            return self.turn_row(inp.link) - self.turn_row(inp.relative_to)
        if inp.kind == "prismatic":
            j = self.m.joint(inp.joint)
            axis = np.array([math.cos(j.axis), math.sin(j.axis)])
            return axis @ (self.point_rows(inp.link, j.name) - self.point_rows(inp.relative_to, j.name))
        a, b = inp.between
        (xa, ya), (xb, yb) = self.positions[a], self.positions[b]
        u = np.array([xb - xa, yb - ya]) / math.hypot(xb - xa, yb - ya)
        la, lb = self.m.links_of(a)[0].name, self.m.links_of(b)[0].name
        return u @ (self.point_rows(lb, b) - self.point_rows(la, a))


def _rank(a: Array) -> int:
    if a.size == 0:
        return 0
    s = np.linalg.svd(a, compute_uv=False)
    return int(np.sum(s > RANK_TOLERANCE * max(s[0], 1.0)))


def _farthest(m: Mechanism) -> tuple[str, str, float]:
    """The two pairs or points of the sketch farthest apart, and their distance."""
    names = list(m.positions)
    spots = np.array([m.positions[n] for n in names])
    d = spots[:, None, :] - spots[None, :, :]
    dist = np.hypot(d[..., 0], d[..., 1])
    i, k = np.unravel_index(int(np.argmax(dist)), dist.shape)
    return names[min(i, k)], names[max(i, k)], float(dist[i, k])


def length_scale(m: Mechanism) -> float:
    """The largest distance between two pairs or points of the sketch."""
    return _farthest(m)[2]


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


def grubler(m: Mechanism) -> int:
    pairs = sum(len(m.links_of(j.name)) - 1 if j.revolute else 1 for j in m.joints)
    return 3 * (len(m.links) - 1) - 2 * pairs


def _describe_input(inp: Input) -> str:
    if inp.kind == "distance":
        return f"the actuator between {inp.between[0]} and {inp.between[1]}"
    return f"the input on {inp.joint}"


def _degrees(n: int) -> str:
    return f"{n} degree{'' if n == 1 else 's'} of freedom"


def _check_input_count(m: Mechanism, mobility: int, count: int) -> None:
    given = len(m.inputs)
    if given == mobility:
        return
    why = f"Grübler's count gives {count}"
    if mobility != count:
        redundant = mobility - count
        why += (f"; {redundant} constraint{' is' if redundant == 1 else 's are'} redundant in the sketch, where links "
                "are drawn exactly parallel, as in a parallelogram, or in line, as at a dead centre")
    if mobility == 0:
        raise InputError(f"the mechanism cannot move: its links form a rigid structure ({why}), so it takes no input",
                         m.path, m.inputs[0].where.line, m.inputs[0].where.key)
    if given > mobility:
        extra = m.inputs[mobility].where
        raise InputError(f"the mechanism has {_degrees(mobility)} ({why}), but {given} inputs are given; "
                         "give one input per degree of freedom", m.path, extra.line, extra.key)
    raise InputError(f"the mechanism has {_degrees(mobility)} ({why}), but only {given} "
                     f"input{' is' if given == 1 else 's are'} given; give one input per degree of freedom, "
                     "or the rest of the mechanism is left free", m.path, m.inputs_where.line, "inputs")


def _in_line(m: Mechanism) -> list[tuple[str, str, str, str, str]]:
    """Two-link chains drawn in line: (p, q, r, link1, link2) where the revolute pair q joins
    link1, which carries the pair p, to link2, which carries r, and p, q, r lie on one line."""
    out = []
    pos = m.positions
    for q in m.joints:
        if not q.revolute:
            continue
        on = m.links_of(q.name)
        for i, l1 in enumerate(on):
            for l2 in on[i + 1:]:
                for p in l1.joints:
                    for r in l2.joints:
                        if q.name in (p, r) or p == r:
                            continue
                        (px, py), (qx, qy), (rx, ry) = pos[p], pos[q.name], pos[r]
                        a, b = math.hypot(px - qx, py - qy), math.hypot(rx - qx, ry - qy)
                        cross = (px - qx) * (ry - qy) - (py - qy) * (rx - qx)
                        if a > 0 and b > 0 and abs(cross) <= RANK_TOLERANCE * a * b:
                            out.append((p, q.name, r, l1.name, l2.name))
    return out


def _check_dead_centre(m: Mechanism, scale: float, mobility: int) -> None:
    """The constraints lose rank at the sketch (more degrees of freedom than Grübler's count): when
    moving the middle pair of a chain drawn in line off that line restores the rank, the sketch
    is at a dead centre, not a mechanism with a redundant constraint (a parallelogram)."""
    rank = _Jacobian(m, scale).n - mobility
    found = []
    for p, q, r, l1, l2 in _in_line(m):
        (px, py), (qx, qy), (rx, ry) = m.positions[p], m.positions[q], m.positions[r]
        dx, dy = (rx - px, ry - py) if (rx, ry) != (px, py) else (qx - px, qy - py)
        step = OFF_LINE * scale / math.hypot(dx, dy)
        moved = {**m.positions, q: (qx - dy * step, qy + dx * step)}
        if _rank(_Jacobian(m, scale, moved).constraints()) > rank:
            found.append((p, q, r, l1, l2))
    moving = [f for f in found if not (m.link(f[3]).fixed or m.link(f[4]).fixed)]
    found = moving or found
    if not found:
        return
    p, q, r, l1, l2 = found[0]
    chains = and_list(f"{a}, {b} and {c} (links {x} and {y})" for a, b, c, x, y in found)
    where = m.joint(q).where
    raise InputError(f"the sketch is drawn at a dead centre: the pairs {chains} are in line, "
                     f"so the links can move there in more ways than the mechanism can (the sketch has "
                     f"{_degrees(mobility)}, Grübler's count gives {grubler(m)}); redraw the sketch with {l1} and {l2} "
                     f"off the dead centre ({q} off the line through {p} and {r})", m.path, where.line, where.key)


def _free_links(jac: _Jacobian, full: Array) -> list[str]:
    """The moving links that still move when every input is held: the null space of the full Jacobian."""
    _, s, vt = np.linalg.svd(full)
    rank = int(np.sum(s > RANK_TOLERANCE * max(s[0], 1.0)))
    free = np.abs(vt[rank:]).max(axis=0)
    return [lk.name for lk in jac.moving if free[jac.col[lk.name]:jac.col[lk.name] + 3].max() > RANK_TOLERANCE]


def _cannot_move(inp: Input) -> str:
    if inp.kind == "revolute":
        return (f"the input on {inp.joint} cannot move in the sketch ({inp.link} and {inp.relative_to} are locked "
                "together there, or the sketch is at a dead centre for this input)")
    return (f"{_describe_input(inp)} cannot move in the sketch (its links are locked together there, "
            "or the sketch is at a dead centre for this input)")


def _check_inputs_determine(m: Mechanism, jac: _Jacobian, c: Array) -> None:
    """Each input must fix a motion that the constraints and the inputs before it leave free."""
    rows = [jac.input_row(i) for i in m.inputs]
    for k, inp in enumerate(m.inputs):
        before = np.vstack([c, *rows[:k]]) if k else c
        if _rank(np.vstack([before, rows[k]])) > _rank(before):
            continue
        if k == 0:
            cause = _cannot_move(inp)
        else:
            earlier = and_list(_describe_input(i) for i in m.inputs[:k])
            cause = f"{_describe_input(inp)} drives the same motion as {earlier}"
        free = _free_links(jac, np.vstack([c, *rows]))
        left = f"link {free[0]} is" if len(free) == 1 else f"links {and_list(free)} are"
        raise InputError(f"the inputs do not determine the sketch configuration: {cause}, so {left} left free; "
                         "drive independent motions", m.path, inp.where.line, inp.where.key)


def analyse(m: Mechanism) -> Topology:
    """Build the topology and check that the inputs drive the mechanism exactly."""
    scale = _check_scale(m)
    jac = _Jacobian(m, scale)
    c = jac.constraints()
    mobility = jac.n - _rank(c)
    count = grubler(m)
    if mobility > count:
        _check_dead_centre(m, scale, mobility)
    _check_input_count(m, mobility, count)
    _check_inputs_determine(m, jac, c)
    directions = tuple(link_direction(m, lk) for lk in m.links)
    members = tuple(mb for lk in m.links for mb in truss(m, lk))
    sketch = tuple(sketch_input(m, i) for i in m.inputs)
    return Topology(m, scale, sketch_origin(m, scale), count, mobility, mobility - count, members, directions, sketch)
