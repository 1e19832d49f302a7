"""Two links on their own pivots tied by two links or slots (``pivots``): the closure as one
polynomial by a resultant, its real roots certified, every root back-substituted and polished.

Body k turns by theta_k from the sketch about its pivot P_k (known), so its pair of sketch offset a
from the pivot sits at P_k + R(theta_k) a.  A tie from the pair a of body j to the point b of body k
(k the other body) has v = P_j + R(theta_j) a - P_k - R(theta_k) b and says

    |v|^2 = l^2                       (a link),
    R(theta_k) n . v = 0              (a slot of body k, n its sketch normal),

each of trigonometric degree 1 in each angle (|R a|^2 = |a|^2, R(theta_k) n . R(theta_k) b = n . b).
With t_k = tan(theta_k / 2), cos = (1 - t^2) / q, sin = 2 t / q, q = 1 + t^2, each times q_0 q_1 is a
polynomial of degree 2 in each t_k with exact integer coefficients (the data on the grid of
``triad.grid``, divided by it; n scaled to integers).  Their resultant in t_1 is P(t_0), of degree
at most 8 (the Bezout number of two curves of bidegree (2, 2)), its factors (1 + t_0^2) divided out.
Every assembly's theta_0 is a real root of P; theta_0 = pi (t_0 infinite) is checked on its own,
from the two equations' coefficients of t_0^2.  Real roots are isolated by arb
on its factors over the integers and counted again by Sturm's theorem, as a triad's
(``realroots``).  Each root is back-substituted (every real root in t_1 of either equation, and
half a turn), polished by Newton's method on the two equations at 50 digits and kept only where it
converges, both equations hold to 1e-30 L^2 and theta_0 stays at the root; a root with no assembly
(a common root of the two equations in t_1 that is not real) is rejected and counted as such.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any

import flint

from .pivots import Pivoted, Tie
from .polynomial import NEWTON_STEPS
from .realroots import isolate
from .resultant import LOOSE, MP, SAME_ROOT, Assembled, Count, _add, _clean, _roots, _values, univariate
from .triad import Exact, NotReducible

NAMES = ("t0", "t1")


def _ints(v: Exact, unit: Fraction) -> tuple[int, int]:
    x, y = v[0] / unit, v[1] / unit
    if x.denominator != 1 or y.denominator != 1:
        raise ValueError("a coordinate off the grid")
    return int(x), int(y)


def _normal(n: Exact) -> tuple[int, int]:
    scale = math.lcm(n[0].denominator, n[1].denominator)
    return int(n[0] * scale), int(n[1] * scale)


Equation = tuple[list[tuple[int | None, tuple[int, int]]], int, int, tuple[int, int] | None]


def equations(shape: Pivoted, pivots: list[Exact], unit: Fraction) -> list[Equation]:
    """Each tie as (the terms of v: (the angle that turns the vector, or None; the vector over the grid),
    l^2 over the grid's square, the body whose slot it is, its integer normal or None)."""
    out: list[Equation] = []
    for tie in shape.ties:
        j, k = tie.body, 1 - tie.body
        pj, pk = _ints(pivots[j], unit), _ints(pivots[k], unit)
        b = _ints(tie.b, unit)
        terms = [(None, (pj[0] - pk[0], pj[1] - pk[1])), (j, _ints(tie.a, unit)), (k, (-b[0], -b[1]))]
        l2 = tie.length2 / unit**2
        if l2.denominator != 1:
            raise ValueError("a squared length off the grid")
        out.append((terms, int(l2), k, _normal(tie.normal) if tie.normal else None))
    return out


def polynomial(ctx: Any, eq: Equation) -> Any:
    """q_0 q_1 times the tie's equation as a polynomial in t_0, t_1."""
    terms, l2, k, normal = eq
    t = ctx.gens()
    one = ctx.from_dict({(0, 0): 1})
    q = [1 + t[0] ** 2, 1 + t[1] ** 2]
    c, s = [1 - t[0] ** 2, 1 - t[1] ** 2], [2 * t[0], 2 * t[1]]
    x = y = 0 * one
    for v, (ax, ay) in terms:  # q_0 q_1 v
        if v is None:
            x, y = x + ax * q[0] * q[1], y + ay * q[0] * q[1]
        else:
            x, y = x + (c[v] * ax - s[v] * ay) * q[1 - v], y + (s[v] * ax + c[v] * ay) * q[1 - v]
    if normal is None:
        e = x * x + y * y - l2 * (q[0] * q[1]) ** 2
        return _divide(_divide(e, q[0]), q[1])
    nx, ny = c[k] * normal[0] - s[k] * normal[1], s[k] * normal[0] + c[k] * normal[1]  # q_k R(theta_k) n
    return _divide(nx * x + ny * y, q[k])


def _divide(a: Any, b: Any) -> Any:
    quo, rem = divmod(a, b)
    if rem != 0:
        raise ArithmeticError("a factor (1 + t^2) does not divide a tie's equation")
    return quo


def solve(shape: Pivoted, pivots: list[Exact], unit: Fraction, scale: float) -> Count:
    """Every assembly of the two bodies about these pivots (the programs' coordinates)."""
    ctx = flint.fmpz_mpoly_ctx.get(NAMES, "lex")
    eqs = equations(shape, pivots, unit)
    polys = [polynomial(ctx, e) for e in eqs]
    p = _clean(polys[0].resultant(polys[1], "t1"), ctx)
    if p == 0:
        raise NotReducible("the group's equations do not fix it at this position (its ties share a curve)")
    eliminant = univariate(p, 0) if not p.is_constant() else flint.fmpz_poly([1])
    intervals = isolate(eliminant) if eliminant.degree() > 0 else []
    size = MP.mpf(scale) / MP.mpf(unit.numerator) * unit.denominator  # L in grid units
    found: list[Assembled] = []
    for a, b, mult in intervals:
        lo, hi = (MP.mpf(v.numerator) / v.denominator for v in (a, b))
        t = (lo + hi) / 2
        for tr in _candidates(polys, t):
            got = _polish(eqs, [_angle(t), _angle(tr)], size, 0 if mult > 1 else NEWTON_STEPS)
            if got is not None and lo - SAME_ROOT <= MP.tan(got[0] / 2) <= hi + SAME_ROOT:
                _add(found, _assembled(got, eqs, size))  # else Newton went to another root's assembly
    at_pi = False
    for tr in _at_pi(polys):
        got = _polish(eqs, [MP.pi, _angle(tr)], size, NEWTON_STEPS)
        if got is not None and abs(abs(MP.atan2(MP.sin(got[0]), MP.cos(got[0]))) - MP.pi) < SAME_ROOT:
            _add(found, _assembled(got, eqs, size))
            at_pi = True
    found = [_placed(shape, pivots, a) for a in found]
    factors = tuple(sorted(g.degree() for g, _ in eliminant.factor()[1])) or (0,)
    return Count(max(eliminant.degree(), 0), factors, len(intervals), at_pi,
                 tuple(sorted(found, key=lambda r: r.theta)))


def _candidates(polys: list[Any], t: Any) -> list[Any]:
    """Every real t_1 (None for half a turn) where either equation holds at t_0 = t."""
    out: list[Any] = []
    for p in polys:
        out += [r for r in _roots(_values(p, {0: t}, 1)) if r is not None or None not in out]
    return out


def _at_pi(polys: list[Any]) -> list[Any]:
    """The t_1 (None for pi) of every real solution with theta_0 = pi: the common real roots of the
    equations' coefficients of t_0^2 (their values there, times t_0^-2)."""
    tops = []
    for p in polys:
        top: dict[int, int] = {}
        for (e0, e1), c in p.to_dict().items():
            if e0 == 2:
                top[int(e1)] = top.get(int(e1), 0) + int(c)
        tops.append(flint.fmpz_poly([top.get(k, 0) for k in range(3)]))
    if tops[0].is_zero() and tops[1].is_zero():
        raise NotReducible("the group's equations do not fix it where its first link is turned half a turn")
    common = tops[0] if tops[1].is_zero() else tops[1] if tops[0].is_zero() else tops[0].gcd(tops[1])
    out: list[Any] = []
    if all(p.degree() < 2 for p in tops):  # both leading coefficients in t_1 vanish: theta_1 = pi too
        out.append(None)
    if common.degree() > 0:
        out += [MP.mpf((a + b).numerator) / (2 * (a + b).denominator) for a, b, _ in isolate(common)]
    return out


def _angle(t: Any) -> Any:
    return MP.pi if t is None else 2 * MP.atan(t)


def _equations(eqs: list[Equation], angles: list[Any], size: Any) -> tuple[list[Any], list[list[Any]]]:
    """The two ties' residuals (a link's |v|^2 - l^2, a slot's size times the pair's distance from its
    line: both in grid units squared) and their Jacobian in (theta_0, theta_1)."""
    rot = [(MP.cos(a), MP.sin(a)) for a in angles]
    res, jac = [], []
    for terms, l2, k, normal in eqs:
        vx = vy = MP.mpf(0)
        d = [[MP.mpf(0), MP.mpf(0)], [MP.mpf(0), MP.mpf(0)]]  # dv / dtheta_m
        for m, (ax, ay) in terms:
            if m is None:
                vx, vy = vx + ax, vy + ay
                continue
            c, s = rot[m]
            x, y = c * ax - s * ay, s * ax + c * ay
            vx, vy = vx + x, vy + y
            d[m] = [d[m][0] - y, d[m][1] + x]
        if normal is None:
            res.append(vx * vx + vy * vy - l2)
            jac.append([2 * (vx * d[m][0] + vy * d[m][1]) for m in (0, 1)])
            continue
        c, s = rot[k]
        norm = size / MP.sqrt(MP.mpf(normal[0] ** 2 + normal[1] ** 2))
        nx, ny = (c * normal[0] - s * normal[1]) * norm, (s * normal[0] + c * normal[1]) * norm
        res.append(nx * vx + ny * vy)
        row = [nx * d[m][0] + ny * d[m][1] for m in (0, 1)]
        row[k] += -ny * vx + nx * vy
        jac.append(row)
    return res, jac


def _polish(eqs: list[Equation], angles: list[Any], size: Any, steps: int) -> list[Any] | None:
    """Newton's method on the two equations at 50 digits from a candidate that nearly closes (None where
    it does not, or where Newton does not bring the equations to 1e-30 L^2)."""
    res, jac = _equations(eqs, angles, size)
    if max(abs(r) for r in res) / size**2 > LOOSE:
        return None
    for _ in range(steps):
        try:
            step = MP.lu_solve(MP.matrix(jac), MP.matrix(res))
        except ZeroDivisionError:
            return None
        angles = [a - step[m] for m, a in enumerate(angles)]
        res, jac = _equations(eqs, angles, size)
        if max(abs(step[m]) for m in (0, 1)) < MP.mpf(10) ** (5 - MP.dps):
            break
    if max(abs(r) for r in res) / size**2 > MP.mpf(10) ** -30:
        return None
    return angles


def _assembled(angles: list[Any], eqs: list[Equation], size: Any) -> Assembled:
    res, _ = _equations(eqs, angles, size)
    wrapped = [float(MP.atan2(MP.sin(a), MP.cos(a))) for a in angles]
    wrapped = [math.pi if w <= -math.pi else w for w in wrapped]
    return Assembled(wrapped[0], (wrapped[0], wrapped[1]), (), float(max(abs(r) for r in res) / size**2))


def _placed(shape: Pivoted, pivots: list[Exact], a: Assembled) -> Assembled:
    """The assembly with every pair's position (at 50 digits, rounded once), in the order of ``shape.pairs``."""
    def turned(v: Exact, angle: float) -> tuple[Any, Any]:
        c, s = MP.cos(MP.mpf(angle)), MP.sin(MP.mpf(angle))
        x, y = _mp(v[0]), _mp(v[1])
        return c * x - s * y, s * x + c * y

    out = []
    for spot in shape.spots:
        ax, ay = turned(spot.a, a.angles[spot.body])
        bx, by = turned(spot.b, a.angles[spot.turn])
        p = pivots[spot.body]
        out.append((float(_mp(p[0]) + ax + bx), float(_mp(p[1]) + ay + by)))
    return Assembled(a.theta, a.angles, tuple(out), a.error)


def _mp(x: Fraction) -> Any:
    return MP.mpf(x.numerator) / x.denominator


__all__ = ["Tie", "solve"]
