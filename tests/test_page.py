"""NAME.html in a real headless browser: Debian's chromium driven by Selenium through Debian's
chromedriver (never a browser a library downloads).

Each page must load with no message in the browser's console, play (the row advances, and
stops when paused), and put every drawn pair and point, at the row the slider is moved to, where
the generated Python program's CSV has it.  A screenshot of each page is written to the test's
folder and to build/screenshots/ for review.
"""

from __future__ import annotations

import json
import math
import re
import shutil
import time
from collections.abc import Iterator
from pathlib import Path

import pytest
from programs import build, need, parse, run_python

from linkgen.steplog import StepLog

ROOT = Path(__file__).resolve().parents[1]
BROWSER, DRIVER = "/usr/bin/chromium", "/usr/bin/chromedriver"
FLAGS = ("--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync", "--window-size=1500,1000")
SAMPLES = sorted(ROOT.glob("samples/*/*.yaml"))
QUICK = [ROOT / "samples" / "fourbar" / "fourbar.yaml",
         ROOT / "tests" / "mechanisms" / "fourbar_partial.yaml"]  # a plain one and one whose rows fail (make test)
SHOTS = ROOT / "build" / "screenshots"


@pytest.fixture(scope="module")
def browser(tmp_path_factory: pytest.TempPathFactory) -> Iterator[object]:
    need("chromium")
    need("chromedriver")
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = BROWSER
    for flag in (*FLAGS, f"--user-data-dir={tmp_path_factory.mktemp('profile')}"):
        options.add_argument(flag)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    driver = webdriver.Chrome(service=Service(DRIVER), options=options)
    yield driver
    driver.quit()


def _row(driver) -> int:
    return int(driver.execute_script("return document.body.dataset.row"))


def _move(driver, row: int) -> None:
    """Move the slider to a row as a user's drag does: set its value and fire its input event."""
    driver.execute_script("const s = document.getElementById('row'); s.value = arguments[0];"
                          "s.dispatchEvent(new Event('input'));", row)


def _drawn(driver) -> dict[str, tuple[str | None, str | None, str | None]]:
    """(cx, cy, visibility) of every pair and point as the page's DOM has them."""
    return driver.execute_script(
        "const out = {}; for (const c of document.querySelectorAll('circle.pair'))"
        " out[c.dataset.name] = [c.getAttribute('cx'), c.getAttribute('cy'), c.getAttribute('visibility')];"
        " return out;")


def _check_row(driver, log: StepLog, csv: tuple[list[str], list[list[float]], list[int]], row: int) -> int:
    """The drawn pairs at ``row`` against the CSV; returns how many were compared.  A failed row has
    no outputs: its moving pairs are hidden, the fixed pivots stay where the file draws them."""
    header, data, codes = csv
    fixed = {v.entity: v.value[:2] for v in log.variables if v.role == "pair" and v.constant}
    scale = log.length_scale
    drawn = _drawn(driver)
    compared = 0
    for name, (cx, cy, shown) in drawn.items():
        if f"{name}.x" not in header:
            continue
        x, y = data[row][header.index(f"{name}.x")], data[row][header.index(f"{name}.y")]
        if math.isnan(x) and name in fixed:
            x, y = fixed[name]
        elif math.isnan(x):
            assert shown == "hidden", (row, name, codes[row])
            continue
        assert shown == "visible", (row, name)
        for got, want in ((float(cx), x), (float(cy), y)):
            assert abs(got - want) <= 1e-8 * max(scale, abs(want)), (row, name, got, want)
        compared += 1
    return compared


def _page(driver, mechanism: Path, tmp_path: Path) -> None:
    log = build(mechanism, tmp_path, motion=True)
    csv = parse(run_python(log, tmp_path))
    codes = csv[2]
    driver.get((tmp_path / f"{log.name}.html").as_uri())
    assert driver.execute_script("return document.readyState") == "complete"
    assert driver.get_log("browser") == []  # no error, warning or message of the page

    # it plays, and stops when paused
    assert _row(driver) == 0
    play = driver.find_element("id", "play")
    play.click()
    deadline = time.monotonic() + 5
    while _row(driver) == 0 and time.monotonic() < deadline:
        time.sleep(0.05)
    assert _row(driver) > 0, "the animation did not advance"
    play.click()
    stopped = _row(driver)
    time.sleep(0.3)
    assert _row(driver) == stopped and play.text == "Play"

    # the slider puts the mechanism at a row's positions; the arrow key steps one row
    traced = [n for n in driver.execute_script(
        "return Array.from(document.querySelectorAll('#traces input:checked')).map(b => b.value)")
              if f"{n}.x" in csv[0]]
    assert traced
    failing = [k for k, c in enumerate(codes) if c > 0]
    rows = sorted({0, len(codes) // 3, 2 * len(codes) // 3, len(codes) - 1, *failing[:1], *failing[-1:]})
    compared = 0
    for row in rows:
        _move(driver, row)
        assert _row(driver) == row
        compared += _check_row(driver, log, csv, row)
        text = driver.find_element("id", "readout").text
        assert f"row {row} of {len(codes) - 1}" in text
        assert (f"status {codes[row]}" in text) if codes[row] > 0 else ("status" not in text)
        for name in traced:  # the traced points' coordinates under the readout, to 3 decimals
            x, y = (csv[1][row][csv[0].index(f"{name}.{f}")] for f in "xy")
            if all(math.isfinite(v) and 1e-3 <= abs(v) < 1e5 for v in (x, y)):
                assert f"{name} {x:.3f} {y:.3f}" in text, (row, name, text)
    assert compared >= len(rows)
    slider = driver.find_element("id", "row")
    _move(driver, 10)
    slider.send_keys("\ue014")  # the right arrow key
    assert _row(driver) == 11
    _check_row(driver, log, csv, 11)

    # every plot panel's cursor stands at the row's input
    sweep = json.loads(driver.execute_script("return document.getElementById('sweep').textContent"))
    cursors = driver.execute_script(
        "return Array.from(document.querySelectorAll('#plots g.panel')).map(g => [g.dataset.x0, g.dataset.x1,"
        " g.dataset.left, g.dataset.width, g.querySelector('line.cursor').getAttribute('x1')]);")
    assert cursors
    for a, b, left, width, x in cursors:
        want = float(left) + (sweep["x"][11] - float(a)) / (float(b) - float(a)) * float(width)
        assert abs(float(x) - want) <= 0.01

    _move(driver, len(codes) // 3)
    shot = tmp_path / f"{log.name}.png"
    assert driver.save_screenshot(str(shot))
    assert shot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    SHOTS.mkdir(parents=True, exist_ok=True)
    shutil.copyfile(shot, SHOTS / shot.name)
    assert driver.get_log("browser") == []


@pytest.mark.parametrize("mechanism", QUICK, ids=lambda p: p.stem)
def test_page_plays_and_draws_the_rows_of_the_csv(browser, mechanism: Path, tmp_path: Path):
    _page(browser, mechanism, tmp_path)


@pytest.mark.long
@pytest.mark.parametrize("mechanism", [s for s in SAMPLES if s not in QUICK], ids=lambda p: p.stem)
def test_every_sample_page_plays_and_draws_the_rows_of_the_csv(browser, mechanism: Path, tmp_path: Path):
    _page(browser, mechanism, tmp_path)


def test_page_is_self_contained(tmp_path: Path):
    """No address the page would fetch: no src or href but its own files and fragments, no
    external script or style, and its data is JSON."""
    log = build(QUICK[0], tmp_path, motion=True)
    text = (tmp_path / f"{log.name}.html").read_text(encoding="utf-8")
    assert re.findall(r"\bsrc=", text) == []
    links = re.findall(r'\bhref="([^"]*)"', text)
    assert all(h.startswith("#") or h in ("data:,", f"{log.name}.md") for h in links), links
    assert set(re.findall(r"https?://[^\s\"')]+", text)) <= {"http://www.w3.org/2000/svg"}  # the SVG namespace
    assert "@import" not in text and "url(http" not in text
    data = re.search(r'<script type="application/json" id="sweep">\n(.*?)\n</script>', text, flags=re.S)
    assert data is not None
    assert json.loads(data.group(1))["rows"] == log.samples
