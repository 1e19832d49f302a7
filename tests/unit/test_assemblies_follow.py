"""The step log's listing of the assemblies and the mechanism redrawn in one of them."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from linkgen.assemblies import whole_log
from linkgen.assemblies.follow import census_of, chosen, listing, moved
from linkgen.errors import InputError
from linkgen.validate import read_mechanism

ROOT = Path(__file__).resolve().parents[2]
INVERTED = str(ROOT / "samples" / "inverted_slider" / "inverted_slider.yaml")
UNCOUNTED = str(ROOT / "tests" / "assemblies" / "moving_slot.yaml")  # a group linkgen does not count


def _lengths(m) -> dict[tuple[str, str], float]:
    """Every distance between two pairs or points of one link, from the file's coordinates."""
    out = {}
    for lk in m.links:
        spots = {j: (m.joint(j).x, m.joint(j).y) for j in lk.joints} | {p.name: (p.x, p.y) for p in lk.points}
        names = sorted(spots)
        for i, a in enumerate(names):
            for b in names[i + 1:]:
                out[(a, b)] = math.dist(spots[a], spots[b])
    return out


def test_the_redrawn_mechanism_keeps_every_length_and_turns_the_slide_with_its_guide():
    log = whole_log(INVERTED)
    found = listing(log)
    assert found.counted and found.follows == 1 and [a.sketch for a in found.listing] == [True, False]
    m = read_mechanism(INVERTED)
    other = moved(m, log, found.listing[1])
    before, after = _lengths(m), _lengths(other)
    assert all(abs(before[k] - after[k]) <= 1e-12 * log.length_scale for k in before if "S" not in k)
    assert [(j.x, j.y) for j in other.joints if j.name in m.fixed.joints] == \
           [(j.x, j.y) for j in m.joints if j.name in m.fixed.joints]
    assert (other.joint("A").x, other.joint("A").y) == (m.joint("A").x, m.joint("A").y)  # the crank is the input
    s, o2 = other.joint("S"), other.joint("O2")
    line = math.atan2(s.y - o2.y, s.x - o2.x)  # the lever's slot runs through O2 in the sketch
    assert abs(math.remainder(line - s.axis, math.pi)) < 1e-12
    assert abs(math.remainder(s.axis - m.joint("S").axis, 2 * math.pi)) > 0.1  # it did turn


def test_the_listing_reads_back_as_the_census():
    log = whole_log(INVERTED)
    from dataclasses import replace

    census = census_of(replace(log, assemblies=listing(log)))
    assert [a.number for a in census.assemblies] == [1, 2]
    assert census.assemblies[1].values["S.x"] == dict(listing(log).listing[1].values)["S.x"]


def test_a_group_it_cannot_count_is_recorded_and_cannot_be_chosen():
    log = whole_log(UNCOUNTED)
    found = listing(log)
    assert not found.counted and found.listing == () and "cannot count" in found.notes[0]
    with pytest.raises(InputError, match="linkgen cannot count"):
        chosen(read_mechanism(UNCOUNTED), 1, found, True)
