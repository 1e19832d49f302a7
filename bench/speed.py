"""The speed targets of issue 19, each measured alone: C ns and instructions per configuration, the
generated Python's us per configuration, the numpy kernel's rows per second.

    python bench/speed.py                    # every target
    python bench/speed.py fourbar_P jansen_foot   # some of them
    python bench/speed.py --lines fourbar_P  # and where its C instructions go, line by line

- C (gcc -O2 -std=c99, double, order 2 unless the build says less): NAME_solve over C_ROWS rows of the
  file's range in order, the warm state kept (bench/languages.py's driver); the median of C_RUNS runs.
  Instructions: the same driver with one run under `valgrind --tool=callgrind`, the instructions of
  NAME_solve and what it calls, per configuration (repeatable on a shared machine, unlike times).
- Python: the generated NAME.py's solve over the file's sweep (bench/languages.py), median of its runs.
- numpy: rows per second of NAME_np.solve at 1e6 rows (bench/languages.py).
- --lines: the instructions per configuration of each line of NAME.c (callgrind_annotate), most first, a
  library call (glibc's sincos, atan2) as "=> function" with all it costs: where a C target's time goes.
"""

from __future__ import annotations

import re
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "bench"))

import languages as lang  # noqa: E402

from linkgen.pipeline import build_log  # noqa: E402
from linkgen.render import render_all  # noqa: E402
from linkgen.writer import write_all  # noqa: E402

C_ROWS, C_RUNS, GRIND_ROWS = 3600, 31, 3600

# name -> (sample, outputs or None for the file's, what is measured, settings over the file's)
FLOAT = {"real": "float"}
TARGETS: dict[str, tuple[str, tuple[str, ...] | None, str, dict[str, object]]] = {
    "fourbar_P": ("fourbar", ("P",), "C", {}),
    "fourbar": ("fourbar", None, "C Python numpy", {}),
    "jansen_foot": ("jansen_foot", None, "C", {}),
    "jansen": ("jansen", None, "C numpy", {}),
    "jansen_C": ("jansen", None, "C", {}),
    "sixbar_fig14": ("sixbar_fig14", None, "C numpy", {}),
    "double_triad": ("double_triad", None, "C", {}),
    # the float builds (issue 19: at least 1.5x the double speed) and the checks off knob (faster than on)
    "fourbar_float": ("fourbar", None, "C", FLOAT),
    "jansen_foot_float": ("jansen_foot", None, "C", FLOAT),
    "jansen_float": ("jansen", None, "C", FLOAT),
    "fourbar_nochecks": ("fourbar", None, "C", {"checks": False}),
    "jansen_nochecks": ("jansen", None, "C", {"checks": False}),
}


def instructions(log, folder: Path, lines: bool = False) -> float:
    """Instructions per configuration of NAME_solve (callgrind, one run of GRIND_ROWS rows); with ``lines``
    printed line by line too (profile())."""
    driver = (folder / "bench_driver.c").read_text()
    driver = re.sub(r"\b3600\b", str(GRIND_ROWS), driver).replace(f"{lang.C_RUNS}]", "1]")
    driver = re.sub(r"run < \d+", "run < 1", driver).replace(f"times[{lang.C_RUNS} / 2]", "times[0]")
    driver = driver.replace(f"qsort(times, {lang.C_RUNS},", "qsort(times, 1,")
    (folder / "grind_driver.c").write_text(driver)
    subprocess.run(["gcc", "-O2", "-std=c99", "-g", f"{log.name}.c", "grind_driver.c", "-lm", "-o", "grind_c"],
                   cwd=folder, check=True)
    out = subprocess.run(["valgrind", "--tool=callgrind", f"--toggle-collect={log.name}_solve",
                          "--callgrind-out-file=grind.out", "./grind_c"], cwd=folder, capture_output=True, text=True,
                         check=True).stderr
    total = int(re.search(r"Collected : (\d+)", out).group(1))  # type: ignore[union-attr]
    if lines:
        print(profile(folder, log.name), flush=True)
    return total / GRIND_ROWS


def profile(folder: Path, name: str, least: float = 0.5) -> str:
    """The lines of NAME.c with at least ``least`` instructions per configuration, most first
    (callgrind_annotate of the grind run): a line's own, and a call's ("=> function", all it costs)."""
    text = subprocess.run(["callgrind_annotate", "--auto=yes", "--show-percs=no", "grind.out"], cwd=folder,
                          capture_output=True, text=True, check=True).stdout
    rows: list[tuple[float, str]] = []
    source = False
    for line in text.splitlines():
        if line.startswith("-- Auto-annotated source:"):
            source = line.split(":", 1)[1].strip() == f"{name}.c"
            continue
        m = re.match(r"\s*([\d,]+)\s+(.*)", line)
        if not m or "PROGRAM TOTALS" in line or "events annotated" in line:
            continue
        count = int(m.group(1).replace(",", "")) / GRIND_ROWS
        what = m.group(2).strip()
        if source and count >= least:
            rows.append((count, what))
    rows.sort(key=lambda r: -r[0])
    return "\n".join(f"{count:8.1f}  {what[:110]}" for count, what in rows)


def measure(name: str, lines: bool = False) -> str:
    sample, outputs, what, options = TARGETS[name]
    log = build_log(str(ROOT / "samples" / sample / f"{sample}.yaml"), outputs, options=options)
    parts = [name]
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        write_all(render_all(log), str(folder))
        if "C" in what:
            lang.C_ROWS, lang.C_RUNS = C_ROWS, C_RUNS
            ns = lang.time_c(log, folder)[0] * 1e9
            parts.append(f"C {ns:.1f} ns, {instructions(log, folder, lines):.0f} instructions")
        if "Python" in what:
            parts.append(f"Python {lang.time_python(log, folder, f'speed_{name}')[0] * 1e6:.2f} us")
        if "numpy" in what:
            lang.NP_ROWS, lang.NP_BUDGET = (10**5, 10**6), 60.0
            rates = lang.time_numpy(log, folder, f'speed_np_{name}')[0]
            parts.append("numpy " + ", ".join(f"{r:.3g} rows/s at {lang.size(n)}" for n, r in rates.items()))
    return ": ".join(parts[:2]) + ("; " + "; ".join(parts[2:]) if parts[2:] else "")


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if a != "--lines"]
    for target in args or list(TARGETS):
        print(measure(target, "--lines" in sys.argv), flush=True)
