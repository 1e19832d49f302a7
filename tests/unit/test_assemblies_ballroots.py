"""linkgen.assemblies.ballroots: the real roots of polynomials built from known roots (exactly, in
fractions), negative coefficients included; None for a double root (arb cannot isolate it)."""

from __future__ import annotations

from fractions import Fraction

import mpmath
import pytest

from linkgen.assemblies.ballroots import real_roots

MP = mpmath.mp.clone()
MP.dps = 50


def _from_roots(real: list[Fraction], pairs: list[tuple[Fraction, Fraction]]) -> list:
    """Coefficients (mpf, highest first) of prod (t - r) prod ((t - a)^2 + b^2), exact in fractions."""
    poly = [Fraction(1)]
    factors = [[Fraction(1), -r] for r in real] + [[Fraction(1), -2 * a, a * a + b * b] for a, b in pairs]
    for f in factors:
        out = [Fraction(0)] * (len(poly) + len(f) - 1)
        for i, x in enumerate(poly):
            for j, y in enumerate(f):
                out[i + j] += x * y
        poly = out
    return [MP.mpf(c.numerator) / c.denominator for c in poly]


@pytest.mark.parametrize("real, pairs", [
    ([Fraction(-3, 7), Fraction(1, 3), Fraction(5, 2), Fraction(-11)], [(Fraction(1, 2), Fraction(1, 5))]
     + [(Fraction(-2), Fraction(3))]),
    ([Fraction(1, 1000), Fraction(2, 1000)], [(Fraction(0), Fraction(1)), (Fraction(3), Fraction(1, 100))]),
    ([], [(Fraction(1), Fraction(1)), (Fraction(-1), Fraction(2))]),
])
def test_the_real_roots_of_a_polynomial_of_known_roots(real, pairs):
    found = real_roots(_from_roots(real, pairs), MP)
    assert found is not None and len(found) == len(real)
    for x, r in zip(sorted(found), sorted(real)):
        assert abs(x - MP.mpf(r.numerator) / r.denominator) < MP.mpf(10) ** -40


def test_a_double_root_is_left_to_the_caller():
    assert real_roots(_from_roots([Fraction(1, 3), Fraction(1, 3), Fraction(2)], [(Fraction(0), Fraction(1))]),
                      MP) is None
