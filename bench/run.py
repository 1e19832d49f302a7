"""Benchmarks: medians and ratios of repeated runs (the machine is shared and noisy).

    python bench/run.py            # the groups that write docs/performance.md (make bench): DOC
    python bench/run.py extract    # one group
    python bench/run.py all        # every group, the ones that only print too
"""

from __future__ import annotations

import statistics
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402
from ladders import write_ladder  # noqa: E402

from linkgen.evaluate import evaluate  # noqa: E402  (linkgen first: it sets BLAS threads)
from linkgen.pipeline import analyse_file, build_log  # noqa: E402
from linkgen.rows import input_rows  # noqa: E402


def median_time(fn, repeat: int) -> float:
    fn()  # warm up: imports, compiled runtime, caches
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def bench_extract() -> None:
    print("## Procedure extraction (parse, topology, LJ-matrix, Solver, Add-links), median")
    with tempfile.TemporaryDirectory() as tmp:
        for n in (25, 50, 100):
            path = write_ladder(n, Path(tmp))
            t = median_time(lambda p=path: analyse_file(str(p)), 5)
            print(f"- chain of {n} dyads (bench/ladders.py): {t * 1e3:.1f} ms")
    fig14 = ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"
    t = median_time(lambda: build_log(str(fig14)), 9)
    print(f"- six-bar of Fig. 14 with its Add-link (9 candidates ranked): {t * 1e3:.1f} ms")


def bench_evaluate() -> None:
    print("## In-process evaluator, median")
    log = build_log(str(ROOT / "samples" / "fourbar" / "fourbar.yaml"))
    for rows in (10**3, 10**5):
        v, r, a = input_rows(log, rows)
        t = median_time(lambda v=v, r=r, a=a: evaluate(log, v, r, a), 5)
        print(f"- four-bar, {rows} rows (vectorised): {t * 1e3:.1f} ms, {t / rows * 1e9:.0f} ns per row")
    log = build_log(str(ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"))
    v, r, a = input_rows(log, 361)
    res = evaluate(log, v, r, a)
    t = median_time(lambda: evaluate(log, v, r, a), 3)
    ok = res.status <= 0
    its = res.iterations[1][ok]
    print(f"- six-bar of Fig. 14, 361 rows (row by row, Newton resolver): {t * 1e3:.1f} ms, "
          f"{t / 361 * 1e6:.0f} us per row; Newton steps per row mean {np.mean(its):.2f}, max {np.max(its)}")


GROUPS = {"extract": bench_extract, "evaluate": bench_evaluate}


C_DRIVER = r"""
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <time.h>
#include "NAME.h"

int main(void)
{
    static const double start[NAME_UP_N_INPUTS] = { START };
    static const double stop[NAME_UP_N_INPUTS] = { STOP };
    static const double speed[NAME_UP_N_INPUTS] = { SPEED };
    NAME_state st;
    double in[NAME_UP_N_INPUTS], ddin[NAME_UP_N_INPUTS], sink = 0.0;
    struct timespec t0, t1;
    const int rows = ROWS;
    int k, i;
    NAME_init(&st);
    clock_gettime(CLOCK_MONOTONIC, &t0);
    for (k = 0; k < rows; k++) {
        for (i = 0; i < NAME_UP_N_INPUTS; i++) {
            in[i] = start[i] + (double)k * (stop[i] - start[i]) / (double)(rows - 1);
            ddin[i] = 0.0;
        }
        NAME_solve(in, speed, ddin, &st);
        sink += st.sigma[NAME_UP_N_STEPS];
    }
    clock_gettime(CLOCK_MONOTONIC, &t1);
    printf("%.6e %g\n", ((t1.tv_sec - t0.tv_sec) + 1e-9 * (t1.tv_nsec - t0.tv_nsec)) / rows, sink);
    return 0;
}
"""


def _programs(sample: str, out: Path, outputs: tuple[str, ...] | None = None, order: int | None = None):
    from linkgen.render import render_all
    from linkgen.writer import write_all

    log = build_log(str(ROOT / "samples" / sample / f"{sample}.yaml"), outputs, order)
    files = render_all(log)
    write_all(files, str(out))
    return log, files


def _time_programs(log, out: Path, rows: int) -> tuple[float, float]:
    """Median seconds per configuration of the C and the Python program (5 runs each)."""
    import subprocess

    lit = repr
    driver = (C_DRIVER.replace("NAME_UP", log.name.upper()).replace("NAME", log.name)
              .replace("START", ", ".join(lit(i.start) for i in log.inputs))
              .replace("STOP", ", ".join(lit(i.stop) for i in log.inputs))
              .replace("SPEED", ", ".join(lit(i.speed) for i in log.inputs)).replace("ROWS", str(rows)))
    (out / "bench_driver.c").write_text(driver)
    subprocess.run(["gcc", "-O2", "-std=c99", f"{log.name}.c", "bench_driver.c", "-lm", "-o", "bench_c"],
                   cwd=out, check=True)
    c_times = [float(subprocess.run(["./bench_c"], cwd=out, check=True, capture_output=True, text=True)
                     .stdout.split()[0]) for _ in range(5)]
    code = (f"import sys, time; sys.path.insert(0, '.'); import {log.name} as m\n"
            f"n = {rows // 10}; state = {{}}; ins = m.INPUTS\n"
            "t = time.perf_counter()\n"
            "for k in range(n):\n"
            "    x = [a + k * (b - a) / (n - 1) for a, b, _ in ins]\n"
            "    m.solve(x, [s for _, _, s in ins], [0.0] * len(ins), m.ORDER, state)\n"
            "print((time.perf_counter() - t) / n)\n")
    py_times = [float(subprocess.run([sys.executable, "-I", "-c", code], cwd=out, check=True, capture_output=True,
                                     text=True).stdout) for _ in range(5)]
    return statistics.median(c_times), statistics.median(py_times)


# (sample, outputs, order): the whole build first, then pruned ones
PRUNED = {
    "sixbar_fig14": [(("J5", "coupler"), 2), (("J5",), 0), (("J6", "crank"), 1)],
    "jansen": [(("foot",), 2), (("foot",), 1), (("foot",), 0), (("C", "triangle_bde"), 0)],
}


def bench_programs(rows: int = 20000) -> None:
    print("## Generated programs: time per configuration (median of 5 runs) and file sizes")
    out_root = ROOT / "bench" / "out"
    for sample in ("fourbar", "sixbar_fig14", "jansen"):
        out = out_root / sample
        log, files = _programs(sample, out)
        c_t, py_t = _time_programs(log, out, rows)
        print(f"- {sample}: C {c_t * 1e9:.0f} ns, Python {py_t * 1e6:.1f} us per configuration "
              f"(Python/C {py_t / c_t:.0f}x)")
        sizes = ", ".join(f"{name} {len(data) / 1024:.1f} KiB" for name, data in sorted(files.items()))
        print(f"  files: {sizes}")
        for n, (outputs, order) in enumerate(PRUNED.get(sample, [])):
            pout = out_root / f"{sample}_pruned{n}"
            plog, _ = _programs(sample, pout, outputs, order)
            pc, pp = _time_programs(plog, pout, rows)
            kept, whole = (sum(1 for st in lg.steps if not st.variant) for lg in (plog, log))
            print(f"  - outputs {','.join(outputs)} order {order}: {kept} of {whole} steps; "
                  f"C {pc * 1e9:.0f} ns ({pc / c_t:.2f} of the whole build), "
                  f"Python {pp * 1e6:.1f} us ({pp / py_t:.2f})")


GROUPS["programs"] = bench_programs


def bench_accuracy() -> None:
    from accuracy import bench_accuracy as run

    run()


GROUPS["accuracy"] = bench_accuracy


def bench_rows() -> None:
    from rows import bench_rows as run

    run()


def bench_builds() -> None:
    from build_time import bench_builds as run

    run()


def bench_kernel() -> None:
    from kernel import bench_kernel as run

    run()


def bench_scaling() -> None:
    from scaling import bench_scaling as run

    run()


def bench_knobs() -> None:
    from knobs import bench_knobs as run

    run()


def bench_peers() -> None:
    from peers import bench_peers as run

    run()


def bench_pareto() -> None:
    from pareto import plot

    plot()


def bench_mcu() -> None:
    from mcu import bench_mcu as run

    run()


def bench_addlinks() -> None:
    from addlinks import bench_addlinks as run

    run()


GROUPS.update(rows=bench_rows, builds=bench_builds, kernel=bench_kernel, scaling=bench_scaling, knobs=bench_knobs,
              peers=bench_peers, pareto=bench_pareto, addlinks=bench_addlinks, mcu=bench_mcu)
# the groups whose results go into docs/ (docs/performance.md, its plots, docs/accuracy-rrr*.svg), in order
DOC = ("knobs", "peers", "pareto", "addlinks", "builds", "mcu", "scaling", "accuracy")


if __name__ == "__main__":
    asked = sys.argv[1:] or list(DOC)
    for name in list(GROUPS) if asked == ["all"] else asked:
        started = time.perf_counter()
        GROUPS[name]()
        print(f"bench {name}: {time.perf_counter() - started:.0f} s", file=sys.stderr, flush=True)
