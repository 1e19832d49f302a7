"""A triad's closure as one polynomial in one unknown, its real roots certified, then polished.

The ternary's pairs sit at ``X + R(theta) a_i`` (X its first pair, a_i their sketch offsets from
it, theta its turn from the sketch); leg i holds pair i at distance l_i from the known B_i:

    |X + R a_i - B_i|^2 = l_i^2,  i = 1, 2, 3.

Subtracting the first equation from the others leaves two equations linear in X,
``M(theta) X = r(theta)``; Cramer's rule gives ``X = N / D`` and the first equation times D^2,

    F = |N|^2 + 2 D N.w_1 + k_1 D^2 = 0   (w_i = R a_i - B_i, k_i = |w_i|^2 - l_i^2),

is one equation in theta.  With ``t = tan(theta / 2)``, ``cos = (1 - t^2) / q``, ``sin = 2 t / q``
and ``q = 1 + t^2``, every w_i is a polynomial over q, and q^6 F is a polynomial of degree 12
in t with exact rational coefficients (the data are the doubles they are, as fractions).  It
carries the factor (1 + t^2)^3, which has no real root; divided out, the 3-RRR triad's
characteristic polynomial has degree 6 (less where theta = pi is a root: t is infinite there,
so theta = pi is checked on its own).

The polynomial is formed exactly over the rationals (python-flint's fmpq_poly); its real roots are
isolated by arb on its factors over the integers and counted again by Sturm's theorem
(``realroots``); the two must agree.  A root where D
vanishes too (the linear equations lose rank, the triad is at a special position) is not
counted: the polynomial's greatest common divisor with D must have no real root.  Each root
is polished by Newton's method on the three leg equations in (X, theta) at 50 digits (mpmath)
and kept only if it converges inside its isolating interval.
"""

from __future__ import annotations

from collections.abc import Callable
from fractions import Fraction
from typing import Any

import flint
import mpmath

from .realroots import Interval, isolate, sturm_count
from .roots import Root, Solution
from .triad import Exact, NotReducible

MP = mpmath.mp.clone()
MP.dps = 50
NEWTON_STEPS = 60  # Newton's method at 50 digits from a root isolated to 1e-45: one or two suffice


def closure(c: Any, s: Any, q: Any, bases: list[Exact], local: list[Exact], lengths2: list[Fraction],
            num: Callable[[Fraction], Any]) -> tuple[Any, Any]:
    """(q^6 F, q^2 D) for cos theta = c / q and sin theta = s / q, in any ring that holds c, s, q
    and the numbers ``num`` makes of the data."""
    w = []
    for (ax, ay), (bx, by) in zip(local, bases):
        w.append((c * num(ax) - s * num(ay) - q * num(bx), s * num(ax) + c * num(ay) - q * num(by)))  # q w_i
    k = [wx * wx + wy * wy - q * q * num(l2) for (wx, wy), l2 in zip(w, lengths2)]  # q^2 k_i
    m = [(2 * (w[i][0] - w[0][0]), 2 * (w[i][1] - w[0][1])) for i in (1, 2)]  # q M
    r = [k[0] - k[i] for i in (1, 2)]  # q^2 r
    d = m[0][0] * m[1][1] - m[0][1] * m[1][0]  # q^2 D
    nx = r[0] * m[1][1] - r[1] * m[0][1]  # q^3 N
    ny = m[0][0] * r[1] - m[1][0] * r[0]
    f = nx * nx + ny * ny + 2 * d * (nx * w[0][0] + ny * w[0][1]) + k[0] * d * d
    return f, d


def characteristic(bases: list[Exact], local: list[Exact], lengths2: list[Fraction]) -> tuple[Any, Any]:
    """The characteristic polynomial in t (the factors 1 + t^2 divided out; an fmpz_poly, primitive)
    and D's, q^2 D (an fmpq_poly)."""
    f, d = closure(*QUARTER, bases, local, lengths2, rational)
    if f == 0 or d == 0:
        raise NotReducible("the triad's equations do not fix it at this position (a ternary similar to its base, "
                           "or coincident pairs)")
    return primitive(f), d


QUARTER = (flint.fmpq_poly([1, 0, -1]), flint.fmpq_poly([0, 2]), flint.fmpq_poly([1, 0, 1]))  # q cos, q sin, q


def rational(x: Fraction) -> Any:
    return flint.fmpq(x.numerator, x.denominator)


def primitive(f: Any) -> Any:
    """The fmpq_poly f with the factors q = 1 + t^2 divided out, as an integer polynomial whose
    coefficients have no common factor (its leading coefficient's sign kept)."""
    q = QUARTER[2]
    while f.degree() >= 2 and f % q == 0:
        f = f // q
    whole = f.numer()
    content = int(whole.content())
    return flint.fmpz_poly([int(c) // content for c in whole.coeffs()])


def special(f: Any, d: Any) -> bool:
    """Whether f and D share a real root (the legs' equations lose rank there)."""
    common = flint.fmpq_poly(f).gcd(d)
    return common.degree() > 0 and sturm_count(common) > 0


def solve(bases: list[Exact], local: list[Exact], lengths2: list[Fraction], scale: float) -> Solution:
    """Every assembly of the triad with these bases (positions as the bases': the same origin)."""
    f, d = characteristic(bases, local, lengths2)
    if special(f, d):
        raise NotReducible("the triad is at a special position here (a root where its legs' equations lose rank)")
    f_pi, d_pi = closure(Fraction(-1), Fraction(0), Fraction(1), bases, local, lengths2, lambda x: x)
    if f_pi == 0 and d_pi == 0:
        raise NotReducible("the triad is at a special position here (turned half a turn, its legs' equations lose "
                           "rank)")
    intervals = isolate(f)
    data = (bases, local, lengths2)
    roots = [_polish(data, (low + high) / 2, (low, high, mult), scale) for low, high, mult in intervals]
    if f_pi == 0:
        roots.append(_polish(data, None, None, scale))
    return Solution(f.degree(), len(intervals), f_pi == 0, tuple(sorted(roots, key=lambda r: r.theta)),
                    scaled(f))


def scaled(f: Any) -> tuple[float, ...]:
    """The fmpz_poly's coefficients, highest first, over the largest's size."""
    coeffs = [int(c) for c in reversed(f.coeffs())]
    top = max(abs(float(x)) for x in coeffs)
    return tuple(float(x) / top for x in coeffs)


Data = tuple[list[Exact], list[Exact], list[Fraction]]


def _mp(x: Fraction) -> Any:
    return MP.mpf(x.numerator) / x.denominator


def _polish(data: Data, t: Fraction | None, interval: Interval | None, scale: float) -> Root:
    """Newton on the leg equations in (X, theta) at 50 digits from the root t in its isolating
    interval (None: theta = pi; a multiple root is t itself)."""
    multiplicity = 1 if interval is None else interval[2]
    bases = [(_mp(x), _mp(y)) for x, y in data[0]]
    local = [(_mp(x), _mp(y)) for x, y in data[1]]
    l2 = [_mp(x) for x in data[2]]
    theta = MP.pi if t is None else 2 * MP.atan(_mp(t))
    x, y = _linear(bases, local, l2, theta)
    size = MP.mpf(scale)
    for _ in range(NEWTON_STEPS if multiplicity == 1 else 0):
        res, jac = _equations(bases, local, l2, x, y, theta)
        step = MP.lu_solve(MP.matrix(jac), MP.matrix(res))
        x, y, theta = x - step[0], y - step[1], theta - step[2]
        if max(abs(step[0]) / size, abs(step[1]) / size, abs(step[2])) < MP.mpf(10) ** (5 - MP.dps):
            break
    else:
        if multiplicity == 1:
            raise ArithmeticError(f"Newton's method did not converge from the root at t = {t}")
    res, _ = _equations(bases, local, l2, x, y, theta)
    error = max(abs(r) for r in res) / size**2
    if error > MP.mpf(10) ** -30:
        raise ArithmeticError(f"the root at t = {t} leaves the legs off by {float(error):.3g} L^2")
    theta = MP.atan2(MP.sin(theta), MP.cos(theta))
    if interval is not None:
        tt = MP.tan(theta / 2)
        lo, hi = _mp(interval[0]), _mp(interval[1])
        if not lo - MP.mpf(10) ** -40 <= tt <= hi + MP.mpf(10) ** -40:
            raise ArithmeticError(f"Newton's method left the isolating interval of the root at t = {t}")
    elif abs(abs(theta) - MP.pi) > MP.mpf(10) ** -40:
        raise ArithmeticError("Newton's method left the root at theta = pi")
    c, s = MP.cos(theta), MP.sin(theta)
    pos = [(float(x + c * ax - s * ay), float(y + s * ax + c * ay)) for ax, ay in local]
    return Root(float(theta) if theta > -MP.pi else float(MP.pi), multiplicity, (pos[0], pos[1], pos[2]),
                float(error))


Point = tuple[Any, Any]


def _linear(bases: list[Point], local: list[Point], l2: list[Any], theta: Any) -> tuple[Any, Any]:
    """X from the two equations linear in it (the leg equations less the first)."""
    c, s = MP.cos(theta), MP.sin(theta)
    w = [(c * ax - s * ay - bx, s * ax + c * ay - by) for (ax, ay), (bx, by) in zip(local, bases)]
    k = [wx * wx + wy * wy - leg2 for (wx, wy), leg2 in zip(w, l2)]
    m = MP.matrix([[2 * (w[i][0] - w[0][0]), 2 * (w[i][1] - w[0][1])] for i in (1, 2)])
    x = MP.lu_solve(m, MP.matrix([k[0] - k[i] for i in (1, 2)]))
    return x[0], x[1]


def _equations(bases: list[Point], local: list[Point], l2: list[Any], x: Any, y: Any,
               theta: Any) -> tuple[list[Any], list[list[Any]]]:
    """The leg equations |X + R a_i - B_i|^2 - l_i^2 and their Jacobian in (x, y, theta)."""
    c, s = MP.cos(theta), MP.sin(theta)
    res, jac = [], []
    for (ax, ay), (bx, by), leg2 in zip(local, bases, l2):
        vx, vy = x + c * ax - s * ay - bx, y + s * ax + c * ay - by
        res.append(vx * vx + vy * vy - leg2)
        jac.append([2 * vx, 2 * vy, 2 * (vx * (-s * ax - c * ay) + vy * (c * ax - s * ay))])
    return res, jac
