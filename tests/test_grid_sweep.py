"""``sweep: grid``: every combination of the inputs' samples values, the first input varying
slowest, in every generated program's CSV, ``linkgen run`` and the in-process evaluator.

The five-bar (two inputs, closed form) on a 4 x 4 grid: C, Python and Octave write the same
bytes, the numpy program the evaluator's, the two within the spec's 1e-9; the input columns are
the grid built here by itertools.product; every row's positions agree with the 50-digit reference
solved at that row's inputs.  A two-input six-bar with a resolver group: every line (the last
input over its range) is solved alone from the sketch, and the programs write the evaluator's bytes.  One input:
grid is together.
"""

from __future__ import annotations

import itertools
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from programs import build, compare, parse, run_c, run_numpy, run_octave, run_python
from reference import Reference, wrap

import linkgen
import linkgen.api
from linkgen.backends.m.words import SCRIPT_VARIABLES
from linkgen.evaluate import evaluate
from linkgen.pipeline import build_log
from linkgen.rows import input_rows, line_length
from linkgen.table import csv

ROOT = Path(__file__).resolve().parent.parent
SAMPLES = 4
POSITION_TOL = 1e-12  # times the length scale (radians for angles), as tests/test_accuracy.py holds them

SIXGRID = """linkgen: 1
name: sixgrid
title: Fig. 14 six-bar with its crank's pivot on a second crank (two inputs, a resolver group)
units: {length: mm, angle: deg}
joints:
  J1: [0, 0]
  J2: [0, 70]
  J3: [100, 0]
  J4: [105, 65]
  J5: [60, 80]
  J6: [-60, 100]
  J7: [-60, 80]
  J8: [-80, 80]
links:
  rocker1: [J1, J2]
  ternary: [J2, J4, J5]
  rocker2: [J3, J4]
  coupler: [J6, J5]
  crank: [J7, J6]
  crank0: [J8, J7]
  frame: {joints: [J1, J3, J8], fixed: true}
inputs:
  - {joint: J8, link: crank0, relative_to: frame, range: [0, 12], speed: 30}
  - {joint: J7, link: crank, relative_to: crank0, range: [60, 180], speed: 360}
samples: 4
sweep: grid
"""


def _grid_file(sample: str, folder: Path, sweep: str = "grid") -> Path:
    """The sample's file with SAMPLES samples and the given sweep."""
    text = (ROOT / "samples" / sample / f"{sample}.yaml").read_text(encoding="utf-8")
    lines = [ln for ln in text.splitlines() if not ln.startswith("samples:")]
    path = folder / f"{sample}.yaml"
    path.write_text("\n".join(lines + [f"samples: {SAMPLES}", f"sweep: {sweep}"]) + "\n", encoding="utf-8")
    return path


def _evaluator(log) -> str:
    values, rates, accs = input_rows(log, log.samples)
    return csv(log, evaluate(log, values, rates, accs, line=line_length(log, log.samples)))


def test_fivebar_grid_in_every_language(tmp_path: Path):
    log = build(_grid_file("fivebar", tmp_path), tmp_path)
    assert log.sweep == "grid"
    c = run_c(log, tmp_path)
    assert run_python(log, tmp_path) == c
    assert run_octave(log, tmp_path) == c
    evaluator = _evaluator(log)
    assert run_numpy(log, tmp_path) == evaluator
    assert linkgen.load(tmp_path / "fivebar.yaml").sweep().shape == (SAMPLES ** 2,)
    assert f"The sweep is a grid of {SAMPLES ** 2} rows" in (tmp_path / "fivebar.md").read_text(encoding="utf-8")
    script = (tmp_path / "fivebar.m").read_text(encoding="utf-8")  # its variables are refused as the name
    assert "stride" in set(re.findall(r"^\s*(?:for\s+)?(\w+)\s*=[^=]", script, re.M)) <= SCRIPT_VARIABLES
    compare(log, c, evaluator)
    _, data, status = parse(c)
    assert len(data) == SAMPLES ** 2 and all(s == 0 for s in status)
    steps = [[i.start + j * (i.stop - i.start) / (SAMPLES - 1) for j in range(SAMPLES)] for i in log.inputs]
    assert [row[:2] for row in data] == [list(p) for p in itertools.product(*steps)]  # the first input slowest


def test_fivebar_grid_rows_match_the_reference(tmp_path: Path):
    """Each row's positions against the 50-digit reference solved at that row's inputs."""
    path = _grid_file("fivebar", tmp_path)
    log = build(path, tmp_path)
    names, data, _ = parse(_evaluator(log))
    ref = Reference(str(path))
    bad = []
    for k, values in enumerate(data):
        row = dict(zip(names, values))
        sol = ref.solve(values[:2], [i.speed for i in log.inputs], ref.guess(row))
        for name, want in sol.columns.items():
            field = name.rsplit(".", 1)[1]
            if field in ("x", "y"):
                err = abs(row[name] - float(want)) / log.length_scale
            elif field == "phi":
                err = abs(float(wrap(row[name] - want)))
            else:
                continue
            if not err <= POSITION_TOL:
                bad.append((k, name, row[name], float(want), err))
    assert not bad, bad[:10]


def _sixgrid(folder: Path):
    path = folder / "sixgrid.yaml"
    path.write_text(SIXGRID, encoding="utf-8")
    return path, build(path, folder)


def _lines_and_continued(log) -> tuple[str, list[str], list[str]]:
    """The evaluator's CSV of a grid, each line evaluated alone from the sketch, and the grid continued
    from row to row without a restart (the rows of the last two)."""
    values, rates, accs = input_rows(log, log.samples)
    lines = [evaluate(log, values[lo:lo + SAMPLES], rates[lo:lo + SAMPLES], accs[lo:lo + SAMPLES])
             for lo in range(0, SAMPLES ** 2, SAMPLES)]  # each line alone, from the sketch
    alone = [row for r in lines for row in csv(log, r).splitlines()[1:]]
    return _evaluator(log), alone, csv(log, evaluate(log, values, rates, accs)).splitlines()[1:]


# the first input's ranges of SIXGRID the restart is looked for on: continuing from the line before gives
# other bits than a restart only by rounding, so one grid alone could stop showing it after any change of a
# primitive's rounding (0..10 deg did for a while, 0..12 does now)
RANGES = ("[0, 10]", "[0, 12]", "[0, 15]")


def test_resolver_grid_restarts_each_line_from_the_sketch(tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    """The evaluator solves each line alone from the sketch (continuing from the line before gives other
    bits on at least one of the RANGES grids: the restart is seen), and C, Python and numpy write its
    bytes."""
    path, log = _sixgrid(tmp_path)
    assert log.groups and line_length(log, log.samples) == SAMPLES
    seen = 0
    for span in RANGES:
        grid = tmp_path / f"sixgrid{span[4:-1]}.yaml"
        grid.write_text(SIXGRID.replace("range: [0, 12]", f"range: {span}"), encoding="utf-8")
        restarted, alone, continued = _lines_and_continued(build_log(str(grid)))
        assert restarted.splitlines()[1:] == alone, span
        seen += continued != alone
    assert seen, "no grid where continuing differs from restarting: the restart is not seen"
    evaluator = _evaluator(log)
    assert run_c(log, tmp_path) == run_python(log, tmp_path) == run_numpy(log, tmp_path) == evaluator
    monkeypatch.setattr(linkgen.api, "CHUNK", 6)  # chunks of whole lines (4 rows), each line from the sketch
    table = linkgen.load(path).sweep()
    names, data, status = parse(evaluator)
    assert table["status"].tolist() == status
    assert np.array_equal(np.array([table[n] for n in names[:-1]]).T, np.array(data), equal_nan=True)


@pytest.mark.long
def test_resolver_grid_in_octave(tmp_path: Path):
    """Octave restarts each line as the evaluator does (3 s of Octave: the long tier)."""
    _, log = _sixgrid(tmp_path)
    assert run_octave(log, tmp_path) == _evaluator(log)


def test_grid_on_one_input_is_together(tmp_path: Path):
    (tmp_path / "grid").mkdir()
    (tmp_path / "together").mkdir()
    grid = build(_grid_file("fourbar", tmp_path / "grid"), tmp_path / "grid")
    together = build(_grid_file("fourbar", tmp_path / "together", "together"), tmp_path / "together")
    assert (grid.sweep, together.sweep) == ("grid", "together")
    out = run_python(together, tmp_path / "together")
    assert len(parse(out)[1]) == SAMPLES
    assert run_python(grid, tmp_path / "grid") == out
    assert _evaluator(grid) == _evaluator(together)
    assert np.array_equal(input_rows(grid, 7)[0], input_rows(together, 7)[0])


def test_run_samples_on_a_grid(tmp_path: Path):
    """linkgen run --samples N on a grid: N^2 rows, the evaluator's bytes; a grid over the row limit
    is a command-line error."""
    path = _grid_file("fivebar", tmp_path)
    log = build(path, tmp_path)
    done = subprocess.run([sys.executable, "-m", "linkgen", "run", str(path), "--samples", "3"],
                          capture_output=True, text=True)
    values, rates, accs = input_rows(log, 3)
    assert done.returncode == 0 and done.stdout == csv(log, evaluate(log, values, rates, accs))
    assert len(done.stdout.splitlines()) == 1 + 9
    done = subprocess.run([sys.executable, "-m", "linkgen", "run", str(path), "--samples", "5000"],
                          capture_output=True, text=True)
    assert done.returncode == 2 and "has 25000000 rows; at most 10000000" in done.stderr and not done.stdout
