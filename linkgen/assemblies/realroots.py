"""The real roots of a polynomial with integer coefficients, isolated exactly and counted twice.

``isolate`` factors the polynomial over the integers (FLINT's ``fmpz_poly_factor``, through
python-flint) and isolates every complex root of each factor with arb
(``arb_fmpz_poly_complex_roots``: certified disjoint balls, a real root's imaginary part exactly
zero) at PRECISION bits, each ball far narrower than TIGHT of its size, with its factor's exponent as
its multiplicity.  Sturm's theorem (exact rational remainders, ``sturm_count``) counts the distinct
real roots again: the two must agree, and the balls be disjoint.  A root's isolating interval is
then its ball widened to SIMPLE of its size (MULTIPLE for a multiple root) about its midpoint, cut
a third of the way to the next balls: it holds that root and no other.  (The width matters to a caller that
checks a root polished at 50 digits against it: near theta = pi, where t = tan(theta / 2) is 1e16 and
more, the polished t is known to 1e-18 only, and a ball's 1e-44 would reject it.)
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

import flint

PRECISION = 200  # bits (60 digits): every root's ball narrower than TIGHT
TIGHT = Fraction(1, 10**50)  # a ball's width at most, relative to max(1, |root|)
SIMPLE = Fraction(1, 10**12)  # a simple root's interval, relative to max(1, |root|): Newton's start at 50 digits
MULTIPLE = Fraction(1, 10**45)  # a multiple root's: its midpoint is taken as the root (Newton converges slowly there)

Interval = tuple[Fraction, Fraction, int]  # (low, high, multiplicity)


def sturm_count(p: Any) -> int:
    """Distinct real roots of p (an fmpz_poly or fmpq_poly of degree >= 0, not zero) by Sturm's
    theorem: sign changes of the sequence p, p', -rem(p, p'), ... at -inf and at +inf."""
    seq = [flint.fmpq_poly(p)]
    step = seq[0].derivative()
    while not step.is_zero():
        seq.append(step)
        step = -(seq[-2] % seq[-1])

    def changes(signs: list[int]) -> int:
        return sum(1 for a, b in zip(signs, signs[1:]) if a != b)

    at_plus = [1 if g.leading_coefficient() > 0 else -1 for g in seq]
    at_minus = [s * (-1) ** g.degree() for s, g in zip(at_plus, seq)]
    return changes(at_minus) - changes(at_plus)


def isolate(p: Any) -> list[Interval]:
    """The real roots of the fmpz_poly p (degree >= 1) in increasing order: each an isolating
    interval of rationals (see the module's doc) and its multiplicity.  ArithmeticError where arb's
    isolation and Sturm's count disagree (never seen; it would be a bug in one of them)."""
    old, flint.ctx.prec = flint.ctx.prec, PRECISION
    try:
        found = p.complex_roots()
    finally:
        flint.ctx.prec = old
    out = sorted((_exact(z.real.mid()) - _exact(z.real.rad()), _exact(z.real.mid()) + _exact(z.real.rad()), int(m))
                 for z, m in found if z.imag == 0)
    count = sturm_count(p)
    if count != len(out):
        raise ArithmeticError(f"root isolation found {len(out)} real roots, Sturm's theorem {count}")
    for (_, high, _), (low, _, _) in zip(out, out[1:]):
        if not high < low:
            raise ArithmeticError("two real roots' isolating intervals overlap")
    for low, high, _ in out:
        if high - low > TIGHT * max(Fraction(1), abs(low), abs(high)):
            raise ArithmeticError(f"a real root isolated only to [{float(low)}, {float(high)}]")
    return [_widened(out, k) for k in range(len(out))]


def _widened(balls: list[Interval], k: int) -> Interval:
    """Root k's ball widened to SIMPLE (MULTIPLE) of its size about its midpoint, cut a third of the way
    to its neighbours' balls (no real root lies between two balls; the intervals stay disjoint)."""
    low, high, mult = balls[k]
    mid = (low + high) / 2
    half = (SIMPLE if mult == 1 else MULTIPLE) * max(Fraction(1), abs(mid)) / 2
    low, high = min(low, mid - half), max(high, mid + half)
    if k > 0:
        low = max(low, balls[k][0] - (balls[k][0] - balls[k - 1][1]) / 3)
    if k + 1 < len(balls):
        high = min(high, balls[k][1] + (balls[k + 1][0] - balls[k][1]) / 3)
    return low, high, mult


def _exact(x: Any) -> Fraction:
    """An arf (a ball's midpoint or radius) as the exact rational it is."""
    man, exp = (int(v) for v in x.man_exp())
    return Fraction(man * 2**exp) if exp >= 0 else Fraction(man, 2**-exp)
