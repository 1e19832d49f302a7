"""An independent reference solver for the accuracy tests, written from the format spec alone.

Only ``linkgen.validate.read_mechanism`` is used (to parse the file); none of linkgen's
procedure, primitives, topology or evaluator.

Unknowns are the poses ``(x, y, r)`` of the moving links: a point drawn at ``(X, Y)`` on
the link sits at ``(x, y) + R(r) (X, Y)``, so every link is at the identity pose in the
sketch and the fixed link stays there.  Constraints: every revolute pair (k-1 for a pair
on k links), every prismatic pair (the slider's copy of ``at`` on the guide's line, no
relative rotation), and one driving constraint per input, with the input value exactly
as the spec defines it.

Positions: Newton's method on the 50-digit residuals (see :meth:`Reference.newton`),
started from a pose built from linkgen's float row, so the same assembly is selected.
Derivatives use truncated Taylor arithmetic in time (:class:`Jet`): evaluating the
constraints on ``q + q' t + q'' t^2 / 2`` gives the Jacobian, ``C_t`` and the
velocity-product term of ``d^2 C / dt^2`` exactly, in the same 50-digit arithmetic as
the positions.  Velocities and accelerations then come from the differentiated
constraints ``C_q q' = -C_t`` and ``C_q q'' = -gamma``.  This was chosen over
``mpmath.diff`` because it has no step size, no truncation error and needs one
position solve per row instead of several (the two agree to 1e-49 on the four-bar).

The number type is whatever the caller passes: mpmath numbers of :data:`MP` for the
50-digit reference, plain floats for the quick continuation check.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mpmath
import numpy as np

from linkgen.validate import read_mechanism

MP = mpmath.MPContext()
MP.dps = 50


class Jet:
    """A truncated Taylor series ``c0 + c1 t + c2 t^2`` (so d/dt = c1, d2/dt2 = 2 c2)."""

    __slots__ = ("c",)

    def __init__(self, c0, c1=0, c2=0):
        self.c = (c0, c1, c2)

    def __add__(self, o):
        a, b = self.c, _coef(o)
        return Jet(a[0] + b[0], a[1] + b[1], a[2] + b[2])

    __radd__ = __add__

    def __neg__(self):
        a = self.c
        return Jet(-a[0], -a[1], -a[2])

    def __sub__(self, o):
        return self + (-o)

    def __rsub__(self, o):
        return (-self) + o

    def __mul__(self, o):
        a = self.c
        if not isinstance(o, Jet):
            return Jet(a[0] * o, a[1] * o, a[2] * o)
        b = o.c
        return Jet(a[0] * b[0], a[0] * b[1] + a[1] * b[0], a[0] * b[2] + a[1] * b[1] + a[2] * b[0])

    __rmul__ = __mul__


def _coef(x) -> tuple:
    return x.c if isinstance(x, Jet) else (x, 0, 0)


def _plain(x) -> bool:
    return isinstance(x, (int, float))


def _is_mp(x) -> bool:
    """True when a number or a Jet's value is an mpmath number."""
    return _is_mp(x.c[0]) if isinstance(x, Jet) else not _plain(x)


def sin(x):
    """sin of a number or a Jet."""
    if isinstance(x, Jet):
        a, b, c = x.c
        s, k = sin(a), cos(a)
        return Jet(s, k * b, k * c - s * b * b / 2)
    return math.sin(x) if _plain(x) else MP.sin(x)


def cos(x):
    """cos of a number or a Jet."""
    if isinstance(x, Jet):
        a, b, c = x.c
        s, k = sin(a), cos(a)
        return Jet(k, -s * b, -s * c - k * b * b / 2)
    return math.cos(x) if _plain(x) else MP.cos(x)


def derivatives(x) -> tuple:
    """(value, first, second time derivative) of a Jet or a constant."""
    a, b, c = _coef(x)
    return a, b, 2 * c


def wrap(x):
    """An angle wrapped to (-pi, pi]."""
    if _plain(x):
        return x - 2 * math.pi * math.ceil((x - math.pi) / (2 * math.pi))
    return x - 2 * MP.pi * MP.ceil((x - MP.pi) / (2 * MP.pi))


def nearest_turn(x, start: float, stop: float):
    """The angle x plus the whole turns that bring it nearest the range [start, stop]: inside it
    where possible, the turn nearest start among equals."""
    two_pi = 2 * math.pi if _plain(x) else 2 * MP.pi
    lo, hi = min(start, stop), max(start, stop)
    first = math.floor(float((lo - x) / two_pi)) - 1
    turns = [x + k * two_pi for k in range(first, first + 4 + math.ceil((hi - lo) / float(two_pi)))]
    return min(turns, key=lambda t: (max(lo - t, t - hi, 0), abs(t - start)))


def _atan2(y, x, exact: bool):
    return MP.atan2(MP.mpf(y), MP.mpf(x)) if exact else math.atan2(y, x)


@dataclass
class Solution:
    """One row: every CSV output column (inputs excluded) and the conditioning of the solve."""

    columns: dict  # name -> number
    q: list
    cond: float  # smallest / largest singular value of the scaled Jacobian
    iterations: int


class Reference:
    """The constraint model of one mechanism file."""

    def __init__(self, path: str):
        m = read_mechanism(path)
        self.m = m
        self.joints = {j.name: j for j in m.joints}
        self.links = {lk.name: lk for lk in m.links}
        self.on = {j.name: [lk.name for lk in m.links if j.name in lk.joints] for j in m.joints}
        self.moving = [lk.name for lk in m.links if not lk.fixed]
        self.slot = {name: 3 * i for i, name in enumerate(self.moving)}
        self.n = 3 * len(self.moving)
        self.guide, self.slider = {}, {}
        for j in m.joints:
            if j.kind == "prismatic":
                self.guide[j.name] = self.guide_of(j.name)
                self.slider[j.name] = next(lk for lk in self.on[j.name] if lk != self.guide[j.name])
        spots = [(j.x, j.y) for j in m.joints] + [(p.x, p.y) for p in m.points]
        self.directions = {e: {lk.name: self.direction(lk.name, e) for lk in m.links} for e in (False, True)}
        self.offsets = {e: [self.input_offset(i, e) if inp.kind == "revolute" else 0
                            for i, inp in enumerate(m.inputs)] for e in (False, True)}
        self.length_scale = max(math.hypot(a[0] - b[0], a[1] - b[1]) for a in spots for b in spots)

    # -- the spec's definitions -------------------------------------------------
    def guide_of(self, joint: str) -> str:
        """The fixed link if it carries the pair, else the input's reference link, else the first listed."""
        on = self.on[joint]
        fixed = [lk for lk in on if self.links[lk].fixed]
        if fixed:
            return fixed[0]
        given = [i for i in self.m.inputs if i.kind == "prismatic" and i.joint == joint and i.relative_to]
        return given[0].relative_to if given else on[0]

    def _axis_of(self, link: str, exact: bool):
        pj = next(j for j in self.links[link].joints if self.joints[j].kind == "prismatic")
        return MP.mpf(self.joints[pj].axis) if exact else self.joints[pj].axis

    def _aim(self, link: str, origin: tuple, targets: list, exact: bool):
        for t in targets:
            if t != origin:
                return _atan2(t[1] - origin[1], t[0] - origin[0], exact)
        return self._axis_of(link, exact)

    def direction(self, link: str, exact: bool = True):
        """Sketch angle of the link: first pair to the next pair (then points) not at the same spot."""
        lk = self.links[link]
        spots = [(self.joints[j].x, self.joints[j].y) for j in lk.joints] + [(p.x, p.y) for p in lk.points]
        return self._aim(link, spots[0], spots[1:], exact)

    def input_direction(self, link: str, joint: str, exact: bool = True):
        """Sketch angle of a link for an input at ``joint``: to the next pair after it, cyclically, then points."""
        lk = self.links[link]
        js = list(lk.joints)
        k = js.index(joint)
        order = js[k + 1:] + js[:k]
        targets = [(self.joints[j].x, self.joints[j].y) for j in order] + [(p.x, p.y) for p in lk.points]
        return self._aim(link, (self.joints[joint].x, self.joints[joint].y), targets, exact)

    def input_offset(self, i: int, exact: bool = True):
        """theta - (r_L - r_F) for a revolute input: the input value at the sketch."""
        inp = self.m.inputs[i]
        off = self.input_direction(inp.link, inp.joint, exact)
        if not self.links[inp.relative_to].fixed:
            off = off - self.input_direction(inp.relative_to, inp.joint, exact)
        return off

    def sketch_inputs(self, exact: bool = False) -> list:
        """Input values at which the mechanism is assembled as drawn: an angle as the spec's
        representative nearest its range (a row a whole turn away is another pose where the
        mechanism passes a change point)."""
        out = []
        for i, inp in enumerate(self.m.inputs):
            if inp.kind == "revolute":
                out.append(nearest_turn(wrap(self.input_offset(i, exact)), inp.start, inp.stop))
            elif inp.kind == "prismatic":
                out.append(MP.mpf(0) if exact else 0.0)
            else:
                a, b = (self.joints[j] for j in inp.between)
                out.append(MP.hypot(a.x - b.x, a.y - b.y) if exact else math.hypot(a.x - b.x, a.y - b.y))
        return out

    def column_names(self) -> list[str]:
        """The spec's default CSV header (status excluded) at order 2."""
        names = []
        for inp in self.m.inputs:
            if inp.kind == "revolute":
                names.append(f"theta_{inp.joint}")
            elif inp.kind == "prismatic":
                names.append(f"s_{inp.joint}")
            else:
                names.append(f"d_{inp.between[0]}_{inp.between[1]}")
        for name in [j.name for j in self.m.joints] + [p.name for p in self.m.points]:
            names += [f"{name}.{c}" for c in ("x", "y", "vx", "vy", "ax", "ay")]
        for lk in self.m.links:
            names += [f"{lk.name}.{c}" for c in ("phi", "omega", "alpha")]
        for j in self.m.joints:
            if j.kind == "prismatic":
                names += [f"{j.name}.{c}" for c in ("s", "ds", "dds")]
        return names

    # -- kinematics of the poses ------------------------------------------------
    def rot(self, q, link: str):
        return 0 if self.links[link].fixed else q[self.slot[link] + 2]

    def place(self, q, link: str, x: float, y: float) -> tuple:
        """Where the point drawn at (x, y) on ``link`` is."""
        if self.links[link].fixed:
            return x, y
        i = self.slot[link]
        c, s = cos(q[i + 2]), sin(q[i + 2])
        return q[i] + c * x - s * y, q[i + 1] + s * x + c * y

    def axis(self, q, joint: str) -> tuple:
        """Unit direction of a prismatic pair's line (it turns with the guide)."""
        j = self.joints[joint]
        a = self.rot(q, self.guide[joint]) + (MP.mpf(j.axis) if _is_mp(q[0]) else j.axis)
        return cos(a), sin(a)

    def slide(self, q, joint: str) -> tuple:
        """The slider's copy of ``at`` and its offset from the guide's copy."""
        j = self.joints[joint]
        ps = self.place(q, self.slider[joint], j.x, j.y)
        pg = self.place(q, self.guide[joint], j.x, j.y)
        return ps, (ps[0] - pg[0], ps[1] - pg[1])

    def constraint_scales(self) -> list[float]:
        """What each entry of ``constraints`` is measured against: L for a length, 1 for an angle."""
        out: list[float] = []
        for j in self.m.joints:
            if j.kind == "revolute":
                out += [self.length_scale] * (2 * (len(self.on[j.name]) - 1))
            else:
                out += [self.length_scale, 1.0]
        return out + [1.0 if inp.kind == "revolute" else self.length_scale for inp in self.m.inputs]

    def constraints(self, q, u) -> list:
        """Residuals of every pair and of the driving constraints at input values ``u``."""
        out = []
        for j in self.m.joints:
            on = self.on[j.name]
            if j.kind == "revolute":
                a = self.place(q, on[0], j.x, j.y)
                for other in on[1:]:
                    b = self.place(q, other, j.x, j.y)
                    out += [a[0] - b[0], a[1] - b[1]]
            else:
                e = self.axis(q, j.name)
                _, d = self.slide(q, j.name)
                out.append(e[0] * d[1] - e[1] * d[0])
                out.append(self.rot(q, self.slider[j.name]) - self.rot(q, self.guide[j.name]))
        for i, (inp, v) in enumerate(zip(self.m.inputs, u)):
            if inp.kind == "revolute":
                off = self.offsets[_is_mp(q[0])][i]
                out.append(self.rot(q, inp.link) - self.rot(q, inp.relative_to) + off - v)
            elif inp.kind == "prismatic":
                e = self.axis(q, inp.joint)
                _, d = self.slide(q, inp.joint)
                out.append(e[0] * d[0] + e[1] * d[1] - v)
            else:
                a, b = (self.joints[n] for n in inp.between)
                pa = self.place(q, self.on[a.name][0], a.x, a.y)
                pb = self.place(q, self.on[b.name][0], b.x, b.y)
                dx, dy = pa[0] - pb[0], pa[1] - pb[1]
                out.append((dx * dx + dy * dy - v * v) * (1 / (2 * math.hypot(a.x - b.x, a.y - b.y))))
        return out

    def outputs(self, q) -> dict:
        """Every output of the spec's default set, as numbers or Jets, keyed by column stem."""
        exact = _is_mp(q[0])
        col = {}
        for j in self.m.joints:
            if j.kind == "revolute":
                p = self.place(q, self.on[j.name][0], j.x, j.y)
            else:
                p, _ = self.slide(q, j.name)
            col[f"{j.name}.x"], col[f"{j.name}.y"] = p
        for pt in self.m.points:
            col[f"{pt.name}.x"], col[f"{pt.name}.y"] = self.place(q, pt.link, pt.x, pt.y)
        for lk in self.m.links:
            col[f"{lk.name}.phi"] = self.directions[exact][lk.name] + self.rot(q, lk.name)
        for j in self.m.joints:
            if j.kind == "prismatic":
                e = self.axis(q, j.name)
                _, d = self.slide(q, j.name)
                col[f"{j.name}.s"] = e[0] * d[0] + e[1] * d[1]
        return col

    # -- solving -----------------------------------------------------------------
    def jacobian(self, q, u) -> list:
        """Rows of dC/dq, column by column through first-order Jets."""
        cols = []
        for k in range(self.n):
            qk = list(q)
            qk[k] = Jet(q[k], 1)
            cols.append([_coef(c)[1] for c in self.constraints(qk, u)])
        return [list(r) for r in zip(*cols)]

    def _lstsq(self, a: list, b: list, exact: bool) -> list:
        if not exact:
            # equilibrated as in cond: rotations in length units, rows of unit length (else a sketch
            # drawn far out leaves singular values 1e19 apart, and lstsq drops the input's row)
            cols = np.ones(self.n)
            cols[2::3] = self.length_scale
            m = np.array(a, dtype=float) / cols
            rows = np.linalg.norm(m, axis=1)
            rows[rows == 0] = 1.0
            y = np.linalg.lstsq(m / rows[:, None], np.array(b, dtype=float) / rows, rcond=None)[0]
            return list(y / cols)
        am, bm = MP.matrix(a), MP.matrix(b)
        x = MP.lu_solve(am, bm) if len(a) == self.n else MP.qr_solve(am, bm)[0]
        return [x[i] for i in range(self.n)]

    def cond(self, jac: list) -> float:
        """Smallest over largest singular value of the Jacobian, made scale-free: rotation columns
        scaled by the length scale and every row to unit length, so the number is the same for a
        sketch and for the sketch scaled (a row that drives an angle would otherwise move with it)."""
        a = np.array([[float(x) for x in row] for row in jac])
        a[:, 2::3] /= self.length_scale
        norms = np.linalg.norm(a, axis=1)
        a = a[norms > 0] / norms[norms > 0, None]
        s = np.linalg.svd(a, compute_uv=False)
        return float(s[-1] / s[0]) if s[0] > 0 else 0.0

    def newton(self, q0: list, u: list, exact: bool = True, max_iter: int = 20) -> tuple[list, list, int]:
        """Newton from ``q0`` (least squares where constraints are redundant): q, Jacobian at q, iterations.

        Residuals are in the working precision, the corrections use the Jacobian in float:
        each step still gains about 13 digits (the float Jacobian is off by 1e-16 times its
        condition number), so 50 digits take 4 steps from a float start.  The returned
        Jacobian, used for the rates, is at full precision.
        """
        q = [MP.mpf(x) for x in q0] if exact else [float(x) for x in q0]
        tol = MP.mpf(10) ** (-MP.dps + 5) if exact else 1e-14
        scale = [self.length_scale, self.length_scale, 1] * len(self.moving)
        uf = [float(v) for v in u]
        for it in range(1, max_iter + 1):
            res = [float(r) for r in self.constraints(q, u)]
            dq = self._lstsq(self.jacobian([float(x) for x in q], uf), res, False)
            if not all(math.isfinite(d) for d in dq):
                break
            q = [a - b for a, b in zip(q, dq)]
            small = max(abs(d) / s for d, s in zip(dq, scale)) < tol
            if small and max(abs(r) for r in self.constraints(q, u)) < tol * self.length_scale * 1e3:
                return q, self.jacobian(q, u), it
        raise ArithmeticError(f"reference Newton did not converge from {[float(x) for x in q0]}")

    def turned_inputs(self, q, values) -> list:
        """Input values with revolute ones shifted by whole turns to match the poses ``q``."""
        u = []
        exact = _is_mp(q[0])
        for i, (inp, v) in enumerate(zip(self.m.inputs, values)):
            v = MP.mpf(v) if exact else float(v)
            if inp.kind == "revolute":
                now = self.rot(q, inp.link) - self.rot(q, inp.relative_to) + self.offsets[exact][i]
                two_pi = 2 * MP.pi if exact else 2 * math.pi
                v = v + two_pi * round(float((now - v) / two_pi))
            u.append(v)
        return u

    def solve(self, values, rates, q0: list) -> Solution:
        """Positions, velocities and accelerations at 50 digits; ``q0`` picks the assembly."""
        u = self.turned_inputs([MP.mpf(x) for x in q0], values)
        q, jac, its = self.newton(q0, u)
        rates = [MP.mpf(r) for r in rates]
        ut = [Jet(v, r) for v, r in zip(u, rates)]
        ct = [_coef(c)[1] for c in self.constraints(q, ut)]
        qd = self._lstsq(jac, [-c for c in ct], True)
        gamma = [2 * _coef(c)[2] for c in self.constraints([Jet(a, b) for a, b in zip(q, qd)], ut)]
        qdd = self._lstsq(jac, [-g for g in gamma], True)
        jets = [Jet(a, b, c / 2) for a, b, c in zip(q, qd, qdd)]
        cols = {}
        for stem, x in self.outputs(jets).items():
            v, d, dd = derivatives(x)
            name, kind = stem.rsplit(".", 1)
            first, second = {"x": ("vx", "ax"), "y": ("vy", "ay"), "phi": ("omega", "alpha"),
                             "s": ("ds", "dds")}[kind]
            cols[stem] = wrap(v) if kind == "phi" else v
            cols[f"{name}.{first}"], cols[f"{name}.{second}"] = d, dd
        return Solution(cols, q, self.cond(jac), its)

    # -- starting points -----------------------------------------------------------
    def anchors(self, link: str, row: dict, with_guides: bool = True) -> list[tuple]:
        """(sketch x, sketch y, x, y) of the known spots of ``link`` in a CSV row.

        Revolute pairs and points on the link, and prismatic pairs it slides on (their column
        is the slider's copy).  With ``with_guides``, also the guide's copy of ``at``
        (the slider's copy minus s along the turned axis).
        """
        out = []
        lk = self.links[link]
        for name in lk.joints:
            j = self.joints[name]
            if j.kind == "revolute" or self.slider[name] == link:
                out.append((j.x, j.y, row[f"{name}.x"], row[f"{name}.y"]))
            elif with_guides:
                a = j.axis + row[f"{link}.phi"] - self.direction(link, False)
                s = row[f"{name}.s"]
                out.append((j.x, j.y, row[f"{name}.x"] - s * math.cos(a), row[f"{name}.y"] - s * math.sin(a)))
        out += [(p.x, p.y, row[f"{p.name}.x"], row[f"{p.name}.y"]) for p in lk.points]
        return out

    def guess(self, row: dict) -> list[float]:
        """Poses from a float CSV row (default columns): angle from phi, offset from one known spot."""
        q = []
        for link in self.moving:
            r = row[f"{link}.phi"] - self.direction(link, False)
            sx, sy, x, y = self.anchors(link, row)[0]
            c, s = math.cos(r), math.sin(r)
            q += [x - (c * sx - s * sy), y - (s * sx + c * sy), r]
        return q

    def sketch_pose(self) -> list[float]:
        return [0.0] * self.n


def walked(ref: Reference, q: list, u: float, target: float, step: float = math.radians(1)) -> list:
    """The pose q at the (one) input u carried to target by float Newton in equal steps of at most step."""
    steps = max(1, math.ceil(abs(target - u) / step))
    for j in range(1, steps + 1):
        q = ref.newton(q, ref.turned_inputs(q, [u + (target - u) * j / steps]), exact=False)[0]
    return q
