"""extraction.closure: the loop-closure equations of a resolver group, read off its chosen block's steps
(the Fig. 14 six-bar's, checked against its sketch by hand), and the groups it refuses."""

from __future__ import annotations

from pathlib import Path

import pytest
from mechanism_text import SLIDER_TRIAD

from linkgen.extraction import extract
from linkgen.extraction.closure import ClosureRefused, with_closures
from linkgen.topology import analyse
from linkgen.validate import read_mechanism

ROOT = Path(__file__).resolve().parents[2]
FIG14 = ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"


def _procedure(path: Path):
    return extract(analyse(read_mechanism(str(path))))


def test_fig14_group_has_four_lengths_and_one_frame_on_three_positions():
    proc = _procedure(FIG14)
    steps, (group,) = with_closures(proc.steps, proc.variables, proc.groups)
    c = group.closure
    assert c is not None and c.unknowns == ("p_J4", "p_J2", "p_J5")
    # rocker2 holds J4 (the chain's other length is the Add-link J6-J4: no constraint), rocker1 and the
    # ternary's J2-J4 hold J2, the unused coupler is the residual's
    assert [(d.points, d.link, d.step) for d in c.distances] == [
        (("p_J3", "p_J4"), "rocker2", 4), (("p_J1", "p_J2"), "rocker1", 5), (("p_J4", "p_J2"), "ternary", 5),
        (("p_J6", "p_J5"), "coupler", 7)]
    assert [d.length ** 2 for d in c.distances] == pytest.approx([5 ** 2 + 65 ** 2, 70 ** 2, 105 ** 2 + 5 ** 2,
                                                                  120 ** 2 + 20 ** 2], rel=1e-15)
    (frame,) = c.frames
    # step 6 places J5 by link_point on the ternary's J4 and J2
    assert (frame.point, frame.origin, frame.base, frame.link, frame.step) == (
        "p_J5", "p_J4", ("p_J4", "p_J2"), "ternary", 6)
    # J5 - J4 = (-45, 15) = w (J2 - J4) = w (-105, 5): w = (-45 + 15i)(-105 - 5i) / 11050 = along + i across
    assert frame.w == pytest.approx((4800 / 11050, -1350 / 11050), rel=1e-15)
    reason = next(s for s in steps if s.number == group.step).reason
    assert reason == ("Newton on the loop-closure equations of J4, J2 and J5 until rocker2, rocker1, ternary and "
                      "coupler keep their shapes; then add1 read off the solution")


def test_the_other_steps_keep_their_reasons_and_the_fallbacks_have_no_equations():
    proc = _procedure(FIG14)
    steps, (group,) = with_closures(proc.steps, proc.variables, proc.groups)
    assert [s for s in steps if s.number != group.step] == [s for s in proc.steps if s.number != group.step]
    assert all(v.closure is None for v in group.variants)


def test_a_group_placed_by_a_prismatic_chain_is_refused(tmp_path: Path):
    path = tmp_path / "slider_triad.yaml"
    path.write_text(SLIDER_TRIAD)
    proc = _procedure(path)
    with pytest.raises(ClosureRefused, match="revolute pairs only, and step 5 of group 1 places J2 by PRR_links"):
        with_closures(proc.steps, proc.variables, proc.groups)


def test_an_actuators_length_is_read_from_its_input():
    """cylinder_triad: the cylinder J3-J4 is the input; its chain's length is the input's record."""
    proc = _procedure(ROOT / "tests" / "mechanisms" / "cylinder_triad.yaml")
    _, (group,) = with_closures(proc.steps, proc.variables, proc.groups)
    assert group.closure is not None
    first = group.closure.distances[0]
    assert (first.points, first.variable, first.link) == (("p_J3", "p_J4"), "in1", "d_J3_J4")
    assert first.length == pytest.approx(65.19202405202648, rel=1e-15)  # the sketch's J3-J4
    assert [d.variable for d in group.closure.distances[1:]] == ["", "", ""]
