"""linkgen.topology: trusses, link directions, the inputs' sketch values, the length scale and the
origin, each against the sketch worked by hand."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

from linkgen.loader import parse
from linkgen.model import Mechanism
from linkgen.topology import Direction, _farthest, analyse, input_direction, sketch_input, truss, wrap_angle
from linkgen.validate import validate

FOURBAR = """linkgen: 1
name: fourbar
joints: {O1: [0, 0], A: [20, 0], B: [80, 50], O2: [90, 0]}
links:
  frame: {joints: [O1, O2], fixed: true}
  crank: [O1, A]
  coupler: {joints: [A, B], points: {P: [60, 70]}}
  rocker: [O2, B]
inputs:
  - {joint: O1, link: crank, relative_to: frame, range: [0, 360]}
"""


def mechanism(text: str) -> Mechanism:
    return validate(parse(text, "m.yaml"), "m.yaml")


def test_wrap_angle_is_in_the_half_open_turn():
    assert wrap_angle(math.pi) == math.pi and wrap_angle(-math.pi) == math.pi
    assert wrap_angle(3 * math.pi / 2) == pytest.approx(-math.pi / 2, abs=1e-15)
    assert wrap_angle(-7.0) == pytest.approx(2 * math.pi - 7.0, abs=1e-15)
    assert wrap_angle(0.25 + 6 * math.pi) == pytest.approx(0.25, abs=1e-14)


def test_a_link_of_k_pairs_is_the_truss_of_its_k_choose_2_members():
    text = FOURBAR.replace("A: [20, 0], B: [80, 50]", "A: [20, 0], B: [80, 50], T: [23, 4]").replace(
        "crank: [O1, A]", "crank: [O1, A, T]").replace("links:", "links:\n  tail: [T, O2]")
    m = mechanism(text)
    members = {(mb.a, mb.b): mb.length for mb in truss(m, m.link("crank"))}
    assert members == {("O1", "A"): 20.0, ("O1", "T"): math.hypot(23, 4), ("A", "T"): 5.0}  # a 3-4-5 triangle
    assert [mb.label for mb in truss(m, m.link("crank"))] == ["crank:O1-A", "crank:O1-T", "crank:A-T"]


def test_a_link_points_from_its_first_pair_to_the_next_elsewhere():
    topo = analyse(mechanism(FOURBAR))
    assert topo.direction("coupler") == Direction("A", "B", "", math.atan2(50, 60))
    assert topo.direction("rocker") == Direction("O2", "B", "", math.atan2(50, -10))
    assert topo.direction("frame").angle == 0.0


def test_a_block_whose_pairs_coincide_points_along_its_slide_axis():
    m = mechanism("""linkgen: 1
name: slider_crank
joints: {O: [0, 0], A: [10, 8], B: [45, -5], S: {type: prismatic, at: [45, -5], axis: 30}}
links:
  frame: {joints: [O, S], fixed: true}
  crank: [O, A]
  rod: [A, B]
  block: [B, S]
inputs:
  - {joint: O, link: crank, relative_to: frame, range: [0, 360]}
""")
    assert analyse(m).direction("block") == Direction("B", "", "S", math.radians(30))


def test_an_input_pair_sees_a_link_towards_its_next_pair_cyclically():
    m = mechanism(FOURBAR)
    assert input_direction(m, m.link("coupler"), "B") == Direction("B", "A", "", math.atan2(-50, -60))
    assert input_direction(m, m.link("frame"), "O2") == Direction("O2", "O1", "", math.pi)


@pytest.mark.parametrize("crank_at, angles, expected", [
    ("[20, 0]", "[0, 360]", 0.0),
    ("[0, 20]", "[0, 360]", 90.0),
    ("[0, 20]", "[360, 720]", 450.0),  # the turn inside the range
    ("[0, 20]", "[-720, -360]", -630.0),
    ("[0, 20]", "[100, 200]", 90.0),  # the turn nearest the range
    ("[0, -20]", "[0, 180]", -90.0),  # as near the end as 270: the one nearer the start
    ("[0, -20]", "[180, 0]", 270.0),
])
def test_a_revolute_inputs_sketch_value_is_the_turn_nearest_its_range(crank_at: str, angles: str, expected: float):
    text = FOURBAR.replace("A: [20, 0]", f"A: {crank_at}").replace("range: [0, 360]", f"range: {angles}")
    m = mechanism(text)
    assert math.degrees(sketch_input(m, m.inputs[0])) == pytest.approx(expected, abs=1e-12)


def test_an_input_against_a_moving_link_measures_from_that_links_direction_at_the_pair():
    """coupler against crank at A: the coupler points to B (atan2(50, 60)), the crank from A back to O1 (pi)."""
    m = mechanism(FOURBAR.replace("{joint: O1, link: crank, relative_to: frame", "{joint: A, link: coupler, "
                                                                              "relative_to: crank"))
    assert sketch_input(m, m.inputs[0]) == pytest.approx(math.atan2(50, 60) + math.pi, abs=1e-15)


def test_prismatic_inputs_start_at_0_and_distance_inputs_at_the_drawn_distance():
    text = FOURBAR.replace("{joint: O1, link: crank, relative_to: frame, range: [0, 360]}",
                           "{between: [O1, B], range: [90, 100]}")
    m = mechanism(text)
    assert sketch_input(m, m.inputs[0]) == math.hypot(80, 50)


def test_the_length_scale_and_the_origin():
    """The scale is the largest distance, O1 to B; the origin the bounding box's centre (45, 35) on a grid of
    2^(e - 5) for the scale's binary exponent e (94.3 = 0.737 * 2^7): 4, so (44, 36)."""
    topo = analyse(mechanism(FOURBAR))
    assert topo.length_scale == math.hypot(80, 50)
    assert topo.origin == (44.0, 36.0)
    assert (topo.grubler, topo.mobility, topo.redundant) == (1, 1, 0)
    assert [round(mb.length, 12) for mb in topo.members] == [90.0, 20.0, round(math.hypot(60, 50), 12),
                                                             round(math.hypot(10, 50), 12)]
    assert topo.sketch_inputs == (0.0,)


def test_a_sketch_scaled_by_a_power_of_two_scales_its_origin_exactly():
    text = FOURBAR
    for old, new in (("[0, 0]", "[0, 0]"), ("[20, 0]", "[640, 0]"), ("[80, 50]", "[2560, 1600]"),
                     ("[90, 0]", "[2880, 0]"), ("[60, 70]", "[1920, 2240]")):
        text = text.replace(old, new)
    assert analyse(mechanism(text)).origin == (44.0 * 32, 36.0 * 32)


def _farthest_by_every_pair(points: dict[str, tuple[float, float]]) -> tuple[str, str, float]:
    """The first farthest pair in declaration order, comparing every pair."""
    names = list(points)
    best = (names[0], names[0], 0.0)
    for i, a in enumerate(names):
        for b in names[i + 1:]:
            (xa, ya), (xb, yb) = points[a], points[b]
            d = float(np.hypot(xb - xa, yb - ya))
            if d > best[2]:
                best = (a, b, d)
    return best


@pytest.mark.parametrize("seed", range(6))
def test_the_length_scale_is_the_farthest_pair_found_by_every_pair(seed: int):
    """_farthest compares only the spots that can end the farthest pair; on random sketches, on a grid
    (ties: the first pair in declaration order wins) and on a circle (every spot can), it finds what
    comparing every pair finds."""
    rng = np.random.default_rng(seed)
    for shape in ("random", "grid", "circle"):
        n = int(rng.integers(2, 40))
        if shape == "random":
            xy = rng.normal(size=(n, 2)) * 10.0 ** int(rng.integers(-3, 4))
        elif shape == "grid":
            xy = rng.integers(-3, 4, size=(n, 2)).astype(float)
        else:
            a = rng.uniform(0, 2 * np.pi, n)
            xy = np.c_[np.cos(a), np.sin(a)] * 7.3
        points = {f"p{k}": (float(x), float(y)) for k, (x, y) in enumerate(xy)}
        assert _farthest(SimpleNamespace(positions=points)) == _farthest_by_every_pair(points)
