"""Grashof's law (linkgen.summary.grashof) by hand, and the four-bar loops found in a mechanism."""

from __future__ import annotations

from pathlib import Path

import pytest

from linkgen.pipeline import build_log
from linkgen.summary.grashof import four_bars, grashof_class, grashof_kind

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize(("lengths", "grashof", "kind"), [
    # (frame d, crank a, coupler b, rocker c): s + l against p + q by hand
    ((90, 20, 78, 51), "Grashof", "crank-rocker"),  # 20 + 90 < 78 + 51; the crank shortest
    ((20, 60, 70, 50), "Grashof", "double-crank"),  # 20 + 70 < 60 + 50; the frame shortest
    ((60, 50, 20, 70), "Grashof", "double-rocker"),  # 20 + 70 < 60 + 50; the coupler shortest
    ((60, 50, 70, 20), "Grashof", "rocker-crank"),  # the link at O2 shortest
    ((60, 40, 50, 41), "non-Grashof", "triple-rocker"),  # 40 + 60 > 50 + 41
    ((60, 20, 60, 20), "change point", "double-crank"),  # a parallelogram: 20 + 60 = 20 + 60, both cranks shortest
    ((60, 20, 50, 30), "change point", "crank-rocker"),  # 20 + 60 = 50 + 30
])
def test_grashof_class_and_type_by_hand(lengths, grashof, kind):
    assert grashof_class(lengths, 60.0) == grashof
    assert grashof_kind(lengths, 60.0) == kind


def test_loops_are_found_once_and_turned_to_their_driven_link():
    """jansen: two loops on the crank (O-A-C-B and O-A-E-B), each driven by the crank at O; Fig. 14:
    the loop J1-J2-J4-J3 of its ternary, which no input drives; the slider-crank has none."""
    loops = four_bars(build_log(str(ROOT / "samples" / "jansen" / "jansen.yaml"), sweep=False))
    assert [(f.pairs, f.driven) for f in loops] == [(("O", "A", "C", "B"), "theta_O"),
                                                    (("O", "A", "E", "B"), "theta_O")]
    (loop,) = four_bars(build_log(str(ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"), sweep=False))
    assert loop.pairs == ("J1", "J2", "J4", "J3") and loop.driven == ""
    assert loop.lengths[:2] == (100.0, 70.0)  # |J1 J3| and |J1 J2| as drawn
    assert four_bars(build_log(str(ROOT / "samples" / "slider_crank" / "slider_crank.yaml"), sweep=False)) == ()
