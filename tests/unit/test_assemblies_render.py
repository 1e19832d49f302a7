"""One SVG per assembly: well-formed, the same page for all, the same bytes every time, each
pair drawn where the assembly has it."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

from linkgen.assemblies import assemblies, whole_log
from linkgen.assemblies.render import MARGIN, page, render_all

ROOT = Path(__file__).resolve().parents[2]
SVG = "{http://www.w3.org/2000/svg}"


def test_every_assembly_is_drawn_on_one_page_where_it_is():
    path = str(ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml")
    log = whole_log(path)
    c = assemblies(path, log, [90.0])
    files = render_all(log, c)
    assert sorted(files) == [f"sixbar_fig14_assembly_{k}.svg" for k in range(1, 5)]
    assert files == render_all(log, c)
    x0, y1, scale, height = page(log, c)
    sizes = set()
    for a in c.assemblies:
        root = ET.fromstring(files[f"sixbar_fig14_assembly_{a.number}.svg"])
        sizes.add((root.get("width"), root.get("height")))
        circles = root.findall(f"{SVG}circle")
        labels = [t.text for t in root.findall(f"{SVG}text")]
        assert len(circles) == len(log.pairs)
        for p, circle in zip(log.pairs, circles):
            assert abs(float(circle.get("cx")) - (MARGIN + (a.values[f"{p.name}.x"] - x0) * scale)) <= 0.005
            assert abs(float(circle.get("cy")) - (MARGIN + (y1 - a.values[f"{p.name}.y"]) * scale)) <= 0.005
        caption = labels[-1]
        assert caption.startswith(f"assembly {a.number} of 4 at theta_J7 = 90 deg")
        assert ("(the sketch's)" in caption) == a.sketch
    assert sizes == {("480", f"{height:.2f}".rstrip("0").rstrip("."))}


def test_no_assembly_no_figure():
    path = str(ROOT / "tests" / "mechanisms" / "fourbar_partial.yaml")
    log = whole_log(path)
    assert render_all(log, assemblies(path, log, [90.0])) == {}
