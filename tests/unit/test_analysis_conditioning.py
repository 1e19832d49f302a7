"""analysis.conditioning: a chain's sigma over the sweep, against the angle at its joint."""

from __future__ import annotations

import numpy as np
import pytest
from linkages import four_bar, sigma, toggle

from linkgen.pipeline import build_log

TWO_TOGGLES = (40, 85, 25, 90)


def test_sigma_over_the_sweep_and_the_limit_positions(tmp_path):
    """The chain A-B-O2's sigma is |sin| of the angle at B: its lowest and highest on the rows
    reached (between the toggles) as the hand formula gives them, to 3 digits, and its limit
    positions at the toggles, to 1e-8."""
    log = build_log(str(four_bar(tmp_path, "two_toggles", *TWO_TOGGLES, 90)))
    folded, stretched = toggle(*TWO_TOGGLES, far=False), toggle(*TWO_TOGGLES, far=True)
    theta = np.linspace(0.0, 2 * np.pi, log.samples)
    reached = theta[(theta > folded) & (theta < stretched)]
    hand = [sigma(*TWO_TOGGLES, t) for t in reached]
    (row,) = [c for c in log.conditioning if c.step == 3]
    assert (row.low, row.high) == (float(f"{min(hand):.3g}"), float(f"{max(hand):.3g}"))
    assert [s.kind for s in row.singular] == ["limit", "limit"]
    assert [s.inputs[0] for s in row.singular] == pytest.approx([folded, stretched], abs=1e-8)


def test_a_change_point_is_listed_with_sigma_zero(tmp_path):
    log = build_log(str(four_bar(tmp_path, "parallelogram", 20, 60, 20, 60, 45, ground=30)))
    (row,) = [c for c in log.conditioning if c.step == 3]
    assert [(s.kind, s.sigma) for s in row.singular] == [("change point", 0.0)] * 2
    assert [s.inputs[0] for s in row.singular] == list(log.step(3).change_points)


def test_a_sweep_is_optional(tmp_path):
    assert build_log(str(four_bar(tmp_path, "two_toggles", *TWO_TOGGLES, 90)), sweep=False).conditioning == ()
