"""linkgen.assemblies.realroots: real roots isolated by arb, counted by Sturm's theorem, against
closed forms and sympy's exact isolation (Vincent-Akritas-Strzebonski) as the independent route."""

from __future__ import annotations

import random
from fractions import Fraction

import flint
import pytest
import sympy

from linkgen.assemblies import realroots
from linkgen.assemblies.realroots import isolate, sturm_count

X = flint.fmpz_poly([0, 1])


def test_closed_form_roots_and_multiplicities() -> None:
    """(x^2 - 2)(3x - 1)^2 (x + 5)(x^2 + 1): -5, -sqrt 2, 1/3 twice, sqrt 2; no root of x^2 + 1."""
    p = (X**2 - 2) * (3 * X - 1) ** 2 * (X + 5) * (X**2 + 1)
    found = isolate(p)
    assert [m for _, _, m in found] == [1, 1, 2, 1]
    (a5, b5, _), (am, bm, _), (a3, b3, _), (ap, bp, _) = found
    assert a5 <= -5 <= b5
    assert am**2 > 2 > bm**2 and bm < 0  # -sqrt 2 inside (negative numbers: squares reversed)
    assert a3 <= Fraction(1, 3) <= b3
    assert ap**2 < 2 < bp**2 and ap > 0
    for low, high, mult in found:
        width = realroots.SIMPLE if mult == 1 else realroots.MULTIPLE
        assert high - low <= width * max(Fraction(1), abs(low), abs(high))
    assert sturm_count(p) == 4
    _each_holds_one_root(p, found)


def _each_holds_one_root(p, found) -> None:
    """Each interval holds exactly one distinct real root (sympy's exact count) and they are disjoint."""
    poly = sympy.Poly([int(c) for c in reversed(p.coeffs())], sympy.Symbol("t"), domain="ZZ")
    for low, high, _ in found:
        assert poly.count_roots(sympy.Rational(low.numerator, low.denominator),
                                sympy.Rational(high.numerator, high.denominator)) == 1
    assert all(a[1] < b[0] for a, b in zip(found, found[1:]))


def test_a_huge_root_gets_a_relative_interval() -> None:
    """A root near 1e17 (a triad near half a turn: t = tan(theta / 2)) is isolated to 1e-12 of its size,
    not to arb's 1e-44: a root polished at 50 digits, known there to 1e-18, falls inside it."""
    big = 10**17 + 3
    found = isolate((X - big) * (7 * X + 2))
    low, high, _ = found[1]
    assert low < big < high and high - low > realroots.SIMPLE * big / 4
    _each_holds_one_root((X - big) * (7 * X + 2), found)

def test_no_real_root() -> None:
    p = (X**2 + 1) * (X**2 + X + 7)
    assert isolate(p) == []
    assert sturm_count(p) == 0


def test_clustered_roots_are_told_apart() -> None:
    """Roots 1e-30 apart are two roots, each interval holding its own."""
    n = 10**30
    p = (n * X - n) * (n * X - (n + 1)) * (X - 3)
    found = isolate(p)
    assert len(found) == 3
    assert found[0][0] <= 1 <= found[0][1] < found[1][0] <= Fraction(n + 1, n) <= found[1][1]
    _each_holds_one_root(p, found)


@pytest.mark.parametrize("seed", range(6))
def test_against_sympy(seed: int) -> None:
    """Random integer polynomials of degree 6 to 12 (some with repeated factors): the same distinct real
    roots with the same multiplicities as sympy's exact isolation, each of our intervals inside sympy's
    refined one or holding its midpoint."""
    rng = random.Random(seed)
    t = sympy.Symbol("t")
    coeffs = [rng.randint(-50, 50) for _ in range(rng.randint(4, 7))]
    base = flint.fmpz_poly(coeffs or [1])
    p = base * (X - rng.randint(-3, 3)) ** 2 * flint.fmpz_poly([rng.randint(-9, 9), rng.randint(1, 9)])
    ref = sympy.Poly([int(c) for c in reversed(p.coeffs())], t, domain="ZZ").intervals(eps=sympy.Rational(1, 10**30))
    found = isolate(p)
    assert len(found) == len(ref) == sturm_count(p)
    for (low, high, mult), ((a, b), m) in zip(found, ref):
        assert mult == m
        a, b = Fraction(int(a.p), int(a.q)), Fraction(int(b.p), int(b.q))
        assert max(low, a) <= min(high, b)  # the two isolating intervals of one root meet
    _each_holds_one_root(p, found)


def test_sturm_count_of_rational_polynomial() -> None:
    """An fmpq_poly: (t - 1/2)(t + 2/3)(t^2 - 3) has four real roots; t^2 (t^2 + 1) one."""
    t = flint.fmpq_poly([0, 1])
    assert sturm_count((t - flint.fmpq(1, 2)) * (t + flint.fmpq(2, 3)) * (t**2 - 3)) == 4
    assert sturm_count(t**2 * (t**2 + 1)) == 1
    assert sturm_count(flint.fmpq_poly([5])) == 0


def test_disagreement_is_an_error(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(realroots, "sturm_count", lambda p: 3)
    with pytest.raises(ArithmeticError, match="Sturm's theorem 3"):
        isolate(X**2 - 2)
