"""linkgen.validate.inputs: revolute, prismatic and distance inputs read into radians and length units
(worked out by hand from the file's numbers), the guide and slider of each prismatic pair, and the inputs
a mechanism cannot be given."""

from __future__ import annotations

import math

import pytest
from mechanism_text import FOURBAR, PATH, refused

from linkgen.loader import parse
from linkgen.model import Input, Prismatic, Where
from linkgen.validate import validate

INVERTED = """linkgen: 1
name: inverted
units: {length: mm, angle: deg}
joints:
  O1: [0, 0]
  A: [1, 0]
  O2: [3, 0]
  S: {type: prismatic, at: [1, 0], axis: 0}
links:
  frame: {joints: [O1, O2], fixed: true}
  crank: [O1, A]
  lever: [O2, S]
  block: [A, S]
inputs:
  - {joint: O1, link: crank, relative_to: frame, range: [0, 90]}
"""
ACTUATOR = FOURBAR.replace("  - {joint: O1, link: crank, relative_to: frame, range: [0, 360], speed: 360}",
                           "  - {between: [A, O2], range: [60, 80], speed: 4}")


def read(text: str):
    return validate(parse(text, PATH), PATH)


def test_a_revolute_input_is_in_radians():
    (i,) = read(FOURBAR).inputs
    assert (i.index, i.kind, i.joint, i.link, i.relative_to, i.between) == (0, "revolute", "O1", "crank", "frame", ())
    assert (i.start, i.stop, i.speed) == (0.0, 2 * math.pi, 2 * math.pi)  # [0, 360] degrees at 360 degrees a second
    assert (i.column, i.where.line, i.where.key) == ("theta_O1", 16, "inputs[0]")


def test_a_missing_speed_is_one_unit_a_second():
    (i,) = read(INVERTED).inputs
    assert (i.start, i.stop, i.speed) == (0.0, math.pi / 2, math.pi / 180)


def test_a_distance_input_is_in_length_units_between_its_pairs():
    (i,) = read(ACTUATOR).inputs
    assert (i.kind, i.joint, i.link, i.relative_to, i.between) == ("distance", "", "", "", ("A", "O2"))
    assert (i.start, i.stop, i.speed, i.column) == (60.0, 80.0, 4.0, "d_A_O2")


@pytest.mark.parametrize("extra, guide, slider", [
    ("", "lever", "block"),  # neither link is fixed and no input says: the first link that lists S
    ("  - {joint: S, relative_to: block, range: [0.5, 1.5]}\n", "block", "lever"),  # the input's relative_to
    ("  - {joint: S, link: block, range: [0.5, 1.5]}\n", "lever", "block"),
])
def test_the_guide_of_a_prismatic_pair(extra: str, guide: str, slider: str):
    m = read(INVERTED + extra)
    assert m.prismatic == (Prismatic("S", guide, slider),)
    if extra:  # the input moves the slider along the guide, in length units
        i = m.inputs[1]
        assert (i.kind, i.joint, i.link, i.relative_to, i.column) == ("prismatic", "S", slider, guide, "s_S")
        assert (i.start, i.stop, i.speed) == (0.5, 1.5, 1.0)


def test_the_fixed_link_is_the_guide_of_its_prismatic_pairs_whatever_the_input_says():
    text = INVERTED.replace("frame: {joints: [O1, O2], fixed: true}", "frame: {joints: [O1, O2, S], fixed: true}")
    text = text.replace("lever: [O2, S]", "lever: [O2, A]")
    m = read(text.replace("range: [0, 90]}", "range: [0, 90]}\n  - {joint: S, relative_to: block, range: [0, 1]}"))
    assert m.prismatic == (Prismatic("S", "frame", "block"),)
    assert (m.inputs[1].link, m.inputs[1].relative_to) == ("block", "frame")


@pytest.mark.parametrize("edit, line, key, message", [
    ("  - {joint: O1, link: crank, range: [0, 1]}", 16, "inputs[0].relative_to",
     "a revolute input on O1 needs relative_to: the link it turns against"),
    ("  - {joint: O1, link: frame, relative_to: crank, range: [0, 1]}", 16, "inputs[0].link",
     "the driven link frame is the fixed link; drive the moving link and give the frame as relative_to "
     "(link: crank, relative_to: frame)"),
    ("  - {joint: O1, link: rocker, relative_to: frame, range: [0, 1]}", 16, "inputs[0].link",
     "link rocker does not carry the pair O1, so the input on O1 cannot move it; O1 joins frame and crank"),
    ("  - {joint: O1, link: crank, relative_to: frame, range: [0, 1, 2]}", 16, "inputs[0].range",
     "expected the input range as [from, to], two numbers, got 3"),
    ("  - {between: [A, B], range: [0, 1]}", 16, "inputs[0].between",
     "A and B are both on link coupler, so their distance cannot change; an actuator acts between pairs that "
     "share no link"),
    ("  - {joint: O1, link: crank, relative_to: frame, range: [0, 1]}\n"
     "  - {joint: O1, link: crank, relative_to: frame, range: [0, 1]}", 17, "inputs[1].joint",
     "the pair O1 already carries an input (line 16); a pair carries at most one input"),
])
def test_inputs_a_mechanism_cannot_be_given(edit: str, line: int, key: str, message: str):
    text = FOURBAR.replace("  - {joint: O1, link: crank, relative_to: frame, range: [0, 360], speed: 360}", edit)
    error = refused(text)
    assert (error.line, error.key, error.message) == (line, key, message)


def test_two_inputs_cannot_share_a_csv_column():
    """d_A_B_C is the column of an actuator between A and B_C and of one between A_B and C."""
    text = FOURBAR.replace("O2", "B_C").replace("  A:", "  A_B: [20, 1]\n  C: [85, 60]\n  A:")
    text = text.replace("crank: [O1, A]", "crank: [O1, A, A_B]\n  strut: [A_B, B]")
    text = text.replace("joints: [A, B]", "joints: [A, B, C]").replace("rocker: [B_C, B]", "rocker: [B_C, B, C]")
    text = text.replace("  - {joint: O1, link: crank, relative_to: frame, range: [0, 360], speed: 360}",
                        "  - {between: [A, B_C], range: [60, 70]}\n  - {between: [A_B, C], range: [60, 70]}")
    error = refused(text)
    assert (error.line, error.key) == (20, "inputs[1]")
    assert error.message == ("this input's CSV column would be d_A_B_C, as is the column of the input on line 19; "
                             "rename one of the pairs")
    for between in (("A", "B_C"), ("A_B", "C")):
        assert Input(0, "distance", "", "", "", between, 0.0, 1.0, 1.0, Where(0, "")).column == "d_A_B_C"
