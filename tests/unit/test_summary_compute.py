"""The engineering summary (linkgen.summary.compute) against closed forms: a four-bar's limit
positions, transmission angle and rocker swing by the law of cosines, a
slider-crank's stroke and time ratio from its stretched and folded positions."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from linkgen.pipeline import build_log
from linkgen.summary.compute import summarize
from tests.linkages import four_bar, sigma, toggle

ROOT = Path(__file__).resolve().parents[2]


def _summary(path: Path):
    return summarize(build_log(str(path), sweep=False))


def test_non_grashof_assembling_range_and_limit_positions_in_degrees(tmp_path):
    a, b, c, d = 40.0, 50.0, 41.0, 60.0
    s = _summary(four_bar(tmp_path, "ng", a, b, c, d, 30.0, samples=361))
    limit = math.degrees(toggle(a, b, c, d, far=True))  # |A O2| = b + c; the folded toggle is out of reach
    (rng,) = s.inputs
    assert rng.unit == "deg"
    assert (rng.low, rng.high) == pytest.approx((-limit, limit), abs=1e-9)
    assert [p.kind for p in s.positions] == ["limit", "limit"]
    assert [p.inputs[0] for p in s.positions] == pytest.approx([limit, 360 - limit], abs=1e-9)
    (loop,) = s.four_bars
    assert (loop.grashof, loop.kind, loop.driven) == ("non-Grashof", "triple-rocker", "theta_O1")
    # rows at k degrees (k = 0 .. 360) fail beyond the limits
    failing = sum(1 for k in range(361) if limit < k < 360 - limit)
    assert s.failed == failing and sum(f.rows for f in s.failures) == failing
    assert all(f.meaning.endswith("the chain cannot close") for f in s.failures)
    (t,) = s.transmission
    assert t.at_limit and t.minimum == 0.0 and t.at[0] == pytest.approx(limit, abs=1e-9)


def test_a_limit_outside_the_sweeps_range_is_not_the_sweeps_least_transmission_angle(tmp_path):
    """The non-Grashof four-bar swept over -20..20 deg only, inside its limits: the chain's least transmission
    angle is the sweep's, the least over the range of the closed form (sigma is its sine), not 0 at a limit."""
    a, b, c, d = 40.0, 50.0, 41.0, 60.0
    limit = math.degrees(toggle(a, b, c, d, far=True))
    assert limit > 20
    path = four_bar(tmp_path, "ng", a, b, c, d, 0.0, samples=41)
    path.write_text(path.read_text().replace("range: [0, 360]", "range: [-20, 20]"))
    s = _summary(path)
    assert s.failed == 0
    (t,) = s.transmission
    grid = [math.radians(-20 + k / 100) for k in range(4001)]
    least = min(math.degrees(math.asin(sigma(a, b, c, d, x))) for x in grid)
    assert not t.at_limit and t.minimum == pytest.approx(least, abs=1e-6)
    assert -20 <= t.at[0] <= 20


def _apart(x: float, y: float) -> float:
    """How far apart two angles in degrees are, modulo whole turns."""
    return abs((x - y + 180) % 360 - 180)


def _toggle_rocker(a: float, b: float, c: float, d: float, reach: float) -> float:
    """The rocker's angle (degrees from the frame line O1 -> O2, B above it) with |O1 B| = reach."""
    psi = math.acos((d * d + c * c - reach * reach) / (2 * d * c))  # the angle at O2 between O2 -> O1 and O2 -> B
    return math.degrees(math.pi - psi)


def test_crank_rocker_transmission_angle_and_swing_in_closed_form(tmp_path):
    a, b, c, d = 20.0, 78.0, 51.0, 90.0
    s = _summary(four_bar(tmp_path, "cr", a, b, c, d, 40.0, samples=361))
    (loop,) = s.four_bars
    assert (loop.grashof, loop.kind) == ("Grashof", "crank-rocker")
    assert s.failed == 0 and s.inputs[0].low is None and s.inputs[0].high is None
    # the angle at B is extreme with the crank along the frame line (|A O2| = d - a or d + a)
    mus = [math.degrees(math.acos((b * b + c * c - q * q) / (2 * b * c))) for q in (d - a, d + a)]
    least = min(min(mu, 180 - mu) for mu in mus)
    (t,) = s.transmission
    assert t.minimum == pytest.approx(least, abs=1e-9)
    at_zero = min(mus[0], 180 - mus[0]) < min(mus[1], 180 - mus[1])
    assert _apart(t.at[0], 0.0 if at_zero else 180.0) < 1e-5
    rocker = next(r for r in s.travels if r.name == "rocker.phi")
    ends = sorted([_toggle_rocker(a, b, c, d, b - a), _toggle_rocker(a, b, c, d, b + a)])
    assert not rocker.turns and (rocker.low, rocker.high) == pytest.approx(ends, abs=1e-9)
    assert rocker.travel == pytest.approx(ends[1] - ends[0], abs=1e-9)
    # time ratio: the crank angles of the two toggles (crank along the coupler, stretched and folded)
    q = [math.acos((d * d + (b + sign * a) ** 2 - c * c) / (2 * d * (b + sign * a))) for sign in (1, -1)]
    forward = math.degrees(math.pi + q[1] - q[0])  # from the folded toggle (crank at pi + q1) to the stretched (q0)
    forward = forward % 360
    assert rocker.time_ratio == pytest.approx(max(forward, 360 - forward) / min(forward, 360 - forward), abs=1e-6)
    crank = next(r for r in s.travels if r.name == "crank.phi")
    assert crank.turns and crank.travel == pytest.approx(360.0)


SLIDER = """linkgen: 1
name: {name}
title: slider-crank r {r}, l {l}, offset {e}
units: {{length: mm, angle: deg}}
joints:
  O: [0, 0]
  A: [{r}, 0]
  B: [{bx!r}, {y}]
  S: {{type: prismatic, at: [{bx!r}, {y}], axis: 0}}
links:
  frame: {{joints: [O, S], fixed: true}}
  crank: [O, A]
  rod: [A, B]
  block: [B, S]
inputs:
  - {{joint: O, link: crank, relative_to: frame, range: [0, 360], speed: 360}}
samples: 361
"""


@pytest.mark.parametrize(("r", "rod", "e"), [(20.0, 65.0, 13.0), (25.0, 80.0, 0.0), (10.0, 40.0, -15.0)])
def test_slider_crank_stroke_and_time_ratio_in_closed_form(tmp_path, r, rod, e):
    l = rod  # noqa: E741 - the rod's length, l as the textbooks write it
    path = tmp_path / "sc.yaml"
    path.write_text(SLIDER.format(name="sc", r=r, l=l, e=e, bx=r + math.sqrt(l * l - e * e), y=-e))
    s = _summary(path)
    far, near = math.sqrt((l + r) ** 2 - e * e), math.sqrt((l - r) ** 2 - e * e)
    slide = next(t for t in s.travels if t.quantity == "slide")
    assert slide.unit == "mm" and slide.travel == pytest.approx(far - near, abs=1e-9)
    if e == 0:
        assert slide.travel == pytest.approx(2 * r, abs=1e-12)
    # the crank angles of the stretched and folded positions: A on the line O B, beyond or before O
    t_far = math.degrees(math.atan2(-e, far))
    t_near = math.degrees(math.atan2(-e, near)) + 180
    forward = (t_near - t_far) % 360
    assert slide.time_ratio == pytest.approx(max(forward, 360 - forward) / min(forward, 360 - forward), abs=1e-6)
    assert _apart(slide.at_high[0], t_far) < 1e-5 and _apart(slide.at_low[0], t_near) < 1e-5
    # the transmission angle at the slider: cos of the rod's angle to the slide, least with the crank normal to it
    (t,) = s.transmission
    assert t.minimum == pytest.approx(math.degrees(math.acos((r + abs(e)) / l)), abs=1e-9)


def test_the_summary_is_built_with_the_sweep_and_is_the_one_found_alone():
    """build_log with the sweep carries the summary of its pruned log (the manual's), and it is
    the summary of the log without the conditioning (linkgen check's)."""
    path = str(ROOT / "samples" / "slider_crank" / "slider_crank.yaml")
    assert build_log(path).summary == summarize(build_log(path, sweep=False))
    assert build_log(path, sweep=False).summary is None


def test_sample_summaries_name_the_fixed_facts():
    s = _summary(ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml")
    assert s.mobility == 1 and s.failed == 0
    assert [t.step for t in s.transmission] == [5]  # step 4 closes on the Add-link: the resolver sets it
    (loop,) = s.four_bars
    assert loop.pairs == ("J1", "J2", "J4", "J3") and loop.grashof == "non-Grashof"  # 100 + 105.1 > 70 + 65.2
    s = _summary(ROOT / "samples" / "actuator" / "actuator.yaml")
    (rng,) = s.inputs
    assert rng.kind != "revolute" and rng.unit == "mm"
    assert next(t for t in s.travels if t.quantity == "slide").travel == pytest.approx(2050 - 1300, abs=1e-9)


def test_parallelogram_change_points_where_the_crank_lies_along_the_frame():
    """tests/mechanisms/parallelogram.yaml: the coupler and the frame are 60, the cranks 20 sqrt 2; the
    two branches of B cross where the crank lies along the frame line: 0 and 180 degrees (the rows
    at 0, 180 and 360 are singular)."""
    s = _summary(ROOT / "tests" / "mechanisms" / "parallelogram.yaml")
    (loop,) = s.four_bars
    assert (loop.grashof, loop.kind) == ("change point", "double-crank")
    assert [p.kind for p in s.positions] == ["change point", "change point"]
    assert [p.inputs[0] for p in s.positions] == pytest.approx([0.0, 180.0], abs=1e-9)
    assert (s.singular, s.failed) == (3, 0)
    assert all(t.turns for t in s.travels if t.name in ("crank.phi", "rocker.phi"))


def test_a_resolvers_extreme_is_the_greatest_of_a_fine_sweep_around_it(tmp_path):
    """Fig. 14 (a resolver: Newton on the rate): rocker1's greatest angle against a sweep of 1001
    rows a thousandth of a degree apart around the place found (the sweep's own rows, from the
    sketch): no row above it, the nearest within the second-order error of the step."""
    import linkgen

    sample = ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"
    rocker = next(t for t in _summary(sample).travels if t.name == "rocker1.phi")
    place = rocker.at_high[0]
    fine = tmp_path / "fine.yaml"
    fine.write_text(sample.read_text().replace("range: [0, 360]", f"range: [{place - 0.5!r}, {place + 0.5!r}]")
                    .replace("samples: 361", "samples: 1001"))
    rows = linkgen.load(fine).sweep()
    angles = [math.degrees(x) for x in rows["rocker1.phi"]]
    assert max(angles) <= rocker.high + 1e-12
    assert rocker.high - max(angles) < 1e-9
    assert abs(math.degrees(rows["theta_J7"][angles.index(max(angles))]) - place) < 2e-3


def test_a_sweep_across_the_seam_gives_limits_and_swings_inside_it(tmp_path):
    """The non-Grashof four-bar swept over -180..180 degrees: its limits at -+theta_l (law of cosines), not
    at 360 - theta_l outside the sweep; the crank swings 2 theta_l between them, not to the first failing
    rows (its angle is computed before the chain that fails there)."""
    a, b, c, d = 40.0, 50.0, 41.0, 60.0
    path = four_bar(tmp_path, "seam", a, b, c, d, 30.0, samples=73)
    path.write_text(path.read_text(encoding="utf-8").replace("range: [0, 360]", "range: [-180, 180]"),
                    encoding="utf-8")
    s = _summary(path)
    limit = math.degrees(toggle(a, b, c, d, far=True))
    assert [p.inputs[0] for p in s.positions] == pytest.approx([-limit, limit], abs=1e-9)
    crank = next(t for t in s.travels if t.name == "crank.phi")
    assert (crank.low, crank.high, crank.travel) == pytest.approx((-limit, limit, 2 * limit), abs=1e-7)


@pytest.mark.parametrize("ground", [45.0, 60.0, 75.0, -150.0])
def test_a_rocker_swing_is_stated_round_its_middle_within_a_half_turn(tmp_path, ground):
    """The rocker's angles from the frame line, turned with the frame: the swing's ends are the
    closed form's plus the ground angle (modulo a turn), stated with their middle in (-180, 180]
    however the sweep's first row unwraps."""
    a, b, c, d = 20.0, 78.0, 51.0, 90.0
    s = _summary(four_bar(tmp_path, "turned", a, b, c, d, 40.0, ground=ground, samples=361))
    rocker = next(r for r in s.travels if r.name == "rocker.phi")
    ends = sorted([_toggle_rocker(a, b, c, d, b - a), _toggle_rocker(a, b, c, d, b + a)])
    assert -180 < (rocker.low + rocker.high) / 2 <= 180
    assert rocker.high - rocker.low == pytest.approx(ends[1] - ends[0], abs=1e-9)
    assert _apart(rocker.low, ends[0] + ground) < 1e-9 and _apart(rocker.high, ends[1] + ground) < 1e-9
