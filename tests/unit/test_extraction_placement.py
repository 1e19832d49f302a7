"""extraction.placement: link angles, slide lines and points placed at their sketch offsets (values by hand)."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from linkgen.extraction import Procedure, extract
from linkgen.extraction.placement import rot
from linkgen.topology import analyse
from linkgen.validate import read_mechanism

ROOT = Path(__file__).resolve().parents[2]
SLOTTED = Path(__file__).with_name("slotted_coupler.yaml")  # a slide on a moving guide, the coupler


def _extract(path: Path) -> Procedure:
    return extract(analyse(read_mechanism(str(path))))


def _arg(step, label: str) -> float:
    return next(a.value for a in step.args if a.label == label)


@pytest.fixture(scope="module")
def slotted() -> Procedure:
    return _extract(SLOTTED)


@pytest.mark.parametrize("angle, x, y, expected", [
    (0.0, 3.0, 4.0, (3.0, 4.0)),
    (math.pi / 2, 1.0, 0.0, (0.0, -1.0)),  # the frame's x axis is the old y axis
    (math.pi / 6, math.cos(math.pi / 6), math.sin(math.pi / 6), (1.0, 0.0)),
    (math.pi, 2.0, -5.0, (-2.0, 5.0)),
])
def test_rot_gives_the_coordinates_in_a_turned_frame(angle: float, x: float, y: float, expected: tuple[float, float]):
    assert rot(angle, x, y) == pytest.approx(expected, abs=1e-15)


def test_a_point_of_a_link_with_two_known_pairs_is_linear_in_them():
    proc = _extract(ROOT / "samples" / "fourbar" / "fourbar.yaml")
    (step,) = [s for s in proc.steps if s.target == "P"]
    # P (60, 70) from B (80, 50) = (-20, 20), along B -> A = (-60, -50) and across it (50, -60), over |AB|^2:
    # B is the nearer base (|BP| / |AB| = 0.36; from A it would be 1.03); 20/610 and -220/610 by hand
    assert step.function == "pair_point" and [a.var for a in step.args[:2]] == ["p_B", "p_A"]
    assert (_arg(step, "along"), _arg(step, "across")) == (2 / 61, -22 / 61)
    assert "link_angle" not in {s.function for s in proc.steps if s.number < step.number}  # no angle needed


def test_a_pair_of_a_link_with_two_known_pairs_is_placed_in_their_frame():
    proc = _extract(ROOT / "samples" / "jansen" / "jansen.yaml")
    (step,) = [s for s in proc.steps if s.target == "D"]
    # D (-74.79.., 8.14..) of the triangle B C D, a pair the chain D-F reads: in the frame of B -> C (B nearer)
    b, c, d = (-38, -7.8), (-24.0135350971, 31.2720974548), (-74.7943653809, 8.1431702059)
    r, base = (d[0] - b[0], d[1] - b[1]), (c[0] - b[0], c[1] - b[1])
    q = math.hypot(*base)
    assert step.function == "link_point" and [a.var for a in step.args[:2]] == ["p_B", "p_C"]
    assert _arg(step, "gsi") == pytest.approx((r[0] * base[0] + r[1] * base[1]) / q, rel=1e-14)
    assert _arg(step, "eta") == pytest.approx((base[0] * r[1] - base[1] * r[0]) / q, rel=1e-14)


def test_a_point_of_a_link_with_one_known_pair_is_at_its_offset_along_the_links_angle():
    proc = _extract(ROOT / "samples" / "inverted_slider" / "inverted_slider.yaml")
    (step,) = [s for s in proc.steps if s.target == "P"]
    # the lever turns about O2 (0, 0) with its slide S, whose axis points at P: P lies |P - O2| = 120 along it
    assert step.function == "coupler_point" and [a.var for a in step.args[:2]] == ["p_O2", "psi_S"]
    assert (_arg(step, "gsi"), _arg(step, "eta")) == pytest.approx((math.hypot(25.143490647704816,
                                                                              117.33628968928915), 0.0), abs=1e-12)


def test_a_moving_guides_line_turns_with_it_and_its_copy_of_the_pair_is_a_point_of_it(slotted: Procedure):
    line = next(s for s in slotted.steps if s.action == "line")
    assert (line.function, line.target, [a.var for a in line.args[:1]]) == ("offset_angle", "S", ["phi_coupler"])
    assert _arg(line, "off") == pytest.approx(math.pi / 2 - math.atan2(50, 60), rel=1e-15)
    (copy,) = [s for s in slotted.steps if s.outputs == ("g_S",)]
    # S (50, 25) is the middle of A (20, 0) and B (80, 50), both known on the coupler
    assert copy.function == "link_point" and [a.var for a in copy.args[:2]] == ["p_A", "p_B"]
    assert (_arg(copy, "gsi"), _arg(copy, "eta")) == pytest.approx((math.hypot(60, 50) / 2, 0.0), abs=1e-14)


def test_a_fixed_guides_line_is_two_constants():
    proc = _extract(ROOT / "tests" / "mechanisms" / "slider_crank.yaml")
    records = {v.name: v for v in proc.variables}
    assert (records["g_S"].value, records["psi_S"].value) == ((45.0, -5.0), (0.0,))
    assert not [s for s in proc.steps if set(s.outputs) & {"g_S", "psi_S"}]


def test_a_link_whose_pairs_coincide_keeps_a_constant_angle_to_its_slide():
    proc = _extract(ROOT / "tests" / "mechanisms" / "slider_crank.yaml")
    (block,) = [s for s in proc.steps if s.target == "block"]
    # the frame points O (0, 0) -> S (45, -5); the block (B = S) along the slide's axis 0
    assert (block.function, block.args[0].var) == ("offset_angle", "phi_frame")
    assert _arg(block, "off") == pytest.approx(math.atan2(5, 45), rel=1e-15)


def test_a_link_angle_is_measured_between_two_known_pairs_of_the_link(slotted: Procedure):
    angles = {s.target: s for s in slotted.steps if s.function == "link_angle"}
    assert [a.var for a in angles["coupler"].args[:2]] == ["p_A", "p_B"]
    assert [a.var for a in angles["rod"].args[:2]] == ["p_E", "p_O3"]
    assert all(_arg(s, "off") == 0.0 for s in angles.values())  # each measured along its own direction


def test_a_point_on_pairs_a_resolver_group_places_is_placed_in_their_frame():
    """triad_far's P sits on the ternary whose pairs J4, J5 the group iterates: their distance carries the
    group's tolerance, so P takes their direction only (link_point), after the group, as every point."""
    proc = _extract(ROOT / "tests" / "mechanisms" / "triad_far.yaml")
    (step,) = [s for s in proc.steps if s.target == "P"]
    grouped = {o for s in proc.steps if s.group for o in s.outputs}
    assert step.function == "link_point" and step.group == 0 and {a.var for a in step.args[:2]} <= grouped
    assert "pair_point" not in {s.function for s in proc.steps}
