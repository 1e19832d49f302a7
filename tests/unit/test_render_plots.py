"""render.plots on the partial four-bar (crank 40, coupler 50, rocker sqrt(2000), frame 90) with a
sweep made by hand: the axis, units and scales read off the file, the limit positions from the law of
cosines, the y ranges worked out by hand, and curves whose vertices are the hand values mapped
through the panel layout (plots.LEFT, TOP, PANEL_W, ... as the module documents them)."""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from linkgen.motion import Singular
from linkgen.pipeline import build_log
from linkgen.render import plots
from linkgen.steplog import StepLog
from linkgen.sweepdata import Sweep

ROOT = Path(__file__).resolve().parents[2]
PARTIAL = ROOT / "tests" / "mechanisms" / "fourbar_partial.yaml"
SVG = "{http://www.w3.org/2000/svg}"
A, B, C, D = 40.0, 50.0, math.sqrt(2000.0), 90.0
LIMIT = math.degrees(math.acos((A * A + D * D - (B + C) ** 2) / (2 * A * D)))  # |A O2| = coupler + rocker
THETA = (-90.0, -45.0, 0.0, 45.0, 90.0)  # the hand sweep's crank angles (deg)
BX = (10.0, 20.0, math.nan, 40.0, 50.0)  # B.x per row (row 2 failed)
SIGMA3 = (1.0, 0.5, math.nan, 0.25, 0.0)


@pytest.fixture(scope="module")
def log() -> StepLog:
    return build_log(str(PARTIAL))


def _sweep(log: StepLog, sigma: bool = True) -> Sweep:
    names = tuple(c.name for c in log.columns)
    data = np.zeros((5, len(names)))
    data[:, 0] = np.radians(THETA)
    data[:, names.index("B.x")] = BX
    data[2, :] = np.nan
    data[2, 0] = 0.0
    ax, ay = A * np.cos(np.radians(THETA)), A * np.sin(np.radians(THETA))
    ax[2] = ay[2] = np.nan
    places = {"O1": (np.zeros(5), np.zeros(5)), "A": (ax, ay), "B": (np.array(BX), np.array([5.0, 6, math.nan, 7, 8])),
              "O2": (np.full(5, 90.0), np.zeros(5))}
    return Sweep(names, data, np.array([0, 0, 1, 0, 0]), {3: np.array(SIGMA3)} if sigma else {}, places,
                 np.arange(5))


def _panel(root: ET.Element, title: str) -> ET.Element:
    (found,) = [g for g in root.iter(f"{SVG}g") if g.get("class") == "panel"
                and any(t.text == title for t in g.iter(f"{SVG}text"))]
    return found


def _vertex(theta: float, value: float, top: float, y0: float, y1: float) -> str:
    """A vertex by the layout: x over -90..90 deg across PANEL_W from LEFT, y up from the panel's bottom."""
    px = plots.LEFT + (theta + 90) / 180 * plots.PANEL_W
    py = top + plots.PANEL_H - (value - y0) / (y1 - y0) * plots.PANEL_H
    return f"{round(px, 1):g} {round(py, 1):g}"


def test_the_axis_is_the_moving_input_in_the_files_unit(log: StepLog):
    assert plots.input_axis(log) == plots.Axis(0, "theta_O1 (deg)", 180 / math.pi, True, "theta_O1", "deg")
    assert plots.input_axis(replace(log, angle_unit="rad")) == plots.Axis(0, "theta_O1 (rad)", 1.0, False,
                                                                          "theta_O1", "rad")
    sliding = replace(log.inputs[0], kind="prismatic")
    assert plots.input_axis(replace(log, inputs=(sliding,))) == plots.Axis(0, "theta_O1 (mm)", 1.0, False,
                                                                            "theta_O1", "mm")
    still = replace(log.inputs[0], start=0.5, stop=0.5)
    assert plots.input_axis(replace(log, inputs=(still,))) == plots.Axis(-1, "row", 1.0, False)


def test_units_and_scales(log: StepLog):
    deg = 180 / math.pi
    assert plots._unit(log, "acceleration") == ("mm/s²", 1.0)
    assert plots._unit(log, "angular_velocity") == ("deg/s", deg)
    assert plots._unit(replace(log, angle_unit="rad"), "angle") == ("rad", 1.0)
    w, L = math.pi / 6, log.length_scale  # 30 deg/s
    expected = {"position": L, "velocity": L * w, "acceleration": L * w * w, "angle": 1.0, "angular_velocity": w,
                "angular_acceleration": w * w}
    assert {q: plots._scale(log, q) for q in expected} == pytest.approx(expected, rel=1e-15)
    sliding = replace(log.inputs[0], kind="prismatic", speed=L / 2)  # half a length scale a second
    assert plots._scale(replace(log, inputs=(sliding,)), "velocity") == pytest.approx(L / 2, rel=1e-15)


def test_the_figures_follow_the_log(log: StepLog):
    files = [f.file for f in plots.figures(log)]
    assert files == [f"fourbar_partial_{k}.svg" for k in ("points", "angles", "conditioning", "paths")]
    assert "theta_O1 (deg)" in plots.figures(log)[0].caption
    assert [f.file for f in plots.figures(replace(log, conditioning=()))] == [files[0], files[1], files[3]]


def test_the_limit_positions_are_at_the_law_of_cosines(log: StepLog):
    axis = plots.input_axis(log)
    marks = plots.singular_inputs(log, axis)
    assert [(s, k) for s, _, k in marks] == [(3, "limit"), (3, "limit")]
    assert [x for _, x, _ in marks] == pytest.approx([-LIMIT, LIMIT], abs=1e-6)
    # a sweep over 0..360 deg: -LIMIT moves by a turn; a minimum is never marked
    (cond,) = log.conditioning
    turned = replace(log, inputs=(replace(log.inputs[0], start=0.0, stop=2 * math.pi),),
                     conditioning=(replace(cond, singular=(*cond.singular, Singular((0.3,), "minimum", 0.01))),))
    assert [x for _, x, _ in plots.singular_inputs(turned, axis)] == pytest.approx([LIMIT, 360 - LIMIT], abs=1e-6)
    assert plots.singular_inputs(log, plots.Axis(-1, "row", 1.0, False)) == []


@pytest.mark.parametrize("values, ref, out", [
    ([np.array([0.0, 10.0, 5.0])], 1.0, ((-0.6, 10.6), False)),  # 6 % of the span either side
    ([np.array([5.0, 5.0]), np.array([math.nan])], 1.0, ((4.5, 5.5), False)),  # one value: 10 % of it
    ([np.array([1e-15, -1e-15])], 2.0, ((-0.1, 0.1), False)),  # rounding about 0: 5 % of the scale
    ([np.array([math.nan])], 1.0, ((-1.0, 1.0), False)),
    ([np.append(np.arange(100.0), 1e6)], 1.0, ((1 - 5.88, 99 + 5.88), True)),  # percentiles 1 and 99 of 0..99, 1e6
])
def test_the_y_range(values: list[np.ndarray], ref: float, out: tuple[tuple[float, float], bool]):
    (low, high), clipped = plots._range(values, ref)
    assert (low, high) == pytest.approx(out[0], abs=1e-12) and clipped == out[1]


def test_x_range_and_wraps():
    assert plots._xlim(np.array([1.0, math.nan, 3.0])) == (1.0, 3.0)
    assert plots._xlim(np.array([2.0, 2.0])) == (1.0, 3.0)
    deg = 180 / math.pi
    wrapped = plots._wraps(np.array([170.0, 179.0, -179.0, -170.0, 0.0]), "angle", deg)
    assert np.isnan(wrapped).tolist() == [False, False, True, False, False]  # only the jump of a turn
    values = np.array([3.0, -3.0])
    assert np.isnan(plots._wraps(values, "angle", 1.0)[1])  # 6 rad > pi: a gap
    assert plots._wraps(values, "angular_velocity", 1.0) is values


def test_a_curve_is_the_hand_values_through_the_panel(log: StepLog):
    """B's position panel (second row of panels: owners A, B): its range 0..50 padded by 3, its B.x
    curve broken at the failed row."""
    root = ET.fromstring(plots.render_plots(log, _sweep(log))["fourbar_partial_points.svg"])
    panel = _panel(root, "B position")
    top = plots.HEAD + (plots.TOP + plots.PANEL_H + plots.BOTTOM) + plots.TOP
    assert [panel.get(f"data-{k}") for k in ("x0", "x1", "y0", "y1", "left", "top")] == [
        "-90", "90", "-3", "53", f"{plots.LEFT:g}", f"{top:g}"]
    path = next(p for p in panel.iter(f"{SVG}path") if p.get("data-column") == "B.x")
    v = [_vertex(t, b, top, -3.0, 53.0) for t, b in zip(THETA, BX)]
    assert path.get("d") == f"M{v[0]}L{v[1]}M{v[3]}L{v[4]}" == "M62 332.5L124.5 312.8M249.5 273.5L312 253.9"


def test_the_conditioning_panel_marks_the_limits(log: StepLog):
    root = ET.fromstring(plots.render_plots(log, _sweep(log))["fourbar_partial_conditioning.svg"])
    panel = _panel(root, "step 3: B")
    top = plots.HEAD + plots.TOP
    path = next(panel.iter(f"{SVG}path"))
    v = [_vertex(t, s, top, 0.0, 1.05) for t, s in zip(THETA, SIGMA3)]
    assert path.get("d") == f"M{v[0]}L{v[1]}M{v[3]}L{v[4]}"
    marks = sorted(float(ln.get("x1", "nan")) for ln in panel.iter(f"{SVG}line")
                   if ln.get("stroke-dasharray") == "4 3")
    expected = [plots.LEFT + (x + 90) / 180 * plots.PANEL_W for x in (-LIMIT, LIMIT)]
    assert marks == pytest.approx(expected, abs=0.051)
    assert [t.text for t in panel.iter(f"{SVG}text") if t.text and t.text.startswith("limit")] == [
        "limit (step 3)", "limit (step 3)"]
    blank = ET.fromstring(plots.render_plots(log, _sweep(log, sigma=False))["fourbar_partial_conditioning.svg"])
    assert "not measured (built without checks)" in [t.text for t in _panel(blank, "step 3: B").iter(f"{SVG}text")]


def test_the_paths_are_the_moving_places(log: StepLog):
    text = plots.render_plots(log, _sweep(log))["fourbar_partial_paths.svg"]
    root = ET.fromstring(text)
    paths = {p.get("data-name"): p.get("d", "") for p in root.iter(f"{SVG}path")}
    assert set(paths) == {"A", "B"}  # O1 and O2 stand still
    assert [len(re.findall("[ML]", d)) for d in paths.values()] == [4, 4]  # four solved rows each
    assert all(d.count("M") == 2 for d in paths.values())  # broken at the failed row
