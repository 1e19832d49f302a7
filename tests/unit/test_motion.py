"""linkgen.motion: gaps combine into the reach, worked by hand on made-up gaps."""

from __future__ import annotations

import math

import pytest

from linkgen.motion import Gap, Reach, reach_between

TURN = 2 * math.pi


def test_a_point_is_a_gap_of_one_value():
    assert Gap(3, 1.0, 1.0).point
    assert not Gap(3, 1.0, 2.0).point and not Gap(3, None, 2.0).point and not Gap(3, 1.0, None).point


def test_a_sliding_input_is_reached_between_the_middles_of_the_nearest_gaps():
    """Gaps [2, 4] (middle 3) and [10, 12] above the sketch at 0, [-8, -6] below: the reach is
    (-7, 3), named by their steps."""
    gaps = (Gap(5, 10.0, 12.0), Gap(3, 2.0, 4.0), Gap(6, -8.0, -6.0))
    assert reach_between(gaps, 0.0, periodic=False) == Reach(-7.0, 6, 3.0, 3, False)


def test_a_gap_cut_by_the_span_ends_at_its_first_failing_value():
    """A gap open above (it runs past the span) bounds the reach at the value given."""
    assert reach_between((Gap(4, 5.0, None),), 0.0, periodic=False) == Reach(None, 0, 5.0, 4, False)
    assert reach_between((Gap(4, None, -5.0),), 0.0, periodic=False) == Reach(-5.0, 4, None, 0, False)


def test_overlapping_gaps_are_one_named_by_the_first():
    """Step 6's gap [1, 3] and step 3's [2, 7] overlap: one gap [1, 7] of step 6, middle 4 (step 3's
    own middle would be 4.5); [8, 9] stays apart."""
    gaps = (Gap(3, 2.0, 7.0), Gap(6, 1.0, 3.0), Gap(2, 8.0, 9.0))
    assert reach_between(gaps, 0.0, periodic=False) == Reach(None, 0, 4.0, 6, False)
    assert reach_between(gaps, 7.5, periodic=False) == Reach(4.0, 6, 8.5, 2, False)


def test_an_open_gap_swallows_what_it_overlaps():
    assert reach_between((Gap(2, 3.0, None), Gap(3, 4.0, 6.0)), 0.0, periodic=False) == Reach(None, 0, 3.0, 2, False)


def test_a_point_does_not_merge():
    """A point inside another gap bounds the reach itself (the chain's margin dips there)."""
    gaps = (Gap(2, 1.0, 5.0), Gap(4, 1.5, 1.5))
    assert reach_between(gaps, 0.0, periodic=False) == Reach(None, 0, 1.5, 4, False)


def test_an_angle_with_one_gap_has_no_reach():
    """It is reached all round but in the gap, where rows fail anyway."""
    assert reach_between((Gap(3, 2.0, 3.0),), 0.0, periodic=True) is None


def test_an_angle_is_reached_between_gaps_a_turn_apart():
    """Gaps with middles 1 and 3 around a sketch at 0: below, 3 a turn back; above, 1."""
    gaps = (Gap(3, 0.5, 1.5), Gap(6, 2.5, 3.5))
    reach = reach_between(gaps, 0.0, periodic=True)
    assert reach == Reach(float(f"{3.0 - TURN:.12g}"), 6, 1.0, 3, True)


def test_an_angle_merges_gaps_across_the_turn():
    """[5, 6.5] runs past the turn into [0.1, 0.4] (a turn on: [6.38, 6.68]): one gap [5, 6.68],
    middle 5.84, named by step 6; with [2, 3] (middle 2.5) a sketch at 4 is reached in (2.5, 5.84)."""
    gaps = (Gap(3, 0.1, 0.4), Gap(6, 5.0, 6.5), Gap(7, 2.0, 3.0))
    reach = reach_between(gaps, 4.0, periodic=True)
    assert reach is not None and (reach.low, reach.low_step, reach.high_step) == (2.5, 7, 6)
    assert reach.high == pytest.approx((5.0 + 0.4 + TURN) / 2, abs=1e-11)


def test_a_row_past_the_reach_fails_with_the_code_of_its_side():
    """Reason 1 of the step on each side; a side without a bound takes the other's."""
    assert Reach(-1.0, 6, 2.0, 3, True).codes() == (61, 31)
    assert Reach(None, 0, 2.0, 3, False).codes() == (31, 31)
