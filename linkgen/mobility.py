"""Stage 3, mobility: Grübler's count and the rank of the constraint Jacobian at the sketch, which sees
redundant constraints (an exactly drawn parallelogram) and dead centres; the inputs must drive every
degree of freedom, each one a motion the others leave free.

The Jacobian is sparse (a pair's rows touch its links only).  Sparse elimination first: when every
constraint and then every input removes a clear freedom, the mobility is Grübler's count and the
inputs drive it (no redundancy, no dead centre), found in time linear in the size of a chain.
Anything else (a redundant or nearly redundant row, or as many inputs as the count does not give)
is decided by the dense singular values, as the format specifies, and explained."""

from __future__ import annotations

import heapq
import math

import numpy as np
import numpy.typing as npt

from .errors import InputError, and_list
from .model import Input, Mechanism

RANK_TOLERANCE = 1e-9  # relative, as the format specifies
CLEAR = 1e-6  # a pivot of the sparse elimination at least this large is a freedom removed beyond doubt
OFF_LINE = 1e-3  # how far (relative to the length scale) a pair in line is moved to see if it causes a rank drop
Array = npt.NDArray[np.float64]
Row = dict[int, float]  # a sparse row of the Jacobian: column -> entry


def check_mobility(m: Mechanism, scale: float) -> tuple[int, int]:
    """Grübler's count and the mobility at the sketch, once the inputs are found to drive it exactly."""
    jac = _Jacobian(m, scale)
    count = grubler(m)
    if len(m.inputs) == count and _clearly_driven(jac):
        return count, count
    c = jac.dense(jac.constraints())
    mobility = jac.n - _rank(c)
    if mobility > count:
        _check_dead_centre(m, scale, mobility)
    _check_input_count(m, mobility, count)
    _check_inputs_determine(m, jac, c)
    return count, mobility


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

    def point_rows(self, link: str, name: str) -> tuple[Row, Row]:
        """d(velocity of a point on link)/d(unknowns): two sparse rows."""
        if link not in self.col:
            return {}, {}
        c = self.col[link]
        ref = self.positions[self.m.link(link).joints[0]]
        x, y = self.positions[name]
        return {c: 1.0, c + 2: -(y - ref[1]) / self.scale}, {c + 1: 1.0, c + 2: (x - ref[0]) / self.scale}

    def turn_row(self, link: str) -> Row:
        return {self.col[link] + 2: 1.0} if link in self.col else {}

    def relative(self, a: str, b: str, name: str) -> tuple[Row, Row]:
        """The velocity of the point ``name`` on link a relative to link b."""
        (ax, ay), (bx, by) = self.point_rows(a, name), self.point_rows(b, name)
        return _combine((1.0, ax), (-1.0, bx)), _combine((1.0, ay), (-1.0, by))

    def constraints(self, order: list[str] | None = None) -> list[Row]:
        """The rows of every pair, in declaration order or the ``order`` given."""
        rows: list[Row] = []
        for j in order or [j.name for j in self.m.joints]:
            on = [lk.name for lk in self.m.links_of(j)]
            joint = self.m.joint(j)
            if joint.revolute:
                for other in on[1:]:
                    rows.extend(self.relative(on[0], other, j))
            else:
                p = self.m.prismatic_of(j)
                rx, ry = self.relative(p.slider, p.guide, j)
                rows.append(_combine((-math.sin(joint.axis), rx), (math.cos(joint.axis), ry)))
                rows.append(_combine((1.0, self.turn_row(p.slider)), (-1.0, self.turn_row(p.guide))))
        return rows

    def input_row(self, inp: Input) -> Row:
        if inp.kind == "revolute":
            return _combine((1.0, self.turn_row(inp.link)), (-1.0, self.turn_row(inp.relative_to)))
        if inp.kind == "prismatic":
            j = self.m.joint(inp.joint)
            rx, ry = self.relative(inp.link, inp.relative_to, j.name)
            return _combine((math.cos(j.axis), rx), (math.sin(j.axis), ry))
        a, b = inp.between
        (xa, ya), (xb, yb) = self.positions[a], self.positions[b]
        length = math.hypot(xb - xa, yb - ya)
        la, lb = self.m.links_of(a)[0].name, self.m.links_of(b)[0].name
        (ax, ay), (bx, by) = self.point_rows(la, a), self.point_rows(lb, b)
        return _combine(((xb - xa) / length, _combine((1.0, bx), (-1.0, ax))),
                        ((yb - ya) / length, _combine((1.0, by), (-1.0, ay))))

    def dense(self, rows: list[Row]) -> Array:
        out = np.zeros((len(rows), self.n))
        for i, row in enumerate(rows):
            for c, value in row.items():
                out[i, c] = value
        return out


def _combine(*terms: tuple[float, Row]) -> Row:
    """The sum of the rows, each times its factor."""
    out: Row = {}
    for factor, row in terms:
        for c, value in row.items():
            out[c] = out.get(c, 0.0) + factor * value
    return out


def _reached(m: Mechanism) -> list[str]:
    """The pairs in the order the links reach them from the frame (then any not reached),
    so that the rows of a chain of links come in the order of the chain."""
    order = list(dict.fromkeys(m.fixed.joints))
    seen, walked = set(order), {m.fixed.name}
    for j in order:  # grows while it is walked: breadth first
        for lk in m.links_of(j):
            if lk.name not in walked:
                walked.add(lk.name)
                order += [p for p in lk.joints if p not in seen]
                seen.update(lk.joints)
    return order + [j.name for j in m.joints if j.name not in seen]


def _clearly_driven(jac: _Jacobian) -> bool:
    """Sparse Gaussian elimination of the constraints, then the inputs, each row against the rows
    before it: True when every row keeps an entry of at least CLEAR (no redundant constraint, and
    every input drives a motion the constraints and the inputs before it leave free)."""
    pivots: dict[int, tuple[int, Row]] = {}  # pivot column -> (its rank, its row)
    for row in jac.constraints(_reached(jac.m)) + [jac.input_row(i) for i in jac.m.inputs]:
        r = dict(row)
        queue = [(pivots[c][0], c) for c in r if c in pivots]
        heapq.heapify(queue)
        queued = {c for _, c in queue}
        while queue:  # by rank: a pivot row is zero in the columns of the pivots before it
            _, c = heapq.heappop(queue)
            rank, p = pivots[c]
            f = r.pop(c) / p[c]
            for k, v in p.items():
                if k != c:
                    r[k] = r.get(k, 0.0) - f * v
                    if k in pivots and k not in queued:
                        queued.add(k)
                        heapq.heappush(queue, (pivots[k][0], k))
        c = max(r, key=lambda k: abs(r[k]), default=-1)
        if c < 0 or abs(r[c]) < CLEAR:
            return False
        pivots[c] = (len(pivots), r)
    return True


def _rank(a: Array) -> int:
    if a.size == 0:
        return 0
    s = np.linalg.svd(a, compute_uv=False)
    return int(np.sum(s > RANK_TOLERANCE * max(s[0], 1.0)))


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
        jac = _Jacobian(m, scale, moved)
        if _rank(jac.dense(jac.constraints())) > rank:
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
    rows = [jac.dense([jac.input_row(i)])[0] for i in m.inputs]
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
