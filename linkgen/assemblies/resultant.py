"""Two bodies on four-bars tied by two couplers: the closure as one polynomial by resultants, its
real roots certified, every root back-substituted and polished (the class-IV count).

Body k's first leg turns by phi_k from the sketch, the body by theta_k, so its pairs sit at

    G_k + R(phi_k) v_k + R(theta_k) a     (G_k the leg's base now, v_k the leg's sketch vector).

Four equations hold the four angles: each body's second leg (F_L in phi_L, theta_L; F_R), and the two couplers (C_1,
C_2 in all four). A second leg that is a block on a slide fixed to the frame keeps its pair P on a line, n . P = n .
a (a the pair's sketch position): n . (G + R(phi) v + R(theta) h - a) = 0 is linear in cos and sin of each angle, so
times (1 + t_phi^2)(1 + t_theta^2) it too is of degree 2 in each (n scaled to integers, the powers of 2 of its
binary fractions cleared). With t = tan(angle / 2) each is a polynomial of degree 2 in each of its unknowns with
exact integer coefficients (the data on the grid of ``triad.grid``, divided by it). Resultants eliminate phi_L (F_L
against each coupler), then phi_R (F_R against both), then theta_R (by evaluation and interpolation:
``interpolate``), leaving P(t_L), t_L = tan(theta_L / 2). Every assembly's theta_L is a root of P (a resultant
vanishes wherever its two polynomials have a common root, finite or where both leading coefficients vanish); theta_L
= pi (t_L infinite) is checked on its own, from the equations' leading coefficients in t_L. P also has roots where
F_L's two branches (or F_R's) close the two couplers separately: every real root is back-substituted (both roots of
F_L and of F_R, every root of the theta_R resultant, and half a turn for each), polished by Newton's method on the
four equations at 50 digits, and kept only where it converges, every equation holds to 1e-30 L^2 and theta_L stays
at the root (to 1e-30). Real roots are isolated from the exact coefficients by FLINT (arb's certified
``complex_roots`` on each irreducible factor of P); no Sturm count (125 s).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Sequence
from dataclasses import dataclass, replace
from fractions import Fraction
from typing import Any

import flint
import mpmath

from . import ballroots, interpolate
from .bodies import TwoBodies
from .triad import Exact, NotReducible

MP = mpmath.mp.clone()
MP.dps = 50
NAMES = ("pL", "tL", "pR", "tR")  # phi_L, theta_L, phi_R, theta_R as tangent half-angles
NEWTON_STEPS = 60
LOOSE = 1e-8  # a candidate of the back-substitution whose equations hold to this (over L^2) is polished
SAME_ROOT = MP.mpf(10) ** -30  # a polished theta_L is this root's (relative); real roots are further apart
ISOLATION_BITS = 200  # the precision FLINT isolates the roots to (about 60 digits)

Term = tuple[int | None, tuple[int, int]]  # (the angle that turns the vector, or None), the vector over the grid


@dataclass(frozen=True)
class Assembled:
    """One assembly of the group: theta_L, its angles (radians; four, or two for ``pivoted``) and every body
    pair's position."""

    theta: float
    angles: tuple[float, ...]
    positions: tuple[tuple[float, float], ...]  # in the order of TwoBodies.pairs
    error: float  # the worst equation's residual after polishing, over L^2


@dataclass(frozen=True)
class Count:
    """The group at one position of its bases: P's degree, its irreducible factors' degrees, its real
    roots, and the assemblies they give."""

    degree: int
    factors: tuple[int, ...]
    real_roots: int
    at_pi: bool  # an assembly has theta_L = pi
    roots: tuple[Assembled, ...]  # by theta_L

    @property
    def rejected(self) -> int:
        return self.real_roots - len({r.theta for r in self.roots if abs(r.theta) < math.pi})


Equation = tuple[list[Term], int, tuple[int, int] | None]  # |sum|^2 = length2, or normal . sum = 0 (a slide)


def equations(bodies: TwoBodies, bases: Sequence[Exact], unit: Fraction) -> list[Equation]:
    """[(terms, length2 over unit^2, None)] of F_L, F_R, C_1, C_2, or (terms, 0, integer normal) for a
    second leg on a slide; ``bases`` the first and second legs' bases of body 0 then body 1, now (a
    slide leg's second base is not used)."""
    def grid(v: Exact) -> tuple[int, int]:
        x, y = v[0] / unit, v[1] / unit
        if x.denominator != 1 or y.denominator != 1:
            raise ValueError("a coordinate off the grid")
        return int(x), int(y)

    def neg(v: tuple[int, int]) -> tuple[int, int]:
        return -v[0], -v[1]

    def l2(x: Fraction) -> int:
        v = x / unit**2
        if v.denominator != 1:
            raise ValueError("a squared length off the grid")
        return int(v)

    (left, right), (c1, c2) = bodies.bodies, bodies.couplers
    gl, gr = grid(bases[0]), grid(bases[2])
    hl, hr = bases[1], bases[3]
    out: list[Equation] = []
    for k, (b, g, h) in enumerate(((left, gl, hl), (right, gr, hr))):
        normal = None
        if b.line is not None:
            (nx, ny), h = b.line
            scale = math.lcm(nx.denominator, ny.denominator)
            normal = (int(nx * scale), int(ny * scale))
        out.append(([(None, g), (2 * k, grid(b.leg)), (2 * k + 1, grid(b.held)), (None, neg(grid(h)))],
                    l2(b.length2), normal))
    for c in (c1, c2):
        out.append(([(None, gl), (0, grid(left.leg)), (1, grid(c.left)), (None, neg(gr)), (2, neg(grid(right.leg))),
                     (3, neg(grid(c.right)))], l2(c.length2), None))
    return out


def polynomial(ctx: Any, terms: list[Term], length2: int, normal: tuple[int, int] | None = None) -> Any:
    """|sum of the terms|^2 - length2 over (1 + t^2) for each angle the terms turn by; with a
    ``normal``, normal . (sum of the terms) times (1 + t^2) for each angle."""
    gens = ctx.gens()
    used = sorted({v for v, _ in terms if v is not None})
    q = {v: 1 + gens[v] ** 2 for v in used}
    x = y = ctx.from_dict({})
    for v, (ax, ay) in terms:
        rest = ctx.from_dict({tuple(0 for _ in NAMES): 1})
        for u in used:
            if u != v:
                rest = rest * q[u]
        if v is None:
            x, y = x + ax * rest, y + ay * rest
        else:
            c, s = 1 - gens[v] ** 2, 2 * gens[v]
            x, y = x + (c * ax - s * ay) * rest, y + (s * ax + c * ay) * rest
    if normal is not None:
        return normal[0] * x + normal[1] * y
    whole = ctx.from_dict({tuple(0 for _ in NAMES): 1})
    for u in used:
        whole = whole * q[u]
    e = x * x + y * y - length2 * whole * whole
    for u in used:
        e = _exact_quotient(e, q[u])
    return e


def _exact_quotient(a: Any, b: Any) -> Any:
    quo, rem = divmod(a, b)
    if rem != 0:
        raise ArithmeticError("a factor (1 + t^2) does not divide the equation")
    return quo


def _clean(p: Any, ctx: Any) -> Any:
    """p without its content and its factors 1 + t^2 (no real root)."""
    if p == 0:
        return p
    p = p.primitive()[1]
    for g in ctx.gens():
        q = 1 + g * g
        while True:
            quo, rem = divmod(p, q)
            if rem != 0 or quo.is_constant():
                break
            p = quo
    return p


def eliminate(f_l: Any, f_r: Any, c1: Any, c2: Any, ctx: Any) -> tuple[Any, Any, Any]:
    """(S_1, S_2, P): the couplers' resultants in theta_L, theta_R and their resultant, an fmpz_poly in
    t_L (by evaluation and interpolation: ``interpolate``)."""
    s = []
    for c in (c1, c2):
        r = _clean(f_l.resultant(c, "pL"), ctx)
        s.append(_clean(f_r.resultant(r, "pR"), ctx))
    if s[0] == 0 or s[1] == 0:
        raise NotReducible("the group's equations do not fix it at this position")
    return s[0], s[1], interpolate.resultant(s[0], s[1], 3, 1)


def univariate(p: Any, index: int) -> Any:
    """An fmpz_mpoly in the variable ``index`` only as an fmpz_poly."""
    if any(e for exps in p.to_dict() for k, e in enumerate(exps) if k != index):
        raise ArithmeticError("the eliminant still has other unknowns")
    coeffs = {int(exps[index]): int(c) for exps, c in p.to_dict().items()}
    return flint.fmpz_poly([coeffs.get(k, 0) for k in range(max(coeffs) + 1)])


def real_roots(f: Any, factors: Any = None) -> list[tuple[Any, Any]]:
    """Every distinct real root of the integer polynomial f as an isolating interval (lo, hi) of
    mpf, by FLINT's certified isolation (arb's complex_roots: ball arithmetic on the exact
    coefficients) on each irreducible factor (``factors``: f's, when already known)."""
    factors = factors or f.factor()[1]
    out = []
    for g, _ in factors:
        if g.degree() < 1:
            continue
        old, flint.ctx.prec = flint.ctx.prec, ISOLATION_BITS
        try:
            found = [z for z, _ in g.complex_roots()]
        finally:
            flint.ctx.prec = old
        for r in (z.real for z in found if z.imag == 0):  # arb returns a real root's ball on the real line
            mid, rad = (MP.mpf(tuple(int(v) for v in x.man_exp())) for x in (r.mid(), r.rad()))
            out.append((mid - rad, mid + rad))
    return sorted(out)


@functools.lru_cache(maxsize=8)  # an elimination takes seconds: a process's builds of one mechanism share it
def solve(bodies: TwoBodies, bases: tuple[Exact, ...], unit: Fraction, scale: float) -> Count:
    """Every assembly of the two bodies with these legs' bases (first and second of body 0, then of
    body 1; positions as the bases': the same origin)."""
    ctx = flint.fmpz_mpoly_ctx.get(NAMES, "lex")
    eqs = equations(bodies, bases, unit)
    polys = [polynomial(ctx, *e) for e in eqs]
    s1, s2, eliminant = eliminate(polys[0], polys[1], polys[2], polys[3], ctx)
    if eliminant == 0:
        raise NotReducible("the group's equations do not fix it at this position (its couplers' resultants "
                           "share a factor)")
    _, factors = eliminant.factor()
    intervals = real_roots(eliminant, factors)
    size = MP.mpf(scale) / MP.mpf(unit.numerator) * unit.denominator  # L in grid units
    found: list[Assembled] = []
    mids = [(lo + hi) / 2 for lo, hi in intervals]
    if any(b - a < SAME_ROOT * (1 + abs(a)) for a, b in zip(mids, mids[1:])):
        raise ArithmeticError("two real roots of the class-IV eliminant are too close to tell apart at 50 digits")
    for t in mids:
        for a, t_polished in _over(eqs, polys, s1, t, None, size):
            if abs(t_polished - t) < SAME_ROOT * (1 + abs(t)):
                _add(found, a)  # else Newton went to another root's assembly: found there
    at_pi = False
    for t_r in _at_pi(polys, ctx):  # theta_L = pi
        for a, _ in _over(eqs, polys, s1, None, t_r, size):
            _add(found, a)
            at_pi = True
    found = [replace(a, positions=positions(bodies, bases, a.angles)) for a in found]
    return Count(eliminant.degree(), tuple(sorted(g.degree() for g, _ in factors)), len(intervals), at_pi,
                 tuple(sorted(found, key=lambda r: r.theta)))


def _add(found: list[Assembled], a: Assembled) -> None:
    """Add an assembly unless it is one already found (the same four angles to 1e-25)."""
    for b in found:
        if max(abs(math.remainder(x - y, 2 * math.pi)) for x, y in zip(a.angles, b.angles)) < 1e-12:
            return
    found.append(a)


def _at_pi(polys: list[Any], ctx: Any) -> list[Any]:
    """The theta_R (as t_R, None for pi) of every real solution with theta_L = pi: the equations'
    coefficients of t_L^2 (their values there), eliminated as above down to theta_R."""
    at = []
    for e in polys:
        if e.degrees()[1] == 0:
            at.append(e)
            continue
        top = {(k[0], 0, k[2], k[3]): c for k, c in e.to_dict().items() if k[1] == 2}
        at.append(ctx.from_dict(top))
    f_l, f_r, c1, c2 = at
    s = [_clean(f_r.resultant(_clean(f_l.resultant(c, "pL"), ctx), "pR"), ctx) for c in (c1, c2)]
    common = s[0].gcd(s[1]) if s[0] != 0 or s[1] != 0 else s[0]
    if common == 0:
        raise NotReducible("the group's equations do not fix it where its first body is turned half a turn")
    candidates: list[Any] = [None]  # theta_R = pi with theta_L = pi
    if not common.is_constant():
        candidates += [(lo + hi) / 2 for lo, hi in real_roots(univariate(common, 3))]
    return candidates


def _values(p: Any, fixed: dict[int, Any], free: int) -> list[Any]:
    """The coefficients (highest first) of p in the unknown ``free`` at the values ``fixed``."""
    out: dict[int, Any] = {}
    for exps, c in p.to_dict().items():
        term = MP.mpf(int(c))
        for k, v in fixed.items():
            if exps[k]:
                term *= v ** int(exps[k])
        out[int(exps[free])] = out.get(int(exps[free]), 0) + term
    return [out.get(k, MP.mpf(0)) for k in range(max(out, default=0), -1, -1)]


def _roots(coeffs: list[Any]) -> list[Any]:
    """The real roots of a polynomial (mpf coefficients, highest first), and None for infinity (half a turn)."""
    while coeffs and coeffs[0] == 0:
        coeffs = coeffs[1:]
    out: list[Any] = [None]
    if len(coeffs) == 2:
        out.append(-coeffs[1] / coeffs[0])
    elif len(coeffs) == 3:  # a leg's equation: the closed form
        a, b, c = coeffs
        disc = b * b - 4 * a * c
        if disc >= -MP.mpf(10) ** -40 * b * b:
            root = MP.sqrt(max(disc, 0))
            out += [(-b + root) / (2 * a), (-b - root) / (2 * a)]
    elif len(coeffs) > 3:
        balls = ballroots.real_roots(coeffs, MP)
        out += balls if balls is not None else [MP.re(z) for z in MP.polyroots(coeffs, maxsteps=200, extraprec=400)
                                                if abs(MP.im(z)) <= MP.mpf(10) ** -20 * (1 + abs(z))]
    return out


def _angle(t: Any) -> Any:
    return MP.pi if t is None else 2 * MP.atan(t)


def _over(eqs: list[Any], polys: list[Any], s1: Any, t_l: Any, t_r: Any, size: Any) -> list[tuple[Assembled, Any]]:
    """Every assembly over theta_L (t_l; None for pi): both roots of F_L, every root of S_1 in t_R
    (or t_r where given), both roots of F_R, each half a turn too; polished (with its t_L at 50 digits)."""
    out = []
    p_ls = _roots(_values(polys[0], {1: t_l}, 0)) if t_l is not None else _pi_roots(polys[0], 1, 0)
    t_rs = _roots(_values(s1, {1: t_l}, 3)) if t_l is not None else [t_r]
    for p_l in p_ls:
        for tr in t_rs:
            for p_r in _roots(_values(polys[1], {3: tr}, 2)) if tr is not None else _pi_roots(polys[1], 3, 2):
                angles = [_angle(p_l), _angle(t_l), _angle(p_r), _angle(tr)]
                res, _ = _equations(eqs, angles, size)
                if max(abs(r) for r in res) / size**2 > LOOSE:
                    continue
                out.append(_polish(eqs, angles, size))
    return out


def _pi_roots(f: Any, turned: int, free: int) -> list[Any]:
    """The roots in the unknown ``free`` of F (a body's second leg) where its body is turned half a
    turn (its coefficients of t^2 in the unknown ``turned``)."""
    top: dict[int, Any] = {}
    for exps, c in f.to_dict().items():
        if exps[turned] == 2:
            top[int(exps[free])] = top.get(int(exps[free]), 0) + MP.mpf(int(c))
    return _roots([top.get(k, MP.mpf(0)) for k in range(max(top, default=0), -1, -1)])


def _equations(eqs: list[Any], angles: list[Any], size: Any) -> tuple[list[Any], list[list[Any]]]:
    """The four equations |sum of the terms|^2 - length^2 (grid units) at the angles, and their
    Jacobian; a slide's as size times its pair's distance from the line (also an area)."""
    rot = [(MP.cos(a), MP.sin(a)) for a in angles]
    res, jac = [], []
    for terms, length2, normal in eqs:
        vx = vy = MP.mpf(0)
        turned = []
        for v, (ax, ay) in terms:
            if v is None:
                vx, vy = vx + ax, vy + ay
                continue
            c, s = rot[v]
            x, y = c * ax - s * ay, s * ax + c * ay
            vx, vy = vx + x, vy + y
            turned.append((v, -y, x))  # d/dangle of R(angle) a
        row = [MP.mpf(0)] * 4
        if normal is not None:
            nx, ny = (MP.mpf(n) * size / MP.sqrt(MP.mpf(normal[0] ** 2 + normal[1] ** 2)) for n in normal)
            res.append(nx * vx + ny * vy)
            for v, dx, dy in turned:
                row[v] += nx * dx + ny * dy
        else:
            res.append(vx * vx + vy * vy - length2)
            for v, dx, dy in turned:
                row[v] += 2 * (vx * dx + vy * dy)
        jac.append(row)
    return res, jac


def _polish(eqs: list[Any], angles: list[Any], size: Any) -> tuple[Assembled, Any]:
    """Newton's method on the four equations at 50 digits from a candidate that nearly closes."""
    for _ in range(NEWTON_STEPS):
        res, jac = _equations(eqs, angles, size)
        step = MP.lu_solve(MP.matrix(jac), MP.matrix(res))
        angles = [a - step[k] for k, a in enumerate(angles)]
        if max(abs(step[k]) for k in range(4)) < MP.mpf(10) ** (5 - MP.dps):
            break
    else:
        raise ArithmeticError("Newton's method did not converge from a root of the class-IV eliminant")
    res, _ = _equations(eqs, angles, size)
    error = max(abs(r) for r in res) / size**2
    if error > MP.mpf(10) ** -30:
        raise ArithmeticError(f"a root of the class-IV eliminant leaves its equations off by {float(error):.3g} L^2")
    wrapped = tuple(float(MP.atan2(MP.sin(a), MP.cos(a))) for a in angles)
    wrapped = tuple(math.pi if w <= -math.pi else w for w in wrapped)
    return Assembled(wrapped[1], (wrapped[0], wrapped[1], wrapped[2], wrapped[3]), (), float(error)), \
        MP.tan(angles[1] / 2)


def positions(bodies: TwoBodies, bases: Sequence[Exact], angles: tuple[float, ...]) -> tuple[tuple[float, float], ...]:
    """Every body pair's position at the four angles (at 50 digits, rounded once), in the order of
    ``bodies.pairs``."""
    out = []
    for k, body in enumerate(bodies.bodies):
        g = bases[2 * k]
        phi, theta = MP.mpf(angles[2 * k]), MP.mpf(angles[2 * k + 1])
        cp, sp, ct, st = MP.cos(phi), MP.sin(phi), MP.cos(theta), MP.sin(theta)
        vx, vy = (_mp(x) for x in body.leg)
        px, py = _mp(g[0]) + cp * vx - sp * vy, _mp(g[1]) + sp * vx + cp * vy
        for ax, ay in body.local:
            x, y = _mp(ax), _mp(ay)
            out.append((float(px + ct * x - st * y), float(py + st * x + ct * y)))
    return tuple(out)


def _mp(x: Fraction) -> Any:
    return MP.mpf(x.numerator) / x.denominator
