"""render.svg: the sketch drawn to scale (positions worked out by hand from the page layout), labels, and
numbers rounded to 0.01 so the bytes are the same everywhere."""

from __future__ import annotations

import random
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from linkgen.pipeline import build_log
from linkgen.render.svg import MARGIN, PLACES, WIDTH, Box, Segment, _box, _crosses, _f, _Labels, _overlaps, render_svg
from linkgen.render.svgwriter import esc

ROOT = Path(__file__).resolve().parents[2]
NS = {"s": "http://www.w3.org/2000/svg"}


def _svg(path: Path) -> ET.Element:
    return ET.fromstring(render_svg(build_log(str(path))))


@pytest.mark.parametrize("x, text", [
    (2.0, "2"), (1.25, "1.25"), (12.3456, "12.35"), (-3.1, "-3.1"), (-0.001, "0"), (0.004, "0"), (100.0, "100"),
])
def test_numbers_have_at_most_two_decimals_and_no_trailing_zeros(x: float, text: str):
    assert _f(x) == text


def test_text_is_escaped():
    assert esc("a<b & c>d") == "a&lt;b &amp; c&gt;d"


def test_the_fourbar_is_drawn_to_scale():
    svg = _svg(ROOT / "samples" / "fourbar" / "fourbar.yaml")
    # the sketch spans x 0..90 and y 0..70 (O1, A, B, O2 and P (60, 70)): the wider span fills the width
    scale = (WIDTH - 2 * MARGIN) / 90
    assert float(svg.get("height")) == pytest.approx(70 * scale + 2 * MARGIN, abs=0.005)
    circles = [(float(c.get("cx")), float(c.get("cy")), c.get("fill")) for c in svg.iterfind("s:circle", NS)]
    expected = [(0, 0, "#555555"), (20, 0, "white"), (80, 50, "white"), (90, 0, "#555555"), (60, 70, "black")]
    for (cx, cy, fill), (x, y, colour) in zip(circles, expected, strict=True):
        assert (cx, cy) == pytest.approx((MARGIN + x * scale, MARGIN + (70 - y) * scale), abs=0.005)
        assert fill == colour  # fixed pivots filled, moving pairs white, points black


def test_each_pair_and_point_is_labelled_with_the_step_that_finds_it():
    log = build_log(str(ROOT / "samples" / "fourbar" / "fourbar.yaml"))
    labels = [t.text for t in ET.fromstring(render_svg(log)).iterfind("s:text", NS)]
    found = {p: s.number for s in log.steps for p in s.determines}
    found["P"] = next(s.number for s in log.steps if s.target == "P")
    assert [f"{p} ({found[p]})" for p in ("O1", "A", "B", "O2", "P")] == [t for t in labels if t and "(" in t][:5]
    assert found == {"O1": 1, "O2": 1, "A": 2, "B": 3, "P": 4}


def test_add_links_are_dotted_lines_between_their_pairs():
    log = build_log(str(ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"))
    svg = ET.fromstring(render_svg(log))
    dotted = [ln for ln in svg.iterfind("s:line", NS) if ln.get("stroke-dasharray") == "2 4"]
    assert len(dotted) == len(log.add_links) >= 1
    names = [t.text for t in svg.iterfind("s:text", NS) if t.text and t.text.startswith("Add-link")]
    assert names == [f"Add-link {a.name}" for a in log.add_links]


def test_a_prismatic_pair_is_a_block_turned_to_its_axis():
    svg = _svg(ROOT / "tests" / "mechanisms" / "whitworth.yaml")
    # S slides along 53.13 degrees (the 3-4-5 direction); the page's y axis points down
    (rect,) = [r for r in svg.iterfind("s:rect", NS) if r.get("transform", "").startswith("rotate(-53.13 ")]
    axis = [ln for ln in svg.iterfind("s:line", NS) if ln.get("stroke-dasharray") == "4 2"]
    dx, dy = (float(axis[0].get("x2")) - float(axis[0].get("x1")), float(axis[0].get("y2")) - float(axis[0].get("y1")))
    assert (dx, dy) == pytest.approx((80 * 0.6, -80 * 0.8), abs=0.01)
    assert rect.get("width") == "14"


@pytest.mark.parametrize("sample", ["fourbar", "jansen", "sixbar_slider"])
def test_every_number_is_rounded_to_two_decimals(sample: str):
    text = render_svg(build_log(str(ROOT / "samples" / sample / f"{sample}.yaml")))
    assert re.findall(r"\d\.\d\d", text) and not re.findall(r"\d\.\d{3,}", text)



def test_labels_are_placed_as_by_counting_every_label_marker_and_line():
    """The cell index finds what a place covers: the placements equal a search that counts every
    label, marker and line placed before (random figures, labels far wider than a cell, lines long)."""
    rng = random.Random(7)
    for _ in range(20):
        width, height = rng.uniform(100, 900), rng.uniform(100, 400)
        fast = _Labels(width, height)
        marks: list[Box] = []
        lines: list[Segment] = []
        placed: list[Box] = []
        want = []
        for _ in range(40):
            x, y, kind = rng.uniform(0, width), rng.uniform(0, height), rng.random()
            if kind < 0.3:
                fast.mark(x, y, 6)
                marks.append((x - 6, y - 6, x + 6, y + 6))
            elif kind < 0.6:
                b = (rng.uniform(0, width), rng.uniform(0, height))
                fast.line((x, y), b)
                lines.append(((x, y), b))
            else:
                text = "J" * rng.randint(1, 12)
                best: tuple[int, float, float, bool] | None = None
                for dx, dy in PLACES:
                    box = _box(x + dx, y + dy, text, dx < 0)
                    cost = (100 * sum(_overlaps(box, b) for b in placed) + 20 * sum(_overlaps(box, b) for b in marks)
                            + 5 * sum(_crosses(box, s) for s in lines)
                            + 50 * (box[0] < 0 or box[2] > width or box[1] < 0 or box[3] > height))
                    if best is None or cost < best[0]:
                        best = (cost, x + dx, y + dy, dx < 0)
                    if cost == 0:
                        break
                assert best is not None
                placed.append(_box(best[1], best[2], text, best[3]))
                want.append((_f(best[1]), _f(best[2]), best[3]))
                fast.put(x, y, text)
        got = [(m[1], m[2], m[3] is not None) for m in
               (re.match(r'<text x="([^"]+)" y="([^"]+)"( text-anchor="end")?>', t) for t in fast.out) if m]
        assert got == want
