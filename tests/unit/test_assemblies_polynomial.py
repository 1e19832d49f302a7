"""The triad's characteristic polynomial: it vanishes exactly at a pose built to close, has degree 6
(the factor (1 + t^2)^3 divided out: checked in sympy's arithmetic), and every root polished
satisfies the leg equations, checked here with mpmath from the data alone (the root counting itself:
test_assemblies_realroots.py)."""

from __future__ import annotations

import random
from fractions import Fraction

import mpmath
import numpy as np
import pytest
import sympy

from linkgen.assemblies.polynomial import characteristic, closure, solve
from linkgen.assemblies.triad import NotReducible

MP = mpmath.mp.clone()
MP.dps = 50
T = sympy.Symbol("t")


def _sympy(f) -> sympy.Poly:
    """linkgen's polynomial (python-flint's fmpz_poly) as sympy's, to check it by sympy's arithmetic."""
    return sympy.Poly([int(c) for c in reversed(f.coeffs())], T, domain="QQ")


def _mp(v: Fraction) -> mpmath.mpf:
    return MP.mpf(v.numerator) / v.denominator

# the Fig. 14 triad at its sketch: bases J1, J3, J6; the ternary's J2, J4, J5 (offsets from J2); legs squared
FIG14 = ([(Fraction(0), Fraction(0)), (Fraction(100), Fraction(0)), (Fraction(-60), Fraction(100))],
         [(Fraction(0), Fraction(0)), (Fraction(105), Fraction(-5)), (Fraction(60), Fraction(10))],
         [Fraction(70**2), Fraction(5**2 + 65**2), Fraction(120**2 + 20**2)])


def _posed(seed: int, t0: Fraction) -> tuple[list, list, list]:
    """Random integer bases and offsets, and leg lengths that make the ternary close at
    X = (x, y) turned by theta with tan(theta / 2) = t0 (cos and sin rational: exact)."""
    rng = random.Random(seed)
    bases = [(Fraction(rng.randint(-90, 90)), Fraction(rng.randint(-90, 90))) for _ in range(3)]
    local = [(Fraction(0), Fraction(0))] + [(Fraction(rng.randint(-60, 60)), Fraction(rng.randint(-60, 60)))
                                            for _ in range(2)]
    x, y = Fraction(rng.randint(-30, 30)), Fraction(rng.randint(-30, 30))
    c, s = (1 - t0 * t0) / (1 + t0 * t0), 2 * t0 / (1 + t0 * t0)
    lengths2 = [(x + c * ax - s * ay - bx) ** 2 + (y + s * ax + c * ay - by) ** 2
                for (ax, ay), (bx, by) in zip(local, bases)]
    return bases, local, lengths2


@pytest.mark.parametrize("seed", range(4))
def test_the_polynomial_vanishes_exactly_where_the_triad_closes_and_has_degree_6(seed):
    t0 = Fraction(seed + 2, 7)
    bases, local, lengths2 = _posed(seed, t0)
    f = _sympy(characteristic(bases, local, lengths2)[0])
    assert f.eval(sympy.Rational(t0.numerator, t0.denominator)) == 0
    assert f.degree() == 6
    one = sympy.Poly(1 - T**2, T, domain="QQ"), sympy.Poly(2 * T, T, domain="QQ"), sympy.Poly(1 + T**2, T, domain="QQ")
    raw, _ = closure(*one, bases, local, lengths2, lambda v: sympy.Rational(v.numerator, v.denominator))
    quotient, remainder = sympy.div(raw, f * sympy.Poly((1 + T**2) ** 3, T, domain="QQ"))
    assert remainder.is_zero and quotient.degree() == 0  # q^6 F is f (1 + t^2)^3 up to a constant


def test_the_closure_is_the_first_leg_equation_times_d_squared():
    """At any theta, F = D^2 E_1 with X from the two linear equations (Cramer), computed here in mpmath."""
    bases, local, lengths2 = FIG14
    theta = MP.mpf("0.7")
    c, s = MP.cos(theta), MP.sin(theta)
    f, d = closure(c, s, MP.mpf(1), bases, local, lengths2, _mp)
    b = [(_mp(bx), _mp(by)) for bx, by in bases]
    a = [(_mp(ax), _mp(ay)) for ax, ay in local]
    p = [(c * ax - s * ay, s * ax + c * ay) for ax, ay in a]
    rows = [[2 * ((p[i][0] - b[i][0]) - (p[0][0] - b[0][0])), 2 * ((p[i][1] - b[i][1]) - (p[0][1] - b[0][1]))]
            for i in (1, 2)]
    k = [(px - bx) ** 2 + (py - by) ** 2 - _mp(l2) for (px, py), (bx, by), l2 in zip(p, b, lengths2)]
    x = MP.lu_solve(MP.matrix(rows), MP.matrix([k[0] - k[1], k[0] - k[2]]))
    e1 = (x[0] + p[0][0] - b[0][0]) ** 2 + (x[1] + p[0][1] - b[0][1]) ** 2 - _mp(lengths2[0])
    assert abs(d - MP.det(MP.matrix(rows))) < MP.mpf(10) ** -40
    assert abs(f - d * d * e1) < MP.mpf(10) ** -30 * abs(f)


def _leg_errors(bases, local, lengths2, root):
    """The leg and ternary-side errors of a root's positions, in mpmath from the data."""
    p = [(MP.mpf(x), MP.mpf(y)) for x, y in root.positions]
    legs = [abs(MP.sqrt((px - _mp(bx)) ** 2 + (py - _mp(by)) ** 2) - MP.sqrt(_mp(l2)))
            for (px, py), (bx, by), l2 in zip(p, bases, lengths2)]
    sides = [abs(MP.hypot(p[i][0] - p[j][0], p[i][1] - p[j][1])
                 - MP.hypot(_mp(local[i][0] - local[j][0]), _mp(local[i][1] - local[j][1])))
             for i, j in ((0, 1), (0, 2), (1, 2))]
    return max(legs + sides)


def test_fig14_at_its_sketch_has_four_assemblies_one_the_sketch():
    sol = solve(*FIG14, 180.0)
    assert (sol.degree, sol.real_roots, sol.at_pi, len(sol.roots)) == (6, 4, False, 4)
    assert [r.theta for r in sol.roots] == sorted(r.theta for r in sol.roots)
    assert sol.roots[1].theta == 0.0 and sol.roots[1].positions == ((0.0, 70.0), (105.0, 65.0), (60.0, 80.0))
    for r in sol.roots:
        assert _leg_errors(*FIG14, r) < 1e-12 * 180 and r.error < 1e-40 and r.multiplicity == 1


@pytest.mark.parametrize("seed", range(3))
def test_a_root_at_half_a_turn_is_found_though_t_is_infinite_there(seed):
    """Turned by pi the pose has t = infinity: the degree drops to 5 and theta = pi is checked on its own."""
    rng = random.Random(seed)
    bases = [(Fraction(rng.randint(-90, 90)), Fraction(rng.randint(-90, 90))) for _ in range(3)]
    local = [(Fraction(0), Fraction(0))] + [(Fraction(rng.randint(-60, 60)), Fraction(rng.randint(-60, 60)))
                                            for _ in range(2)]
    x, y = Fraction(rng.randint(-30, 30)), Fraction(rng.randint(-30, 30))
    lengths2 = [(x - ax - bx) ** 2 + (y - ay - by) ** 2 for (ax, ay), (bx, by) in zip(local, bases)]
    sol = solve(bases, local, lengths2, 200.0)
    assert sol.at_pi and sol.degree == 5
    assert sol.roots[-1].theta == pytest.approx(np.pi, abs=1e-15)
    assert sol.roots[-1].positions[0] == pytest.approx((float(x), float(y)), abs=1e-12)
    for r in sol.roots:
        assert _leg_errors(bases, local, lengths2, r) < 1e-12 * 200


def test_a_triad_that_moves_with_its_legs_parallel_is_not_counted():
    """The ternary congruent to its base triangle, every leg as long: unturned it translates on a
    circle (a self-motion), so the root t = 0 is one where D vanishes too, and no count is given."""
    bases = [(Fraction(0), Fraction(0)), (Fraction(50), Fraction(0)), (Fraction(10), Fraction(40))]
    local = [(bx - bases[0][0], by - bases[0][1]) for bx, by in bases]
    with pytest.raises(NotReducible, match="special position"):
        solve(bases, local, [Fraction(30**2)] * 3, 60.0)


def test_a_pose_where_the_legs_meet_in_one_point_is_a_double_root():
    """The three legs' lines through one point: the pose is singular (two assemblies meet there), a
    double root of the polynomial, counted once and flagged, its positions those of the pose."""
    t0 = Fraction(1, 3)
    c, s = (1 - t0 * t0) / (1 + t0 * t0), 2 * t0 / (1 + t0 * t0)
    local = [(Fraction(0), Fraction(0)), (Fraction(40), Fraction(-10)), (Fraction(15), Fraction(30))]
    pose = [(5 + c * ax - s * ay, 7 + s * ax + c * ay) for ax, ay in local]
    meet = (Fraction(100), Fraction(-50))
    bases = [(px + k * (meet[0] - px), py + k * (meet[1] - py))
             for (px, py), k in zip(pose, (Fraction(2), Fraction(3, 2), Fraction(5, 2)))]
    lengths2 = [(px - bx) ** 2 + (py - by) ** 2 for (px, py), (bx, by) in zip(pose, bases)]
    sol = solve(bases, local, lengths2, 300.0)
    double = [r for r in sol.roots if r.multiplicity == 2]
    assert len(double) == 1 and double[0].theta == pytest.approx(2 * np.arctan(1 / 3), abs=1e-15)
    assert double[0].positions == tuple((float(x), float(y)) for x, y in pose)
    assert sol.real_roots == len(sol.roots)
