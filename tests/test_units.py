"""units: file (options: {units: file}, linkgen build/run --units file): the programs take and give
angles in the file's unit, degrees for the samples.

The four-bar built with units: file is run in every language: C (gcc -O2, the strict flags), Python and
Octave write the same bytes (Octave on the four-bar); the numpy kernel and ``linkgen run --units file``
agree with C within 1e-12, as in SI, and write the same bytes where there is no resolver (the in-process
evaluator runs the kernel's formulas).  The independent route is the SI
build's C program: every column of the degree build is the SI one, the angle columns (inputs, link
angles and their rates) times 180/pi, within ANGLE_EPS eps of the column's scale (tests/programs.scales),
the others as they are within BOUND_EPS eps, beyond what the rows' inputs move them by: the two sweeps step
the input in different units, 1 degree against 2 pi / 360 radians, so the rows differ in the last bits of
their inputs, and each column moves by that times its slope (_input_shifts).  Octave runs the sweep in
OCTAVE_ROWS rows.
"""

from __future__ import annotations

import dataclasses
import functools
import math
import subprocess
from pathlib import Path

import mpmath
import pytest
from click.testing import CliRunner
from programs import ROOT, STRICT, compare, compile_step, need, parse, run_numpy, run_octave, run_python, scales

from linkgen.cli import cli
from linkgen.pipeline import build_log
from linkgen.render import render_all
from linkgen.steplog import StepLog
from linkgen.writer import write_all

# the four-bar (closed form) in make test; a resolver sample (double_triad: its numpy kernel hands rows to
# NAME.py) in the long tier (10 s)
CASES = [pytest.param("fourbar"), pytest.param("double_triad", marks=pytest.mark.long)]
DEGREE = 180 / math.pi
BOUND_EPS = 6  # any column, beyond what the rows' different inputs move it by (measured 2.0 and 3.6 eps)
ANGLE_EPS = 4  # the angle columns (measured 2.8 eps)
EPS = 2.0**-52
OCTAVE_ROWS = 25
ANGULAR = ("angle", "angular_velocity", "angular_acceleration")


def _path(name: str) -> Path:
    return ROOT / "samples" / name / f"{name}.yaml"


@functools.cache
def _log(name: str, units: str, samples: int | None = None) -> StepLog:
    log = build_log(str(_path(name)), sweep=False, options={"units": units})
    return log if samples is None else dataclasses.replace(log, samples=samples)


def _c(log: StepLog, outdir: Path) -> str:
    """The C sweep, built with gcc -O2 and the strict flags: no diagnostic."""
    write_all(render_all(log), str(outdir))
    compile_step([need("gcc"), *STRICT, "-O2", f"{log.name}.c", f"{log.name}_main.c", "-lm", "-o", "sweep"], outdir)
    return subprocess.run([str(outdir / "sweep")], check=True, capture_output=True, text=True).stdout


@pytest.mark.parametrize("name", CASES)
def test_every_language_writes_the_same_degrees(tmp_path: Path, name: str):
    log = _log(name, "file")
    c = _c(log, tmp_path)
    assert run_python(log, tmp_path) == c
    if name == "fourbar":
        short = _log(name, "file", OCTAVE_ROWS)
        write_all(render_all(short), str(tmp_path / "m"))
        assert run_octave(short, tmp_path / "m") == _c(short, tmp_path / "m")
    kernel = run_numpy(log, tmp_path)
    assert compare(log, c, kernel, tol=1e-12) <= 1e-12
    out = tmp_path / "run.csv"
    done = CliRunner().invoke(cli, ["run", str(_path(name)), "--units", "file", "-o", str(out)])
    assert done.exit_code == 0, done.output
    if log.groups:  # the evaluator's resolver follows the kernel's within rounding, as in SI
        assert compare(log, c, out.read_text(), tol=1e-12) <= 1e-12
    else:  # the evaluator runs the kernel's formulas
        assert out.read_text() == kernel


def _input_shifts(radians: list[list[float]], expected: list[list[float]],
                  degrees: list[list[float]]) -> list[list[float]]:
    """Per row and column, what the two sweeps' different inputs move a value by: the rows step the input
    in different units, so their radians differ by a few ulps (the degree row's input times pi / 180,
    exactly, against the SI row's, plus the degree program's own conversion, an ulp), and a column moves by
    that times its slope (the expected sweep's central difference, twice over for its error; 0 at the ends)."""
    out = []
    for k, (si, dg) in enumerate(zip(radians, degrees)):
        d_in = abs(float(mpmath.mpf(dg[0]) * mpmath.pi / 180 - mpmath.mpf(si[0]))) + EPS * abs(si[0])
        if 0 < k < len(radians) - 1:
            step = radians[k + 1][0] - radians[k - 1][0]
            out.append([2 * abs(a - b) / step * d_in for a, b in zip(expected[k + 1], expected[k - 1])])
        else:
            out.append([0.0] * len(si))
    return out


@pytest.mark.parametrize("name", CASES)
def test_the_degrees_are_the_si_radians_times_180_over_pi(tmp_path: Path, name: str):
    si, deg = _log(name, "si"), _log(name, "file")
    assert [c.name for c in si.columns] == [c.name for c in deg.columns]
    header, radians, status_si = parse(_c(si, tmp_path / "si"))
    _, degrees, status_deg = parse(_c(deg, tmp_path / "deg"))
    assert status_si == status_deg
    factor = [DEGREE if c.quantity in ANGULAR else 1.0 for c in si.columns]
    assert {h for h, f in zip(header, factor) if f != 1.0} == {header[0]} | {
        f"{c.name.split('.')[0]}.{field}" for c in si.columns if c.name.endswith(".phi")
        for field in ("phi", "omega", "alpha")}
    expected = [[x * f for x, f in zip(row, factor)] for row in radians]
    scale = scales(deg, expected)
    angular = {h for h, f in zip(header, factor) if f != 1.0}
    diffs = [((abs(x - y) - shift) / max(abs(x), s), h)
             for a, b, moved in zip(expected, degrees, _input_shifts(radians, expected, degrees))
             for x, y, s, h, shift in zip(a, b, scale, header, moved)]
    worst = max(diffs)
    assert worst[0] <= BOUND_EPS * EPS, (worst[0] / EPS, worst[1])
    worst = max(d for d in diffs if d[1] in angular)
    assert worst[0] <= ANGLE_EPS * EPS, (worst[0] / EPS, worst[1])
    if name == "fourbar":  # 0..360 degrees in 361 rows: the sweep steps the input in degrees
        assert [row[0] for row in degrees] == [float(k) for k in range(361)]
