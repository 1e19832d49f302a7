"""angles: unit (options: {angles: unit}, linkgen build --angles unit): the links' directions as unit
vectors, checked against the angle build (the default) of the same mechanism, an independent route
(atan2 in the programs, then cos and sin of the C library here).

On every row the unit build has the angle build's status and, in every column that is not a link's,
its bits (the same steps place the pairs); a link's (ux, uy) is (cos, sin) of its angle phi, (dux, duy)
omega (-sin, cos) and (ddux, dduy) alpha (-sin, cos) - omega^2 (cos, sin), within BOUND_EPS eps of the
column's scale (1 for the unit vector; for the rates the scale S of angular velocities or accelerations
of tests/programs.scales: measured at most 1.9 eps on every sample).  A crank's angle is exact in the
angle build (crank_angle: the input's, no atan2 of the pairs it places) while its direction comes from those
pairs (link_direction, no trigonometry, as before crank_angle): there the comparison sees the pairs' rounding,
eps of the length scale L over the crank's length l, so the bound is BOUND_EPS L / l (measured: 4.5 eps on
the four-bar's crank, 123 on triad_needle's: at most 1.95 eps L / l).  C (gcc -O2, the
strict flags), Python and Octave compute the same bits; the numpy kernel and the in-process evaluator
(which runs it) agree with them as in the angle build.
"""

from __future__ import annotations

import dataclasses
import functools
import math
import subprocess
from pathlib import Path

import numpy as np
import pytest
from programs import (
    CXXFLAGS,
    ROOT,
    SAMPLES,
    STRICT,
    compare,
    compile_step,
    different_bits,
    need,
    parse,
    run_numpy,
    run_octave,
    run_python,
    scales,
)

from linkgen import status
from linkgen.evaluate import evaluate
from linkgen.pipeline import build_log
from linkgen.render import render_all
from linkgen.rows import input_rows
from linkgen.steplog import StepLog
from linkgen.table import csv
from linkgen.writer import write_all

BOUND_EPS = 4
EPS = 2.0**-52
MECHANISMS = SAMPLES + sorted((ROOT / "tests" / "mechanisms").glob("*.yaml"))
SAMPLE_NAMES = {p.stem for p in SAMPLES}


def cases(fast: tuple[str, ...], names: set[str] | None = None) -> list:
    """The mechanisms (those named, or all), ``fast`` in `make test` and the others in the long tier."""
    return [pytest.param(p, id=p.stem, marks=() if p.stem in fast else pytest.mark.long) for p in MECHANISMS
            if names is None or p.stem in names]


# make test: steps in place and added, a constant direction and a chain's angle (a resolver's renumbered
# fallbacks in tests/unit/test_directions.py; the resolver samples in the long tier), Octave on the four-bar
CASES = cases(("fourbar", "inverted_slider"))
OCTAVE_ROWS = 25  # Octave is slow: the sweep's ranges in fewer rows


@functools.cache
def _log(path: Path, angles: str) -> StepLog:
    return build_log(str(path), sweep=False, options={"angles": angles})  # the programs need no sweep


def _c_sweep(log: StepLog, outdir: Path, flags: tuple[str, ...] = ("-O2",)) -> str:
    """The C sweep, built with gcc and the strict flags: no diagnostic."""
    write_all(render_all(log), str(outdir))
    compile_step([need("gcc"), *STRICT, *flags, f"{log.name}.c", f"{log.name}_main.c", "-lm", "-o", "sweep"], outdir)
    return subprocess.run([str(outdir / "sweep")], check=True, capture_output=True, text=True).stdout


RATE = {"dux": "omega", "duy": "omega", "ddux": "alpha", "dduy": "alpha"}  # the angle's column of a rate's scale


def _same(x: float, y: float) -> bool:
    return x == y or (math.isnan(x) and math.isnan(y))


def _angle_builds_code(angle: StepLog, unit: StepLog, code: int) -> int:
    """A status code of the unit build as the angle build numbers its step: the fallback blocks'
    steps come after the new direction steps."""
    first = [min((s.number for s in log.steps if s.variant), default=0) for log in (angle, unit)]
    step = status.step(code)
    if first[0] and step >= first[1]:
        step -= first[1] - first[0]
    return int(status.code(step, status.reason(code))) if code else 0


def _expected(phi: float, omega: float, alpha: float) -> dict[str, float]:
    """The chain rule of (cos phi, sin phi)."""
    c, s = math.cos(phi), math.sin(phi)
    return {"ux": c, "uy": s, "dux": -omega * s, "duy": omega * c, "ddux": -alpha * s - omega * omega * c,
            "dduy": alpha * c - omega * omega * s}


@pytest.mark.parametrize("mechanism", CASES)
def test_directions_are_cos_and_sin_of_the_angle_builds_angles(mechanism: Path, tmp_path: Path):
    angle, unit = _log(mechanism, "angle"), _log(mechanism, "unit")
    (tmp_path / "a").mkdir()
    (tmp_path / "u").mkdir()
    head_a, rows_a, codes_a = parse(_c_sweep(angle, tmp_path / "a"))
    head_u, rows_u, codes_u = parse(_c_sweep(unit, tmp_path / "u"))
    assert codes_a == [_angle_builds_code(angle, unit, code) for code in codes_u]
    links = [h[:-4] for h in head_a if h.endswith(".phi")]
    kept = [h for h in head_a[:-1] if h.rsplit(".", 1)[0] not in links]
    assert kept == [h for h in head_u[:-1] if h.rsplit(".", 1)[0] not in links]  # the inputs stay angles
    scale = dict(zip(head_a, scales(angle, rows_a)))
    lever = {s.links[0]: angle.length_scale / s.args[1].value for s in angle.steps if s.function == "crank_input"}
    cranks = {s.target: max(1.0, lever[s.target]) for s in angle.steps if s.function == "crank_angle"}
    worst = worst_crank = 0.0
    for row_a, row_u in zip(rows_a, rows_u):
        a, u = dict(zip(head_a, row_a)), dict(zip(head_u, row_u))
        assert all(_same(a[h], u[h]) for h in kept), "a column that is not a link's differs"
        for link in links:
            rates = [a.get(f"{link}.{r}", 0.0) for r in ("omega", "alpha")]
            for name, want in _expected(a[f"{link}.phi"], *rates).items():
                if f"{link}.{name}" not in u:  # beyond the build's order
                    continue
                got = u[f"{link}.{name}"]
                if math.isnan(want) or math.isnan(got):
                    assert math.isnan(want) and math.isnan(got), (link, name, want, got)
                    continue
                unit_scale = 1.0 if name in ("ux", "uy") else scale[f"{link}.{RATE[name]}"]
                if link in cranks:
                    worst_crank = max(worst_crank, abs(got - want) / unit_scale / EPS / cranks[link])
                else:
                    worst = max(worst, abs(got - want) / unit_scale / EPS)
    print(f"{unit.name}: worst {worst:.3g} eps of the scale, a crank's {worst_crank:.3g} eps L / l")
    assert worst <= BOUND_EPS and worst_crank <= BOUND_EPS


@pytest.mark.parametrize("mechanism", CASES)
def test_python_numpy_and_the_evaluator_agree_with_the_c_program(mechanism: Path, tmp_path: Path):
    """Python the same bits as C; the numpy kernel within the spec's 1e-9 (its cosines and sines, where a
    step places a point from an angle, round otherwise than the C library's, by up to 2 eps, and near a
    change point the chains magnify that: 4.7e-11 measured on the parallelogram); the evaluator's CSV is
    the kernel's where there is no resolver.  With one the kernel solves rows on lanes and the evaluator
    one by one: the same statuses, and the kernel's last bits of the positions, which the derivatives
    magnify, bound as tests/test_np_resolver.py bounds them: a rate's 1e-9 over the row's worst sigma, an
    acceleration's over its square (measured: 1.9e-9 of the scale at sigma 0.044 in
    triad_straight_through's row 96, 0.2 degrees from a crossing of assemblies, where a 1-ulp difference
    of the crank's pair becomes 3e-15 L in the ternary's and 2e-9 in the rocker's acceleration)."""
    log = _log(mechanism, "unit")
    c = _c_sweep(log, tmp_path)
    assert different_bits(c, run_python(log, tmp_path)) == []
    numpy = run_numpy(log, tmp_path)
    result = evaluate(log, *input_rows(log, log.samples))
    evaluator = csv(log, result)
    if log.groups:
        assert parse(evaluator)[2] == parse(numpy)[2]
        worst = np.fmin.reduce([np.asarray(s, dtype=float) for s in result.sigma.values()], initial=1.0)
        compare(log, numpy, c, sigma=list(np.maximum(np.nan_to_num(worst, nan=1.0), log.policy.singular)))
    else:
        assert evaluator == numpy
        compare(log, numpy, c)


@pytest.mark.parametrize("mechanism", cases(("fourbar",), SAMPLE_NAMES))
def test_octave_computes_the_c_programs_bits(mechanism: Path, tmp_path: Path):
    log = dataclasses.replace(_log(mechanism, "unit"), samples=OCTAVE_ROWS)
    c = _c_sweep(log, tmp_path)
    assert different_bits(run_octave(log, tmp_path), c) == []


def test_a_pruned_unit_build_gives_the_whole_builds_bits(tmp_path: Path):
    """--outputs rocker,P --order 1: only the rocker's direction step and what P needs; the columns
    it keeps are the whole unit build's to the bit."""
    fourbar = ROOT / "samples" / "fourbar" / "fourbar.yaml"
    pruned = build_log(str(fourbar), ("rocker", "P"), 1, options={"angles": "unit"})
    assert [s.function for s in pruned.steps if s.function.endswith("direction")] == ["link_direction"]
    (tmp_path / "p").mkdir()
    (tmp_path / "w").mkdir()
    head_p, rows_p, status_p = parse(_c_sweep(pruned, tmp_path / "p"))
    head_w, rows_w, status_w = parse(_c_sweep(_log(fourbar, "unit"), tmp_path / "w"))
    assert head_p[:7] == ["theta_O1", "rocker.ux", "rocker.uy", "rocker.dux", "rocker.duy", "P.x", "P.y"]
    assert status_p == status_w
    for rp, rw in zip(rows_p, rows_w):
        whole = dict(zip(head_w, rw))
        assert all(_same(x, whole[h]) for h, x in zip(head_p, rp))


@pytest.mark.long
@pytest.mark.parametrize("mechanism", cases((), SAMPLE_NAMES))
def test_clang_and_cpp_build_the_unit_programs_without_a_diagnostic(mechanism: Path, tmp_path: Path):
    """clang -O3 strict writes gcc's bits; NAME.c compiles as C++ and NAME.h includes into a C++ host."""
    log = _log(mechanism, "unit")
    c = _c_sweep(log, tmp_path)
    compile_step([need("clang"), *STRICT, "-O3", f"{log.name}.c", f"{log.name}_main.c", "-lm", "-o", "clang"],
                 tmp_path)
    assert subprocess.run([str(tmp_path / "clang")], check=True, capture_output=True, text=True).stdout == c
    compile_step([need("g++"), "-x", "c++", *CXXFLAGS, "-O2", "-c", f"{log.name}.c", "-o", "lib.o"], tmp_path)
    (tmp_path / "host.cpp").write_text(f'#include "{log.name}.h"\nint main() {{ {log.name}_state s; '
                                       f'{log.name}_init(&s); return s.status; }}\n')
    compile_step([need("g++"), *CXXFLAGS, "host.cpp", "lib.o", "-lm", "-o", "host"], tmp_path)
