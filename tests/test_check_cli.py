"""linkgen check, build's summary line and warning, procedure's headings, the commands' help,
and the SVG figure's labels and slide lines (issue 22)."""

from __future__ import annotations

import json
import math
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from click.testing import CliRunner

from linkgen.cli import cli
from linkgen.pipeline import build_log
from linkgen.render.svg import render_svg
from tests.linkages import four_bar, toggle

ROOT = Path(__file__).resolve().parents[1]
SAMPLES = sorted(ROOT.glob("samples/*/*.yaml"))
SIXBAR = ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"
SVG = "{http://www.w3.org/2000/svg}"


def _run(args: list, cwd: Path, monkeypatch: pytest.MonkeyPatch) -> tuple[int, str, str]:
    monkeypatch.chdir(cwd)
    result = CliRunner().invoke(cli, [str(a) for a in args])
    if result.exception is not None and not isinstance(result.exception, SystemExit):
        raise result.exception
    return result.exit_code, result.stdout, result.stderr


def test_check_reports_the_non_grashof_range_and_limits_in_degrees_and_writes_nothing(tmp_path, monkeypatch):
    a, b, c, d = 40.0, 50.0, 41.0, 60.0
    path = four_bar(tmp_path, "ng", a, b, c, d, 30.0, samples=361)
    before = sorted(tmp_path.iterdir())
    code, out, err = _run(["check", path], tmp_path, monkeypatch)
    assert (code, err) == (0, "") and sorted(tmp_path.iterdir()) == before
    limit = math.degrees(toggle(a, b, c, d, far=True))
    found = re.search(r"assembles from (\S+) to (\S+) deg", out)
    assert found and (float(found[1]), float(found[2])) == pytest.approx((-limit, limit), abs=1e-9)
    limits = [float(x) for x in re.findall(r"^limit of step 3 \(B\) at theta_O1 = (\S+) deg$", out, re.M)]
    assert limits == pytest.approx([limit, 360 - limit], abs=1e-9)
    assert "non-Grashof (s + l > p + q), triple-rocker" in out and "transmission angle (sigma is its sine)" in out
    code, out, _ = _run(["check", path, "--json"], tmp_path, monkeypatch)
    data = json.loads(out)
    assert code == 0 and data["inputs"][0]["high"] == pytest.approx(limit, abs=1e-9)
    assert data["failed"] == sum(1 for k in range(361) if limit < k < 360 - limit)


def test_build_warns_when_most_rows_fail(tmp_path, monkeypatch):
    # toggles at |A O2| = b + c = 70 (cos = 0.2) and |b - c| = 10 (cos = 1): it assembles within 78.46 degrees of 0
    path = four_bar(tmp_path, "mostly", 50.0, 30.0, 40.0, 60.0, 30.0, samples=361)
    limit = math.degrees(math.acos(0.2))
    failing = sum(1 for k in range(361) if limit < k < 360 - limit)
    code, out, err = _run(["build", path, "-o", "out"], tmp_path, monkeypatch)
    summary, warning = err.splitlines()
    written = out.split()
    assert code == 0 and "out/mostly.md" in written and all((tmp_path / f).is_file() for f in written)
    # the rows at 0 and 360 degrees are singular: the chain folds there (|A O2| = d - a = b - c)
    assert summary.startswith(f"linkgen: mostly: 361 rows: {361 - failing - 2} assemble, 0 near a singular "
                              f"position, 2 singular, {failing} fail")
    assert "least transmission angle 0 deg (step 3, B) at the limit position" in summary
    assert warning.startswith(f"linkgen: warning: {failing} of 361 rows of mostly fail")


def test_procedure_gives_fallback_blocks_a_heading_and_pruned_builds_say_why_steps_are_missing(tmp_path, monkeypatch):
    log = build_log(str(SIXBAR), sweep=False)
    _, out, _ = _run(["procedure", SIXBAR], tmp_path, monkeypatch)
    lines = out.splitlines()
    headings = [line for line in lines if line.startswith("# ")]
    blocks = [b for g in log.groups for b in g.variants]
    assert len(headings) == len(blocks) and blocks
    for block, heading in zip(blocks, headings):
        assert heading.startswith(f"# fallback block {block.variant} of the resolver of step ")
        k = lines.index(heading)
        assert int(lines[k + 1].split()[0]) == block.steps[0]
    assert all(line.endswith("so its angle is known") for line in lines if "link_angle" in line)
    _, out, _ = _run(["procedure", SIXBAR, "--outputs", "J2"], tmp_path, monkeypatch)
    listed = {int(line.split()[0]) for line in out.splitlines() if not line.startswith("#")}
    missing = sorted(set(range(1, max(listed) + 1)) - listed)
    note = out.splitlines()[-1]
    assert missing and note.startswith(f"# Steps {', '.join(map(str, missing))} of the whole procedure are left out")


@pytest.mark.parametrize("command", ["build", "run", "lj", "candidates", "procedure", "assemblies", "check"])
def test_every_command_help_has_examples(command, tmp_path, monkeypatch):
    _, out, _ = _run([command, "--help"], tmp_path, monkeypatch)
    examples = out.split("Examples:")[1].split()
    assert examples[:2] == ["linkgen", command]
    assert "GOOD_LEVER" not in out


def test_candidates_help_prints_the_lever_number(tmp_path, monkeypatch):
    from linkgen.policy import GOOD_LEVER

    _, out, _ = _run(["candidates", "--help"], tmp_path, monkeypatch)
    assert f"below {GOOD_LEVER:g} after" in " ".join(out.split())


def _texts(svg: str) -> list[tuple[float, float, str, bool]]:
    root = ET.fromstring(svg)
    return [(float(t.get("x")), float(t.get("y")), t.text or "", t.get("text-anchor") == "end")
            for t in root.iter(f"{SVG}text")]


def test_svg_labels_a_pair_with_the_step_that_first_finds_it(tmp_path, monkeypatch):
    """The first line of the procedure (fallback blocks come after it) that names each pair."""
    _, out, _ = _run(["procedure", SIXBAR], tmp_path, monkeypatch)
    first: dict[str, int] = {}
    for line in out.splitlines():
        if line.startswith("#"):
            break
        number, _, target = line.split()[:3]
        first.setdefault(target, int(number))
    labels = {m[1]: int(m[2]) for _, _, text, _ in _texts(render_svg(build_log(str(SIXBAR), sweep=False)))
              if (m := re.fullmatch(r"(J\d) \((\d+)\)", text))}
    assert labels["J2"] == first["J2"] and labels["J4"] == first["J4"] and labels["J5"] == first["J5"]
    assert labels["J6"] == first["J6"]


@pytest.mark.parametrize("sample", SAMPLES, ids=lambda p: p.stem)
def test_svg_labels_do_not_overlap(sample):
    """Boxes of 6.5 pixels a character (the 12-pixel sans-serif's wide average), 11 high."""
    boxes = []
    for x, y, text, end in _texts(render_svg(build_log(str(sample), sweep=False)))[:-1]:  # the last: the legend
        width = 6.5 * len(text)
        left = x - width if end else x
        boxes.append((left, y - 11, left + width, y, text))
    for i, a in enumerate(boxes):
        for b in boxes[i + 1:]:
            assert not (a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]), (a[4], b[4])


def test_svg_draws_an_offset_slider_cranks_slide_line_and_offset():
    """slider_crank: the guide 13 below O, along x; the frame is the slide line, not O to S."""
    root = ET.fromstring(render_svg(build_log(str(ROOT / "samples" / "slider_crank" / "slider_crank.yaml"),
                                              sweep=False)))
    lines = [{k: float(ln.get(k)) for k in ("x1", "y1", "x2", "y2")} for ln in root.iter(f"{SVG}line")]
    circles = {(float(c.get("cx")), float(c.get("cy"))) for c in root.iter(f"{SVG}circle")}
    rect = next(root.iter(f"{SVG}rect"))  # the white background, then the slider
    slider = [r for r in root.iter(f"{SVG}rect") if r is not rect][0]
    sx, sy = float(slider.get("x")) + 7, float(slider.get("y")) + 5
    o = min(circles)  # O: the leftmost pivot
    slide = [ln for ln in lines if ln["y1"] == ln["y2"] == sy]
    assert slide and slide[0]["x1"] < o[0] < sx < slide[0]["x2"]  # the slide line passes under O and through S
    assert not any({(ln["x1"], ln["y1"]), (ln["x2"], ln["y2"])} == {o, (sx, sy)} for ln in lines)
    perpendicular = [ln for ln in lines if ln["x1"] == ln["x2"] == o[0] and {ln["y1"], ln["y2"]} == {o[1], sy}]
    assert perpendicular
    texts = [t for _, _, t, _ in _texts(ET.tostring(root, encoding="unicode"))]
    assert "offset 13" in texts
