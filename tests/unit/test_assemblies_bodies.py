"""linkgen.assemblies.bodies: quaternary_fold's group read as two bodies on four-bars tied by two
couplers (checked by hand against its file), and a triad's group refused."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from linkgen.assemblies import whole_log
from linkgen.assemblies.bodies import two_bodies_of
from linkgen.assemblies.triad import NotReducible

ROOT = Path(__file__).resolve().parents[2]


def test_quaternary_folds_group_is_two_quaternaries_on_four_bars_tied_by_two_couplers():
    log = whole_log(str(ROOT / "tests" / "mechanisms" / "quaternary_fold.yaml"))
    b = two_bodies_of(log, log.groups[0])
    left, right = b.bodies
    assert (left.link, set(left.pairs), right.link, set(right.pairs)) == ("left", {"A1", "A2", "A3", "A4"}, "right",
                                                                          {"B1", "B2", "B3", "B4"})
    legs = {(left.base, left.pair), (left.other_base,), (right.base, right.pair), (right.other_base,)}
    assert legs == {("G1", "A1"), ("G2",), ("G3", "B1"), ("G4",)}
    assert {c.link for c in b.couplers} == {"upper", "lower"}
    upper = next(c for c in b.couplers if c.link == "upper")
    assert float(upper.length2) == pytest.approx((103.5 - 5.8) ** 2 + (109.2 - 110.4) ** 2, rel=1e-15)
    assert float(left.length2) == pytest.approx((46.0 - 44.2) ** 2 + (68.1 - 3.1) ** 2, rel=1e-15)


def test_a_triads_group_is_not_two_bodies():
    log = whole_log(str(ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"))
    with pytest.raises(NotReducible, match="not two links on four-bars"):
        two_bodies_of(log, log.groups[0])


def test_quaternary_slides_right_body_has_its_block_as_second_leg_on_the_frame_line():
    """quaternary_slide.yaml: right rides on leg3 (from G3) and the block on B2, whose line is the slide S's
    axis (80 deg) through B2's sketch position (153.9, 69.0), in the programs' coordinates (less the origin)."""
    log = whole_log(str(ROOT / "tests" / "regressions" / "quaternary_slide.yaml"))
    left, right = two_bodies_of(log, log.groups[0]).bodies
    assert (left.legs, right.legs, right.base, right.other_base) == (("leg1", "leg2"), ("leg3", "block"), "G3", "S")
    assert left.line is None and right.line is not None
    (nx, ny), (ax, ay) = right.line
    assert (float(nx), float(ny)) == pytest.approx((-math.sin(math.radians(80)), math.cos(math.radians(80))), abs=1e-15)
    assert (float(ax) + log.origin[0], float(ay) + log.origin[1]) == pytest.approx((153.9, 69.0), abs=1e-12)
    assert float(right.held[0]) == pytest.approx(153.9 - 75.9, abs=1e-12)
