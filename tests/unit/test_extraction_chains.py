"""extraction.chains: each dyad kind, and branches read off the sketch (a mirrored sketch flips them)."""

from __future__ import annotations

from pathlib import Path

import pytest

from linkgen.extraction import extract
from linkgen.topology import analyse
from linkgen.validate import read_mechanism

ROOT = Path(__file__).resolve().parents[2]
MECHANISMS = ROOT / "tests" / "mechanisms"


def _mirrored(path: Path, tmp: Path) -> Path:
    """The same file with every y coordinate negated (axes and angles mirror too)."""
    import re
    text = path.read_text()
    text = re.sub(r"\[(-?[0-9.]+), (-?[0-9.]+)\]", lambda m: f"[{m.group(1)}, {-float(m.group(2))!r}]", text)
    text = re.sub(r"axis: (-?[0-9.]+)", lambda m: f"axis: {-float(m.group(1))!r}", text)
    out = tmp / path.name
    out.write_text(text)
    return out


@pytest.mark.parametrize("name, function, branch", [
    ("slider_crank", "PRR_links", 1),  # B (45, -5) is 35 ahead of A (10, 8) along the slide's axis 0
    ("inverted", "RPR_links", -1),  # O2 (60, 0) is (40, -10).(cos 166, sin 166) = -41.2 along from A (20, 10)
])
def test_a_slide_branch_is_the_distance_along_the_axis(name: str, function: str, branch: int, tmp_path: Path):
    """A distance along a slide is the same in the mirrored sketch (axis and offsets mirror together)."""
    plain = extract(analyse(read_mechanism(str(MECHANISMS / f"{name}.yaml"))))
    mirror = extract(analyse(read_mechanism(str(_mirrored(MECHANISMS / f"{name}.yaml", tmp_path)))))
    (a,) = [s for s in plain.steps if s.function == function]
    (b,) = [s for s in mirror.steps if s.function == function]
    assert a.branch == b.branch == branch


def test_fourbar_3r_branch_is_the_side_of_the_middle_pair(tmp_path: Path):
    fourbar = ROOT / "samples" / "fourbar" / "fourbar.yaml"
    plain = extract(analyse(read_mechanism(str(fourbar))))
    mirror = extract(analyse(read_mechanism(str(_mirrored(fourbar, tmp_path)))))
    (a,) = [s for s in plain.steps if s.function == "RRR_links"]
    (b,) = [s for s in mirror.steps if s.function == "RRR_links"]
    # B (80, 50) is left of A (20, 0) -> O2 (90, 0); mirrored to (80, -50) it is right of it
    assert (a.branch, b.branch) == (1, -1)
