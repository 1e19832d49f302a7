"""linkgen.assemblies.resultant, the class-IV route, on a small two-body group built to close at a
rational pose: the equations and the eliminant vanish exactly there, the pose is among the
assemblies found, every assembly keeps the six distances (recomputed here in mpmath from the
data alone), and the count agrees with a 50-digit multistart search (tests/assembly_oracle.py;
long: 20 s a group).  Sympy's Sturm count of the eliminant's real roots is not run: on its
degree-192 eliminant it took minutes."""

from __future__ import annotations

import math
import random
from fractions import Fraction
from pathlib import Path

import flint
import mpmath
import pytest
from assembly_oracle import bodies_search

from linkgen.assemblies.bodies import Body, Coupler, TwoBodies
from linkgen.assemblies.resultant import NAMES, eliminate, equations, polynomial, solve, univariate

ROOT = Path(__file__).resolve().parents[2]
MP = mpmath.mp.clone()
MP.dps = 50
UNIT = Fraction(1, 625)  # rotations by t = 1/2, 1/3, 2, 3 have cos, sin in fifths: the data stay on this grid


def _rot(t: Fraction | None, v: tuple[Fraction, Fraction]) -> tuple[Fraction, Fraction]:
    """v turned by the angle of tangent half-angle t (None: half a turn)."""
    c, s = (Fraction(-1), Fraction(0)) if t is None else ((1 - t * t) / (1 + t * t), 2 * t / (1 + t * t))
    return c * v[0] - s * v[1], s * v[0] + c * v[1]


def _posed(seed: int, turns: tuple[Fraction | None, ...] = (Fraction(1, 2), Fraction(1, 3), Fraction(2), Fraction(3))):
    """Two bodies (three pairs each) with integer sketch data, closed at phi_L, theta_L, phi_R, theta_R
    of tangents ``turns`` (exact); the legs' and couplers' lengths are those of that pose."""
    rng = random.Random(seed)

    def pt(r: int = 60) -> tuple[Fraction, Fraction]:
        return Fraction(rng.randint(-r, r)), Fraction(rng.randint(-r, r))

    bases = [pt(), pt()] + [(x + 150, y) for x, y in (pt(), pt())]  # body 1's bases right of body 0's
    made, where = [], []
    for k in (0, 1):
        leg, local = pt(40), [(Fraction(0), Fraction(0)), pt(30), pt(30)]
        g = bases[2 * k]
        turned = _rot(turns[2 * k], leg)
        anchor = (g[0] + turned[0], g[1] + turned[1])
        spots = [(anchor[0] + x, anchor[1] + y) for x, y in (_rot(turns[2 * k + 1], a) for a in local)]
        h = bases[2 * k + 1]
        d = (spots[1][0] - h[0], spots[1][1] - h[1])
        made.append(Body(f"body{k}", f"G{k}", f"P{k}", leg, f"H{k}", local[1], d[0] ** 2 + d[1] ** 2,
                         (f"leg{k}", f"other{k}"), (f"P{k}", f"Q{k}", f"R{k}"), tuple(local)))
        where.append(spots)
    ties = []
    for j in (1, 2):
        a, b = where[0][j], where[1][j]
        ties.append(Coupler(f"c{j}", made[0].local[j], made[1].local[j], (a[0] - b[0]) ** 2 + (a[1] - b[1]) ** 2))
    return TwoBodies(1, (made[0], made[1]), (ties[0], ties[1])), bases, turns


def _distances(bodies, bases, a) -> list[float]:
    """The six distance errors of an assembly's pair positions over the group's size, in mpmath."""
    pos = dict(zip(bodies.pairs, a.positions))
    (left, right), out = bodies.bodies, []
    for k, body in enumerate((left, right)):
        for pair, base, offset in ((body.pair, bases[2 * k], body.leg), (body.pairs[1], bases[2 * k + 1], None)):
            length2 = offset[0] ** 2 + offset[1] ** 2 if offset else body.length2
            x, y = (MP.mpf(v) for v in pos[pair])
            out.append(abs(MP.sqrt((x - MP.mpf(base[0].numerator) / base[0].denominator) ** 2
                                   + (y - MP.mpf(base[1].numerator) / base[1].denominator) ** 2)
                           - MP.sqrt(MP.mpf(length2.numerator) / length2.denominator)))
    for j, c in zip((1, 2), bodies.couplers):
        (x, y), (u, v) = pos[left.pairs[j]], pos[right.pairs[j]]
        out.append(abs(math.hypot(x - u, y - v) - math.sqrt(c.length2)))
    return [float(e) / 200 for e in out]


def _at(p, values) -> Fraction:
    """The integer polynomial p at exact values of its unknowns."""
    return sum((Fraction(int(c)) * math.prod(v ** int(e) for v, e in zip(values, exps))
                for exps, c in p.to_dict().items()), Fraction(0))


@pytest.mark.parametrize("seed", [3])
def test_the_eliminant_vanishes_at_the_pose_and_every_assembly_is_one(seed):
    bodies, bases, turns = _posed(seed)
    ctx = flint.fmpz_mpoly_ctx.get(NAMES, "lex")
    polys = [polynomial(ctx, *e) for e in equations(bodies, bases, UNIT)]
    assert all(_at(p, turns) == 0 for p in polys)
    s1, s2, eliminant = eliminate(*polys, ctx)
    assert eliminant == univariate(s1.resultant(s2, "tR"), 1)  # interpolated: FLINT's own resultant
    t_l = turns[1]
    assert sum(int(c) * t_l ** k for k, c in enumerate(eliminant.coeffs())) == 0
    count = solve(bodies, tuple(bases), UNIT, 200.0)
    assert any(max(abs(math.remainder(a - 2 * math.atan(float(t)), 2 * math.pi)) for a, t in zip(r.angles, turns))
               < 1e-12 for r in count.roots)
    assert all(max(_distances(bodies, bases, r)) < 1e-12 for r in count.roots)


@pytest.mark.long
@pytest.mark.parametrize("seed", [3, 5])
def test_the_small_groups_count_is_the_multistart_searchs(seed):
    bodies, bases, _ = _posed(seed)
    count = solve(bodies, tuple(bases), UNIT, 200.0)
    left, right = bodies.bodies

    def mp(v):
        return MP.mpf(v.numerator) / v.denominator

    local = [[(mp(x), mp(y)) for x, y in b.local] for b in (left, right)]
    legs = []
    for k, b in enumerate((left, right)):
        legs.append((k, 0, (mp(bases[2 * k][0]), mp(bases[2 * k][1])), mp(b.leg[0] ** 2 + b.leg[1] ** 2)))
        legs.append((k, 1, (mp(bases[2 * k + 1][0]), mp(bases[2 * k + 1][1])), mp(b.length2)))
    ties = [(j, j, mp(c.length2)) for j, c in zip((1, 2), bodies.couplers)]
    assert len(bodies_search(local, legs, ties)) == len(count.roots)


def test_an_assembly_with_the_first_body_turned_half_a_turn_is_found_on_its_own():
    """theta_L = pi is t_L = infinity, no root of the eliminant: the equations' leading coefficients
    in t_L find it."""
    bodies, bases, turns = _posed(3, (Fraction(1, 2), None, Fraction(2), Fraction(3)))
    count = solve(bodies, tuple(bases), UNIT, 200.0)
    assert count.at_pi
    (half,) = [r for r in count.roots if abs(abs(r.theta) - math.pi) < 1e-12]
    assert half.angles[0] == pytest.approx(2 * math.atan(0.5), abs=1e-12)
    assert all(max(_distances(bodies, bases, r)) < 1e-12 for r in count.roots)


NORMAL = (Fraction(3, 8), Fraction(-1, 2))  # the slide's normal (any rational: scaled to integers)


def _slid(seed: int):
    """_posed with body 1's second leg a block on a frame slide: its pair on the line with NORMAL through a
    point 16 |n| along the line from the pair's posed position (not the pose itself)."""
    bodies, bases, turns = _posed(seed)
    left, right = bodies.bodies
    p = (bases[2][0] + _rot(turns[2], right.leg)[0], bases[2][1] + _rot(turns[2], right.leg)[1])
    q = _rot(turns[3], right.held)
    on = (p[0] + q[0] - 16 * NORMAL[1], p[1] + q[1] + 16 * NORMAL[0])
    slid = Body(right.link, right.base, right.pair, right.leg, "S", right.held, Fraction(0), right.legs,
                right.pairs, right.local, (NORMAL, on))
    return TwoBodies(1, (left, slid), bodies.couplers), bases, turns, on


def test_a_slide_legs_equation_is_the_half_angle_form_of_n_dot_p_and_vanishes_at_the_pose():
    """Body 1's slide equation is (1 + t_phi^2)(1 + t_theta^2) n . (P - a) (sympy, from cos = (1 - t^2) / (1 +
    t^2), sin = 2 t / (1 + t^2)) up to a constant; it and the eliminant vanish exactly at the pose (which is
    among the assemblies, every one on the line and at its distances to 1e-12)."""
    import sympy

    bodies, bases, turns, on = _slid(3)
    ctx = flint.fmpz_mpoly_ctx.get(NAMES, "lex")
    polys = [polynomial(ctx, *e) for e in equations(bodies, bases, UNIT)]
    assert all(_at(p, turns) == 0 for p in polys)
    assert _at(polys[1], (0, 0, turns[2], turns[3] + 1)) != 0
    tp, tt = sympy.symbols("tp tt")
    right = bodies.bodies[1]

    def turned(t, v):
        c, s = (1 - t**2) / (1 + t**2), 2 * t / (1 + t**2)
        return c * sympy.Rational(v[0]) - s * sympy.Rational(v[1]), s * sympy.Rational(v[0]) + c * sympy.Rational(v[1])

    leg, held = turned(tp, right.leg), turned(tt, right.held)
    px = sympy.Rational(bases[2][0]) + leg[0] + held[0]
    py = sympy.Rational(bases[2][1]) + leg[1] + held[1]
    nx, ny, ax, ay = (sympy.Rational(v) for v in (*NORMAL, *on))
    want = sympy.expand(sympy.cancel((1 + tp**2) * (1 + tt**2) * (nx * (px - ax) + ny * (py - ay))))
    got = sympy.expand(sum(int(c) * tp ** int(e[2]) * tt ** int(e[3]) for e, c in polys[1].to_dict().items()))
    ratio = sympy.cancel(got / want)
    assert ratio.is_number and ratio != 0
    _, _, p = eliminate(*polys, ctx)
    assert sum(int(c) * turns[1] ** k for k, c in enumerate(p.coeffs())) == 0
    count = solve(bodies, tuple(bases), UNIT, 200.0)
    assert any(max(abs(math.remainder(a - 2 * math.atan(float(t)), 2 * math.pi)) for a, t in zip(r.angles, turns))
               < 1e-12 for r in count.roots)
    n = math.hypot(*NORMAL)
    for r in count.roots:
        pos = dict(zip(bodies.pairs, r.positions))
        x, y = pos[right.pairs[1]]
        assert abs(float(NORMAL[0]) * (x - float(on[0])) + float(NORMAL[1]) * (y - float(on[1]))) / n / 200 < 1e-12
        errors = _distances(bodies, bases, r)
        assert max(errors[:3] + errors[4:]) < 1e-12  # the fourth: body 1's second leg, a slide here
