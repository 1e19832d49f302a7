"""Stage 3, mobility: Grübler's count and the rank of the constraint Jacobian at the sketch, which sees
redundant constraints (an exactly drawn parallelogram) and dead centres; the inputs must drive every
degree of freedom, each one a motion the others leave free."""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from .errors import InputError, and_list
from .model import Input, Mechanism

RANK_TOLERANCE = 1e-9  # relative, as the format specifies
OFF_LINE = 1e-3  # how far (relative to the length scale) a pair in line is moved to see if it causes a rank drop
Array = npt.NDArray[np.float64]


def check_mobility(m: Mechanism, scale: float) -> tuple[int, int]:
    """Grübler's count and the mobility at the sketch, once the inputs are found to drive it exactly."""
    jac = _Jacobian(m, scale)
    c = jac.constraints()
    mobility = jac.n - _rank(c)
    count = grubler(m)
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
