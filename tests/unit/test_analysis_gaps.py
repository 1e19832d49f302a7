"""analysis.gaps: where a chain cannot close, against the law of cosines."""

from __future__ import annotations

import math

import pytest
from linkages import four_bar, toggle

from linkgen.pipeline import build_log

TWO_TOGGLES = (40, 85, 25, 90)  # b + c < a + d and |b - c| > d - a: the chain stretches and folds


def test_a_four_bar_that_stretches_and_folds_has_two_gaps(tmp_path):
    """Its chain cannot close with the crank within the folded toggle angle of the ground line
    nor beyond the stretched one: two gaps, each end to 1e-9."""
    log = build_log(str(four_bar(tmp_path, "two_toggles", *TWO_TOGGLES, 90)), sweep=False)
    folded, stretched = toggle(*TWO_TOGGLES, far=False), toggle(*TWO_TOGGLES, far=True)
    assert [g.step for g in log.gaps] == [3, 3] and log.step(3).function == "RRR_links"
    assert [(g.low, g.high) for g in log.gaps] == [pytest.approx((-folded, folded), abs=1e-9),
                                                    pytest.approx((stretched, 2 * math.pi - stretched), abs=1e-9)]


def test_the_reach_lies_between_the_middles_of_the_gaps(tmp_path):
    """The gaps lie symmetric about the ground line: their middles are 0 and pi."""
    log = build_log(str(four_bar(tmp_path, "two_toggles", *TWO_TOGGLES, 90)), sweep=False)
    reach = log.reach
    assert reach is not None and reach.periodic and (reach.low_step, reach.high_step) == (3, 3)
    assert (reach.low, reach.high) == pytest.approx((0.0, math.pi), abs=1e-10)
    assert "reach_at" in log.runtime


def test_a_gap_narrower_than_a_row_is_found_at_the_deepest_margin(tmp_path):
    """b + c = a + d - 1e-5: the chain cannot close only within 1e-3 rad of pi (the stretched
    toggles), between the search's rows (a quarter degree away); the margin's dip finds it, at
    pi, where |A O2| is largest."""
    lengths = (40, 100 - 1e-5, 30, 90)
    log = build_log(str(four_bar(tmp_path, "dip", *lengths, 90.25)), sweep=False)
    (dip,) = [g for g in log.gaps if g.point]
    stretched = toggle(*lengths, far=True)
    assert stretched < dip.low < 2 * math.pi - stretched and dip.low == pytest.approx(math.pi, abs=1e-6)


def test_a_crank_rocker_has_none(tmp_path):
    log = build_log(str(four_bar(tmp_path, "crank_rocker", 20, 70, 50, 60, 60)), sweep=False)
    assert log.gaps == () and log.reach is None
