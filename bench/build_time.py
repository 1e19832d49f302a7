"""What `linkgen build` of each sample costs: as a command and in-process.

    python bench/run.py builds

Per sample: the wall time of `linkgen build FILE -o DIR` in a new process (the median of RUNS), the
same build in-process (build_log, render_all, write_all; the median of RUNS after one), and, once,
the wall time of a process that only imports linkgen's command line (Python's start-up and the
imports every command pays).  Writes the section "Build time" of docs/performance.md.
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from performance_doc import write_section

from linkgen.pipeline import build_log
from linkgen.render import render_all
from linkgen.writer import write_all

ROOT = Path(__file__).resolve().parents[1]
RUNS = 5


def _wall(command: list[str]) -> float:
    t = time.perf_counter()
    subprocess.run(command, check=True, capture_output=True, cwd=ROOT)
    return time.perf_counter() - t


def _in_process(path: Path, out: str) -> float:
    t = time.perf_counter()
    write_all(render_all(build_log(str(path))), out)
    return time.perf_counter() - t


def bench_builds() -> None:
    start = statistics.median(_wall([sys.executable, "-c", "import linkgen.cli"]) for _ in range(RUNS))
    lines = ["## Build time", "",
             f"`make bench` (`bench/build_time.py`): `linkgen build FILE -o DIR` of each sample in a new process "
             f"(the median of {RUNS}),", f"and the same build in-process (`build_log`, `render_all`, `write_all`; "
             f"the median of {RUNS} after one).", f"A process that only imports linkgen's command line takes "
             f"{start:.2f} s (Python's start-up and the imports every command pays).", "",
             "| sample | `linkgen build` | in-process | command less in-process |", "| --- | ---: | ---: | ---: |"]
    with tempfile.TemporaryDirectory() as tmp:
        for path in sorted(ROOT.glob("samples/*/*.yaml")):
            out = str(Path(tmp) / path.stem)
            command = statistics.median(_wall([sys.executable, "-m", "linkgen", "build", str(path), "-o", out])
                                        for _ in range(RUNS))
            _in_process(path, out)
            inside = statistics.median(_in_process(path, out) for _ in range(RUNS))
            lines.append(f"| {path.stem} | {command:.2f} s | {inside:.3f} s | {command - inside:.2f} s |")
    text = "\n".join(lines) + "\n"
    print(text)
    write_section("Build time", text)
