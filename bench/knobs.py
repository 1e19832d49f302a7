"""Every sample at every knob setting: time per configuration in each language and the worst error
against the 50-digit reference (issue 19).

    python bench/run.py knobs

For each sample, the settings of bench/settings.py are built with
``linkgen.pipeline.build_log(path, options=...)`` (as `linkgen build` does), rendered and timed by
bench/languages.py; the C, Python and numpy sweeps are compared with the reference of
bench/exact.py.  Where a language's program is byte for byte the default's (but for the banner
line that states the settings) the knob does not act there: it is not run again and the table marks
its numbers with '='.  Writes the section "Knobs" of docs/performance.md and bench/out/knobs.json
(for the Pareto plot).
"""

from __future__ import annotations

import json
import math
import shutil
import statistics
from dataclasses import asdict, dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

import exact  # noqa: E402
import languages as lang  # noqa: E402
import settings  # noqa: E402
from performance_doc import write_section  # noqa: E402

from linkgen.pipeline import build_log  # noqa: E402
from linkgen.render import render_all  # noqa: E402
from linkgen.writer import write_all  # noqa: E402

OUT = ROOT / "bench" / "out" / "knobs"
RESULTS = ROOT / "bench" / "out" / "knobs.json"
NAN = math.nan


@dataclass
class Measured:
    """One sample at one setting."""

    sample: str
    setting: dict
    label: str
    c: float = NAN  # seconds per configuration
    python: float = NAN
    numpy: dict[int, float] = field(default_factory=dict)  # rows -> rows per second
    octave: float = NAN
    errors: dict[str, exact.Errors] = field(default_factory=dict)  # language -> errors
    same: list[str] = field(default_factory=list)  # languages whose program is the default's
    failed: str = ""  # why the setting did not build


class Sample:
    """The measurements of one sample, each distinct program measured once."""

    def __init__(self, path: Path):
        self.path, self.name = path, path.stem
        self.exact, self.picked = exact.of_sample(str(path))
        self.cache: dict[tuple[str, tuple[bytes, ...]], tuple[object, exact.Errors]] = {}
        self.default: dict[str, tuple[bytes, ...]] = {}
        self.octave: dict[tuple[bytes, ...], str] = {}  # Octave program -> its job's label
        self.octave_jobs: list[tuple[str, object, Path]] = []
        self.octave_of: list[tuple[str, Measured]] = []
        self.resolver = False

    def _run(self, language: str, key: tuple[bytes, ...], log, folder: Path, unique: str):
        """(timing, errors) of one language's program, measured the first time its key is seen."""
        if (language, key) not in self.cache:
            timer = {"C": lambda: lang.time_c(log, folder), "Python": lambda: lang.time_python(log, folder, unique),
                     "numpy": lambda: lang.time_numpy(log, folder, unique)}[language]
            timing, text = timer()
            self.cache[(language, key)] = (timing, exact.csv_errors(self.exact, self.picked, text))
        return self.cache[(language, key)]

    def measure(self, setting: settings.Setting, index: int) -> Measured:
        """Build one setting (as `linkgen build` does) and measure each language's program."""
        m = Measured(self.name, dict(setting), settings.label(setting))
        try:
            log = build_log(str(self.path), options=setting)
            files = render_all(log)
        except Exception as exc:  # a knob not made to work yet: say so and go on
            m.failed = f"{type(exc).__name__}: {str(exc)[:200]}"
            return m
        self.resolver = bool(log.groups)
        folder = OUT / self.name / str(index)
        shutil.rmtree(folder, ignore_errors=True)
        write_all(files, str(folder))
        for language in lang.LANGUAGES:
            key = lang.program_key(files, log.name, language)
            if not setting:
                self.default[language] = key
            elif key == self.default.get(language):
                m.same.append(language)
            if language == "Octave":
                if key not in self.octave:
                    self.octave[key] = f"o{len(self.octave_jobs)}"
                    self.octave_jobs.append((self.octave[key], log, folder))
                self.octave_of.append((self.octave[key], m))
                continue
            try:
                timing, errors = self._run(language, key, log, folder, f"bench_{self.name}_{index}_{language}")
            except Exception as exc:  # a program that does not compile or run: say so and go on
                m.failed += f"{language}: {type(exc).__name__}: {str(exc)[:200]} "
                continue
            m.errors[language] = errors
            if language == "C":
                m.c = timing  # type: ignore[assignment]
            elif language == "Python":
                m.python = timing  # type: ignore[assignment]
            else:
                m.numpy = timing  # type: ignore[assignment]
        return m

    def run(self) -> list[Measured]:
        """The default, each knob alone, the fastest and the most accurate combinations; then Octave."""
        done = [self.measure({}, 0)]
        for setting in settings.singles(self.resolver)[1:]:
            done.append(self.measure(setting, len(done)))
        ok = [m for m in done if "C" in m.errors and math.isfinite(m.c)]
        combos = {"fastest": settings.best([(m.setting, m.c) for m in ok], lambda a, b: a < b),
                  "most accurate": settings.best([(m.setting, m.errors["C"].position) for m in ok],
                                                 lambda a, b: a < b)}
        for name, setting in combos.items():
            m = self.measure(setting, len(done))
            m.label = f"{name}: {m.label}"
            done.append(m)
        try:
            times = lang.time_octave(self.octave_jobs)
        except Exception as exc:  # noqa: BLE001 (Octave failing leaves the other languages' numbers)
            times = {}
            done[0].failed += f"Octave: {type(exc).__name__}: {str(exc)[:200]} "
        for label, m in self.octave_of:
            m.octave = times.get(label, NAN)
        return done


def _time(seconds: float) -> str:
    """A time per configuration in ns, us or ms."""
    if not math.isfinite(seconds):
        return "-"
    for scale, unit in ((1e9, "ns"), (1e6, "us"), (1e3, "ms")):
        if seconds * scale < 1000 or unit == "ms":
            return f"{seconds * scale:.3g} {unit}"
    return "-"


def _rows(rates: dict[int, float], rows: int) -> str:
    """Rows per second at ``rows``; at 1e5 rows not run, the largest size run in brackets."""
    if rows in rates:
        return f"{rates[rows]:.3g}"
    if rows == 10**5 and rates:
        return f"({rates[max(rates)]:.3g} at {lang.size(max(rates))})"
    return "-"


def _error(m: Measured, language: str, kind: str = "position") -> str:
    e = m.errors.get(language)
    value = getattr(e, kind) if e else NAN
    return f"{value:.1e}" if math.isfinite(value) or math.isinf(value) else "-"


def _same(m: Measured, language: str, text: str) -> str:
    return f"= {text}" if language in m.same and text != "-" else text


def table(done: list[Measured]) -> list[str]:
    """One sample's table and its notes."""
    default = done[0].c
    lines = ["| setting | C | C / default | Python | numpy, 1e5 rows | numpy, 1e6 rows | Octave | "
             "C: positions | C: rates | Python: positions | numpy: positions |",
             "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    notes = []
    for m in done:
        ratio = f"{m.c / default:.2f}" if math.isfinite(m.c) and math.isfinite(default) else "-"
        cells = [m.label, _same(m, "C", _time(m.c)), ratio, _same(m, "Python", _time(m.python)),
                 _same(m, "numpy", _rows(m.numpy, 10**5)), _same(m, "numpy", _rows(m.numpy, 10**6)),
                 _same(m, "Octave", _time(m.octave)), _same(m, "C", _error(m, "C")),
                 _same(m, "C", _error(m, "C", "rate")), _same(m, "Python", _error(m, "Python")),
                 _same(m, "numpy", _error(m, "numpy"))]
        lines.append("| " + " | ".join(cells) + " |")
        if m.failed:
            notes.append(f"- {m.label}: {m.failed.strip()}")
        for language, e in m.errors.items():
            if e.failed and language not in m.same:
                notes.append(f"- {m.label}, {language}: fails {e.failed} of the {e.failed + e.compared} rows the "
                             "reference solves")
            if e.unmatched and language not in m.same:
                notes.append(f"- {m.label}, {language}: no reference for {', '.join(e.unmatched)}")
    return lines + ([""] + notes if notes else [])


def summary(results: dict[str, list[Measured]]) -> list[str]:
    """Each knob's effect over the samples: the median (and range) of its C time and C error over
    the default's."""
    by: dict[str, list[tuple[float, float]]] = {}
    acts: dict[str, set[str]] = {}
    for done in results.values():
        base = done[0]
        for m in done[1:]:
            if m.label.startswith(("fastest", "most accurate")) or not m.errors:
                continue  # a combination measured above, or a setting that did not build
            acts.setdefault(m.label, set()).update(x for x in lang.LANGUAGES if x not in m.same)
            if "C" not in m.errors or "C" not in base.errors:
                continue
            t = m.c / base.c
            e = m.errors["C"].position / base.errors["C"].position if base.errors["C"].position else NAN
            by.setdefault(m.label, []).append((t, e))
    lines = ["| setting | samples | programs it changes | C time / default: median (least, most) | C position error "
             "/ default's: median (least, most) |", "| --- | ---: | --- | ---: | ---: |"]
    for name, pairs in by.items():
        cols = []
        for k in (0, 1):
            vals = sorted(p[k] for p in pairs if math.isfinite(p[k]))
            cols.append(f"{statistics.median(vals):.3g} ({vals[0]:.3g}, {vals[-1]:.3g})" if vals else "-")
        changed = ", ".join(x for x in lang.LANGUAGES if x in acts.get(name, set())) or "none"
        lines.append(f"| {name} | {len(pairs)} | {changed} | {cols[0]} | {cols[1]} |")
    return lines


TEXT = """## Knobs: time and error per setting

`make bench` (`bench/knobs.py`) builds every sample at the default settings, with each knob of
`linkgen/options.py` turned alone (the real type; the checks; the angle form; and where the mechanism
has Add-links the resolver's strategy, polish, predictor order and a tolerance of 1e-6), then at the
fastest and the most accurate combinations (each knob at its single setting that was faster, or more
accurate, in C than the default; the default where none was).  Every setting is built as `linkgen
build` builds it (`build_log(path, options=...)`), so a knob shows here once it acts.

- C: `NAME_solve` (gcc -O2 -std=c99) over @C_ROWS@ rows of the file's range in order, the warm
  state kept; the median of @C_RUNS@ runs, per configuration.  Python: the generated `NAME.py`'s
  `solve` over the file's sweep in order (median of @PY_RUNS@ runs).  numpy: rows per second of
  `NAME_np.solve` on all rows at once (median of @NP_RUNS@ calls after one; 1e3, 1e4, 1e5, 1e6 rows
  in turn; '-': not run, as the sizes before predict over @NP_BUDGET@ s a call from the last call
  and the cost per row between the last two; where 1e5 rows are not run, the largest size run in
  brackets).
  Octave: `NAME_solve.m` over @OCTAVE_ROWS@ rows (a smaller run), per configuration.
- Error: the worst over @ROWS@ rows of the sweep (every 10 degrees of a turn) of the program's own
  sweep (`NAME_main.c`, `NAME.py`, `NAME_np.py`) against the 50-digit reference of
  `tests/reference.py` (`bench/exact.py`): positions in units of the length scale L and angles in
  radians ("positions"), velocities and accelerations relative to the larger of the value and its
  quantity's scale ("rates").  A float program rounds its inputs to float too: that is part of its
  error.  Octave's sweep is not compared (the tests hold it to the others).
- `real float` on this x86-64 machine: a scalar float costs what a double does, so the float C gains only
  in its library calls (sincosf, its own atan2); on the microcontrollers the knob is for, whose FPU computes
  in float only, see "Float on a microcontroller" (`bench/mcu.py`).
- `=`: the language's program is the default's byte for byte but for its banner (the line that
  states the settings): the knob does not act in that language; its numbers are the default's.
- The machine is shared (2 cores): read ratios, not single times; no number here is asserted by a test.
"""


def section(results: dict[str, list[Measured]]) -> str:
    text = TEXT
    for key, value in {"C_ROWS": lang.C_ROWS, "C_RUNS": lang.C_RUNS, "PY_RUNS": lang.PY_RUNS, "NP_RUNS": lang.NP_RUNS,
                       "NP_BUDGET": lang.NP_BUDGET, "OCTAVE_ROWS": lang.OCTAVE_ROWS, "ROWS": exact.ROWS}.items():
        text = text.replace(f"@{key}@", f"{value:g}")
    lines = [text, "Each knob over the samples it applies to:", "", *summary(results)]
    for name, done in results.items():
        lines += ["", f"### {name}", "", *table(done)]
    return "\n".join(lines) + "\n"


def bench_knobs(samples: list[Path] | None = None) -> dict[str, list[Measured]]:
    results = {}
    for path in samples or sorted(ROOT.glob("samples/*/*.yaml")):
        print(f"knobs: {path.stem}", flush=True)
        results[path.stem] = Sample(path).run()
    RESULTS.parent.mkdir(parents=True, exist_ok=True)
    RESULTS.write_text(json.dumps({k: [asdict(m) for m in v] for k, v in results.items()}, indent=1,
                                  default=str), encoding="utf-8")
    text = section(results)
    print(text)
    write_section("Knobs: time and error per setting", text)
    return results
