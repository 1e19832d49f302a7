"""A triad with blocks on fixed slides: its closure as one polynomial, real roots certified, then polished.

As in ``polynomial``, the ternary's pairs sit at ``P_i = X + R(theta) a_i``.  A revolute leg holds
P_i at l_i from the known B_i, a block on a slide fixed to the frame keeps it on a line:

    |P_i - B_i|^2 = l_i^2   (revolute),      n_i . P_i = d_i   (slide).

The first revolute leg's equation is kept whole (at least one is needed); the others give two
equations linear in X: a revolute leg's less the kept one, ``2 (w_i - w_r) . X = k_r - k_i``
(w_i = R a_i - B_i, k_i = |w_i|^2 - l_i^2), and a slide's as it is, ``n_i . X = d_i - n_i . R a_i``.
Cramer's rule gives ``X = N / D`` and the kept equation times D^2,

    F = |N|^2 + 2 D N.w_r + k_r D^2 = 0,

is one equation in theta.  With ``t = tan(theta / 2)`` every row is written over q = 1 + t^2 so
that q^6 F is a polynomial in t with exact rational coefficients; its factors (1 + t^2) carry no
real root and are divided out: degree 6 for one slide, as the revolute triad's, and 4 for two (X is
then linear in cos theta and sin theta, the kept circle quadratic in them).
Roots are isolated and counted as the triad's are (``realroots``: arb's isolation checked by
Sturm's theorem), theta = pi checked on its own, every root polished
by Newton's method on the three leg equations at 50 digits and kept only inside its interval.
"""

from __future__ import annotations

from collections.abc import Callable
from fractions import Fraction
from typing import Any

from .polynomial import MP, NEWTON_STEPS, QUARTER, primitive, rational, scaled, special
from .realroots import Interval, isolate
from .roots import Root, Solution
from .triad import Exact, NotReducible

Hold = tuple[Exact, Fraction] | tuple[Exact, Fraction, str]  # (B, l^2) revolute; (n, d, "slide") a slide


def closure(c: Any, s: Any, q: Any, local: list[Exact], holds: list[Hold], num: Callable[[Fraction], Any]) -> tuple[
        Any, Any]:
    """(q^6 F, q^2 D) for cos theta = c / q and sin theta = s / q, in any ring that holds c, s, q and the
    numbers ``num`` makes of the data."""
    turned = [(c * num(ax) - s * num(ay), s * num(ax) + c * num(ay)) for ax, ay in local]  # q R a_i
    kept = next((i for i, h in enumerate(holds) if len(h) == 2), None)
    if kept is None:
        raise NotReducible("every leg of the triad is a block on a slide; linkgen needs one revolute leg")
    w: dict[int, tuple[Any, Any]] = {}
    k: dict[int, Any] = {}
    for i, h in enumerate(holds):
        if len(h) == 2:
            (bx, by), l2 = h[0], h[1]
            w[i] = (turned[i][0] - q * num(bx), turned[i][1] - q * num(by))  # q w_i
            k[i] = w[i][0] * w[i][0] + w[i][1] * w[i][1] - q * q * num(l2)  # q^2 k_i
    rows = []  # (q A, q^2 b) of A X = b
    for i, h in enumerate(holds):
        if i == kept:
            continue
        if len(h) == 2:
            rows.append(((2 * (w[i][0] - w[kept][0]), 2 * (w[i][1] - w[kept][1])), k[kept] - k[i]))
        else:
            (nx, ny), d = h[0], h[1]
            along = num(nx) * turned[i][0] + num(ny) * turned[i][1]  # q n_i . R a_i
            rows.append(((q * num(nx), q * num(ny)), q * (q * num(d) - along)))
    (m0, r0), (m1, r1) = rows
    d = m0[0] * m1[1] - m0[1] * m1[0]  # q^2 D
    x = r0 * m1[1] - r1 * m0[1]  # q^3 N
    y = m0[0] * r1 - m1[0] * r0
    wk = w[kept]
    f = x * x + y * y + 2 * d * (x * wk[0] + y * wk[1]) + k[kept] * d * d
    return f, d


def characteristic(local: list[Exact], holds: list[Hold]) -> tuple[Any, Any]:
    """The characteristic polynomial in t (the factors 1 + t^2 divided out; an fmpz_poly, primitive)
    and q^2 D (an fmpq_poly)."""
    f, d = closure(*QUARTER, local, holds, rational)
    if f == 0 or d == 0:
        raise NotReducible("the triad's equations do not fix it at this position (its slides parallel, or its "
                           "pairs coincident)")
    return primitive(f), d


def solve(local: list[Exact], holds: list[Hold], scale: float) -> Solution:
    """Every assembly of the triad with these legs (positions in the programs' coordinates)."""
    f, d = characteristic(local, holds)
    if special(f, d):
        raise NotReducible("the triad is at a special position here (a root where its legs' equations lose rank)")
    f_pi, d_pi = closure(Fraction(-1), Fraction(0), Fraction(1), local, holds, lambda x: x)
    if f_pi == 0 and d_pi == 0:
        raise NotReducible("the triad is at a special position here (turned half a turn, its legs' equations lose "
                           "rank)")
    if f.degree() < 1:
        raise NotReducible("the triad's polynomial is a constant here: it has no isolated assembly")
    intervals = isolate(f)
    roots = [polish(local, holds, (low + high) / 2, (low, high, mult), scale) for low, high, mult in intervals]
    if f_pi == 0:
        roots.append(polish(local, holds, None, None, scale))
    return Solution(f.degree(), len(intervals), f_pi == 0, tuple(sorted(roots, key=lambda r: r.theta)),
                    scaled(f))


def _mp(x: Fraction) -> Any:
    return MP.mpf(x.numerator) / x.denominator


def polish(local: list[Exact], holds: list[Hold], t: Fraction | None, interval: Interval | None, scale: float) -> Root:
    """Newton on the leg equations in (X, theta) at 50 digits from the root t in its isolating
    interval (None: theta = pi; a multiple root is t itself)."""
    multiplicity = 1 if interval is None else interval[2]
    size = MP.mpf(scale)
    a = [(_mp(x), _mp(y)) for x, y in local]
    data = [((_mp(h[0][0]), _mp(h[0][1])), _mp(h[1]), len(h) == 2) for h in holds]
    theta = MP.pi if t is None else 2 * MP.atan(_mp(t))
    x, y = _start(a, data, theta)
    for _ in range(NEWTON_STEPS if multiplicity == 1 else 0):
        res, jac = equations(a, data, x, y, theta, size)
        step = MP.lu_solve(MP.matrix(jac), MP.matrix(res))
        x, y, theta = x - step[0], y - step[1], theta - step[2]
        if max(abs(step[0]) / size, abs(step[1]) / size, abs(step[2])) < MP.mpf(10) ** (5 - MP.dps):
            break
    else:
        if multiplicity == 1:
            raise ArithmeticError(f"Newton's method did not converge from the root at t = {t}")
    res, _ = equations(a, data, x, y, theta, size)
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
    pos = [(float(x + c * ax - s * ay), float(y + s * ax + c * ay)) for ax, ay in a]
    return Root(float(theta) if theta > -MP.pi else float(MP.pi), multiplicity, (pos[0], pos[1], pos[2]),
                float(error))


Data = list[tuple[tuple[Any, Any], Any, bool]]  # (B, l^2, True) or (n, d, False), at 50 digits


def _start(a: list[tuple[Any, Any]], data: Data, theta: Any) -> tuple[Any, Any]:
    """X from the two equations linear in it at theta (as ``closure`` forms them)."""
    c, s = MP.cos(theta), MP.sin(theta)
    turned = [(c * ax - s * ay, s * ax + c * ay) for ax, ay in a]
    kept = next(i for i, h in enumerate(data) if h[2])

    def w(i: int) -> tuple[Any, Any]:
        return turned[i][0] - data[i][0][0], turned[i][1] - data[i][0][1]

    def k(i: int) -> Any:
        return w(i)[0] ** 2 + w(i)[1] ** 2 - data[i][1]

    rows, rhs = [], []
    for i, (v, d, revolute) in enumerate(data):
        if i == kept:
            continue
        if revolute:
            rows.append([2 * (w(i)[0] - w(kept)[0]), 2 * (w(i)[1] - w(kept)[1])])
            rhs.append(k(kept) - k(i))
        else:
            rows.append([v[0], v[1]])
            rhs.append(d - v[0] * turned[i][0] - v[1] * turned[i][1])
    sol = MP.lu_solve(MP.matrix(rows), MP.matrix(rhs))
    return sol[0], sol[1]


def equations(a: list[tuple[Any, Any]], data: Data, x: Any, y: Any, theta: Any,
              size: Any) -> tuple[list[Any], list[list[Any]]]:
    """The legs' equations and their Jacobian in (x, y, theta): |P_i - B_i|^2 - l_i^2, and a slide's
    (n_i . P_i - d_i) times the length scale (both in L^2)."""
    c, s = MP.cos(theta), MP.sin(theta)
    res, jac = [], []
    for (ax, ay), (v, d, revolute) in zip(a, data):
        px, py = x + c * ax - s * ay, y + s * ax + c * ay
        dx, dy = -s * ax - c * ay, c * ax - s * ay  # dP / dtheta
        if revolute:
            vx, vy = px - v[0], py - v[1]
            res.append(vx * vx + vy * vy - d)
            jac.append([2 * vx, 2 * vy, 2 * (vx * dx + vy * dy)])
        else:
            res.append(size * (v[0] * px + v[1] * py - d))
            jac.append([size * v[0], size * v[1], size * (v[0] * dx + v[1] * dy)])
    return res, jac
