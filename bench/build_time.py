"""What `linkgen build` of each sample costs: as a command, and where its time goes.

    python bench/run.py builds

Per sample, the median of RUNS new processes of `linkgen build FILE -o DIR` (wall time); and of
PROBES processes that import what a build imports, build once (build_log, render_all with the
motion's plots and page, write_all) and build again (the file's sweep evaluated again: the
process keeps the last one, linkgen.sweepdata.file_rows), each timed inside them: the imports,
the first build (which fills the caches a process keeps: templates, the compiled numpy kernel)
and a later build (what a build costs in-process).  Once: the wall time of a bare
`python -c pass` (the interpreter's start-up).
Writes the section "Build time" of docs/performance.md.
"""

from __future__ import annotations

import os
import random
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from performance_doc import write_section

ROOT = Path(__file__).resolve().parents[1]
RUNS = 5  # processes of `linkgen build` per sample
PROBES = 3  # processes timed inside per sample
PROBE = """import gc, sys, time
gc.disable()  # as the command runs (linkgen.cli.main)
t0 = time.perf_counter()
from linkgen import cli
from linkgen.pipeline import build_log
from linkgen.render import render_all
from linkgen.sweepdata import _rows
from linkgen.writer import write_all
t1 = time.perf_counter()
write_all(render_all(build_log(sys.argv[1]), motion=True), sys.argv[2])
t2 = time.perf_counter()
_rows.cache_clear()  # the sweep evaluated again, as in a build of another file
write_all(render_all(build_log(sys.argv[1]), motion=True), sys.argv[2])
print(t1 - t0, t2 - t1, time.perf_counter() - t2)
"""


def _wall(command: list[str]) -> float:
    t = time.perf_counter()
    subprocess.run(command, check=True, capture_output=True, cwd=ROOT)
    return time.perf_counter() - t


def _probe(path: Path, out: str) -> list[float]:
    """Seconds of the imports, the first build and a later build, inside one new process."""
    done = subprocess.run([sys.executable, "-c", PROBE, str(path), out], check=True, capture_output=True, text=True,
                          cwd=ROOT)
    return [float(x) for x in done.stdout.split()]


def _edited(path: Path, folder: str) -> Path:
    """A copy of the mechanism file in folder with its first pair's x moved by a new millionth of a length unit
    (random: no cache of an earlier run holds it)."""
    text = path.read_text()
    first = re.compile(r"\[\s*(-?[\d.]+)").search(text, text.index("joints:"))
    assert first, path
    moved = float(first.group(1)) + 1e-6 * (1 + random.random())
    copy = Path(folder) / "edited" / path.name
    copy.parent.mkdir(exist_ok=True)
    copy.write_text(text[:first.start(1)] + repr(moved) + text[first.end(1):])
    return copy


def bench_builds() -> None:
    start = statistics.median(_wall([sys.executable, "-c", "pass"]) for _ in range(RUNS))
    lines = ["## Build time", "",
             "`make bench` (`bench/build_time.py`): the wall time of `linkgen build FILE -o DIR` of each sample, and",
             "where it goes, timed inside a new process that imports what a build imports, builds once and",
             "builds again: the imports, the first build (it fills the caches a process keeps: compiled",
             f"templates, the numpy kernel) and a later build (a build in-process).  Medians of {RUNS} processes",
             f"of the command and of {PROBES} timed inside; the interpreter's own start-up (`python -c pass`) "
             f"takes {start:.2f} s.  The imports read the package's compiled bytecode (`make install` compiles it:",
             "an editable install where PYTHONDONTWRITEBYTECODE is set has none, and compiling every module took",
             "0.1 s of each command).  The command, and the probes as it, run without the cyclic garbage",
             "collector (linkgen.cli.main: its passes took 10-50 ms of a build).  The compiled code of the",
             "templates and of the generated kernels is kept per user in the temporary directory, keyed on",
             "their text (linkgen.render.make_env, kernel.compiled),",
             "and so are the primitives as the numpy kernel and the Python runtime print them, keyed on a",
             "fingerprint of the package's modules (linkgen.textcache: 15-20 ms of every build's CPU).  A resolver",
             "mechanism's rows are solved one at a time in-process (linkgen.rowsolver, as NAME.py solves them;",
             "the steps between the groups, each block's pass and each group's state reader compiled once as one",
             "function, linkgen.rowblocks): its file's sweep, the reach's search and the summary's refinements are",
             "most of its build.  A triad's census solution is kept per user too, keyed on its exact data",
             "(linkgen.assemblies.roots): a build of an unchanged file finds it, a build after an edit of the",
             "sketch does not, so the command is timed also on a copy of the file whose first pair is moved",
             "by a new millionth of a length unit each run (\"after an edit\": what a user who edits, then builds,",
             "waits).",
             "",
             "| sample | `linkgen build` | after an edit | imports | first build | later build (in-process) |",
             "| --- | ---: | ---: | ---: | ---: | ---: |"]
    with tempfile.TemporaryDirectory() as tmp:
        for path in sorted(ROOT.glob("samples/*/*.yaml")):
            out = str(Path(tmp) / path.stem)
            command = statistics.median(_wall([sys.executable, "-m", "linkgen", "build", str(path), "-o", out])
                                        for _ in range(RUNS))
            edited = statistics.median(_wall([sys.executable, "-m", "linkgen", "build", str(_edited(path, tmp)), "-o",
                                              out]) for _ in range(RUNS))
            probes = [_probe(path, out) for _ in range(PROBES)]
            imports, first, later = (statistics.median(p[k] for p in probes) for k in range(3))
            lines.append(f"| {path.stem} | {command:.2f} s | {edited:.2f} s | {imports:.2f} s | {first:.2f} s "
                         f"| {later:.3f} s |")
    lines += ["", f"The machine's load average when the run ended: {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores."]
    text = "\n".join(lines) + "\n"
    print(text)
    write_section("Build time", text)
