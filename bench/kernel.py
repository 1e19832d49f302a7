"""The vectorised kernel NAME_np.py: rows per second and where its time goes (issue 19).

    python bench/run.py kernel

For the four-bar and Jansen's leg at 1e5 and 1e6 rows (the file's range, its speed): the median
rows per second (wall and CPU time) of NAME_np.solve (written by `linkgen build`, imported from the file; blocks of
rows) into new arrays and into those of its last call (out=), and of the in-process evaluator (the
same module's procedure on all rows at once), each after two calls that warm the caches and the
allocator (new arrays reuse those of the last result nothing holds, SPARE in the driver);
then the time of one solve into its last arrays at 1e5 rows per runtime function, in ns per row
(cProfile: the function's own time).  The machine is shared:
medians and ratios hold better than single times.
"""

from __future__ import annotations

import cProfile
import importlib.util
import pstats
import statistics
import tempfile
import time
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
SAMPLES = ("fourbar", "jansen")
ROWS = (10**5, 10**6)
RUNS = 7


def _module(path: Path) -> ModuleType:
    spec = importlib.util.spec_from_file_location(path.stem, path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _rate(call: Any, rows: int, *args: Any) -> str:
    """Median rows per second of call(*args) over RUNS runs, after two warm-up calls, in wall
    time / in the process's CPU time (on a shared machine the wall time also holds the time the
    other processes took the core: up to 2x here; the CPU time holds none of it)."""
    call(*args)
    call(*args)
    wall, cpu = [], []
    for _ in range(RUNS):
        t, c = time.perf_counter(), time.process_time()
        call(*args)
        wall.append(time.perf_counter() - t)
        cpu.append(time.process_time() - c)
    return f"{rows / statistics.median(wall):.3g} / {rows / statistics.median(cpu):.3g}"


def _inputs(module: ModuleType, rows: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    k = np.arange(rows, dtype=float)[:, None]
    start, stop, speed = (np.array([i[j] for i in module.INPUTS]) for j in range(3))
    return start + k * (stop - start) / (rows - 1), speed, np.zeros(module.N_INPUTS)


def _profile(module: ModuleType, rows: int) -> list[tuple[str, float]]:
    """ns per row of each function of the module over one solve into its last arrays (own
    time), largest first."""
    x, dx, ddx = _inputs(module, rows)
    last = module.solve(x, dx, ddx)
    profile = cProfile.Profile()
    profile.runcall(module.solve, x, dx, ddx, out=last)
    stats = pstats.Stats(profile).stats  # type: ignore[attr-defined]
    own: dict[str, float] = {}
    for (filename, _, name), (_, _, tottime, _, _) in stats.items():
        key = name if filename == module.__file__ else "numpy and Python outside the module"
        own[key] = own.get(key, 0.0) + tottime
    return sorted(((k, t / rows * 1e9) for k, t in own.items()), key=lambda kv: -kv[1])


def bench_kernel() -> None:
    from linkgen.evaluate import evaluate
    from linkgen.pipeline import build_log
    from linkgen.render import render_all
    from linkgen.rows import input_rows
    from linkgen.writer import write_all

    print(f"## The numpy kernel NAME_np.py: rows per second, wall / CPU (median of {RUNS} after 2 warm-up calls)")
    print("| sample | rows | NAME_np.solve | solve into its last arrays | evaluator (all rows at once) | "
          "solve / evaluator (CPU) |")
    print("| --- | ---: | ---: | ---: | ---: | ---: |")
    profiles = {}
    with tempfile.TemporaryDirectory() as tmp:
        for sample in SAMPLES:
            log = build_log(str(ROOT / "samples" / sample / f"{sample}.yaml"))
            write_all(render_all(log), tmp)
            module = _module(Path(tmp) / f"{sample}_np.py")
            for rows in ROWS:
                args = _inputs(module, rows)
                solve = _rate(module.solve, rows, *args)
                last = module.solve(*args)
                reused = _rate(lambda: module.solve(*args, out=last), rows)  # noqa: B023 (called at once)
                whole = _rate(evaluate, rows, log, *input_rows(log, rows))
                ratio = float(solve.split(" / ")[1]) / float(whole.split(" / ")[1])
                print(f"| {sample} | {rows:.0e} | {solve} | {reused} | {whole} | {ratio:.1f} |")
            profiles[sample] = _profile(module, ROWS[0])
    for sample, rows in profiles.items():
        print(f"\n{sample}_np.solve into its last arrays at {ROWS[0]:.0e} rows, ns per row by function (own time): "
              + ", ".join(f"{name} {ns:.0f}" for name, ns in rows if ns >= 0.5))
