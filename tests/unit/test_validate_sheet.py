"""linkgen.validate.sheet: the file read in its units, the one namespace of pairs, points and links,
magnitudes held to the supported range (at most 1e30 in size, named in the file's unit), text held to one
plain line, and the suggestions of a close name."""

from __future__ import annotations

import math

import pytest
from mechanism_text import PATH, fourbar, refused

from linkgen.errors import InputError
from linkgen.loader import parse
from linkgen.model import Joint, Where
from linkgen.policy import MAX_MAGNITUDE
from linkgen.validate.sheet import Sheet, bad_character, did_you_mean


def sheet(text: str) -> Sheet:
    return Sheet(parse(text, PATH), PATH)


def fails(call) -> InputError:
    with pytest.raises(InputError) as info:
        call()
    return info.value


def test_a_position_is_two_numbers_in_range():
    s = sheet("p: [1e30, -2.5]\nq: [1, 2, 3]\nr: [1.0000001e30, 0]\n")
    assert s.xy(s.root["p"], "pair A") == (MAX_MAGNITUDE, -2.5)
    error = fails(lambda: s.xy(s.root["q"], "pair B"))
    assert (error.line, error.key) == (2, "q")
    assert error.message == "expected the position of pair B as [x, y], two numbers, got 3 values"
    error = fails(lambda: s.xy(s.root["r"], "pair C"))
    assert (error.line, error.key) == (3, "r[0]")
    assert error.message == ("the x coordinate of pair C is 1.0000001e30, outside the range linkgen supports: at most "
                             "1e30 in size (in the file's length unit)")


def test_a_magnitude_names_the_unit_it_was_given_in():
    s = sheet("a: -1.5e30\n")
    s.length_unit = "mm"
    assert fails(lambda: s.magnitude(s.root["a"], "the stroke")).message.endswith("(in mm)")
    assert fails(lambda: s.magnitude(s.root["a"], "the speed", "degrees per second")).message.endswith(
        "(in degrees per second)")
    assert s.magnitude(sheet("a: -1e30\n").root["a"], "x") == -1e30


def test_an_angle_is_in_the_files_unit():
    s = sheet("a: 90\n")
    assert s.angle(s.root["a"], "the axis") == math.pi / 2  # degrees by default
    s.angle_scale = 1.0
    assert s.angle(s.root["a"], "the axis") == 90.0


def test_pairs_points_and_links_share_one_namespace():
    s = sheet("a: 1\nb: 2\n")
    s.claim("B", s.root["a"], "pair")
    error = fails(lambda: s.claim("B", s.root["b"], "link"))
    assert (error.line, error.key) == (2, "b")
    assert error.message == ("the name B is already used at line 1 (a); pairs, points and links share one set of "
                             "names, so this link needs another")


def test_a_pair_name_is_one_of_the_joints_with_a_suggestion():
    s = sheet("a: pivot\nb: pivt\nc: Q\n")
    joints = {"pivot": Joint("pivot", 0, "revolute", 0.0, 0.0, 0.0, Where(1, "joints.pivot"))}
    assert s.pair_name(s.root["a"], joints, "the driven pair") == "pivot"
    error = fails(lambda: s.pair_name(s.root["b"], joints, "the driven pair"))
    assert (error.line, error.key, error.message) == (2, "b", "pivt is not a pair in joints (did you mean pivot?)")
    assert fails(lambda: s.pair_name(s.root["c"], joints, "the driven pair")).message == "Q is not a pair in joints"


@pytest.mark.parametrize("name, known, hint", [
    ("rocke", ["rocker", "crank"], " (did you mean rocker?)"),
    ("zzz", ["rocker", "crank"], ""),
    ("crank", [], ""),
])
def test_did_you_mean(name: str, known: list[str], hint: str):
    assert did_you_mean(name, known) == hint


@pytest.mark.parametrize("text, bad", [
    ("plain text, ümlauts and 四節 🙂", ""), ("a\tb", "\t"), ("a\u2028b", "\u2028"), ("a\u202eb", "\u202e"),
    ("a\x7fb", "\x7f"), ("\udcff", "\udcff"), ("ok\u061c", "\u061c"), ("a\u00adb", ""),
])
def test_bad_character_finds_the_first_a_line_cannot_carry(text: str, bad: str):
    """Control characters, surrogates, line and paragraph separators and the bidirectional controls; a
    soft hyphen (a format character, not bidirectional) is fine."""
    assert bad_character(text) == bad


def test_one_line_names_the_character_and_its_kind():
    s = sheet('t: "a\\x85b"\nu: "a\\u2066b"\nv: fine\n')
    assert fails(lambda: s.one_line(s.root["t"], "a title", "the title")).message.startswith(
        "the title holds the line break U+0085, ")
    assert fails(lambda: s.one_line(s.root["u"], "a title", "the title")).message.startswith(
        "the title holds the control character U+2066, ")
    assert s.one_line(s.root["v"], "a title", "the title") == "fine"


@pytest.mark.parametrize("text, key, what", [
    (fourbar().replace("[60, 70]", "[1.0000001e30, 70]"), "links.coupler.points.P[0]",
     "the x coordinate of point P is 1.0000001e30, outside the range linkgen supports: at most 1e30 in size (in mm)"),
    (fourbar().replace("[0, 360]", "[-2e30, 360]"), "inputs[0].range[0]",
     "the start of the range is -2e30, outside the range linkgen supports: at most 1e30 in size (in degrees)"),
    (fourbar().replace("speed: 360", "speed: 1.5e30"), "inputs[0].speed",
     "the input speed is 1.5e30, outside the range linkgen supports: at most 1e30 in size (in degrees per second)"),
])
def test_magnitudes_outside_the_range_are_refused_in_the_files_units(text: str, key: str, what: str):
    error = refused(text)
    assert error.key == key
    assert error.message == what
