"""linkgen.primitives.library, the functions that place one thing from known ones (an input, a link's
point, a link's angle, a residual): hand-calculated positions and rates, angles wrapped to (-pi, pi], and
the library's list of every runtime function (the directions of angles: unit are in directions.py)."""

from __future__ import annotations

import math

import pytest
from primitive_calls import PI, STILL, approx, py2

from linkgen.primitives import centres, directions, dyads, library, loops
from linkgen.primitives.dsl import Primitive


def test_the_library_lists_every_primitive_of_the_four_modules_once_by_its_name():
    defined = {p.name for module in (library, dyads, directions, centres, loops) for p in vars(module).values()
               if isinstance(p, Primitive)}
    assert set(library.PRIMITIVES) == defined and len(defined) == 20
    assert all(name == p.name for name, p in library.PRIMITIVES.items())
    # the placing functions first, then the chains, then the residual (the programs paste them in this order)
    order = list(library.PRIMITIVES)
    assert order.index("coupler_point") < order.index("RRR_links") < order.index("PPR_links") < order.index(
        "link_residual") < order.index("link_direction")


@pytest.mark.parametrize(
    ("j2", "off", "angle"),
    [
        # radius 2 at 90 deg turning at 1: v = (-2, 0), a = (0, -2)
        ((1.0, 3.0, -2.0, 0.0, 0.0, -2.0), 0.0, (PI / 2, 1.0, 0.0)),
        # plus angular acceleration 1: tangential a = (-2, 0)
        ((1.0, 3.0, -2.0, 0.0, -2.0, -2.0), 0.0, (PI / 2, 1.0, 1.0)),
        # offset 3 pi/4: 5 pi/4 wraps to -3 pi/4
        ((1.0, 3.0, -2.0, 0.0, 0.0, -2.0), 3 * PI / 4, (-3 * PI / 4, 1.0, 0.0)),
    ],
)
def test_link_angle_hand_cases(j2, off, angle):
    st, _, (got,) = py2("link_angle", (1.0, 1.0, 0, 0, 0, 0), j2, off)
    assert st == 0
    assert got == approx(angle)


@pytest.mark.parametrize(
    ("j1", "j2", "off"),
    [
        ((0.0, 0.0), (-1.0, 0.0), 0.0),  # atan2 = pi stays pi
        ((0.0, 0.0), (-1.0, -0.0), 0.0),  # atan2 = -pi wraps to pi
        ((0.0, 0.0), (1.0, 0.0), -PI),  # 0 - pi wraps to pi
    ],
)
def test_link_angle_wraps_to_half_open_interval(j1, j2, off):
    st, _, ((th, _, _),) = py2("link_angle", (*j1, 0, 0, 0, 0), (*j2, 0, 0, 0, 0), off)
    assert th == PI


def test_offset_angle_hand():
    (got,) = py2("offset_angle", (3.0, 1.0, 2.0), 1.0)[2]
    assert got == approx((4.0 - 2 * PI, 1.0, 2.0))
    (got,) = py2("offset_angle", (PI, 0.0, 0.0), PI)[2]  # 2 pi wraps to 0
    assert got == approx((0.0, 0.0, 0.0))


def test_crank_angle_hand():
    """theta + phi + off wrapped, rates summed; many turns away wrapped all the same (atan2 of sin, cos)."""
    (got,) = py2("crank_angle", (3.0, 1.0, 2.0), (0.5, 0.25, -1.0), 1.0)[2]
    assert got == approx((4.5 - 2 * PI, 1.25, 1.0))
    (got,) = py2("crank_angle", (-2.0, 0.0, 0.0), (-0.5, 0.0, 0.0), -1.0)[2]
    assert got == approx((2 * PI - 3.5, 0.0, 0.0))
    (got,) = py2("crank_angle", (0.3 + 40 * PI, 0.0, 0.0), (0.0, 0.0, 0.0), 0.0)[2]
    assert abs(got[0] - 0.3) < 1e-13


def test_crank_input_hand():
    # direction pi/6 + pi/3 = pi/2, l = 2: r = (0, 2); omega 1.5: r' = (-3, 0), r'' = (0, -4.5)
    (got,) = py2("crank_input", (1.0, 2.0, 0.5, 0.0, 0.0, 0.0), 2.0, (PI / 6, 1.0, 0.0), (PI / 3, 0.5, 0.0))[2]
    assert got == approx((1.0, 4.0, -2.5, 0.0, 0.0, -4.5))


def test_coupler_point_hand():
    # R(90 deg)(2, 1) = (-1, 2); omega 2: v = 2 (-2, -1), a = -4 (-1, 2)
    (got,) = py2("coupler_point", (1.0, 1.0, 0, 0, 0, 0), (PI / 2, 2.0, 0.0), 2.0, 1.0)[2]
    assert got == approx((0.0, 3.0, -4.0, -2.0, 4.0, -8.0))


def test_link_point_hand():
    # d = (3, 4), e = (0.6, 0.8), n = (-0.8, 0.6): jc = (1, 2) + 5 (0.6, 0.8) + 2.5 (-0.8, 0.6) = (2, 7.5);
    # d' = (1, 0): omega = (d x d') / |d|^2 = -4/25, jc' = omega (-ry, rx) with r = (1, 5.5)
    (got,) = py2("link_point", (1.0, 2.0, 0, 0, 0, 0), (4.0, 6.0, 1.0, 0.0, 0.0, 0.0), 5.0, 2.5)[2]
    om = -4 / 25
    al = -2 * om * 3 / 25  # (d x d'' - 2 omega d.d') / |d|^2 with d'' = 0, d.d' = 3
    assert got == approx((2.0, 7.5, -om * 5.5, om * 1.0, -al * 5.5 - om * om * 1.0, al * 1.0 - om * om * 5.5))
    # a point on a crank turning at 2 about j1, as coupler_point places it: the same motion, and a base
    # stretched by rounding (j2 - j1 of any length) does not move it
    (angled,) = py2("coupler_point", (1.0, 1.0, 0, 0, 0, 0), (PI / 2, 2.0, 0.0), 2.0, 1.0)[2]
    for k in (1.0, 1.5):
        (placed,) = py2("link_point", (1.0, 1.0, 0, 0, 0, 0), (1.0, 1.0 + k, -2.0 * k, 0.0, 0.0, -4.0 * k), 2.0, 1.0)[2]
        assert placed == approx(angled)


def test_pair_point_hand():
    # d = (3, 4), n(d) = (-4, 3): jc = (1, 2) + 0.5 (3, 4) + 0.25 (-4, 3) = (1.5, 4.75); d' = (1, 0), n(d') = (0, 1):
    # jc' = (0.5, 0.25); d'' = (0, -2), n(d'') = (2, 0): jc'' = (0.5, -1)
    (got,) = py2("pair_point", (1.0, 2.0, 0, 0, 0, 0), (4.0, 6.0, 1.0, 0.0, 0.0, -2.0), 0.5, 0.25)[2]
    assert got == approx((1.5, 4.75, 0.5, 0.25, 0.5, -1.0))
    # a point on a crank turning at 2 about j1, as coupler_point places it at (2, 1) from j1 along the crank:
    # with the crank's pair at d = (0, 1) from j1, 2 d + 1 n(d) = (-1, 2): (along, across) = (2, 1), the same motion
    (angled,) = py2("coupler_point", (1.0, 1.0, 0, 0, 0, 0), (PI / 2, 2.0, 0.0), 2.0, 1.0)[2]
    (placed,) = py2("pair_point", (1.0, 1.0, 0, 0, 0, 0), (1.0, 2.0, -2.0, 0.0, 0.0, -4.0), 2.0, 1.0)[2]
    assert placed == approx(angled)


def test_slider_input_hand():
    jp, jc = py2("slider_input", STILL, (PI / 2, 0.0, 0.0), (3.0, 1.0, 0.0), 1.0, 0.0)[2]
    assert jp == approx((0.0, 3.0, 0.0, 1.0, 0.0, 0.0))
    assert jc == approx((0.0, 4.0, 0.0, 1.0, 0.0, 0.0))
    # guide turning at 1 about pg, slider still at s = 2: jp' = s w n = (0, 2), jp'' = -s w^2 u = (-2, 0);
    # jc = jp + n: jc' = jp' + w x n = (-1, 2), jc'' = jp'' - w^2 n = (-2, -1)
    jp, jc = py2("slider_input", STILL, (0.0, 1.0, 0.0), (2.0, 0.0, 0.0), 0.0, 1.0)[2]
    assert jp == approx((2.0, 0.0, 0.0, 2.0, -2.0, 0.0))
    assert jc == approx((2.0, 1.0, -1.0, 2.0, -2.0, -1.0))


def test_link_residual_hand():
    # r = 5, r' = d.dv/r = 3/5, r'' = (|dv|^2 + d.da - r'^2)/r = (1 - 0.36)/5
    st, _, (f,) = py2("link_residual", STILL, (3.0, 4.0, 1.0, 0.0, 0.0, 0.0), (4.0, 0.5, 0.25))
    assert st is None  # it cannot fail
    assert f == approx((1.0, 0.6 - 0.5, 0.64 / 5 - 0.25))


def test_link_residual_coincident_pairs_give_the_rates_as_they_part():
    # d(t) = dv t + da t^2/2 with dv = (3, 4), da = (1, 0): |d(t)| = 5t + (dv.da/|dv|) t^2/2 + ...,
    # so r' = 5 and r'' = 3/5 (sympy-free: the series of sqrt(|dv|^2 t^2 + dv.da t^3 + ...))
    st, _, (f,) = py2("link_residual", (1.0, 2.0, 0.0, 0.0, 0.0, 0.0), (1.0, 2.0, 3.0, 4.0, 1.0, 0.0), (0.0, 0.0, 0.0))
    assert st is None  # it cannot fail
    assert f == approx((0.0, 5.0, 0.6))
    # at rest: |d(t)| = |da| t^2 / 2, r' = 0, r'' = |da| = 5
    st, _, (f,) = py2("link_residual", (1.0, 2.0, 0.0, 0.0, 0.0, 0.0), (1.0, 2.0, 0.0, 0.0, 3.0, -4.0), (2.0, 0.0, 0.0))
    assert st is None  # it cannot fail
    assert f == approx((-2.0, 0.0, 5.0))
    # finite differences of the distance just after the pairs meet (r(0) = 0) agree
    t = 1e-4
    r = lambda t: math.hypot(3.0 * t + 0.5 * t * t, 4.0 * t)  # noqa: E731
    assert abs(r(t) / t - 5.0) < 1e-3 and abs((r(2 * t) - 2 * r(t)) / t**2 - 0.6) < 1e-3


def test_link_angle_of_coincident_points_cannot_be_computed():
    st, _, ((th, om, al),) = py2("link_angle", (1.0, 2.0, 0, 0, 0, 0), (1.0, 2.0, 1.0, 0, 0, 0), 0.0)
    assert st == 1
    assert math.isnan(th) and math.isnan(om) and math.isnan(al)
