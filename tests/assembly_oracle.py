"""Independent routes to a mechanism's assemblies, for the tests of ``linkgen assemblies``.

Written from the format spec alone (only ``linkgen.validate.read_mechanism`` parses the file):

* ``tree_assemblies``: the assemblies of a mechanism of revolute pairs that two-link chains
  solve, in closed form at 50 digits (circles cut in two points or none; a link with two known
  pairs placed rigidly; one whose known pairs break its lengths ends the branch).
* ``triad_search``: every pose of a ternary held by three legs, by Newton's method at 50 digits
  from many starts (a multistart search: no polynomial, no elimination).
* ``worst_residual``: how far a configuration (the CSV's columns) breaks the mechanism's
  constraints, measured by the reference model of tests/reference.py.
"""

from __future__ import annotations

import math
import random

import mpmath
from reference import Reference

from linkgen.validate import read_mechanism

MP = mpmath.mp.clone()
MP.dps = 50
TRIAD_STARTS = 64  # starts of the multistart search: one in each 64th of a turn of the ternary
BODIES_STARTS = 400  # starts of the two-body search (measured: see tests/test_assemblies.py)


def _rot(c, s, x, y):
    return c * x - s * y, s * x + c * y


def _place(m, link, known, sketch):
    """Every pair and point of ``link`` from two of its known pairs (rigid), or None when its
    known pairs break its lengths (a constraint of this branch that cannot hold)."""
    lk = m.link(link)
    names = list(lk.joints) + [p.name for p in lk.points]
    have = [n for n in lk.joints if n in known]
    a = have[0]
    b = next(n for n in have[1:] if sketch[n] != sketch[a])
    ax, ay = known[a]
    dx, dy = known[b][0] - ax, known[b][1] - ay
    sx, sy = sketch[b][0] - sketch[a][0], sketch[b][1] - sketch[a][1]
    turn = MP.atan2(dy, dx) - MP.atan2(sy, sx)
    c, s = MP.cos(turn), MP.sin(turn)
    out = {}
    for n in names:
        ox, oy = _rot(c, s, sketch[n][0] - sketch[a][0], sketch[n][1] - sketch[a][1])
        out[n] = (ax + ox, ay + oy)
    tol = MP.mpf(10) ** -30 * max(1, abs(sx) + abs(sy))
    if any(abs(out[n][0] - known[n][0]) + abs(out[n][1] - known[n][1]) > tol for n in have):
        return None
    return out


def tree_assemblies(path: str, values_deg: list[float]) -> list[dict]:
    """Every assembly (pair and point -> position) of a revolute mechanism whose inputs are cranks
    on the frame, at input values in degrees, in closed form."""
    m = read_mechanism(path)
    ref = Reference(path)
    sketch = {k: (MP.mpf(x), MP.mpf(y)) for k, (x, y) in m.positions.items()}
    known = {n: sketch[n] for n in m.fixed.joints}
    for inp, value, at_sketch in zip(m.inputs, values_deg, ref.sketch_inputs(exact=True)):
        assert inp.kind == "revolute" and m.link(inp.relative_to).fixed
        turn = MP.radians(value) - at_sketch
        c, s = MP.cos(turn), MP.sin(turn)
        jx, jy = sketch[inp.joint]
        lk = m.link(inp.link)
        for n in list(lk.joints) + [p.name for p in lk.points]:
            ox, oy = _rot(c, s, sketch[n][0] - jx, sketch[n][1] - jy)
            known[n] = (jx + ox, jy + oy)
    done = {m.fixed.name} | {i.link for i in m.inputs}
    out: list[dict] = []
    _grow(m, sketch, known, done, out)
    return out


def _grow(m, sketch, known, done, out):
    while True:
        ready = [lk.name for lk in m.links if lk.name not in done
                 and len({sketch[n] for n in lk.joints if n in known}) >= 2]
        if not ready:
            break
        placed = _place(m, ready[0], known, sketch)
        if placed is None:
            return
        known = {**known, **placed}
        done = done | {ready[0]}
    unknown = [j.name for j in m.joints if j.name not in known]
    if not unknown:
        out.append(known)
        return
    for p in unknown:
        ends = [(lk.name, n) for lk in m.links_of(p) for n in lk.joints if n in known and n != p]
        if len({n for _, n in ends}) < 2:
            continue
        a = ends[0][1]
        b = next(n for _, n in ends if n != a)
        r1 = MP.hypot(sketch[p][0] - sketch[a][0], sketch[p][1] - sketch[a][1])
        r2 = MP.hypot(sketch[p][0] - sketch[b][0], sketch[p][1] - sketch[b][1])
        (ax, ay), (bx, by) = known[a], known[b]
        d = MP.hypot(bx - ax, by - ay)
        if not abs(r1 - r2) < d < r1 + r2:
            return  # this branch cannot close
        along = (d * d + r1 * r1 - r2 * r2) / (2 * d)
        h = MP.sqrt(r1 * r1 - along * along)
        ux, uy = (bx - ax) / d, (by - ay) / d
        for sign in (1, -1):
            spot = (ax + along * ux - sign * h * uy, ay + along * uy + sign * h * ux)
            _grow(m, sketch, {**known, p: spot}, done, out)
        return
    raise AssertionError("the oracle handles mechanisms that two-link chains solve only")


def triad_search(bases, local, lengths2, starts=TRIAD_STARTS, seed=20):
    """Every pose (x, y, theta) of a ternary (pair offsets ``local`` from its first pair) whose pair i
    lies at squared distance lengths2[i] from bases[i], by Newton's method from ``starts`` starts
    (50 digits; the 3x3 steps by Cramer's rule, each halved until the residual shrinks: a damped
    Newton, whose basins are wide enough for two roots 2.7 degrees apart); distinct poses, by theta."""
    rng = random.Random(seed)
    scale = max([MP.sqrt(v) for v in lengths2] + [MP.hypot(ax, ay) for ax, ay in local]
                + [MP.hypot(p[0] - q[0], p[1] - q[1]) for p in bases for q in bases])  # the triad's own size
    tol = MP.mpf(10) ** -42
    found: list[tuple] = []

    def system(x, y, t):
        c, s = MP.cos(t), MP.sin(t)
        f, jac = [], []
        for (ax, ay), (bx, by), l2 in zip(local, bases, lengths2):
            vx, vy = x + c * ax - s * ay - bx, y + s * ax + c * ay - by
            f.append((vx * vx + vy * vy - l2) / scale)
            jac.append((2 * vx / scale, 2 * vy / scale, 2 * (vx * (-s * ax - c * ay) + vy * (c * ax - s * ay)) / scale))
        return f, jac

    for k in range(starts):
        t = MP.mpf(-math.pi + 2 * math.pi * (k + rng.random()) / starts)  # one start in each slice of the turn
        phi = MP.mpf(rng.uniform(-math.pi, math.pi))  # the first pair somewhere on its leg's circle
        x = bases[0][0] + MP.sqrt(lengths2[0]) * MP.cos(phi)
        y = bases[0][1] + MP.sqrt(lengths2[0]) * MP.sin(phi)
        f, jac = system(x, y, t)
        for _ in range(40):
            det = _det(jac)
            if det == 0:
                break
            step = [_det([tuple(f[r] if k == col else jac[r][k] for k in range(3)) for r in range(3)]) / det
                    for col in range(3)]
            norm, lam = sum(v * v for v in f), 1.0
            while True:
                nx, ny, nt = x - lam * step[0], y - lam * step[1], t - lam * step[2]
                nf, njac = system(nx, ny, nt)
                if sum(v * v for v in nf) < norm or lam < 1e-3:
                    break
                lam /= 2
            if lam < 1e-3:
                break  # stuck at a local minimum of the residual: this start finds nothing
            x, y, t, f, jac = nx, ny, nt, nf, njac
            if lam == 1 and max(abs(step[0]) / scale, abs(step[1]) / scale, abs(step[2])) < tol:
                t = MP.atan2(MP.sin(t), MP.cos(t))
                if not any(abs(t - u[2]) < MP.mpf(10) ** -30 and abs(x - u[0]) < tol * scale for u in found):
                    found.append((x, y, t))
                break
    return sorted(found, key=lambda p: p[2])


def _det(a):
    return (a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
            + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]))


def worst_residual(ref: Reference, row: dict, values) -> float:
    """The largest constraint residual of a configuration (CSV columns) over its scale (L for a
    length, 1 for an angle), the link poses built from the row (tests/reference.py's guess)."""
    q = [MP.mpf(v) for v in ref.guess(row)]
    u = ref.turned_inputs(q, values)
    res = ref.constraints(q, u)
    return max(float(abs(r)) / s for r, s in zip(res, ref.constraint_scales()))


def bodies_search(bodies, legs, couplers, starts=BODIES_STARTS, seed=20, slides=()):
    """Every pose of two rigid bodies held by legs and tied by couplers, by Newton's method at 50
    digits from ``starts`` starts (a multistart search on the six distance equations in the bodies'
    poses: no resultant, no leg angles).  ``bodies``: two lists of pair offsets from each body's
    first pair; ``legs``: (body, pair index, base point, squared length); ``couplers``: (pair index
    on body 0, on body 1, squared length); ``slides``: (body, pair index, unit normal n, d) of blocks on
    fixed slides, n . P = d.  Returns the distinct poses (x0, y0, t0, x1, y1, t1)."""
    rng = random.Random(seed)
    rows = [(k, bodies[k][i], base, l2) for k, i, base, l2 in legs]
    scale = max(MP.sqrt(l2) for *_, l2 in rows)
    tol = MP.mpf(10) ** -40
    found: list[tuple] = []

    def system(z):
        f, jac = [], []
        rot = [(MP.cos(z[3 * k + 2]), MP.sin(z[3 * k + 2])) for k in (0, 1)]

        def point(k, a):
            c, s = rot[k]
            return (z[3 * k] + c * a[0] - s * a[1], z[3 * k + 1] + s * a[0] + c * a[1]), (-s * a[0] - c * a[1],
                                                                                         c * a[0] - s * a[1])

        for k, a, base, l2 in rows:
            (px, py), (dx, dy) = point(k, a)
            vx, vy = px - base[0], py - base[1]
            f.append((vx * vx + vy * vy - l2) / scale**2)
            row = [MP.mpf(0)] * 6
            row[3 * k], row[3 * k + 1], row[3 * k + 2] = 2 * vx, 2 * vy, 2 * (vx * dx + vy * dy)
            jac.append([v / scale**2 for v in row])
        for k, i, n, d in slides:
            (px, py), (dx, dy) = point(k, bodies[k][i])
            f.append((n[0] * px + n[1] * py - d) / scale)
            row = [MP.mpf(0)] * 6
            row[3 * k], row[3 * k + 1], row[3 * k + 2] = n[0], n[1], n[0] * dx + n[1] * dy
            jac.append([v / scale for v in row])
        for i, j, l2 in couplers:
            (px, py), (dx, dy) = point(0, bodies[0][i])
            (qx, qy), (ex, ey) = point(1, bodies[1][j])
            vx, vy = px - qx, py - qy
            f.append((vx * vx + vy * vy - l2) / scale**2)
            row = [2 * vx, 2 * vy, 2 * (vx * dx + vy * dy), -2 * vx, -2 * vy, -2 * (vx * ex + vy * ey)]
            jac.append([v / scale**2 for v in row])
        return f, jac

    first = {k: next(r for r in rows if r[0] == k and r[1] == bodies[k][0]) for k in (0, 1)}
    for _ in range(starts):
        z = []
        for k in (0, 1):
            _, _, base, l2 = first[k]
            phi = rng.uniform(-math.pi, math.pi)
            z += [base[0] + MP.sqrt(l2) * MP.cos(phi), base[1] + MP.sqrt(l2) * MP.sin(phi),
                  MP.mpf(rng.uniform(-math.pi, math.pi))]
        f, jac = system(z)
        for _ in range(60):
            try:
                step = MP.lu_solve(MP.matrix(jac), MP.matrix(f))
            except ZeroDivisionError:
                break
            norm, lam = sum(v * v for v in f), 1.0
            while True:
                nz = [z[i] - lam * step[i] for i in range(6)]
                nf, njac = system(nz)
                if sum(v * v for v in nf) < norm or lam < 1e-3:
                    break
                lam /= 2
            if lam < 1e-3:
                break
            z, f, jac = nz, nf, njac
            if lam == 1 and max(abs(step[i]) / (scale if i % 3 < 2 else 1) for i in range(6)) < tol:
                z[2], z[5] = MP.atan2(MP.sin(z[2]), MP.cos(z[2])), MP.atan2(MP.sin(z[5]), MP.cos(z[5]))
                if not any(max(abs(z[i] - u[i]) for i in range(6)) < MP.mpf(10) ** -25 * scale for u in found):
                    found.append(tuple(z))
                break
    return sorted(found, key=lambda p: p[2])
