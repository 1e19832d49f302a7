"""analysis.sweep: the closing margin, local minima, the span searched, a step's own procedure, zooms found
together."""

from __future__ import annotations

import math

import numpy as np
import pytest
from linkages import four_bar

from linkgen.analysis.sweep import (
    Zooms,
    local_minima,
    margin,
    own,
    run,
    span,
    spanning,
    zoom_min,
    zooms_together,
)
from linkgen.pipeline import build_log

TWO_TOGGLES = (40, 85, 25, 90)


def test_the_margin_of_a_3r_chain_is_its_sides_sum_less_twice_the_longest(tmp_path):
    """Kahan's factor z - (x - y) of sides x >= y >= z is x + y + z - 2x: with sides |A O2|, b and c,
    from the law of cosines, over a turn of the crank (to rounding of the sides)."""
    a, b, c, d = TWO_TOGGLES
    log = spanning(build_log(str(four_bar(tmp_path, "two_toggles", *TWO_TOGGLES, 90)), sweep=False))
    lam = np.linspace(0.0, 1.0, 97)
    result = run(log, lam)
    theta = result.inputs[:, 0]
    q = np.sqrt(a * a + d * d - 2 * a * d * np.cos(theta))
    hand = q + b + c - 2 * np.maximum(q, max(b, c))
    assert margin(log.step(3), result) == pytest.approx(hand, abs=1e-12 * d)
    assert margin(log.step(2), result) is None  # the crank's input: one assembly, no margin


def test_an_angle_is_searched_a_turn_around_the_sketch(tmp_path):
    log = build_log(str(four_bar(tmp_path, "two_toggles", *TWO_TOGGLES, 90)), sweep=False)
    lo, hi, periodic = span(log)
    assert periodic and (lo, hi) == pytest.approx((-math.pi / 2, 3 * math.pi / 2), abs=1e-15)
    assert (spanning(log).inputs[0].start, spanning(log).inputs[0].stop) == (lo, hi)


def test_local_minima_inside_and_across_the_seam():
    v = np.array([0.0, 1.0, 0.5, 2.0, 3.0, 0.0])  # a turn: the last row is the first
    usable = np.ones(6, dtype=bool)
    assert local_minima(v, usable) == [2]
    assert local_minima(v, usable, periodic=True) == [0, 2]
    assert local_minima(v, np.array([True, True, True, False, True, True])) == []


def test_a_steps_own_procedure_is_what_it_reads_from(tmp_path):
    """The rocker's angle (step 6) needs B (step 3), from A (the crank input, step 2) and the
    frame's pairs (step 1); not the crank's and coupler's angles (steps 4 and 5)."""
    log = build_log(str(four_bar(tmp_path, "two_toggles", *TWO_TOGGLES, 90)), sweep=False)
    assert [s.target for s in log.steps] == ["frame", "A", "B", "crank", "coupler", "rocker"]
    assert [s.number for s in own(log, log.step(6)).steps] == [1, 2, 3, 6]


def test_zooms_found_together_are_each_zoom_alone(tmp_path):
    """The closing margin's and an angle's least values near rows of a sweep: every refinement's grids in
    one evaluation give, bit for bit, what zoom_min finds one zoom at a time (a measure with no finite
    value keeps its bracket's start, as zoom_min does)."""
    log = spanning(build_log(str(four_bar(tmp_path, "two_toggles", *TWO_TOGGLES, 90)), sweep=False))
    angle = next(c.variable for c in log.columns[1:] if c.field == "the" and not log.variable(c.variable).constant)
    asked = [(0.1, 0.3, lambda r: margin(log.step(3), r)), (0.6, 0.9, lambda r: np.asarray(r.values[angle][0])),
             (0.2, 0.25, lambda r: np.full(len(r.status), np.nan)), (0.0, 0.05, lambda r: margin(log.step(3), r))]
    alone = [zoom_min(log, lo, hi, value) for lo, hi, value in asked]
    assert zooms_together(log, asked) == alone and alone[2] == (0.2, math.inf)
    zooms = Zooms(log)
    pending = [zooms.ask(lo, hi, value, None) for lo, hi, value in asked]
    assert not zooms.found and [p() for p in pending] == alone
