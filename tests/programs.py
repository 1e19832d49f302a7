"""Build, compile and run the generated programs; compare CSVs by the spec's rule."""

from __future__ import annotations

import csv
import io
import math
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from linkgen.pipeline import build_log
from linkgen.render import render_all
from linkgen.steplog import StepLog
from linkgen.writer import write_all

ROOT = Path(__file__).resolve().parents[1]
CFLAGS = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic"]
SAMPLES = sorted(ROOT.glob("samples/*/*.yaml"))


def need(tool: str) -> str:
    """The tool's path; skip locally when it is missing, fail under CI."""
    path = shutil.which(tool)
    if path is None:
        if os.environ.get("CI"):
            pytest.fail(f"{tool} is required in CI")
        pytest.skip(f"{tool} is not installed")
    return path


def build(mechanism: Path, outdir: Path) -> StepLog:
    log = build_log(str(mechanism))
    write_all(render_all(log), str(outdir))
    return log


def run_c(log: StepLog, outdir: Path, extra: tuple[str, ...] = ()) -> str:
    cc = need("gcc")
    exe = outdir / f"{log.name}_c"
    done = subprocess.run([cc, *CFLAGS, *extra, f"{log.name}.c", f"{log.name}_main.c", "-lm", "-o", str(exe)],
                          cwd=outdir, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return subprocess.run([str(exe)], cwd=outdir, check=True, capture_output=True, text=True).stdout


def run_python(log: StepLog, outdir: Path) -> str:
    return subprocess.run([sys.executable, "-I", f"{log.name}.py"], cwd=outdir, check=True, capture_output=True,
                          text=True).stdout


def run_octave(log: StepLog, outdir: Path) -> str:
    octave = need("octave-cli")
    done = subprocess.run([octave, "--no-gui", "--no-init-file", "--quiet", f"{log.name}.m"], cwd=outdir,
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return done.stdout


def parse(text: str) -> tuple[list[str], list[list[float]], list[int]]:
    rows = list(csv.reader(io.StringIO(text)))
    header, body = rows[0], rows[1:]
    return header, [[float(x) for x in r[:-1]] for r in body], [int(r[-1]) for r in body]


QUANTITIES = ("position", "velocity", "acceleration", "angle", "angular_velocity", "angular_acceleration")


def noise_floors(largest: dict[str, float], length: float) -> dict[str, float]:
    """Scales S per quantity class from the largest magnitudes in a CSV (angles at least 1).

    A class that can be zero in exact arithmetic (the angular accelerations of a Scotch yoke, a
    triad at rest) would leave S at rounding noise, so S is also at least the scale that noise
    comes from: S_omega >= S_v / L, S_a >= S_v^2 / L, S_alpha >= max(S_a / L, S_omega^2).
    """
    out = {q: largest.get(q, 0.0) for q in QUANTITIES}
    out["angle"] = max(out["angle"], 1.0)
    out["angular_velocity"] = max(out["angular_velocity"], out["velocity"] / length)
    out["acceleration"] = max(out["acceleration"], out["velocity"] ** 2 / length)
    out["angular_acceleration"] = max(out["angular_acceleration"], out["acceleration"] / length,
                                      out["angular_velocity"] ** 2)
    return out


def scales(log: StepLog, data: list[list[float]]) -> list[float]:
    """Per column, the scale of its quantity class in the CSV (noise_floors)."""
    by_class: dict[str, float] = {}
    for row in data:
        for c, x in zip(log.columns, row):
            if math.isfinite(x):
                by_class[c.quantity] = max(by_class.get(c.quantity, 0.0), abs(x))
    floors = noise_floors(by_class, log.length_scale)
    return [floors[c.quantity] for c in log.columns]


def compare(log: StepLog, a: str, b: str, tol: float = 1e-9) -> float:
    """Assert two CSVs agree as the spec says; return the worst scaled difference."""
    ha, da, sa = parse(a)
    hb, db, sb = parse(b)
    assert ha == hb == [c.name for c in log.columns] + ["status"]
    assert len(da) == len(db) == log.samples
    assert sa == sb, [(k, x, y) for k, (x, y) in enumerate(zip(sa, sb)) if x != y][:5]
    scale = [max(x, y) for x, y in zip(scales(log, da), scales(log, db))]
    worst = 0.0
    for k, (ra, rb, st) in enumerate(zip(da, db, sa)):
        limit = tol if st == 0 else 1e-6
        for j, (x, y) in enumerate(zip(ra, rb)):
            if math.isnan(x) or math.isnan(y):
                assert math.isnan(x) and math.isnan(y), (k, ha[j], x, y)
                continue
            diff = abs(x - y) / max(abs(x), abs(y), scale[j], 1e-300)
            assert diff <= limit, (k, ha[j], x, y, diff)
            if st == 0:
                worst = max(worst, diff)
    return worst


def different_bits(a: str, b: str) -> list[tuple]:
    """The cells of two CSVs of one sweep that are not the same double: (row, column, a, b)."""
    ha, da, sa = parse(a)
    hb, db, sb = parse(b)
    assert ha == hb and sa == sb
    return [(k, h, x, y) for k, (ra, rb) in enumerate(zip(da, db)) for h, x, y in zip(ha, ra, rb)
            if not (x == y or (x != x and y != y))]
