"""linkgen.validate: a file checked section by section (the modules' own tests are test_validate_*.py)
into the Mechanism, read from disk as from text, and the supported magnitudes (at most 1e30 in size, a
sketch from 1e-30 to 1e30 across) accepted at both ends through the topology's checks."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from mechanism_text import FOURBAR, PATH, check, fourbar, refused

from linkgen.loader import parse
from linkgen.validate import read_mechanism, validate


def test_a_file_on_disk_reads_as_its_text(tmp_path: Path):
    path = tmp_path / "dir" / "four bar.yaml"
    path.parent.mkdir()
    path.write_text(FOURBAR, encoding="utf-8")
    from_disk, from_text = read_mechanism(str(path)), validate(parse(FOURBAR, str(path)), str(path))
    assert from_disk == from_text
    assert (from_disk.path, from_disk.source, from_disk.where.line) == (str(path), "four bar.yaml", 1)


def test_the_mechanism_holds_every_section():
    m = validate(parse(FOURBAR, PATH), PATH)
    assert [j.name for j in m.joints] == ["O1", "A", "B", "O2"]
    assert [lk.name for lk in m.links] == ["frame", "crank", "coupler", "rocker"]
    assert [p.name for p in m.points] == ["P"] and m.fixed.name == "frame"
    assert [i.column for i in m.inputs] == ["theta_O1"] and m.prismatic == ()


def scaled(factor: float, speed: str = "360") -> str:
    text = fourbar().replace("speed: 360", f"speed: {speed}")
    return re.sub(r"(?<!range: )\[(-?\d+), (-?\d+)\]",
                  lambda g: f"[{float(g[1]) * factor!r}, {float(g[2]) * factor!r}]", text)


def test_the_supported_magnitudes_are_accepted_at_both_ends():
    length = check(FOURBAR).length_scale
    small, large = 1e-30 / length, 1e30 / length
    assert check(scaled(small * (1 + 1e-15))).length_scale >= 1e-30
    assert check(scaled(large * (1 - 1e-15))).length_scale <= 1e30
    assert check(scaled(1.0, "1e30")).mechanism.inputs[0].speed == pytest.approx(1e30 * 3.141592653589793 / 180)
    assert check(scaled(1.0, "-1e30"))
    corner = scaled(1e28).replace("[8.999999999999999e+29, 0.0]", "[1e30, 0.0]")
    assert check(corner).length_scale == 1e30
    mirrored = re.sub(r"(?<!range: )\[(-?[0-9.e+]+), (-?[0-9.e+]+)\]",
                      lambda g: f"[{-float(g[1])!r}, {-float(g[2])!r}]", corner)
    assert "[-1e+30, -0.0]" in mirrored
    assert check(mirrored).length_scale == 1e30
    ranged = fourbar().replace("[0, 360]", "[-1e30, 1e30]")
    assert validate(parse(ranged, PATH), PATH).inputs[0].stop == pytest.approx(1e30 * 3.141592653589793 / 180)


@pytest.mark.parametrize("text, what", [
    (scaled(1e-32), "the sketch measures 9.43e-31 mm (from O1 to B"),
    (scaled(1.1e28), "the sketch measures 1.04e30 mm (from O1 to B"),
])
def test_a_sketch_too_small_or_too_large_is_refused(text: str, what: str):
    """Every coordinate is in range; the sketch across (sqrt(80^2 + 50^2) = 94.3 times the factor) is not."""
    error = refused(text)
    assert error.key == "joints.B"
    assert error.message.startswith(what), error.message
