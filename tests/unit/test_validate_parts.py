"""linkgen.validate.parts: the joints: and links: sections read into pairs (a slide axis in radians) and
links (their points numbered across the file), one fixed link, every pair joining two links, and a
mechanism in one piece."""

from __future__ import annotations

import math

import pytest
from mechanism_text import FOURBAR, PATH, refused

from linkgen.loader import parse
from linkgen.validate import validate

SLIDER = FOURBAR.replace("  O2: [90, 0]", "  O2: {type: prismatic, at: [90, 0], axis: 90}")


def read(text: str):
    return validate(parse(text, PATH), PATH)


def test_pairs_in_file_order_with_their_kind_place_and_axis():
    m = read(SLIDER.replace("  A: [20, 0]", "  A: {at: [20, 0]}"))
    got = [(j.name, j.index, j.kind, j.x, j.y, j.axis, j.where.line, j.where.key) for j in m.joints]
    assert got == [("O1", 0, "revolute", 0.0, 0.0, 0.0, 6, "joints.O1"),
                   ("A", 1, "revolute", 20.0, 0.0, 0.0, 7, "joints.A"),
                   ("B", 2, "revolute", 80.0, 50.0, 0.0, 8, "joints.B"),
                   ("O2", 3, "prismatic", 90.0, 0.0, math.pi / 2, 9, "joints.O2")]


def test_links_carry_their_pairs_and_points_numbered_across_links():
    text = FOURBAR.replace("rocker: [O2, B]", "rocker: {joints: [O2, B], points: {Q: [95, 20], R: [99, 9]}}")
    m = read(text)
    assert [(lk.name, lk.index, lk.joints, lk.fixed) for lk in m.links] == [
        ("frame", 0, ("O1", "O2"), True), ("crank", 1, ("O1", "A"), False), ("coupler", 2, ("A", "B"), False),
        ("rocker", 3, ("O2", "B"), False)]
    points = [(p.name, p.index, p.link, p.x, p.y, p.where.key) for p in m.points]
    assert points == [("P", 0, "coupler", 60.0, 70.0, "links.coupler.points.P"),
                      ("Q", 1, "rocker", 95.0, 20.0, "links.rocker.points.Q"),
                      ("R", 2, "rocker", 99.0, 9.0, "links.rocker.points.R")]


@pytest.mark.parametrize("edit, line, key, message", [
    (("frame: {joints: [O1, O2], fixed: true}", "frame: [O1, O2]"), 10, "links",
     "no link is fixed; mark the frame with {joints: [...], fixed: true}"),
    (("crank: [O1, A]", "crank: {joints: [O1, A], fixed: true}"), 12, "links.crank",
     "links frame and crank are both fixed; exactly one link is the frame (pairs on the frame are all listed by that "
     "one link)"),
    (("crank: [O1, A]", "crank: [O1, A, O1]"), 12, "links.crank[2]", "link crank lists the pair O1 twice"),
    (("  A: [20, 0]", "  A: [0, 0]"), 12, "links.crank",
     "link crank carries the revolute pairs O1 and A at the same position (0, 0); a link cannot be hinged twice at one "
     "point"),
    (("coupler: {joints: [A, B], points: {P: [60, 70]}}",
      "coupler: [A, B]\n  spare: {joints: [B], points: {P: [80, 50]}}"), 14, "links.spare.joints",
     "all pairs and points of link spare lie at one position, so the link has no direction; give a pair or point "
     "of the link elsewhere, at its place in the sketch"),
    (("rocker: [O2, B]", "rocker: [O2]\n  brace: [B, O2]"), 14, "links.rocker",
     "link rocker carries only the pair O2; a link needs two pairs (one pair and a point only when it is the driven "
     "link of a revolute input)"),
    (("  O2: [90, 0]\n", "  O2: [90, 0]\n  X: [5, 5]\n"), 10, "joints.X",
     "the pair X is on no link; list it in the two links it joins"),
])
def test_parts_a_mechanism_cannot_have(edit: tuple[str, str], line: int, key: str, message: str):
    error = refused(FOURBAR.replace(*edit))
    assert (error.line, error.key, error.message) == (line, key, message)


def test_a_pair_joins_two_links_or_is_a_point():
    text = FOURBAR.replace("  O2: [90, 0]\n", "  O2: [90, 0]\n  X: [5, 5]\n").replace("[O1, A]", "[O1, A, X]")
    error = refused(text)
    assert (error.line, error.key) == (10, "joints.X")
    assert error.message == ("the pair X is only on link crank, but a pair joins two links; list it in the other link "
                             "too, or make it a point of crank (points: {X: [x, y]})")


def test_a_prismatic_pair_joins_exactly_two_links():
    text = SLIDER.replace("rocker: [O2, B]", "rocker: [O2, B]\n  third: [O2, A]")
    error = refused(text)
    assert (error.line, error.key) == (9, "joints.O2")
    assert error.message == ("the prismatic pair O2 is on 3 links (frame, rocker and third); a prismatic pair joins "
                             "exactly two links, the guide and the slider")


def test_a_driven_link_may_carry_one_pair_and_a_point():
    text = FOURBAR.replace("crank: [O1, A]", "crank: {joints: [O1], points: {T: [5, 5]}}")
    text = text.replace("  A: [20, 0]\n", "").replace("coupler: {joints: [A, B]", "coupler: {joints: [O1, B]")
    m = read(text)
    assert m.link("crank").joints == ("O1",) and m.link("crank").points[0].name == "T"


def test_a_mechanism_in_two_pieces_names_the_links_apart():
    text = FOURBAR.replace("  O2: [90, 0]", "  O2: [90, 0]\n  X: [5, 5]\n  Y: [6, 9]\n  Z: [9, 9]")
    text = text.replace("rocker: [O2, B]", "rocker: [O2, B]\n  arm1: [X, Y, Z]\n  arm2: [X, Y]\n  arm3: [Y, Z]")
    error = refused(text)
    assert (error.line, error.key) == (18, "links.arm1")
    assert error.message == ("the mechanism falls apart: links arm1, arm2 and arm3 share no pair with the fixed link "
                             "frame or the links joined to it")
