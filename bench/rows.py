"""What a failed row costs next to a good one, in the evaluator and the three languages (issue 17,
item 7; the build's cost is bench/build_time.py).

    python bench/run.py rows      # per-row times of the sweeps of the slow mechanisms

Each program solves the sweep of its file's range row by row, with warm starts, as its
sweep program does, and times every call (C: clock_gettime, Python: perf_counter, Octave:
tic/toc, the evaluator: RowSolver.solve).  A row's time is the least of the runs; the table
gives the median of the good rows (status <= 0) and the median and the largest of the
failed ones (reasons 1, 2).  The machine is shared: ratios hold better than times.
"""

from __future__ import annotations

import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
SLOW = ["tests/mechanisms/triad_tie.yaml", "tests/mechanisms/triad_lever.yaml", "tests/mechanisms/triad_limit.yaml",
        "tests/mechanisms/sixbar_partial.yaml", "tests/mechanisms/sixbar_fallback.yaml",
        "samples/sixbar_fig14/sixbar_fig14.yaml", "samples/double_triad/double_triad.yaml"]
ROWS = 61  # rows of each sweep (Octave: OCTAVE_ROWS), over the file's range
OCTAVE_ROWS = 31
RUNS = 3  # runs of each sweep (Octave: 1)

C_DRIVER = r"""
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <time.h>
#include "@NAME@.h"

int main(void)
{
    static const double values[] = { @VALUES@ };
    @NAME@_state st;
    double in[1], din[1] = { @SPEED@ }, ddin[1] = { 0.0 };
    struct timespec t0, t1;
    unsigned k;
    @NAME@_init(&st);
    for (k = 0; k < sizeof values / sizeof values[0]; k++) {
        in[0] = values[k];
        clock_gettime(CLOCK_MONOTONIC, &t0);
        @NAME@_solve(in, din, ddin, &st);
        clock_gettime(CLOCK_MONOTONIC, &t1);
        printf("%d %.9e\n", st.status, (t1.tv_sec - t0.tv_sec) + 1e-9 * (t1.tv_nsec - t0.tv_nsec));
    }
    return 0;
}
"""

PY_DRIVER = r"""
import sys, time
sys.path.insert(0, ".")
import @NAME@ as m
state = {}
for value in [@VALUES@]:
    t = time.perf_counter()
    out = m.solve([value], [@SPEED@], [0.0], m.ORDER, state)
    print(out["status"], time.perf_counter() - t)
"""

M_DRIVER = r"""
warm = [];
for value = [@VALUES@]
    t = tic;
    [out, status, warm] = @NAME@_solve(value, @SPEED@, 0, warm);
    fprintf('%d %.9e\n', status, toc(t));
end
"""


def _fill(text: str, log, values: list[float]) -> str:
    return (text.replace("@NAME@", log.name).replace("@VALUES@", ", ".join(repr(float(v)) for v in values))
            .replace("@SPEED@", repr(log.inputs[0].speed)))


def _parse(text: str) -> list[tuple[int, float]]:
    return [(int(a), float(b)) for a, b in (line.split() for line in text.splitlines() if line.strip())]


def _least(runs: list[list[tuple[int, float]]]) -> list[tuple[int, float]]:
    """Per row: its status and the least of its times over the runs."""
    return [(rows[0][0], min(t for _, t in rows)) for rows in zip(*runs)]


def _evaluator(log, values: list[float]) -> list[tuple[int, float]]:
    from linkgen import status
    from linkgen.rowsolver import RowSolver

    solver = RowSolver(log, max(log.order, 1))
    out = []
    for v in values:
        t = time.perf_counter()
        row = solver.solve([v], [log.inputs[0].speed], [0.0])
        dt = time.perf_counter() - t
        out.append((row.code if row.code > 0 and status.reason(row.code) in status.FAILED else 0, dt))
    return out


def _languages(log, folder: Path) -> dict[str, list[tuple[int, float]]]:
    values = list(np.linspace(log.inputs[0].start, log.inputs[0].stop, ROWS))
    few = list(np.linspace(log.inputs[0].start, log.inputs[0].stop, OCTAVE_ROWS))
    (folder / "driver.c").write_text(_fill(C_DRIVER, log, values))
    subprocess.run(["gcc", "-O2", "-std=c99", f"{log.name}.c", "driver.c", "-lm", "-o", "driver"], cwd=folder,
                   check=True)
    out = {"evaluator": _least([_evaluator(log, values) for _ in range(RUNS)]),
           "C": _least([_parse(subprocess.run(["./driver"], cwd=folder, check=True, capture_output=True,
                                              text=True).stdout) for _ in range(RUNS)]),
           "Python": _least([_parse(subprocess.run([sys.executable, "-I", "-c", _fill(PY_DRIVER, log, values)],
                                                   cwd=folder, check=True, capture_output=True, text=True).stdout)
                             for _ in range(RUNS)])}
    if shutil.which("octave-cli"):
        (folder / "driver_m.m").write_text(_fill(M_DRIVER, log, few))
        out["Octave"] = _parse(subprocess.run(["octave-cli", "--no-gui", "--no-init-file", "--quiet", "driver_m.m"],
                                              cwd=folder, check=True, capture_output=True, text=True).stdout)
    return out


def bench_rows() -> None:
    from linkgen.pipeline import build_log
    from linkgen.render import render_all
    from linkgen.writer import write_all

    print(f"## Good and failed rows: ms per row ({ROWS} rows a sweep, Octave {OCTAVE_ROWS}; least of {RUNS} runs)")
    print("| mechanism | language | good rows | good median | failed rows | failed median | failed max | "
          "failed / good |")
    print("| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: |")
    with tempfile.TemporaryDirectory() as tmp:
        for path in SLOW:
            log = build_log(str(ROOT / path))
            folder = Path(tmp) / log.name
            write_all(render_all(log), str(folder))
            for lang, rows in _languages(log, folder).items():
                good = [t for st, t in rows if not (st > 0 and st % 10 in (1, 2))]
                bad = [t for st, t in rows if st > 0 and st % 10 in (1, 2)]
                g = statistics.median(good) * 1e3
                b = statistics.median(bad) * 1e3 if bad else float("nan")
                worst = max(bad) * 1e3 if bad else float("nan")
                print(f"| {log.name} | {lang} | {len(good)} | {g:.3f} | {len(bad)} | {b:.3f} | {worst:.3f} | "
                      f"{b / g:.1f} |")

