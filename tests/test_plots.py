"""The plots of the sweep, read back from their SVG and checked against routes of their own: the
generated Python program's CSV, the four-bar's closed-form limit positions and crank circle (the writer's pieces by
hand: tests/unit/test_render_svgwriter.py)."""

from __future__ import annotations

import json
import math
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from programs import build, parse, run_python

from linkgen.sweepdata import MAX_ROWS

ROOT = Path(__file__).resolve().parents[1]
SVG = "{http://www.w3.org/2000/svg}"
FOURBAR = ROOT / "samples" / "fourbar" / "fourbar.yaml"
PARTIAL = ROOT / "tests" / "mechanisms" / "fourbar_partial.yaml"  # crank 40, coupler 50, rocker sqrt(2000), frame 90


def _svg(folder: Path, name: str) -> ET.Element:
    return ET.fromstring((folder / name).read_text(encoding="utf-8"))


def _subpaths(d: str) -> list[list[tuple[float, float]]]:
    """A path's d as its stretches of vertices (one per M)."""
    out: list[list[tuple[float, float]]] = []
    for op, x, y in re.findall(r"([ML])(-?[\d.]+) (-?[\d.]+)", d):
        if op == "M":
            out.append([])
        out[-1].append((float(x), float(y)))
    return out


def _panel(root: ET.Element, title: str) -> ET.Element:
    for g in root.iter(f"{SVG}g"):
        if g.get("class") == "panel" and any(t.text == title for t in g.iter(f"{SVG}text")):
            return g
    raise AssertionError(f"no panel {title}")


def _finite_runs(values: list[float]) -> list[int]:
    """Lengths of the stretches of finite values (worked out from the CSV alone)."""
    out, length = [], 0
    for v in values:
        if math.isfinite(v):
            length += 1
        elif length:
            out.append(length)
            length = 0
    return out + ([length] if length else [])


@pytest.fixture(scope="module")
def partial(tmp_path_factory: pytest.TempPathFactory):
    folder = tmp_path_factory.mktemp("partial")
    log = build(PARTIAL, folder, motion=True)
    return log, folder, parse(run_python(log, folder))


@pytest.fixture(scope="module")
def fourbar(tmp_path_factory: pytest.TempPathFactory):
    folder = tmp_path_factory.mktemp("fourbar")
    log = build(FOURBAR, folder, motion=True)
    return log, folder, parse(run_python(log, folder))


def test_failed_rows_are_gaps_and_every_vertex_is_the_csv_value(partial):
    """B.x over a crank that cannot turn fully: one stretch per run of rows the program solves, and
    each vertex maps back through its panel's ranges to the CSV's value (to the 0.1 px the figure keeps)."""
    log, folder, (header, data, codes) = partial
    panel = _panel(_svg(folder, f"{log.name}_points.svg"), "B position")
    path = next(p for p in panel.iter(f"{SVG}path") if p.get("data-column") == "B.x")
    stretches = _subpaths(path.get("d", ""))
    column = [row[header.index("B.x")] for row in data]
    assert any(c > 0 for c in codes) and any(c == 0 for c in codes)
    assert [len(s) for s in stretches] == _finite_runs(column)
    x0, x1, y0, y1, left, top, width, height = (float(panel.get(f"data-{k}", "nan")) for k in
                                                ("x0", "x1", "y0", "y1", "left", "top", "width", "height"))
    vertices = [v for s in stretches for v in s]
    rows = [k for k, v in enumerate(column) if math.isfinite(v)]
    for (px, py), k in zip(vertices, rows):
        theta = math.degrees(data[k][0])
        assert abs(x0 + (px - left) / width * (x1 - x0) - theta) <= 0.06 / width * (x1 - x0)
        assert abs(y0 + (top + height - py) / height * (y1 - y0) - column[k]) <= 0.06 / height * (y1 - y0)


def test_limit_positions_are_marked_at_the_closed_form(partial):
    """The crank's limit positions: |A O2| reaches coupler + rocker, cos(theta) = (a^2 + d^2 - (b + c)^2) / (2 a d)."""
    log, folder, _ = partial
    a, b, c, d = 40.0, 50.0, math.sqrt(2000.0), 90.0
    limit = math.degrees(math.acos((a * a + d * d - (b + c) ** 2) / (2 * a * d)))
    panel = _panel(_svg(folder, f"{log.name}_conditioning.svg"), "step 3: B")
    x0, x1, left, width = (float(panel.get(f"data-{k}", "nan")) for k in ("x0", "x1", "left", "width"))
    marks = sorted(x0 + (float(ln.get("x1", "nan")) - left) / width * (x1 - x0)
                   for ln in panel.iter(f"{SVG}line") if ln.get("stroke-dasharray") == "4 3")
    assert len(marks) == 2
    assert abs(marks[0] + limit) < 0.06 / width * (x1 - x0) and abs(marks[1] - limit) < 0.06 / width * (x1 - x0)
    labels = [t.text for t in panel.iter(f"{SVG}text") if t.text and t.text.startswith("limit")]
    assert labels == ["limit (step 3)", "limit (step 3)"]
    page = (folder / f"{log.name}.html").read_text(encoding="utf-8")
    found = re.findall(r"limit of step 3 \(B\) at theta_O1 = (-?[\d.]+) deg", page)  # the summary's: modulo a turn
    assert sorted((float(x) + 180) % 360 - 180 for x in found) == pytest.approx([-limit, limit], abs=1e-9)


def test_an_angle_that_wraps_is_a_gap(fourbar):
    """The crank's angle runs through 180 degrees once, where atan2 jumps by a turn: two stretches."""
    log, folder, (header, data, _) = fourbar
    column = [row[header.index("crank.phi")] for row in data]
    jumps = sum(abs(b - a) > math.pi for a, b in zip(column, column[1:]))
    panel = _panel(_svg(folder, f"{log.name}_angles.svg"), "crank angle")
    path = next(p for p in panel.iter(f"{SVG}path") if p.get("data-column") == "crank.phi")
    assert jumps == 1 and len(_subpaths(path.get("d", ""))) == 2


def test_the_crank_pin_path_is_its_circle(fourbar):
    """On the paths figure, A's path keeps the crank length (20) from O1 at the scale the drawn
    pivots O1 (0, 0) and O2 (90, 0) give."""
    log, folder, (header, data, _) = fourbar
    root = _svg(folder, f"{log.name}_paths.svg")
    circles = {t.text: None for t in root.iter(f"{SVG}text")}
    pivots = [(float(c.get("cx", "nan")), float(c.get("cy", "nan"))) for c in root.iter(f"{SVG}circle")
              if c.get("fill") == "#555555"]
    assert len(pivots) == 2 and "O1" in circles
    (ax, ay), (bx, by) = sorted(pivots)
    scale = math.hypot(bx - ax, by - ay) / 90.0
    path = next(p for p in root.iter(f"{SVG}path") if p.get("data-name") == "A")
    vertices = [v for s in _subpaths(path.get("d", "")) for v in s]
    assert len(vertices) == len(data)
    for px, py in vertices:
        assert abs(math.hypot(px - ax, py - ay) - 20.0 * scale) <= 0.15
    moving = {h.split(".")[0] for h in header if h.endswith(".x")
              and len({row[header.index(h)] for row in data}) > 1}
    assert moving == {p.get("data-name") for p in root.iter(f"{SVG}path") if p.get("data-name")}


@pytest.mark.parametrize("sample", sorted(ROOT.glob("samples/*/*.yaml")), ids=lambda p: p.stem)
def test_the_manual_shows_every_figure(sample: Path):
    """On the golden files (test_golden keeps them equal to a build): the manual embeds exactly the
    plot files the build writes, and links the page."""
    name = sample.stem
    manual = (sample.parent / "expected" / f"{name}.md").read_text(encoding="utf-8")
    shown = re.findall(r"!\[[^\]]*\]\(([^)]+_(?:points|angles|conditioning|paths)\.svg)\)", manual)
    plots = sorted(p.name for p in (sample.parent / "expected").iterdir()
                   if re.fullmatch(rf"{name}_(points|angles|conditioning|paths)\.svg", p.name))
    assert sorted(shown) == plots and f"{name}_paths.svg" in plots
    assert f"({name}.html)" in manual and (sample.parent / "expected" / f"{name}.html").is_file()


def test_a_long_sweep_is_thinned_and_keeps_every_gap(tmp_path: Path):
    """3001 rows of the partial four-bar: the page and the figures hold at most MAX_ROWS rows, and the
    curve of B.x still breaks exactly where the generated program's CSV has runs of failed rows."""
    text = PARTIAL.read_text(encoding="utf-8").replace("samples: 73", "samples: 3001")
    mechanism = tmp_path / "long_partial.yaml"
    mechanism.write_text(text.replace("name: fourbar_partial", "name: long_partial"), encoding="utf-8")
    log = build(mechanism, tmp_path, motion=True)
    header, data, codes = parse(run_python(log, tmp_path))
    page = (tmp_path / f"{log.name}.html").read_text(encoding="utf-8")
    sweep = json.loads(re.search(r'id="sweep">\n(.*?)\n</script>', page, flags=re.S).group(1))
    assert sweep["rows"] <= MAX_ROWS < len(codes) and sweep["index"][-1] == len(codes) - 1
    column = [row[header.index("B.x")] for row in data]
    kept = sweep["index"]
    for a, b in zip(kept, kept[1:]):  # no curve across a row the page left out that has no value
        inside = column[a + 1:b]
        assert all(math.isfinite(v) for v in inside) or not (math.isfinite(column[a]) and math.isfinite(column[b]))
    panel = _panel(_svg(tmp_path, f"{log.name}_points.svg"), "B position")
    path = next(p for p in panel.iter(f"{SVG}path") if p.get("data-column") == "B.x")
    assert len(_subpaths(path.get("d", ""))) == len(_finite_runs(column))
