"""The resolver strategy closure (options: strategy closure): Newton on all loop-closure equations of a
resolver group, in C, Python and Octave.

The equations on their own, in the generated Python (the C and Octave ones are printed from the same
rows, and their sweeps are compared below): at the sketch every residual vanishes to rounding, and their
Jacobian is the complex-step derivative of their residuals.  The programs against the default build
(strategy newton: an independent iteration, on the Add-link lengths): the same status on every row, and
every value within the tolerance divided by the row's conditioning sigma (the worst step's, from the
in-process evaluator of the newton build) once per derivative order, tol / sigma^(k + 1) for a quantity of
order k, relative to the value or its quantity's scale.  Measured: at most 0.014 of that bound
(triad_tie's rocker1.omega; most mechanisms 1e-5 of it).  C, Python, Octave and the in-process evaluator
compute the same bits.  sixbar_fig14 in make test, every mechanism with an Add-link in the long profile.
"""

from __future__ import annotations

import dataclasses
import functools
import math
import subprocess
import sys
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest
from programs import SANITIZE, STRICT, compile_step, different_bits, need, parse, run_octave, run_python, scales

from linkgen.backends import backends
from linkgen.backends.program import LEVEL
from linkgen.evaluate import evaluate
from linkgen.pipeline import build_log
from linkgen.render import render_all, render_backend
from linkgen.render.view import build_view
from linkgen.rows import input_rows
from linkgen.steplog import StepLog, held
from linkgen.table import csv
from linkgen.writer import write_all

ROOT = Path(__file__).resolve().parents[1]
GROUPS = [ROOT / "samples" / n / f"{n}.yaml" for n in ("sixbar_fig14", "double_triad")] + [
    ROOT / "tests" / "mechanisms" / f"{n}.yaml" for n in (
        "cylinder_triad", "sixbar_fallback", "sixbar_partial", "triad_branch_nearby", "triad_coincident", "triad_far",
        "triad_lever", "triad_limit", "triad_near_singular", "triad_needle", "triad_passing", "triad_sharp_turn",
        "triad_short_base", "triad_straight_through", "triad_tie")]
QUICK = {"sixbar_fig14", "double_triad", "cylinder_triad"}
EQUATIONS = [pytest.param(p, id=p.stem, marks=() if p.stem in QUICK else pytest.mark.long) for p in GROUPS]
PROGRAMS = [pytest.param(p, id=p.stem, marks=() if p.stem == "sixbar_fig14" else pytest.mark.long) for p in GROUPS]
OCTAVE_ROWS = 25  # Octave is slow: its sweep is checked on fewer rows of the same range (continuation between)


@functools.cache
def _closure(path: Path) -> StepLog:
    return build_log(str(path), options={"strategy": "closure"})


def _python_module(log: StepLog) -> ModuleType:
    """The log's generated NAME.py, executed."""
    (py,) = (b for b in backends() if b.name == "py")
    module = ModuleType(log.name)
    exec(compile(render_backend(py, build_view(log))[f"{log.name}.py"], f"<{log.name}.py>", "exec"), module.__dict__)
    return module


@pytest.mark.parametrize("path", EQUATIONS)
def test_the_equations_vanish_at_the_sketch_and_their_jacobian_is_exact(path: Path):
    log = build_log(str(path), options={"strategy": "closure"}, sweep=False)
    module = _python_module(log)
    w = module._Work()
    width = max(log.order, 1) + 1
    for v in log.variables:  # the records a group reads from before it, as the sketch has them
        if not v.constant and v.sketch:
            value = held(dataclasses.replace(v, value=v.sketch), log.origin)
            setattr(w, v.name, (*value, *[0.0] * (width * len(value) - len(value))))
    view = build_view(log)
    for g, group in zip(log.groups, view.groups):
        x0 = [getattr(w, u)[i] for u in view.closure_plan(group).unknowns for i in (0, 1)]
        residuals, jac = getattr(module, f"_closure_equations_{g.number}")(w, x0)
        assert max(abs(r) for r in residuals) <= 16 * sys.float_info.epsilon * log.length_scale
        assert np.linalg.matrix_rank(np.array(jac)) == len(x0)  # the sketch is no singular position
        h = 1e-20 * log.length_scale
        for j in range(len(x0)):
            x = [complex(u) for u in x0]
            x[j] += 1j * h
            column = [r.imag / h for r in getattr(module, f"_closure_equations_{g.number}")(w, x)[0]]
            assert [row[j] for row in jac] == pytest.approx(column, rel=1e-13, abs=1e-15)


def _c_sweep(log: StepLog, folder: Path, extra: tuple[str, ...] = ()) -> str:
    """The C sweep, compiled under gcc -O2 with the strict flags (no diagnostic)."""
    cmd = [need("gcc"), *STRICT, "-O2", *extra, f"{log.name}.c", f"{log.name}_main.c", "-lm", "-o", "sweep"]
    compile_step(cmd, folder)
    return subprocess.run([str(folder / "sweep")], check=True, capture_output=True, text=True).stdout


def _within_the_tolerance_over_the_conditioning(newton: StepLog, closure: str, reference: str,
                                                factor: float = 1.0) -> float:
    """Assert the closure sweep has the newton sweep's statuses and its values within factor times
    tol / sigma^(k + 1) (see the module docstring); return the worst share of that bound."""
    head, got, st_got = parse(closure)
    head2, ref, st_ref = parse(reference)
    assert head == head2 and st_got == st_ref, [k for k, (a, b) in enumerate(zip(st_got, st_ref)) if a != b][:5]
    result = evaluate(newton, *input_rows(newton, len(ref)))
    sigma = np.ones(len(ref))
    for s in result.sigma.values():
        sigma = np.minimum(sigma, np.where(np.isnan(s), 1.0, s))
    scale = [max(x, y) for x, y in zip(scales(newton, got), scales(newton, ref))]
    worst = 0.0
    for k, (row_got, row_ref) in enumerate(zip(got, ref)):
        for j, (c, x, y) in enumerate(zip(newton.columns, row_got, row_ref)):
            if math.isnan(x) or math.isnan(y):
                assert math.isnan(x) and math.isnan(y), (k, c.name, x, y)
                continue
            bound = factor * newton.policy.tolerance / sigma[k] ** (LEVEL[c.quantity] + 1)
            share = abs(x - y) / max(abs(x), abs(y), scale[j]) / bound
            assert share <= 1.0, (k, c.name, x, y, sigma[k])
            worst = max(worst, share)
    return worst


@pytest.fixture(scope="module", params=PROGRAMS)
def built(request, tmp_path_factory) -> tuple[StepLog, StepLog, Path, str]:
    """(newton log, closure log, the closure build's folder, its C sweep); the newton build beside it."""
    folder = tmp_path_factory.mktemp(request.param.stem)
    newton, closure = build_log(str(request.param)), _closure(request.param)
    write_all(render_all(newton), str(folder / "newton"))
    write_all(render_all(closure), str(folder))
    return newton, closure, folder, _c_sweep(closure, folder)


def test_c_agrees_with_the_newton_build(built):
    newton, _, folder, c = built
    _within_the_tolerance_over_the_conditioning(newton, c, _c_sweep(newton, folder / "newton"))


def test_python_and_the_evaluator_compute_the_bits_of_c(built):
    _, closure, folder, c = built
    differ = different_bits(c, run_python(closure, folder))
    assert not differ, differ[:5]
    evaluated = csv(closure, evaluate(closure, *input_rows(closure, closure.samples)))  # linkgen run
    differ = different_bits(c, evaluated)
    assert not differ, differ[:5]


def test_octave_computes_the_bits_of_c(built, tmp_path: Path):
    _, closure, _, _ = built
    small = dataclasses.replace(closure, samples=OCTAVE_ROWS)
    write_all(render_all(small), str(tmp_path))
    differ = different_bits(run_octave(small, tmp_path), _c_sweep(small, tmp_path))
    assert not differ, differ[:5]


@pytest.mark.long
@pytest.mark.parametrize("path", [p for p in GROUPS if p.stem in QUICK], ids=lambda p: p.stem)
def test_c_is_clean_under_sanitizers_and_clang(path: Path, tmp_path: Path):
    closure = _closure(path)
    write_all(render_all(closure), str(tmp_path))
    plain = _c_sweep(closure, tmp_path)
    assert _c_sweep(closure, tmp_path, tuple(SANITIZE)) == plain
    compile_step([need("clang"), *STRICT, "-O2", f"{closure.name}.c", f"{closure.name}_main.c", "-lm", "-o",
                  "sweep_clang"], tmp_path)
    assert not different_bits(subprocess.run([str(tmp_path / "sweep_clang")], check=True, capture_output=True,
                                             text=True).stdout, plain)


@pytest.mark.long
def test_float_compiles_without_a_diagnostic_and_keeps_the_statuses(tmp_path: Path):
    """sixbar_fig14 in float (options: real): no real computed in double behind the user's back, and the
    double program's status on every row (its values are test_real_type's to bound)."""
    path = GROUPS[0]
    log = build_log(str(path), options={"strategy": "closure", "real": "float"})
    write_all(render_all(log), str(tmp_path))
    for cc in ("gcc", "clang"):
        compile_step([need(cc), *STRICT, "-O2", "-Wdouble-promotion", f"{log.name}.c", f"{log.name}_main.c", "-lm",
                      "-o", f"sweep_{cc}"], tmp_path)
    single = subprocess.run([str(tmp_path / "sweep_gcc")], check=True, capture_output=True, text=True).stdout
    write_all(render_all(_closure(path)), str(tmp_path / "double"))
    assert parse(single)[2] == parse(_c_sweep(_closure(path), tmp_path / "double"))[2]


@pytest.mark.long
@pytest.mark.parametrize("options", [dict(polish=p, predictor=k) for p in (True, False) for k in (0, 2)],
                         ids=lambda o: f"polish_{o['polish']}-predictor_{o['predictor']}")
def test_the_other_knobs_keep_the_newton_builds_results(options: dict[str, object], tmp_path: Path):
    """sixbar_fig14 by closure with polish off or on and the predictor of order 0 or 2: the default
    newton build's statuses, its values within the same bound; four times it with polish off, whose
    iteration stops at the tolerance (measured: 1.6 times, J2.vy)."""
    path = GROUPS[0]
    log = build_log(str(path), options={"strategy": "closure", **options})
    write_all(render_all(log), str(tmp_path))
    newton = build_log(str(path))
    write_all(render_all(newton), str(tmp_path / "newton"))
    _within_the_tolerance_over_the_conditioning(newton, _c_sweep(log, tmp_path), _c_sweep(newton, tmp_path / "newton"),
                                                1.0 if options["polish"] else 4.0)
