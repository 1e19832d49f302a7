"""linkgen.model: the validated mechanism's lookups and the inputs' CSV columns."""

from __future__ import annotations

import math

import pytest

from linkgen.loader import parse
from linkgen.model import Mechanism
from linkgen.validate import validate

# A compound hinge (C on three links), a prismatic pair on two moving links, points on two links,
# and all three kinds of input.
TEXT = """linkgen: 1
name: compound
joints:
  O: [0, 0]
  A: [10, 0]
  C: [10, 10]
  D: [0, 20]
  E: [30, 10]
  F: [40, 0]
  S: {type: prismatic, at: [20, 20], axis: 90}
links:
  frame: {joints: [O, F, D], fixed: true}
  crank: [O, A]
  left: {joints: [A, C], points: {P: [5, 5]}}
  up: [C, D]
  right: {joints: [C, E], points: {Q: [20, 10], R: [25, 12]}}
  guide: [E, S]
  slider: [S, F]
inputs:
  - {joint: O, link: crank, relative_to: frame, range: [0, 90]}
  - {joint: S, link: slider, range: [0, 5]}
  - {between: [A, E], range: [20, 25]}
"""


@pytest.fixture(scope="module")
def m() -> Mechanism:
    return validate(parse(TEXT, "m.yaml"), "m.yaml")


def test_lookups_by_name(m: Mechanism):
    assert (m.joint("C").index, m.joint("C").x, m.joint("C").y) == (2, 10.0, 10.0)
    assert m.link("right").joints == ("C", "E")
    assert m.fixed.name == "frame"
    with pytest.raises(KeyError):
        m.joint("P")  # a point is no pair


def test_a_pair_is_on_the_links_that_list_it_in_links_order(m: Mechanism):
    assert [lk.name for lk in m.links_of("C")] == ["left", "up", "right"]
    assert [lk.name for lk in m.links_of("O")] == ["frame", "crank"]
    assert [lk.name for lk in m.links_of("S")] == ["guide", "slider"]


def test_points_in_links_order_and_positions(m: Mechanism):
    assert [(p.name, p.index, p.link) for p in m.points] == [("P", 0, "left"), ("Q", 1, "right"),
                                                             ("R", 2, "right")]
    assert m.positions["R"] == (25.0, 12.0)
    assert m.positions["S"] == (20.0, 20.0)
    assert len(m.positions) == 7 + 3


def test_kinds_and_the_slide_axis_in_radians(m: Mechanism):
    assert [j.name for j in m.joints if not j.revolute] == ["S"]
    assert m.joint("S").axis == math.pi / 2
    assert m.joint("O").axis == 0.0


def test_a_prismatic_pair_without_the_frame_is_guided_by_the_first_link_that_lists_it(m: Mechanism):
    """The format: the fixed link if it carries the pair, else relative_to of an input on it, else the
    first link in links order; the input's link and relative_to become slider and guide."""
    p = m.prismatic_of("S")
    assert (p.guide, p.slider) == ("guide", "slider")
    assert (m.inputs[1].link, m.inputs[1].relative_to) == ("slider", "guide")
    text = TEXT.replace("{joint: S, link: slider,", "{joint: S, relative_to: slider,")
    p = validate(parse(text, "m.yaml"), "m.yaml").prismatic_of("S")
    assert (p.guide, p.slider) == ("slider", "guide")


def test_input_columns_and_units(m: Mechanism):
    assert [i.column for i in m.inputs] == ["theta_O", "s_S", "d_A_E"]
    assert [i.kind for i in m.inputs] == ["revolute", "prismatic", "distance"]
    assert m.inputs[0].stop == math.pi / 2 and m.inputs[0].speed == math.pi / 180  # degrees by default
    assert (m.inputs[1].stop, m.inputs[2].start, m.inputs[2].speed) == (5.0, 20.0, 1.0)
    assert m.inputs[2].between == ("A", "E")
