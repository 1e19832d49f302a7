"""Scaling: the chain of N 3R dyads of bench/ladders.py built in-process, N = 25 .. 1000.

    python bench/scaling.py            # or: python bench/run.py scaling
    python bench/scaling.py 25 100     # other sizes

For each size: reading the file (parse, validate), extraction (topology, mobility, Solver),
the step log and every file rendered from it without the singular analysis, and the whole
build (build_log with change points, reach and conditioning, then every file) while the
previous size's whole build took under BUDGET seconds; the manual's size and all files'.
Medians of a few runs, wall and CPU time.  The table and the
fitted exponents go into docs/performance.md, section "Scaling" (the rest of the file is
left as it is), and to stdout.
"""

from __future__ import annotations

import os
import statistics
import sys
import tempfile
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import TypeVar

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from ladders import write_ladder  # noqa: E402
from performance_doc import write_section  # noqa: E402

from linkgen.analysis import Facts, with_facts  # noqa: E402
from linkgen.extraction import extract  # noqa: E402
from linkgen.pipeline import build_log, draft  # noqa: E402
from linkgen.prune import prune  # noqa: E402
from linkgen.render import render_all  # noqa: E402
from linkgen.topology import analyse  # noqa: E402
from linkgen.validate import read_mechanism  # noqa: E402

SIZES = (25, 50, 100, 200, 400, 1000)
BUDGET = 60.0  # seconds: the whole build of the next size is run only while this one took less
T = TypeVar("T")


@dataclass
class Times:
    wall: float
    cpu: float


@dataclass
class Row:
    n: int
    read: Times
    extraction: Times
    render: Times  # the step log and every file, without the singular analysis
    whole: Times | None  # build_log (with the singular analysis) and every file
    manual: int
    files: int

    @property
    def analysis(self) -> Times | None:
        """The singular analysis: the whole build less reading, extraction, the step log and files."""
        if self.whole is None:
            return None
        parts = (self.read, self.extraction, self.render)
        return Times(self.whole.wall - sum(p.wall for p in parts), self.whole.cpu - sum(p.cpu for p in parts))


def timed(fn: Callable[[], T], runs: int) -> tuple[Times, T]:
    """Median wall and CPU seconds of ``runs`` calls, and the last call's result."""
    walls, cpus = [], []
    for _ in range(runs):
        w, c = time.perf_counter(), time.process_time()
        out = fn()
        walls.append(time.perf_counter() - w)
        cpus.append(time.process_time() - c)
    return Times(statistics.median(walls), statistics.median(cpus)), out


def measure(n: int, folder: Path, whole: bool) -> Row:
    path = str(write_ladder(n, folder))
    runs = 5 if n <= 200 else 3
    read, m = timed(lambda: read_mechanism(path), runs)
    extraction, (topo, proc) = timed(lambda: (lambda t: (t, extract(t)))(analyse(m)), runs)
    render, files = timed(lambda: render_all(prune(with_facts(draft(topo, proc), Facts()))), runs)
    built = timed(lambda: render_all(build_log(path)), runs)[0] if whole else None
    return Row(n, read, extraction, render, built, len(files[f"ladder{n}.md"]), sum(map(len, files.values())))


def fit(rows: list[Row], value: Callable[[Row], float | None]) -> tuple[float, float] | None:
    """(slope, intercept) of log(value) against log(n) over the rows that have a value."""
    pts = [(r.n, v) for r in rows if (v := value(r)) is not None and v > 0]
    if len(pts) < 2:
        return None
    n, v = np.log(np.array(pts)).T
    slope, intercept = np.polyfit(n, v, 1)
    return float(slope), float(intercept)


def exponent(rows: list[Row], value: Callable[[Row], float | None]) -> str:
    found = fit(rows, value)
    return "" if found is None else f"N^{found[0]:.2f}"


def _one(x: float) -> str:
    return f"{x * 1e3:.0f} ms" if x < 1 else f"{x:.2f} s" if x < 100 else f"{x:.0f} s"


def _s(t: Times | None) -> str:
    return "not run" if t is None else f"{_one(t.wall)} ({_one(t.cpu)})"


def table(rows: list[Row]) -> str:
    lines = ["| dyads | read (parse, validate) | extraction | step log and files | whole build "
             "| singular analysis | manual | manual per dyad | all files |",
             "| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    parts = ("read", "extraction", "render", "whole", "analysis")

    def wall(part: str) -> Callable[[Row], float | None]:
        return lambda r: None if getattr(r, part) is None else getattr(r, part).wall

    def cell(r: Row, part: str) -> str:
        found = fit(rows, wall(part))
        if getattr(r, part) is None and found is not None:
            return f"not run (~{_one(np.exp(found[1]) * r.n ** found[0])} by its growth)"
        return _s(getattr(r, part))

    for r in rows:
        times = " | ".join(cell(r, part) for part in parts)
        lines.append(f"| {r.n} | {times} | {r.manual / 1e3:.0f} kB | {r.manual / r.n:.0f} B | {r.files / 1e6:.2f} MB |")

    growth = " | ".join(exponent(rows, wall(part)) for part in parts)
    sizes = f"{exponent(rows, lambda r: r.manual)} | | {exponent(rows, lambda r: r.files)}"
    lines.append(f"| growth | {growth} | {sizes} |")
    return "\n".join(lines) + "\n"


INTRO = """\
## Scaling

`make bench` (`bench/scaling.py`) builds the chain of N 3R dyads of `bench/ladders.py` (each
dyad hung on the two links of the one before, driven by one crank; every chain's sigma above
0.96 over the sweep) in-process and times, as the median of 3 to 5 runs (wall time, CPU time
in parentheses): reading the file (YAML parse and validation), extraction (topology with the
mobility check, the Solver), the step log and every file rendered from it without the
singular analysis, and the whole build (`build_log` with change points, reach and
conditioning, then every file; only while the size before took under {budget:.0f} s).
The singular analysis is the whole build less the other three.  Growth is the slope of
log(time or size) against log(N) over the sizes measured.

"""

OUTRO = """
The manual shows the LJ-matrix whole once (row by row when it is wider than 32 columns) and
at each step only the rows and columns the step changes, so its size per dyad is constant.

The singular analysis grows linearly too.  It searched each chain in its own procedure (the
chain and the steps it reads from) and zoomed into each chain's margin minima ten times,
evaluating that procedure each time: N zooms of up to N steps, N^2.2 (3.4 s at 25 dyads,
68 s at 100, about 9000 s at 1000 by its growth).  Now the chains' own procedures are swept
once, as their union, where each chain closes read off the union's row status
(`analysis/union.py`); the zooms of all chains refine together, each refinement one
evaluation of every distinct sweep position (`sweep.zoom_mins`); and a zoom that asks only
whether a margin reaches zero stops once its grid is flat to TOUCH away from zero (the
chains of the ladder share their brackets for five refinements, then part on rounding).
The facts are unchanged, byte for byte.  At 1000 dyads the analysis evaluates two
procedures seven times in all (the chains' union over the span: change points and gaps, a
sweep and two refinements each; the whole log over the sweep: the conditioning); a kernel
source is rendered once for equal logs (`linkgen.kernel` keeps the last eight), and a
result makes a variable's arrays when it is read, keeping the kernel's own arrays.

Three parts of a build grew faster than N and are bounded now.  The census of assemblies
(`linkgen assemblies`, listed in the manual) walks both branches of every chain: a chain of N
dyads has up to 2^N assemblies (14 dyads took 6 to 10 s, 25 never ended), so a build walks it
only while the assemblies possible (two per chain, six per resolver group) are at most
`pipeline.LISTED` = 1024, and the manual says why it lists none beyond.  The instant
centres at the sketch are n(n-1)/2 for n links, each a step of a log evaluated and
classified (5.7 s at 50 dyads): the manual lists them for at most 20 links
(`render.view.CENTRE_LINKS`; the outputs `ic:LINK1:LINK2` and `linkgen ic` give any of
them).  NAME.svg placed each label by testing every label, marker and line placed before
(14 s at 1000 dyads): a cell index finds the ones a place can meet (the same placements:
goldens byte-identical), and past 16 pairs and points the figure is 40 units wide per pair
or point, so a long chain is drawn long rather than squeezed into 640 units.  The summary's
four-bar loops are found through each pair's neighbours, not every pair against every other
(4.3 s at 1000 dyads, now 0.1 s).

The frame ladder (`ladder(n, "frame")`, the ladder bench/run.py timed before) hangs every
rocker on the frame instead, so the frame carries N + 1 pairs and rule (i) makes it a truss of
N(N+1)/2 members: its LJ-matrix and step log grow as N^2 whatever the code does.  Reading and
extraction of that ladder (one run):

"""


def frame_table(sizes: tuple[int, ...], folder: Path) -> str:
    lines = ["| dyads | frame members | read | extraction |", "| ---: | ---: | ---: | ---: |"]
    for n in sizes:
        path = str(write_ladder(n, folder, "frame"))
        read, m = timed(lambda p=path: read_mechanism(p), 1)
        extraction, topo = timed(lambda m=m: (lambda t: (extract(t), t)[1])(analyse(m)), 1)
        lines.append(f"| {n} | {len(topo.members) - 1 - 2 * n} | {_s(read)} | {_s(extraction)} |")
    return "\n".join(lines) + "\n"


def load() -> str:
    """The machine's load when a run ends: wall times above CPU times are time spent waiting for a core."""
    return (f"\nThe machine's load average when the run ended: {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores "
            "(wall time above CPU time is time spent waiting for a core).\n")


def bench_scaling(sizes: tuple[int, ...] = SIZES) -> None:
    print("## Scaling: a chain of N 3R dyads built in-process (bench/ladders.py)")
    rows: list[Row] = []
    whole = True
    with tempfile.TemporaryDirectory() as tmp:
        measure(3, Path(tmp), True)  # warm up: imports, templates, the compiled primitives
        for n in sizes:
            rows.append(measure(n, Path(tmp), whole))
            whole = whole and rows[-1].whole is not None and rows[-1].whole.wall < BUDGET
            print(f"- {n} dyads: extraction {_s(rows[-1].extraction)}, whole build {_s(rows[-1].whole)}", flush=True)
        frame = frame_table(sizes, Path(tmp))
    text = INTRO.format(budget=BUDGET) + table(rows) + load() + OUTRO + frame
    print(table(rows) + "\n" + frame)
    write_section("Scaling", text)


if __name__ == "__main__":
    bench_scaling(tuple(int(a) for a in sys.argv[1:]) or SIZES)
