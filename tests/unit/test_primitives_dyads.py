"""linkgen.primitives.dyads, the two-link chains: hand-calculated positions, rates and conditionings;
the two assemblies of the 3R and slider chains mirror each other (closed form); toggles, near toggles
and failures give the status and the masked outputs the status rules say."""

from __future__ import annotations

import math
import random

import pytest
from primitive_calls import PI, STILL, all_outputs, approx, field_level, named, py2

from linkgen.primitives import PRIMITIVES


@pytest.mark.parametrize(
    ("j1", "j2", "l1", "l2", "minv", "jb"),
    [
        # 3-4-5: a = (25 + 9 - 16)/10 = 1.8, h = 12/5; l1 grows at 1 with j1, j2 fixed:
        # 1.8 vx + 2.4 vy = 3, -3.2 vx + 2.4 vy = 0; 1.8 ax + 2.4 ay = 1 - |v|^2 = 0, -3.2 ax + 2.4 ay = -1
        (STILL, (5.0, 0, 0, 0, 0, 0), (3.0, 1.0, 0.0), (4.0, 0.0, 0.0), 1, (1.8, 2.4, 0.6, 0.8, 0.2, -0.15)),
        (STILL, (5.0, 0, 0, 0, 0, 0), (3.0, 1.0, 0.0), (4.0, 0.0, 0.0), -1, (1.8, -2.4, 0.6, -0.8, 0.2, 0.15)),
        # sides swapped: a = (25 + 16 - 9)/10 = 3.2
        (STILL, (5.0, 0, 0, 0, 0, 0), (4.0, 0.0, 0.0), (3.0, 0.0, 0.0), 1, (3.2, 2.4, 0, 0, 0, 0)),
        # the first case turned a quarter turn and moved to (1, 1): jb = j1 + 1.8 u + 2.4 n, u = (0, 1)
        ((1.0, 1.0, 0, 0, 0, 0), (1.0, 6.0, 0, 0, 0, 0), (3.0, 1.0, 0.0), (4.0, 0.0, 0.0), 1,
         (-1.4, 2.8, -0.8, 0.6, 0.15, 0.2)),
        # the whole triangle translating at (1, -2) with acceleration (3, 4): jb moves with it
        ((0.0, 0.0, 1.0, -2.0, 3.0, 4.0), (5.0, 0.0, 1.0, -2.0, 3.0, 4.0), (3.0, 0.0, 0.0), (4.0, 0.0, 0.0), 1,
         (1.8, 2.4, 1.0, -2.0, 3.0, 4.0)),
        # ... and turning rigidly about j1 at omega = 1: jb' = (-2.4, 1.8), jb'' = -jb
        (STILL, (5.0, 0.0, 0.0, 5.0, -5.0, 0.0), (3.0, 0.0, 0.0), (4.0, 0.0, 0.0), 1,
         (1.8, 2.4, -2.4, 1.8, -1.8, -2.4)),
    ],
)
def test_rrr_hand_cases(j1, j2, l1, l2, minv, jb):
    st, sigma, (got,) = py2("RRR_links", j1, j2, l1, l2, minv)
    assert st == 0
    assert got == approx(jb)


def test_rrr_right_angle_sigma_is_one():
    st, sigma, _ = py2("RRR_links", STILL, (5.0, 0, 0, 0, 0, 0), (3.0, 0, 0), (4.0, 0, 0), 1)
    assert sigma == approx(1.0)


@pytest.mark.parametrize(
    ("theta", "s"),
    [
        # outer dead centre, crank 1, rod 3, omega 2: x'' = -r w^2 (1 + r/l) = -16/3
        (0.0, (4.0, 0.0, -16.0 / 3.0)),
        # inner dead centre: x'' = w^2 (r - r^2/l) = 8/3
        (PI, (2.0, 0.0, 8.0 / 3.0)),
    ],
)
def test_slider_crank_at_dead_centre(theta, s):
    (pin,) = py2("crank_input", STILL, 1.0, (theta, 2.0, 0.0), (0.0, 0.0, 0.0))[2]
    # crank pin: (cos, sin), velocity w x r, acceleration -w^2 r
    assert pin == approx((math.cos(theta), math.sin(theta), -2 * math.sin(theta), 2 * math.cos(theta),
                          -4 * math.cos(theta), -4 * math.sin(theta)))
    st, sigma, (s_out, jp, jb) = py2("PRR_links", pin, (3.0, 0.0, 0.0), STILL, (0.0, 0.0, 0.0), 0.0, 0.0, 1)
    assert st == 0
    assert sigma == approx(1.0)
    assert s_out == approx(s)
    assert jp == approx((s[0], 0.0, s[1], 0.0, s[2], 0.0))
    assert jb == approx(jp)


def test_slider_crank_offset_pair_on_slider():
    """The pair sits at (gsi, eta) = (1, 0.5) on the slider: jb = jp + (1, 0.5) on a still guide."""
    pin = (0.0, 2.0, -3.0, 0.0, 0.0, -4.5)  # crank of 2 at 90 deg, omega 1.5
    # jb = (s + 1, 0.5); |jb - pin| = 2.5 = |(s + 1, -1.5)|: s + 1 = 2 ahead of the pin (minv = +1)
    st, _, (s, jp, jb) = py2("PRR_links", pin, (2.5, 0.0, 0.0), STILL, (0.0, 0.0, 0.0), 1.0, 0.5, 1)
    assert st == 0
    assert s[0] == approx(1.0)
    assert jp[:2] == approx((1.0, 0.0))
    assert jb[:2] == approx((2.0, 0.5))
    # (jb - pin).(jb' - pin') = 0 with jb' = (s', 0): 2 (s' + 3) - 1.5 * 0 = 0
    assert s[1] == approx(-3.0)
    # again: |jb' - pin'|^2 + (jb - pin).(jb'' - pin'') = 0: 0 + 2 s'' - 1.5 * 4.5 = 0
    assert s[2] == approx(3.375)
    assert jb[2:] == approx((-3.0, 0.0, 3.375, 0.0))


def test_prp_hand():
    # x axis and the vertical through (2, -1) moving right at 1: jb = (2, 0), s1 = 2, s2 = 1
    st, sigma, (s1, jp1, s2, jp2, jb) = py2(
        "PRP_links", STILL, (0.0, 0.0, 0.0), 0.0, 0.0, (2.0, -1.0, 1.0, 0.0, 0.0, 0.0), (PI / 2, 0.0, 0.0), 0.0, 0.0
    )
    assert st == 0
    assert sigma == approx(1.0)
    assert s1 == approx((2.0, 1.0, 0.0))
    assert s2 == approx((1.0, 0.0, 0.0))
    assert jp1 == approx((2.0, 0.0, 1.0, 0.0, 0.0, 0.0))
    assert jp2 == approx(jp1)
    assert jb == approx(jp1)


def test_prp_offsets_hand():
    # slider 1 on the x axis carries jb at (gsi, eta) = (0, 1): jb = jp1 + (0, 1);
    # slider 2 on the vertical through (3, 0) carries it at (1, 0) in its frame: jb = jp2 + (0, 1)
    st, _, (s1, jp1, s2, jp2, jb) = py2(
        "PRP_links", STILL, (0.0, 0.0, 0.0), 0.0, 1.0, (3.0, 0.0, 0, 0, 0, 0), (PI / 2, 0.0, 0.0), 1.0, 0.0
    )
    # jb = (s1, 1) = (3, s2 + 1): s1 = 3, s2 = 0
    assert jb[:2] == approx((3.0, 1.0))
    assert (s1[0], s2[0]) == approx((3.0, 0.0))
    assert jp1[:2] == approx((3.0, 0.0))
    assert jp2[:2] == approx((3.0, 0.0))


@pytest.mark.parametrize(
    ("minv", "psi", "s"),
    [(1, math.atan2(4.0, 3.0), (5.0, 0.0, 0.0)), (-1, math.atan2(-4.0, -3.0), (-5.0, 0.0, 0.0))],
)
def test_rpr_inverted_slider_crank_hand(minv, psi, s):
    # js turns about jg at omega 1 at radius 5: the line jg-js turns with it, nothing slides
    st, sigma, (ang, s_out, jp) = py2("RPR_links", STILL, (3.0, 4.0, -4.0, 3.0, -3.0, -4.0), 0.0, 0.0, 0.0, 0.0, minv)
    assert st == 0
    assert sigma == approx(1.0)
    assert ang == approx((psi, 1.0, 0.0))
    assert s_out == approx(s)
    assert jp == approx((3.0, 4.0, -4.0, 3.0, -3.0, -4.0))


def test_rpr_offset_line_hand():
    # js = (4, 3) sits 3 to the left of the guide's line through jg: line along x, s = 4, jp = js
    st, sigma, (ang, s, jp) = py2("RPR_links", STILL, (4.0, 3.0, 0, 0, 0, 0), 0.0, 3.0, 0.0, 0.0, 1)
    assert st == 0
    assert sigma == approx(0.8)  # t / q = 4 / 5
    assert ang == approx((0.0, 0.0, 0.0))
    assert s == approx((4.0, 0.0, 0.0))
    assert jp == approx((4.0, 3.0, 0.0, 0.0, 0.0, 0.0))
    # js sliding along x at 1: the line does not turn, s grows at 1
    st, _, (ang, s, jp) = py2("RPR_links", STILL, (4.0, 3.0, 1.0, 0, 0, 0), 0.0, 3.0, 0.0, 0.0, 1)
    assert ang == approx((0.0, 0.0, 0.0))
    assert s == approx((4.0, 1.0, 0.0))


@pytest.mark.parametrize(("sgn", "sx", "jpx"), [(1, 2.0, (1.0, 2.0)), (-1, -2.0, (1.0, 0.0))])
def test_ppr_cross_slot_hand(sgn, sx, jpx):
    # b slides on the x axis; a turns about jr = (1, 2) and slides on b along the y direction (cx = 90 deg)
    jr = (1.0, 2.0, 1.0, 1.0, 0.0, 0.0)
    st, sigma, (s1, jp1, sx_out, jpx_out) = py2(
        "PPR_links", jr, STILL, (0.0, 0.0, 0.0), 0.0, 0.0, 0.0, 0.0, PI / 2, sgn
    )
    assert st == 0
    assert sigma == approx(1.0)
    assert s1 == approx((1.0, 1.0, 0.0))
    assert jp1 == approx((1.0, 0.0, 1.0, 0.0, 0.0, 0.0))
    assert sx_out == approx((sx, sgn * 1.0, 0.0))
    assert jpx_out == approx((*jpx, 1.0, 1.0 if sgn > 0 else 0.0, 0.0, 0.0))


def _rrr_row(l1, l2, q, minv=1):
    return named("RRR_links", ((0.0, 0.0, 0.5, 0.25, 1.0, -1.0), (q, 0.0, -0.5, 1.0, 0.0, 2.0),
                                (l1, 0.5, 0.25), (l2, -0.5, 0.125), minv))


def test_rrr_cannot_close():
    for l1, l2, q in ((3.0, 4.0, 10.0), (1.0, 10.0, 2.0), (10.0, 1.0, 2.0), (3.0, 4.0, 0.0), (0.0, 5.0, 5.0),
                      (-1.0, 5.0, 5.0)):
        st, _, fields = all_outputs("RRR_links", _rrr_row(l1, l2, q), 2)
        assert st == 1, (l1, l2, q)
        assert all(math.isnan(x) for _, _, x in fields)


@pytest.mark.parametrize(("l1", "l2", "q", "jbx"), [(2.0, 3.0, 5.0, 2.0), (7.0, 2.0, 5.0, 7.0), (2.0, 7.0, 5.0, -2.0)])
@pytest.mark.parametrize("minv", [1, -1])
def test_rrr_exact_toggle(l1, l2, q, jbx, minv):
    st, sigma, fields = all_outputs("RRR_links", _rrr_row(l1, l2, q, minv), 2)
    assert st == 3
    assert sigma == 0
    values = {f: x for _, f, x in fields}
    assert (values["x"], values["y"]) == (jbx, 0.0)
    assert all(math.isnan(values[f]) for f in ("dx", "dy", "ddx", "ddy"))


def test_rrr_toggle_within_slack_is_a_toggle():
    """l1 + l2 a few ulps short of q (rounding on a real toggle) still closes, at the toggle."""
    q = 5.0
    l1 = 2.0
    l2 = math.nextafter(3.0, 0.0)
    st, sigma, fields = all_outputs("RRR_links", _rrr_row(l1, l2, q), 2)
    assert st == 3
    values = {f: x for _, f, x in fields}
    assert values["x"] == approx(2.0) and abs(values["y"]) < 1e-7


def test_rrr_near_toggle_is_status_4():
    # jb = (1, 1e-4) above the middle of j1 = (0, 0), j2 = (2, 0): sigma = sin(angle at jb) ~ 2e-4
    ln = math.hypot(1.0, 1e-4)
    st, sigma, fields = all_outputs("RRR_links", _rrr_row(ln, ln, 2.0), 2)
    assert st == 4
    assert sigma == pytest.approx(2e-4 / (1 + 1e-8), rel=1e-9)
    assert all(math.isfinite(x) for _, _, x in fields)


@pytest.mark.parametrize("delta", [1e-8, 1e-16])
def test_near_toggles_of_the_slider_chains(delta):
    """A link almost square to the guide (PRR) or js almost on the normal (RPR): sigma ~ sqrt(2 delta).

    1e-8 gives sigma ~ 1.4e-4: status 4 with every rate finite; 1e-16 gives ~1.4e-8: status 3.
    """
    ln = 3.0
    near = ln * (1 - delta)  # the distance of jr from the slider's line, of js from the guide's line
    want = math.sqrt((ln - near) * (ln + near)) / ln  # ln - near is exact (Sterbenz)
    status = 4 if want > 1e-7 else 3
    prr = named("PRR_links", ((0.0, near, 1.0, 0.5, 0.0, 0.0), (ln, 0.5, 0.0), STILL,
                               (0.0, 1.0, 0.5), 0.0, 0.0, 1))
    rpr = named("RPR_links", (STILL, (ln, 0.0, 0.0, 1.0, 0.0, 0.0), 0.0, near, 0.0, 0.0, 1))
    for name, row in (("PRR_links", prr), ("RPR_links", rpr)):
        st, sigma, fields = all_outputs(name, row, 2)
        assert st == status, name
        assert sigma == pytest.approx(want, rel=1e-9), name
        kinds = {o.name: o.kind for o in PRIMITIVES[name].outputs}
        for out, f, x in fields:
            if status == 4 or field_level(kinds[out], f) == 0:
                assert math.isfinite(x), f"{name}.{out}.{f}"
            else:
                assert math.isnan(x), f"{name}.{out}.{f}"


@pytest.mark.parametrize(("gap", "status"), [(1e-4, 4), (1e-9, 3)])
def test_almost_parallel_guides(gap, status):
    """PRP with guides gap radians apart: sigma = |sin(gap)|; positions finite, rates nan at status 3."""
    row = named("PRP_links", (STILL, (0.0, 0.0, 0.0), 0.0, 0.0, (0.0, 1.0, 0.5, 0.0, 0.0, 0.0),
                               (gap, 0.25, 0.0), 0.0, 0.0))
    st, sigma, fields = all_outputs("PRP_links", row, 2)
    assert st == status
    assert sigma == pytest.approx(math.sin(gap), rel=1e-6)
    kinds = {o.name: o.kind for o in PRIMITIVES["PRP_links"].outputs}
    for out, f, x in fields:
        if status == 4 or field_level(kinds[out], f) == 0:
            assert math.isfinite(x), f"{out}.{f}"
        else:
            assert math.isnan(x), f"{out}.{f}"
    values = {(o, f): x for o, f, x in fields}
    # the second guide passes through (0, 1) at angle gap: it meets the x axis at x = -1/tan(gap)
    assert values[("jb", "x")] == pytest.approx(-1 / math.tan(gap), rel=1e-6)


def test_prr_toggle_and_failure():
    def row(ln, y):
        return named("PRR_links", ((0.0, y, 1.0, 0.5, 0.0, 0.0), (ln, 0.5, 0.0), STILL, (0.0, 1.0, 0.5),
                                    0.0, 0.0, 1))

    st, sigma, fields = all_outputs("PRR_links", row(3.0, 3.0), 2)
    assert (st, sigma) == (3, 0)
    values = {(o, f): x for o, f, x in fields}
    assert (values[("s", "v")], values[("jb", "x")], values[("jb", "y")]) == (0.0, 0.0, 0.0)
    assert all(math.isnan(x) for (o, f), x in values.items() if f.startswith("d"))
    st, _, fields = all_outputs("PRR_links", row(2.0, 3.0), 2)
    assert st == 1
    assert all(math.isnan(x) for _, _, x in fields)


def test_rpr_toggle_and_failure():
    def row(bg):
        return named("RPR_links", (STILL, (3.0, 0.0, 0.0, 1.0, 0.0, 0.0), 0.0, bg, 0.0, 0.0, 1))

    st, sigma, fields = all_outputs("RPR_links", row(3.0), 2)
    assert (st, sigma) == (3, 0)
    values = {(o, f): x for o, f, x in fields}
    # js is on the normal through jg at distance 3: the line runs along -y through (3, 0)
    assert values[("psi", "the")] == -PI / 2
    assert (values[("s", "v")], values[("jp", "x")], values[("jp", "y")]) == (0.0, 3.0, 0.0)
    assert all(math.isnan(x) for (o, f), x in values.items() if f.startswith("d"))
    st, _, fields = all_outputs("RPR_links", row(4.0), 2)
    assert st == 1
    assert all(math.isnan(x) for _, _, x in fields)


def _reflect(p: tuple[float, float], a: tuple[float, float], u: tuple[float, float]) -> tuple[float, float]:
    """p reflected in the line through a along the unit vector u."""
    d = (p[0] - a[0], p[1] - a[1])
    along = d[0] * u[0] + d[1] * u[1]
    return a[0] + 2 * along * u[0] - d[0], a[1] + 2 * along * u[1] - d[1]


def _unit(v: tuple[float, float]) -> tuple[float, float]:
    n = math.hypot(*v)
    return v[0] / n, v[1] / n


@pytest.mark.parametrize("seed", range(20))
def test_the_3r_chains_two_assemblies_mirror_each_other_in_the_base(seed: int):
    """jb drawn, l1 and l2 measured from it: minv of jb's side gives jb back, the other minv its mirror
    image in the line j1-j2; with the base at rest the velocity and acceleration mirror too."""
    rng = random.Random(seed)
    j1, j2, jb = ((rng.uniform(-5, 5), rng.uniform(-5, 5)) for _ in range(3))
    l1, l2 = math.dist(jb, j1), math.dist(jb, j2)
    side = 1 if (j2[0] - j1[0]) * (jb[1] - j1[1]) - (j2[1] - j1[1]) * (jb[0] - j1[0]) > 0 else -1
    rates = (rng.uniform(-1, 1), rng.uniform(-1, 1)), (rng.uniform(-1, 1), rng.uniform(-1, 1))
    outs = {}
    for minv in (side, -side):
        st, sigma, (got,) = py2("RRR_links", (*j1, 0, 0, 0, 0), (*j2, 0, 0, 0, 0), (l1, *rates[0]), (l2, *rates[1]),
                                minv)
        assert st in (0, 4)
        outs[minv] = got
    assert outs[side][:2] == pytest.approx(jb, rel=1e-9, abs=1e-9)
    u = _unit((j2[0] - j1[0], j2[1] - j1[1]))
    assert outs[-side][:2] == pytest.approx(_reflect(outs[side][:2], j1, u), rel=1e-9, abs=1e-9)
    for k in (2, 4):  # a rate reflects as a free vector: in the line through the origin
        assert outs[-side][k:k + 2] == pytest.approx(_reflect(outs[side][k:k + 2], (0.0, 0.0), u), rel=1e-7, abs=1e-7)


@pytest.mark.parametrize("seed", range(20))
def test_the_slider_chains_two_assemblies_lie_either_side_of_the_foot_of_jr(seed: int):
    """The 2R1P chain on a still guide: jb is where the circle about jr meets the slider's line; the other
    branch is its mirror image in the foot of the perpendicular from jr (s = the foot's -/+ the half chord)."""
    rng = random.Random(seed)
    pg = (rng.uniform(-5, 5), rng.uniform(-5, 5))
    psi = rng.uniform(-PI, PI)
    u = (math.cos(psi), math.sin(psi))
    off = rng.uniform(-2, 2)  # jr's distance from the line
    foot_s = rng.uniform(-3, 3)
    jr = (pg[0] + foot_s * u[0] - off * u[1], pg[1] + foot_s * u[1] + off * u[0])
    half = rng.uniform(0.5, 3)
    ln = math.hypot(off, half)
    got = {}
    for minv in (1, -1):
        st, _, (s, jp, jb) = py2("PRR_links", (*jr, 0, 0, 0, 0), (ln, 0.0, 0.0), (*pg, 0, 0, 0, 0), (psi, 0.0, 0.0),
                                 0.0, 0.0, minv)
        assert st in (0, 4)
        got[minv] = s[0]
        assert math.dist(jb[:2], jr) == pytest.approx(ln, rel=1e-12)
    assert sorted(got.values()) == pytest.approx([foot_s - half, foot_s + half], rel=1e-9, abs=1e-9)
    assert got[1] == pytest.approx(foot_s + half, rel=1e-9, abs=1e-9)  # minv +1: ahead of the foot along u


def test_every_chain_reports_a_status_and_its_conditioning():
    for name in ("RRR_links", "PRR_links", "PRP_links", "RPR_links", "PPR_links"):
        prim = PRIMITIVES[name]
        assert prim.status is not None and prim.sigma is not None, name


def test_rrr_an_open_triangle_never_fails():
    """RRR_links selects fail 0 on the open test (3 o1 > s2 and 3 o2 > dd): the toggle-side test it replaces,
    computed as the DSL writes it, is false on every open triangle (its sides at most 5 apart): sides alike to
    5 apart, q from the open range's ends to its middle (lo > 0, q > 0 and k > 0, by a margin of about 0.18 q)."""
    rng = random.Random(7)
    eps = 2.0 ** -52
    checked = 0
    for _ in range(20000):
        l1 = 10.0 ** rng.uniform(-30, 30)
        l2 = l1 * rng.choice((1.0, 1.0 + 1e-15, 10.0 ** rng.uniform(-0.7, 0.7)))
        lo_q, hi_q = abs(l1 - l2) * math.sqrt(1.5), (l1 + l2) * math.sqrt(2 / 3)
        q0 = lo_q + (hi_q - lo_q) * rng.choice((0.0, 1.0, rng.random()))
        dx = q0 * rng.uniform(0.1, 1.0)
        dy = math.sqrt(max(q0 * q0 - dx * dx, 0.0))
        dd = dx * dx + dy * dy
        s2, t2 = (l1 + l2) * (l1 + l2), (l1 - l2) * (l1 - l2)
        o1, o2 = s2 - dd, dd - t2
        if not (3 * o1 > s2 and 3 * o2 > dd):
            continue
        q = math.sqrt(dd)
        hi, lo = max(l1, l2), min(l1, l2)
        x, z = max(hi, q), min(lo, q)
        y = hi if q >= hi else lo if q <= lo else q
        k = z - (x - y)
        assert not (k < -8 * eps * x or q == 0 or lo <= 0), (l1, l2, dx, dy)
        assert k > 0.15 * q
        checked += 1
    assert checked > 5000
