"""Build, compile and run the generated programs; compare CSVs by the spec's rule."""

from __future__ import annotations

import csv
import functools
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


@functools.cache
def _log(path: str, text: str) -> StepLog:
    """The step log of a mechanism file, built once per session and content (test modules share it)."""
    return build_log(path)


def build(mechanism: Path, outdir: Path, motion: bool = False) -> StepLog:
    """Write a mechanism's files (with ``motion``, the plots and the page too: render_all)."""
    log = _log(str(mechanism), Path(mechanism).read_text(encoding="utf-8"))
    write_all(render_all(log, motion), str(outdir))
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


def run_numpy(log: StepLog, outdir: Path) -> str:
    return subprocess.run([sys.executable, "-I", f"{log.name}_np.py"], cwd=outdir, check=True, capture_output=True,
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


def compare(log: StepLog, a: str, b: str, tol: float = 1e-9, sigma: list[float] | None = None) -> float:
    """Assert two CSVs agree as the spec says; return the worst scaled difference.

    ``sigma``: each row's worst conditioning, for two routes that round differently through a resolver
    (the numpy kernel's lanes against the programs): last bits of the positions that the derivatives
    magnify, so a rate's limit is divided by sigma and an acceleration's by sigma squared (as
    tests/test_np_resolver.py bounds the kernel against NAME.py)."""
    ha, da, sa = parse(a)
    hb, db, sb = parse(b)
    assert ha == hb == [c.name for c in log.columns] + ["status"]
    assert len(da) == len(db) == log.samples ** (len(log.inputs) if log.sweep == "grid" else 1)
    assert sa == sb, [(k, x, y) for k, (x, y) in enumerate(zip(sa, sb)) if x != y][:5]
    scale = [max(x, y) for x, y in zip(scales(log, da), scales(log, db))]
    level = [2 if "acceleration" in c.quantity else 1 if "velocity" in c.quantity else 0 for c in log.columns]
    worst = 0.0
    for k, (ra, rb, st) in enumerate(zip(da, db, sa)):
        limit = tol if st == 0 else 1e-6
        for j, (x, y) in enumerate(zip(ra, rb)):
            if math.isnan(x) or math.isnan(y):
                assert math.isnan(x) and math.isnan(y), (k, ha[j], x, y)
                continue
            diff = abs(x - y) / max(abs(x), abs(y), scale[j], 1e-300)
            if sigma is not None:
                diff *= sigma[k] ** level[j]
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


# -- compilers and hosts -------------------------------------------------------

STRICT = [*CFLAGS, "-Wshadow", "-Wstrict-prototypes", "-Wmissing-prototypes"]
CXXFLAGS = ["-std=c++11", "-Wall", "-Wextra", "-Werror", "-pedantic"]
SANITIZE = ["-g", "-fsanitize=address,undefined", "-fno-sanitize-recover=all"]


def compile_step(cmd: list[str], cwd: Path) -> None:
    """Run one compiler command; fail with its diagnostics."""
    done = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True)
    assert done.returncode == 0 and not done.stderr, f"{' '.join(cmd)}\n{done.stderr}"


def host_source(log: StepLog, reads: int) -> str:
    """A program that calls NAME_solve as a host project would, in the common subset of C99 and C++.

    It writes the sweep of NAME_main.c (same CSV).  Half way it makes the calls a caller must not
    make: nan, inf, -inf, 1e300 and -1.5e30 (out of the supported range) in each entry of in, din
    and ddin.  In the first `reads` arrays (those the program's order reads) each must be refused
    with NAME_STATUS_BAD_INPUT, every output and sigma nan; the state keeps its warm start, so the
    rest of the sweep is still NAME_main.c's.  In the others the value is not read: the call gives
    what the finite one gives.  Exits 2 on a
    failed check, naming it on stderr.
    """
    name, upper = log.name, log.name.upper()
    lit = ", ".join
    return f"""#include <math.h>
#include <stdio.h>
#include <string.h>

#include "{name}.h"

static const double start[{upper}_N_INPUTS] = {{ {lit(repr(float(i.start)) for i in log.inputs)} }};
static const double stop[{upper}_N_INPUTS] = {{ {lit(repr(float(i.stop)) for i in log.inputs)} }};
static const double speed[{upper}_N_INPUTS] = {{ {lit(repr(float(i.speed)) for i in log.inputs)} }};

static int all_nan(const double x[], int n)
{{
    int i;
    for (i = 0; i < n; i++)
        if (!isnan(x[i])) return 0;
    return 1;
}}

/* Call with value at entry i of array a (0: in, 1: din, 2: ddin); 1 when the answer is right. */
static int bad_call(double rows[3][{upper}_N_INPUTS], int a, int i, double value, {name}_state *st)
{{
    double bad[3][{upper}_N_INPUTS], col[{upper}_N_COLUMNS], col_ok[{upper}_N_COLUMNS];
    {name}_state scratch, good;
    int code;
    memcpy(bad, rows, sizeof bad);
    bad[a][i] = value;
    if (a < {reads}) {{
        code = {name}_solve(bad[0], bad[1], bad[2], st);
        {name}_columns(bad[0], st, col);
        return code == {upper}_STATUS_BAD_INPUT && st->status == code
               && all_nan(col + {upper}_N_INPUTS, {upper}_N_COLUMNS - {upper}_N_INPUTS)
               && all_nan(st->sigma, {upper}_N_STEPS + 1);
    }}
    scratch = *st;
    good = *st;
    code = {name}_solve(bad[0], bad[1], bad[2], &scratch);
    {name}_columns(bad[0], &scratch, col);
    {name}_solve(rows[0], rows[1], rows[2], &good);
    {name}_columns(rows[0], &good, col_ok);
    return code == good.status && memcmp(col, col_ok, sizeof col) == 0;
}}

int main(void)
{{
    static const double values[5] = {{ NAN, INFINITY, -INFINITY, 1e300, -1.5e30 }};
    {name}_state st;
    double rows[3][{upper}_N_INPUTS], col[{upper}_N_COLUMNS];
    int k, i, a, v;
    {name}_init(&st);
    printf("{",".join(c.name for c in log.columns)},status\\n");
    for (k = 0; k < {upper}_SAMPLES; k++) {{
        for (i = 0; i < {upper}_N_INPUTS; i++) {{
            rows[0][i] = start[i] + (double)k * (stop[i] - start[i]) / (double)({upper}_SAMPLES - 1);
            rows[1][i] = speed[i];
            rows[2][i] = 0.0;
        }}
        if (k == {upper}_SAMPLES / 2)
            for (a = 0; a < 3; a++)
                for (i = 0; i < {upper}_N_INPUTS; i++)
                    for (v = 0; v < 5; v++)
                        if (!bad_call(rows, a, i, values[v], &st)) {{
                            fprintf(stderr, "wrong answer: array %d, entry %d, value %g\\n", a, i, values[v]);
                            return 2;
                        }}
        {name}_solve(rows[0], rows[1], rows[2], &st);
        {name}_columns(rows[0], &st, col);
        for (i = 0; i < {upper}_N_COLUMNS; i++) {{
            if (isfinite(col[i])) printf("%.17g,", col[i]);
            else printf("nan,");
        }}
        printf("%d\\n", st.status);
    }}
    return 0;
}}
"""
