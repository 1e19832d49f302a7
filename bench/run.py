"""Benchmarks: medians and ratios of repeated runs (the machine is shared and noisy).

    python bench/run.py            # all
    python bench/run.py extract    # one group
"""

from __future__ import annotations

import statistics
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from linkgen.evaluate import evaluate, input_rows  # noqa: E402  (linkgen first: it sets BLAS threads)
from linkgen.pipeline import build_log  # noqa: E402

import numpy as np  # noqa: E402


def median_time(fn, repeat: int) -> float:
    fn()  # warm up: imports, compiled runtime, caches
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def ladder(n: int, folder: Path) -> Path:
    """A chain of n dyads (each new pair joins the previous one and a ground pivot)."""
    joints = ["  G0: [0, 0]", "  A0: [10, 10]"]
    links = ["  crank: [G0, A0]"]
    for k in range(1, n + 1):
        joints += [f"  G{k}: [{40 * k}, 0]", f"  A{k}: [{40 * k + 5}, {30 + 3 * (k % 2)}]"]
        links += [f"  coupler{k}: [A{k - 1}, A{k}]", f"  rocker{k}: [G{k}, A{k}]"]
    frame = ", ".join(f"G{k}" for k in range(n + 1))
    text = "\n".join(["linkgen: 1", "name: ladder", "joints:", *joints, "links:",
                      f"  frame: {{joints: [{frame}], fixed: true}}", *links, "inputs:",
                      "  - {joint: G0, link: crank, relative_to: frame, range: [40, 50]}"]) + "\n"
    path = folder / f"ladder{n}.yaml"
    path.write_text(text)
    return path


def bench_extract() -> None:
    print("## Procedure extraction (parse, topology, LJ-matrix, Solver, Add-links), median")
    with tempfile.TemporaryDirectory() as tmp:
        for n in (25, 50, 100):
            path = ladder(n, Path(tmp))
            t = median_time(lambda p=path: build_log(str(p)), 5)
            print(f"- chain of {n} dyads: {t * 1e3:.1f} ms")
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

if __name__ == "__main__":
    for name in sys.argv[1:] or list(GROUPS):
        GROUPS[name]()
