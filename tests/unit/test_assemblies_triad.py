"""A resolver group read as a triad: its ternary, legs and exact data, by hand from the sketches;
groups that are not triads refused with their reason."""

from __future__ import annotations

from fractions import Fraction
from pathlib import Path

import pytest

from linkgen.assemblies import whole_log
from linkgen.assemblies.triad import GRID_BITS, NotReducible, grid, group_pairs, known_before, snap, triad_of

ROOT = Path(__file__).resolve().parents[2]
FIG14 = str(ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml")


def test_fig14s_group_is_the_ternary_held_by_two_rockers_and_the_coupler():
    log = whole_log(FIG14)
    (g,) = log.groups
    assert set(group_pairs(log, g)) == {"J2", "J4", "J5"}
    assert {"J1", "J3", "J6", "J7"} <= known_before(log, g) and not {"J2", "J4", "J5"} & known_before(log, g)
    t = triad_of(log, g)
    assert t.ternary == "ternary"
    legs = {leg.pair: (leg.carrier, leg.base, leg.length2) for leg in t.legs}
    assert legs == {"J2": ("rocker1", "J1", 70**2), "J4": ("rocker2", "J3", 5**2 + 65**2),
                    "J5": ("coupler", "J6", 120**2 + 20**2)}
    sketch = {"J2": (0, 70), "J4": (105, 65), "J5": (60, 80)}
    first = sketch[t.pairs[0]]
    assert t.local == tuple((Fraction(sketch[p][0] - first[0]), Fraction(sketch[p][1] - first[1])) for p in t.pairs)
    assert "rocker1 at J1" in t.describe()


def test_a_cylinder_is_a_leg_whose_length_is_its_input():
    log = whole_log(str(ROOT / "tests" / "mechanisms" / "cylinder_triad.yaml"))
    t = triad_of(log, log.groups[0])
    (cylinder,) = [leg for leg in t.legs if leg.carrier == "d_J3_J4"]
    assert (cylinder.pair, cylinder.base, cylinder.length2, cylinder.input) == ("J4", "J3", None, 0)


def test_a_block_on_a_fixed_slide_is_a_leg_and_the_ternary_is_found_past_it():
    log = whole_log(str(ROOT / "tests" / "assemblies" / "slider_leg.yaml"))
    t = triad_of(log, log.groups[0])  # the block joins two pairs the group writes (J4, S): it is no ternary
    assert t.ternary == "ternary" and t.pairs == ("J2", "J4", "J5")
    assert [(leg.carrier, leg.base, leg.line is not None) for leg in t.legs] == [
        ("rocker1", "J1", False), ("block", "S", True), ("coupler", "J6", False)]


def test_a_group_of_class_iv_is_refused():
    log = whole_log(str(ROOT / "tests" / "assemblies" / "class4.yaml"))
    with pytest.raises(NotReducible, match="class IV or higher"):
        triad_of(log, log.groups[0])


def test_the_grid_is_a_power_of_two_far_below_a_double_at_the_length_scale():
    for scale in (1e-30, 0.7, 180.0, 1e30):
        unit = grid(scale)
        assert unit.numerator == 1 or unit.denominator == 1
        assert scale * 2.0**-GRID_BITS <= unit < scale * 2.0 ** (1 - GRID_BITS)
    unit = grid(180.0)
    for x in (0.1, -65.3, 1e-300, 179.99999999999997):
        s = snap(x, unit)
        assert (s / unit).denominator == 1 and abs(s - Fraction(x)) <= unit / 2
    assert snap(70.0, unit) == 70  # sketch numbers on the grid stay as they are
