"""linkgen.assemblies.pivots: class4_slot's and class4's groups read as two links on their own pivots
tied by two ties (checked by hand against their files), and a triad's group refused."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from linkgen.assemblies import whole_log
from linkgen.assemblies.pivots import pivoted_of
from linkgen.assemblies.triad import NotReducible

ROOT = Path(__file__).resolve().parents[2]


def _floats(v):
    return tuple(float(x) for x in v)


def test_class4_slots_group_is_left_and_right_tied_by_upper_and_a_slot():
    """left turns about O1 (0, 0), right about O2 (100, 20); upper ties B (30, 60) to E (80, 80); the block
    keeps C (60, 20) on right's slot at 30 deg through C; the slide pair S rides on the block at C."""
    log = whole_log(str(ROOT / "tests" / "regressions" / "class4_slot.yaml"))
    p = pivoted_of(log, log.groups[0])
    assert (p.links, p.pivots) == (("left", "right"), ("O1", "O2"))
    upper, slot = p.ties
    assert (upper.link, upper.body, _floats(upper.a), _floats(upper.b), float(upper.length2)) == (
        "upper", 0, (30.0, 60.0), (-20.0, 60.0), 50.0**2 + 20.0**2)
    assert upper.normal is None
    assert (slot.link, slot.body, _floats(slot.a), _floats(slot.b)) == ("block", 0, (60.0, 20.0), (-40.0, 0.0))
    assert slot.normal is not None
    assert _floats(slot.normal) == pytest.approx((-math.sin(math.radians(30)), math.cos(math.radians(30))), abs=1e-16)
    spots = {s.pair: (s.body, _floats(s.a), s.turn, _floats(s.b)) for s in p.spots}
    assert spots == {"B": (0, (30.0, 60.0), 0, (0.0, 0.0)), "C": (0, (60.0, 20.0), 0, (0.0, 0.0)),
                     "E": (1, (-20.0, 60.0), 1, (0.0, 0.0)), "S": (0, (60.0, 20.0), 1, (0.0, 0.0))}
    assert p.axes((0.1, 0.25)) == {"S": pytest.approx(math.radians(30) + 0.25, abs=1e-15)}
    assert p.describe() == "the links left (on O1) and right (on O2) tied by upper and the slot of block"


def test_class4s_group_is_tied_by_two_links():
    log = whole_log(str(ROOT / "tests" / "assemblies" / "class4.yaml"))
    p = pivoted_of(log, log.groups[0])
    assert {t.link for t in p.ties} == {"upper", "lower"} and all(t.normal is None for t in p.ties)
    lower = next(t for t in p.ties if t.link == "lower")
    assert float(lower.length2) == (120 - 60) ** 2 + (60 - 20) ** 2


def test_a_triads_group_is_not_two_pivoted_links():
    log = whole_log(str(ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"))
    with pytest.raises(NotReducible, match="not two links on their own pivots"):
        pivoted_of(log, log.groups[0])
