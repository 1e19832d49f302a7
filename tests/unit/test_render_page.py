"""render.page: the page's data written from a sweep made by hand on the partial four-bar (crank
40, coupler 50, rocker sqrt(2000), frame 90), the whitworth's sliding pairs worked out from its
sketch, and the page holding the figures, data and summary it is given, inline."""

from __future__ import annotations

import json
import math
import re
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from linkgen.pipeline import build_log
from linkgen.render import page
from linkgen.render.plots import figures
from linkgen.steplog import StepLog
from linkgen.sweepdata import Sweep

ROOT = Path(__file__).resolve().parents[2]
PARTIAL = ROOT / "tests" / "mechanisms" / "fourbar_partial.yaml"
WHITWORTH = ROOT / "tests" / "mechanisms" / "whitworth.yaml"
THETA = (-90.0, -45.0, 0.0, 45.0, 90.0)  # the hand sweep's crank angles (deg); row 2 failed
R2 = 40 / math.sqrt(2)  # the crank pin at 45 degrees


@pytest.fixture(scope="module")
def log() -> StepLog:
    return build_log(str(PARTIAL))


def _sweep(log: StepLog) -> Sweep:
    names = tuple(c.name for c in log.columns)
    data = np.zeros((5, len(names)))
    data[:, 0] = np.radians(THETA)
    nan = math.nan
    places = {"O1": (np.zeros(5), np.zeros(5)),
              "A": (np.array([0.0, R2, nan, R2, 0.0]), np.array([-40.0, -R2, nan, R2, 40.0])),
              "B": (np.array([10.0, 20, nan, 40, 50]), np.array([5.0, 6, nan, 7, 8])),
              "O2": (np.full(5, 90.0), np.zeros(5))}
    return Sweep(names, data, np.array([0, 0, 1, 0, 0]), {}, places, np.array([0, 3, 6, 9, 12]))


@pytest.mark.parametrize("x, text", [(1 / 3, "0.333333333"), (-0.5, "-0.5"), (123456789012.0, "1.23456789e+11"),
                                     (math.nan, "null"), (math.inf, "null"), (0.0, "0")])
def test_numbers_keep_nine_significant_digits_and_null_for_no_value(x: float, text: str):
    assert page._num(x) == text


def test_arrays_and_units_shown(log: StepLog):
    assert page._array([1.0, math.nan, 2.5]) == "[1,null,2.5]" and page._array(np.array([])) == "[]"
    assert page._shown(log, "revolute") == ("deg", 180 / math.pi)
    assert page._shown(replace(log, angle_unit="rad"), "revolute") == ("rad", 1.0)
    assert page._shown(log, "prismatic") == ("mm", 1.0)
    assert page._shown(replace(log, length_unit=""), "prismatic") == ("length", 1.0)


def test_the_data_of_a_hand_sweep(log: StepLog):
    text = page.sweep_json(log, _sweep(log))
    data = json.loads(text)
    assert data["rows"] == 5 and data["index"] == [0, 3, 6, 9, 12]
    assert (data["unit"], data["axis"]) == ("mm", "theta_O1 (deg)")
    assert data["x"] == pytest.approx(THETA, abs=1e-12)
    (inputs,) = data["inputs"]
    assert (inputs["column"], inputs["unit"]) == ("theta_O1", "deg") and inputs["values"] == pytest.approx(THETA)
    assert data["status"] == [0, 0, 1, 0, 0]
    assert data["box"] == pytest.approx([0.0, -40.0, 90.0, 40.0])  # x from O1 to O2, y over the crank circle
    assert data["links"] == [{"name": "frame", "fixed": True, "members": ["O1", "O2"]},
                             {"name": "crank", "fixed": False, "members": ["O1", "A"]},
                             {"name": "coupler", "fixed": False, "members": ["A", "B"]},
                             {"name": "rocker", "fixed": False, "members": ["O2", "B"]}]
    assert (data["pivots"], data["sliders"], data["points"]) == (["O1", "O2"], [], [])
    assert list(data["places"]) == ["O1", "A", "B", "O2"]
    assert data["places"]["B"] == [[10, 20, None, 40, 50], [5, 6, None, 7, 8]]
    assert data["places"]["A"][0][1] == float(f"{R2:.9g}") == 28.2842712
    assert len(text.splitlines()) == 13 + 3  # one key a line, one place a line


def test_the_data_cannot_close_its_script(log: StepLog):
    sweep = _sweep(log)
    odd = replace(sweep, places={**sweep.places, "x</script>": sweep.places["O1"]})
    text = page.sweep_json(log, odd)
    assert "</" not in text and list(json.loads(text)["places"])[-1] == "x</script>"


def test_the_sliding_pairs_of_the_whitworth():
    """S slides along the lever at 53.13 deg (3-4-5) in the sketch, the lever's first two places O2
    (0, 0) and C (-18, -24); R along the fixed frame at 0 deg, the frame's O1 (0, 20) and O2 (0, 0)."""
    w = build_log(str(WHITWORTH), sweep=False)
    pairs = {p.name: p for p in w.pairs}
    row = (np.zeros(1), np.zeros(1))
    places = {n: row for n in ("O1", "O2", "C", "S", "R")}
    s = json.loads(page._slider(w, pairs["S"], places))
    assert (s["name"], s["fixed"], s["guide"]) == ("S", False, ["O2", "C"])
    assert s["axis"] == pytest.approx(math.atan2(4, 3), abs=1e-9) and s["turn"] == pytest.approx(
        math.atan2(-24, -18), abs=1e-8)
    r = json.loads(page._slider(w, pairs["R"], places))
    assert (r["fixed"], r["guide"], r["axis"]) == (True, ["O1", "O2"], 0)
    assert r["turn"] == pytest.approx(-math.pi / 2, abs=1e-8)
    alone = json.loads(page._slider(w, pairs["S"], {"O2": row}))  # one place of the guide: no turn
    assert (alone["guide"], alone["turn"]) == (["O2"], 0)


def test_the_page_holds_what_it_is_given(log: StepLog):
    """Each figure's SVG text inline under its caption, the data in its script, the summary's limit
    positions at the law of cosines (modulo a turn), and nothing fetched from elsewhere."""
    plots = {fig.file: f"<svg><desc>figure {k}</desc></svg>" for k, fig in enumerate(figures(log))}
    html = page.render_page(log, _sweep(log), plots)
    shown = re.findall(r"<desc>figure (\d)</desc>", html)
    assert shown == ["0", "1", "2", "3"]
    data = re.search(r'<script type="application/json" id="sweep">\n(.*?)\n</script>', html, flags=re.S)
    assert data is not None and json.loads(data.group(1))["index"] == [0, 3, 6, 9, 12]
    assert "<title>" in html and log.title.split("(")[0].strip() in html
    assert not re.search(r"""(src|href)=["']?(https?:)?//""", html)
    a, b, c, d = 40.0, 50.0, math.sqrt(2000.0), 90.0
    limit = math.degrees(math.acos((a * a + d * d - (b + c) ** 2) / (2 * a * d)))
    found = re.findall(r"limit of step 3 \(B\) at theta_O1 = (-?[\d.]+) deg", html)
    assert sorted((float(x) + 180) % 360 - 180 for x in found) == pytest.approx([-limit, limit], abs=1e-6)
    assert "Engineering summary" in html
    assert "Engineering summary" not in page.render_page(replace(log, summary=None), _sweep(log), plots)


def test_an_array_is_its_numbers_as_num_writes_them_and_null_where_not_finite():
    x = np.array([1.0, np.nan, -np.inf, 1e-300, 123456789.123, -0.0, np.inf, 2.5e10, 1 / 3])
    assert page._array(x) == "[" + ",".join(page._num(v) for v in x.tolist()) + "]"
    assert json.loads(page._array(x))[:3] == [1, None, None] and page._array([]) == "[]"
