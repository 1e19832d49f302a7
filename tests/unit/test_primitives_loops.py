"""primitives.loops: the loop strategy's point and residual, their rates proved by sympy (time
derivatives of the displacement formulas) and their values checked by hand."""

from __future__ import annotations

import math

import sympy as sp
from sympy_oracle import time_derivative, to_sympy

from linkgen.primitives import python_backend
from linkgen.primitives.loops import loop_point, loop_residual, loop_turn

STILL_LEG = {sp.Symbol(n, real=True): 0 for n in ("l_dv", "l_ddv")}  # a leg's length is a link's: constant


def _zero(expr: sp.Expr) -> bool:
    """Whether expr (a leg of constant length) vanishes at a few points off the wrap (sympy evaluates it)."""
    expr = expr.subs(STILL_LEG)
    for k in range(3):
        at = {s: sp.Rational(3 + 7 * k + i, 11 + i) for i, s in enumerate(sorted(expr.free_symbols, key=str))}
        if abs(complex(expr.subs(at).evalf(30))) > 1e-25:
            return False
    return True


def test_loop_point_is_the_leg_at_the_angle_s_over_l_with_its_rates():
    q = to_sympy(loop_point).results["j2"]
    for pos, vel, acc in (("x", "dx", "ddx"), ("y", "dy", "ddy")):
        assert _zero(time_derivative(loop_point, q[pos]) - q[vel])
        assert _zero(time_derivative(loop_point, q[vel]) - q[acc])
    call = python_backend(2)["loop_point"]
    st, j2 = call((1.0, 2.0, 0.0, 0.0, 0.0, 0.0), (2.0, 0.0, 0.0), (math.pi, 0.0, 0.0))
    assert st == 0
    assert abs(j2[0] - 1.0) < 1e-15 and abs(j2[1] - 4.0) < 1e-15  # a quarter turn of a leg of 2 (arc pi)
    for length, arc in ((0.0, 1.0), (1e-310, 1e-290)):  # no leg, or an arc of 1e20 rad: no angle
        st, j2 = call((1.0, 2.0, 0.0, 0.0, 0.0, 0.0), (length, 0.0, 0.0), (arc, 1.0, 0.0))
        assert st == 1 and all(x != x for x in j2)


def test_loop_residual_is_the_arc_between_the_angle_that_comes_back_and_the_one_assumed():
    f = to_sympy(loop_residual).results["f"]
    assert _zero(time_derivative(loop_residual, f["v"]) - f["dv"])
    assert _zero(time_derivative(loop_residual, f["dv"]) - f["ddv"])
    call = python_backend(2)["loop_residual"]
    back = (1 + 2 * math.cos(0.6), 2 + 2 * math.sin(0.6), 0.0, 0.0, 0.0, 0.0)
    st, (v, dv, ddv) = call((1.0, 2.0, 0.0, 0.0, 0.0, 0.0), back, (2.0, 0.0, 0.0), (1.0, 0.5, 0.0))
    assert st == 0 and abs(v - 2 * (0.6 - 0.5)) < 1e-15 and dv == -0.5 and ddv == 0.0
    st, (v, _, _) = call((0.0, 0.0, 0.0, 0.0, 0.0, 0.0), (-1.0, -1e-3, 0.0, 0.0, 0.0, 0.0), (1.0, 0.0, 0.0),
                         (3.1, 0.0, 0.0))
    assert st == 0 and -math.pi < v <= math.pi and abs(v - (math.atan2(-1e-3, -1.0) - 3.1 + 2 * math.pi)) < 1e-15
    st, (v, _, _) = call((1.0, 2.0, 0.0, 0.0, 0.0, 0.0), back, (2.0, 0.0, 0.0), (1.0 + 2 * 14 * math.pi, 0.0, 0.0))
    assert st == 0 and abs(v - 2 * (0.6 - 0.5)) < 1e-13  # the angle assumed seven turns away: the same arc
    st, _ = call((1.0, 1.0, 0.0, 0.0, 0.0, 0.0), (1.0, 1.0, 0.0, 0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 0.0, 0.0))
    assert st == 1  # the two points coincide
    st, (v, _, _) = call((1.0, 2.0, 0.0, 0.0, 0.0, 0.0), back, (0.0, 0.0, 0.0), (1.0, 0.0, 0.0))
    assert st == 1 and v != v  # a leg of length 0: no angle


def test_loop_turn_is_the_bodys_cross_product_and_refuses_its_mirror_image():
    c = to_sympy(loop_turn).results["c"]
    assert _zero(time_derivative(loop_turn, c["v"]) - c["dv"])
    assert _zero(time_derivative(loop_turn, c["dv"]) - c["ddv"])
    call = python_backend(2)["loop_turn"]
    x1, x2, x3 = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0), (2.0, 0.0, 1.0, 0.0, 0.0, 0.0), (0.0, 3.0, 0.0, 0.0, 0.0, 0.0)
    st, (v, dv, ddv) = call(x1, x2, x3, 1)
    assert st == 0 and v == 6.0 and dv == 3.0 and ddv == 0.0  # (2, 0) x (0, 3); x2 moving at (1, 0): (1, 0) x (0, 3)
    st, (v, _, _) = call(x1, x2, x3, -1)
    assert st == 1 and v != v  # drawn the other way round: this one is the mirror image
