"""A triad with blocks on fixed slides: its polynomial against sympy's own elimination, its roots
against the legs' equations, theta = pi on its own, and its reading from tests/assemblies/slider_leg.yaml."""

from __future__ import annotations

import math
from fractions import Fraction
from pathlib import Path

import sympy

from linkgen.assemblies import whole_log
from linkgen.assemblies.polynomial import characteristic as revolute_characteristic
from linkgen.assemblies.slides import characteristic, solve
from linkgen.assemblies.triad import grid, snap, triad_of

ROOT = Path(__file__).resolve().parents[2]
F = Fraction
LOCAL = [(F(0), F(0)), (F(105), F(-5)), (F(60), F(10))]  # Fig. 14's ternary, J2 first (sketch (0, 70))
B1, L1 = (F(0), F(0)), F(70) ** 2  # rocker1 from J1
B3, L3 = (F(-60), F(100)), F(120) ** 2 + F(20) ** 2  # the coupler from J6 (at the sketch)
N = (F(-1), F(5))  # the slide's normal (not a unit vector: any normal is the line's)
D = N[0] * 105 + N[1] * 65  # through J4's sketch position


def _sympy_eliminant(local, holds):
    """The closure's numerator in t by sympy's own route: the equations in (x, y, t), the revolute ones
    less the first, sympy's solve for (x, y), substituted into the first, (1 + t^2) divided out."""
    x, y, t = sympy.symbols("x y t")
    c, s = (1 - t**2) / (1 + t**2), 2 * t / (1 + t**2)
    eqs, first = [], None
    for (ax, ay), h in zip(local, holds):
        px, py = x + c * ax - s * ay, y + s * ax + c * ay
        if len(h) == 2:
            e = (px - h[0][0]) ** 2 + (py - h[0][1]) ** 2 - h[1]
            if first is None:
                first = e
                continue
            eqs.append(sympy.expand(e - first))
        else:
            eqs.append(h[0][0] * px + h[0][1] * py - h[1])
    sol = sympy.solve(eqs, [x, y], dict=True)[0]
    num = sympy.numer(sympy.together(first.subs(sol)))
    p = sympy.Poly(num, t)
    q = sympy.Poly(1 + t**2, t)
    while p.rem(q).is_zero:
        p = p.quo(q)
    return sympy.Poly(p.as_expr(), sympy.Symbol("t"))


def _sympy(f) -> sympy.Poly:
    """linkgen's polynomial (python-flint's fmpz_poly) as sympy's."""
    return sympy.Poly([int(c) for c in reversed(f.coeffs())], sympy.Symbol("t"))


def test_the_polynomial_is_sympys_elimination_for_one_and_two_slides():
    for holds in ([(B1, L1), (N, D, "slide"), (B3, L3)],
                  [(B1, L1), (N, D, "slide"), ((F(1), F(1)), F(130), "slide")]):
        f = _sympy(characteristic(LOCAL, holds)[0])
        g = _sympy_eliminant(LOCAL, holds)
        assert f.degree() == g.degree() == (6 if len(holds[2]) == 2 else 4) and (f.monic() - g.monic()).is_zero


def test_with_revolute_legs_only_it_is_the_triads_polynomial():
    holds = [(B1, L1), ((F(100), F(0)), F(65) ** 2 + F(5) ** 2), (B3, L3)]
    f = _sympy(characteristic(LOCAL, holds)[0])
    g = _sympy(revolute_characteristic([h[0] for h in holds], LOCAL, [h[1] for h in holds])[0])
    assert (f.monic() - g.monic()).is_zero and f.degree() == 6


def _check(local, holds, sol):
    for r in sol.roots:
        for (px, py), h in zip(r.positions, holds):
            if len(h) == 2:
                assert abs(math.hypot(px - h[0][0], py - h[0][1]) - math.sqrt(h[1])) < 1e-12 * 200
            else:
                assert abs(float(h[0][0]) * px + float(h[0][1]) * py - float(h[1])) / math.hypot(*h[0]) < 1e-12 * 200
        (x0, y0), (x1, y1) = r.positions[0], r.positions[1]
        turned = math.atan2(y1 - y0, x1 - x0) - math.atan2(float(local[1][1]), float(local[1][0]))
        assert abs(math.remainder(turned - r.theta, 2 * math.pi)) < 1e-12


def test_every_root_holds_the_legs_and_the_count_is_the_polynomials_real_roots():
    holds = [(B1, L1), (N, D, "slide"), (B3, L3)]
    sol = solve(LOCAL, holds, 200.0)
    g = _sympy_eliminant(LOCAL, holds)
    assert sol.degree == 6 and sol.real_roots == len(set(sympy.real_roots(g))) == len(sol.roots)
    assert min(abs(r.theta) for r in sol.roots) < 1e-15  # the sketch itself
    _check(LOCAL, holds, sol)


def test_half_a_turn_is_found_on_its_own():
    """Legs made for the ternary turned by pi about J2 at (10, 20): theta = pi is a root, t infinite."""
    turned = [(10 - ax, 20 - ay) for ax, ay in LOCAL]
    b3 = (F(-60), F(100))
    holds = [(B1, F(10) ** 2 + F(20) ** 2), (N, N[0] * turned[1][0] + N[1] * turned[1][1], "slide"),
             (b3, (turned[2][0] - b3[0]) ** 2 + (turned[2][1] - b3[1]) ** 2)]
    sol = solve(LOCAL, holds, 200.0)
    assert sol.at_pi and sol.degree < 6 and any(r.theta == math.pi for r in sol.roots)
    assert sol.real_roots + 1 == len(sol.roots)
    _check(LOCAL, holds, sol)
    at = next(r for r in sol.roots if r.theta == math.pi)
    assert max(abs(p - float(q)) for a, b in zip(at.positions, turned) for p, q in zip(a, b)) < 1e-12


def test_slider_legs_block_is_a_leg_on_the_line_of_its_slide():
    log = whole_log(str(ROOT / "tests" / "assemblies" / "slider_leg.yaml"))
    t = triad_of(log, log.groups[0])
    (block,) = [leg for leg in t.legs if leg.line]
    assert (block.carrier, block.pair, block.base) == ("block", "J4", "S")
    n, d = block.line
    axis = math.radians(80)
    assert float(n[0]) == -math.sin(axis) and float(n[1]) == math.cos(axis)
    unit = grid(log.length_scale)
    assert d == n[0] * snap(105 - log.origin[0], unit) + n[1] * snap(65 - log.origin[1], unit)
    assert "block on the slide S" in t.describe()
