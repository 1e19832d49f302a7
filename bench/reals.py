"""The C programs in float against double (options: real): time per configuration and worst error.

    python bench/run.py reals

For the four-bar and Jansen's leg (every default output, order 2), builds the C library in double
and in float and times NAME_solve over ROWS rows of the file's range, in order with the warm state
kept (gcc -O2 -std=c99; the least of RUNS runs, per configuration).  The error is the float
sweep's (NAME_main.c) worst difference from the double sweep's, relative to the larger of the
value and its quantity's scale (tests/programs.scales; angles modulo 2 pi), in eps of float.
Writes the section "Real type" of docs/performance.md.
"""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

from performance_doc import write_section  # noqa: E402
from programs import parse, scales  # noqa: E402

from linkgen.pipeline import build_log  # noqa: E402
from linkgen.policy import EPSILON  # noqa: E402
from linkgen.render import render_all  # noqa: E402
from linkgen.writer import write_all  # noqa: E402

SAMPLES = ("fourbar", "jansen")
ROWS = 3600
RUNS = 15

DRIVER = r"""
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <time.h>
#include "@NAME@.h"

static const double start[] = { @START@ }, stop[] = { @STOP@ }, speed[] = { @SPEED@ };

int main(void)
{
    static @NAME@_real in[@ROWS@][@UP@_N_INPUTS];
    @NAME@_real din[@UP@_N_INPUTS], ddin[@UP@_N_INPUTS];
    @NAME@_state st;
    struct timespec t0, t1;
    double best = 1e300, t;
    int k, i, run, bad = 0;
    for (k = 0; k < @ROWS@; k++)
        for (i = 0; i < @UP@_N_INPUTS; i++)
            in[k][i] = (@NAME@_real)(start[i] + k * (stop[i] - start[i]) / (@ROWS@ - 1));
    for (i = 0; i < @UP@_N_INPUTS; i++) { din[i] = (@NAME@_real)speed[i]; ddin[i] = 0; }
    for (run = 0; run < @RUNS@; run++) {
        @NAME@_init(&st);
        clock_gettime(CLOCK_MONOTONIC, &t0);
        for (k = 0; k < @ROWS@; k++) bad += @NAME@_solve(in[k], din, ddin, &st) > 0;
        clock_gettime(CLOCK_MONOTONIC, &t1);
        t = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
        if (t < best) best = t;
    }
    printf("%.6e %d\n", best / @ROWS@, bad);
    return 0;
}
"""


def _build(sample: str, real: str, out: Path) -> tuple[float, str]:
    """Seconds per configuration of NAME_solve in ``real``, and the sweep's CSV."""
    log = build_log(str(ROOT / "samples" / sample / f"{sample}.yaml"), options={"real": real})
    write_all(render_all(log), str(out))
    text = DRIVER
    for key, value in {"NAME": log.name, "UP": log.name.upper(), "ROWS": str(ROWS), "RUNS": str(RUNS),
                       "START": ", ".join(repr(i.start) for i in log.inputs),
                       "STOP": ", ".join(repr(i.stop) for i in log.inputs),
                       "SPEED": ", ".join(repr(i.speed) for i in log.inputs)}.items():
        text = text.replace(f"@{key}@", value)
    (out / "bench_real.c").write_text(text)
    cc = ["gcc", "-O2", "-std=c99", f"{log.name}.c"]
    subprocess.run([*cc, "bench_real.c", "-lm", "-o", "bench_real"], cwd=out, check=True)
    subprocess.run([*cc, f"{log.name}_main.c", "-lm", "-o", "sweep"], cwd=out, check=True)
    def run(exe: str) -> str:
        return subprocess.run([exe], cwd=out, check=True, capture_output=True, text=True).stdout

    return float(run("./bench_real").split()[0]), run("./sweep")


def worst_error(sample: str, exact: str, rounded: str) -> float:
    """The float sweep's worst scaled difference from the double sweep's (rows of status <= 0)."""
    log = build_log(str(ROOT / "samples" / sample / f"{sample}.yaml"), sweep=False)
    _, ref, status = parse(exact)
    _, got, _ = parse(rounded)
    scale = [max(x, y) for x, y in zip(scales(log, ref), scales(log, got))]
    worst = 0.0
    for row_ref, row_got, st in zip(ref, got, status):
        for c, x, y, s in zip(log.columns, row_ref, row_got, scale):
            if st <= 0 and math.isfinite(x) and math.isfinite(y):
                diff = abs(math.remainder(x - y, 2 * math.pi)) if c.quantity == "angle" else abs(x - y)
                worst = max(worst, diff / max(abs(x), abs(y), s))
    return worst


def section(rows: list[tuple[str, float, float, float]]) -> str:
    lines = ["## Real type", "",
             "`make bench` (`bench/reals.py`) builds the C library of each sample in double and in float",
             "(`--real float`; every default output, order 2) and times `NAME_solve` over 3600 rows of the",
             "file's range in order, the warm state kept (gcc -O2 -std=c99, the least of 15 runs, per",
             "configuration).  The error is the float sweep's worst difference from the double program's,",
             "relative to the larger of the value and its quantity's scale (angles modulo 2 pi), in eps of",
             "float (1.19e-7).  The tests hold every sample's float sweep to 32 eps of float over the worst",
             "sigma (tests/test_real_type.py).", "",
             "| sample | C double | C float | float speed-up | worst float error |",
             "| --- | ---: | ---: | ---: | ---: |"]
    for sample, double, single, error in rows:
        lines.append(f"| {sample} | {double * 1e9:.0f} ns | {single * 1e9:.0f} ns | {double / single:.2f}x | "
                     f"{error:.2e} ({error / EPSILON['float']:.1f} eps) |")
    return "\n".join(lines) + "\n"


def bench_reals() -> None:
    rows = []
    for sample in SAMPLES:
        out = ROOT / "bench" / "out" / "reals" / sample
        (out / "double").mkdir(parents=True, exist_ok=True)
        (out / "float").mkdir(parents=True, exist_ok=True)
        double, exact = _build(sample, "double", out / "double")
        single, rounded = _build(sample, "float", out / "float")
        rows.append((sample, double, single, worst_error(sample, exact, rounded)))
    text = section(rows)
    print(text)
    write_section("Real type", text)
