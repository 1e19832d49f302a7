"""linkgen.assemblies.pivoted: each tie's polynomial is, exactly, sympy's tangent half-angle form of
its trigonometric equation; the eliminant is sympy's own resultant of those; every assembly solve
returns keeps both equations (evaluated here in floating point from the file's numbers)."""

from __future__ import annotations

import math
from fractions import Fraction
from pathlib import Path

import flint
import sympy

from linkgen.assemblies import whole_log
from linkgen.assemblies.pivoted import NAMES, equations, polynomial, solve
from linkgen.assemblies.pivots import pivoted_of
from linkgen.assemblies.triad import grid, snap

ROOT = Path(__file__).resolve().parents[2]
SLOT = ROOT / "tests" / "regressions" / "class4_slot.yaml"
T0, T1 = sympy.symbols("t0 t1")


def _setup(pivots_at=((0.0, 0.0), (100.0, 20.0))):
    log = whole_log(str(SLOT))
    shape = pivoted_of(log, log.groups[0])
    unit = grid(log.length_scale)
    pivots = [(snap(x - log.origin[0], unit), snap(y - log.origin[1], unit)) for x, y in pivots_at]
    return log, shape, unit, pivots


def _sympy_form(eq):
    """q_0 q_1 times the tie's trigonometric equation, built from cos and sin with sympy."""
    terms, l2, k, normal = eq
    t = (T0, T1)
    cos = [(1 - x**2) / (1 + x**2) for x in t]
    sin = [2 * x / (1 + x**2) for x in t]
    vx = vy = sympy.Integer(0)
    for m, (ax, ay) in terms:
        if m is None:
            vx, vy = vx + ax, vy + ay
        else:
            vx, vy = vx + cos[m] * ax - sin[m] * ay, vy + sin[m] * ax + cos[m] * ay
    if normal is None:
        e = vx**2 + vy**2 - l2
    else:
        e = (cos[k] * normal[0] - sin[k] * normal[1]) * vx + (sin[k] * normal[0] + cos[k] * normal[1]) * vy
    return sympy.Poly(sympy.cancel(e * (1 + T0**2) * (1 + T1**2)), T0, T1)


def _as_sympy(p):
    return sympy.Poly(sum(int(c) * T0 ** int(e[0]) * T1 ** int(e[1]) for e, c in p.to_dict().items()), T0, T1)


def test_each_ties_polynomial_is_its_half_angle_form_and_the_eliminant_sympys_resultant():
    _, shape, unit, pivots = _setup()
    ctx = flint.fmpz_mpoly_ctx.get(NAMES, "lex")
    eqs = equations(shape, pivots, unit)
    mine = [polynomial(ctx, e) for e in eqs]
    theirs = [_sympy_form(e) for e in eqs]
    for a, b in zip(mine, theirs):
        assert _as_sympy(a) == b and a.degrees() == (2, 2)
    res = sympy.Poly(sympy.resultant(theirs[0].as_expr(), theirs[1].as_expr(), T1), T0)
    flint_res = sympy.Poly(_as_sympy(mine[0].resultant(mine[1], "t1")).as_expr(), T0)
    assert res.primitive()[1] == flint_res.primitive()[1] or res.primitive()[1] == -flint_res.primitive()[1]


def test_every_assembly_keeps_both_ties():
    """At the sketch's pivots: two assemblies, the sketch's (no turn) one; the other keeps upper's
    length and C on right's slot (from the file's numbers, in floating point)."""
    log, shape, unit, pivots = _setup()
    count = solve(shape, pivots, unit, log.length_scale)
    assert count.real_roots == 2 and count.degree == 6 and count.rejected == 0
    assert any(max(abs(a) for a in r.angles) < 1e-15 for r in count.roots)
    for r in count.roots:
        a, b = r.angles
        p = dict(zip(shape.pairs, r.positions))
        o2 = (100.0 - log.origin[0], 20.0 - log.origin[1])
        assert abs(math.hypot(p["B"][0] - p["E"][0], p["B"][1] - p["E"][1]) - math.hypot(50, 20)) < 1e-12
        n = (-math.sin(math.radians(30) + b), math.cos(math.radians(30) + b))
        s0 = (o2[0] + math.cos(b) * -40.0, o2[1] + math.sin(b) * -40.0)  # C's sketch place on right, turned
        assert abs(n[0] * (p["C"][0] - s0[0]) + n[1] * (p["C"][1] - s0[1])) < 1e-12
        assert abs(math.hypot(p["B"][0] + log.origin[0], p["B"][1] + log.origin[1]) - math.hypot(30, 60)) < 1e-12
        assert a == r.theta


def test_an_assembly_with_the_first_link_turned_half_a_turn_is_found_on_its_own():
    """Ties made to close exactly at theta_0 = pi (t_0 infinite: no root of the eliminant) and
    tan(theta_1 / 2) = 1/2 (cos 3/5, sin 4/5): the solve finds that assembly, from the equations'
    coefficients of t_0^2, and says so."""
    from linkgen.assemblies.pivots import Pivoted, Tie

    def turned(v, c, s):
        return (c * v[0] - s * v[1], s * v[0] + c * v[1])

    f = Fraction
    p0, p1 = (f(0), f(0)), (f(100), f(20))
    c1, s1 = f(3, 5), f(4, 5)
    a, b, a2, b2 = (f(30), f(60)), (f(-20), f(60)), (f(60), f(20)), (f(-40), f(0))

    def v(x, y):  # P_0 + R(pi) x - P_1 - R(theta_1) y
        ry = turned(y, c1, s1)
        return (p0[0] - x[0] - p1[0] - ry[0], p0[1] - x[1] - p1[1] - ry[1])

    link = v(a, b)
    w = v(a2, b2)
    normal = turned((-w[1], w[0]), c1, -s1)  # R(-theta_1) of w's normal: R(theta_1) n . w = 0
    shape = Pivoted(1, ("left", "right"), ("P0", "P1"),
                    (Tie("upper", 0, a, b, link[0] ** 2 + link[1] ** 2), Tie("block", 0, a2, b2, f(0), normal)), (), ())
    count = solve(shape, [p0, p1], f(1, 625), 100.0)
    assert count.at_pi
    assert any(abs(abs(r.angles[0]) - math.pi) < 1e-15 and abs(r.angles[1] - 2 * math.atan(0.5)) < 1e-15
               for r in count.roots)
