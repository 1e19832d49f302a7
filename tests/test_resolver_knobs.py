"""The resolver's knobs (options: strategy, polish, predictor) act as docs/mechanism-format.md says,
checked against the default build (Newton, polish, second-order predictor).

Every combination gives the default build's status on every row and its pair and point positions
to within BOUND times the tolerance asked for over the row's conditioning (the smallest sigma of
its steps in the default build), relative to the length scale (measured: at most 1.37, on
sixbar_partial), in C, Python and Octave, the three agreeing as tests/programs.compare requires;
the one exception is a fixed-point build's row whose iteration does not contract, reported with
reason 6.  The fixed-point iteration is provoked to that where it must fail: sixbar_fallback's
row 5 lies 3 degrees past a limit position (a fold of every block's lengths), so started from the
last row's state (predictor 0) its slope there is stale; Newton solves the row.  The predictor
of order 0 takes more Newton steps than orders 1 and 2 (the programs count them), and order 2
needs positions and rates only, so a program's positions do not depend on the order it computes.
The full cross-product over the resolver mechanisms is the long tier.
"""

from __future__ import annotations

import importlib.util
import itertools
import subprocess
from pathlib import Path
from types import ModuleType
from typing import Any

import pytest
from programs import ROOT, STRICT, compare, need, parse, run_octave, run_python

from linkgen import status
from linkgen.pipeline import build_log
from linkgen.render import render_all
from linkgen.rows import input_rows
from linkgen.rowsolver import RowSolver
from linkgen.steplog import StepLog
from linkgen.writer import write_all

BOUND = 4
FIG14 = ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"
FALLBACK = ROOT / "tests" / "mechanisms" / "sixbar_fallback.yaml"
COMBINATIONS = [dict(strategy=s, polish=p, predictor=k)
                for s, p, k in itertools.product(("newton", "fixed-point"), (True, False), (0, 1, 2))]


def _program(mechanism: Path, options: dict[str, Any], folder: Path) -> tuple[StepLog, ModuleType]:
    """The build's step log (without the manual's conditioning sweep: the programs are the same)
    and its Python program, imported."""
    log = build_log(str(mechanism), sweep=False, options=options)
    write_all(render_all(log), str(folder))
    spec = importlib.util.spec_from_file_location(f"knobs_{folder.name}", folder / f"{log.name}.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return log, module


def _sweep(log: StepLog, module: ModuleType, order: int | None = None) -> list[dict[str, Any]]:
    """The Python program's rows over the file's sweep, one call each with the state kept."""
    state: dict[str, Any] = {}
    n, out = log.samples, []
    for k in range(n):
        x = [i.start + k * (i.stop - i.start) / (n - 1) for i in log.inputs]
        out.append(module.solve(x, [i.speed for i in log.inputs], [0.0] * len(x),
                                module.ORDER if order is None else order, state))
    return out


def _positions(log: StepLog) -> list[str]:
    """The output columns of pair, point and slider positions (the inputs come first)."""
    return [c.name for c in log.columns[len(log.inputs):] if c.quantity == "position"]


def _check_against_default(log: StepLog, default: list[dict[str, Any]], rows: list[dict[str, Any]],
                           fixed_point: bool) -> int:
    """Statuses as the default's (a fixed-point row may instead not contract) and positions within
    the bound of log's tolerance; returns the rows that did not contract."""
    stuck = 0
    for k, (ref, got) in enumerate(zip(default, rows)):
        if got["status"] != ref["status"]:
            assert fixed_point and status.reason(got["status"]) == status.NOT_CONTRACTING, (k, ref["status"],
                                                                                            got["status"])
            stuck += 1
            continue
        if ref["status"] > 0:
            continue
        sigma = min([x for x in ref["sigma"] if x == x] + [1.0])  # a block's chains' too: it can fold
        if sigma == 0.0:  # a block that did not solve the row (a tie), no bound
            continue
        for name in _positions(log):
            assert abs(got[name] - ref[name]) <= BOUND * log.policy.tolerance * log.length_scale / sigma, (k, name)
    return stuck


@pytest.fixture(scope="module")
def fig14(tmp_path_factory) -> dict[int, tuple[StepLog, ModuleType, list[dict[str, Any]]]]:
    """sixbar_fig14 built with each predictor order, swept by its Python program."""
    out = {}
    for k in (0, 1, 2):
        log, module = _program(FIG14, {"predictor": k}, tmp_path_factory.mktemp(f"fig14_predictor{k}"))
        out[k] = (log, module, _sweep(log, module))
    return out


def _all_steps(log: StepLog, module: ModuleType) -> int:
    """The Newton steps of every pass of the sweep's rows: a row's own (its iterations) and those of the
    continuation that follows a row the warm start does not solve on its path (which no row reports)."""
    steps = [0]
    solve_block = module.solve_block

    def counted(*args: Any) -> Any:
        out = solve_block(*args)
        steps[0] += out[2]
        return out

    module.solve_block = counted
    try:
        _sweep(log, module)
    finally:
        module.solve_block = solve_block
    return steps[0]


def test_the_predictor_of_order_0_needs_more_newton_steps(fig14):
    steps = {k: _all_steps(log, module) for k, (log, module, _) in fig14.items()}
    assert steps[0] > steps[1] >= steps[2], steps  # the default (2) takes no more than the first order
    log, _, default = fig14[2]
    for k in (0, 1):
        assert _check_against_default(log, default, fig14[k][2], False) == 0


def test_the_second_order_start_does_not_depend_on_the_order_computed(fig14):
    log, module, _ = fig14[2]
    positions = [[r[c] for c in _positions(log)] + [r["status"]] for r in _sweep(log, module, 0)]
    assert positions == [[r[c] for c in _positions(log)] + [r["status"]] for r in fig14[2][2]]


def test_fixed_point_reports_that_it_does_not_contract_past_a_limit_position(tmp_path):
    log, default = _program(FALLBACK, {}, tmp_path / "default")
    log_fp, fixed = _program(FALLBACK, {"strategy": "fixed-point", "predictor": 0}, tmp_path / "fixed")
    ref, rows = _sweep(log, default), _sweep(log_fp, fixed)
    assert (ref[5]["status"], rows[5]["status"]) == (0, status.code(8, status.NOT_CONTRACTING))
    assert log_fp.step(8).action == "resolve" and all(v != v for v in [rows[5][c] for c in _positions(log)])
    assert _check_against_default(log, ref, rows, True) == 1
    assert any(c.code == rows[5]["status"] for c in log_fp.status_codes)
    solver = RowSolver(log_fp, log_fp.order)  # linkgen run: the evaluator runs the build's settings too
    for k, (values, rates, accs) in enumerate(zip(*input_rows(log_fp, log_fp.samples))):
        row = solver.solve(values, rates, accs)
        assert (row.code, list(row.iterations.values())) == (rows[k]["status"], rows[k]["iterations"]), k


TOLERANCE_AND_CAP = [{"tolerance": 1e-6, "polish": False}, {"iterations": 2, "predictor": 0}]


def test_the_tolerance_and_the_cap_act(fig14, tmp_path):
    """Without polish a row stops at the tolerance: at 1e-6 its positions move off the default's by more
    than 1e-9 of the length scale, within the bound; capped at 2 steps, the predictor of order 0 (which
    takes 3 on some rows) never takes more, and the rows it cannot solve so are followed from the last."""
    log, _, default = fig14[1]
    loose, capped = (_program(FIG14, o, tmp_path / str(k)) for k, o in enumerate(TOLERANCE_AND_CAP))
    rows = _sweep(*loose)
    assert _check_against_default(loose[0], default, rows, False) == 0
    assert max(abs(a[c] - b[c]) for a, b in zip(default, rows) for c in _positions(log)) > 1e-9 * log.length_scale
    assert max(max(r["iterations"]) for r in fig14[0][2]) > 2
    rows = _sweep(*capped)
    assert max(max(r["iterations"]) for r in rows) == 2
    assert _check_against_default(log, default, rows, False) == 0


def test_a_fixed_point_build_without_polish_in_c_is_its_python_program(tmp_path):
    """C (gcc, the strict flags, -O2) and Python of one non-default build write the same sweep."""
    log, _ = _program(FIG14, {"strategy": "fixed-point", "polish": False, "predictor": 2}, tmp_path)
    done = subprocess.run([need("gcc"), *STRICT, "-O2", f"{log.name}.c", f"{log.name}_main.c", "-lm", "-o", "sweep"],
                          cwd=tmp_path, capture_output=True, text=True)
    assert done.returncode == 0 and not done.stderr, done.stderr
    c = subprocess.run([str(tmp_path / "sweep")], check=True, capture_output=True, text=True).stdout
    compare(log, c, run_python(log, tmp_path))


# -- the long tier: every combination, every resolver mechanism, every language --------------------

RESOLVED = [ROOT / "samples" / n / f"{n}.yaml" for n in ("sixbar_fig14", "double_triad")] + sorted(
    p for p in (ROOT / "tests" / "mechanisms").glob("*.yaml") if p.stem.startswith(("triad", "sixbar", "cylinder")))


def _languages(log: StepLog, folder: Path) -> dict[str, str]:
    """The CSV sweeps of C (gcc and clang, strict, -O2: the same bits), Python and Octave."""
    sweeps = {}
    for cc in ("gcc", "clang"):
        done = subprocess.run([need(cc), *STRICT, "-O2", f"{log.name}.c", f"{log.name}_main.c", "-lm", "-o", cc],
                              cwd=folder, capture_output=True, text=True)
        assert done.returncode == 0 and not done.stderr, done.stderr
        sweeps[cc] = subprocess.run([str(folder / cc)], check=True, capture_output=True, text=True).stdout
    assert sweeps.pop("clang") == sweeps["gcc"]
    return {"C": sweeps["gcc"], "Python": run_python(log, folder), "Octave": run_octave(log, folder)}


@pytest.mark.long
@pytest.mark.parametrize("mechanism", RESOLVED, ids=lambda p: p.stem)
def test_every_combination_in_every_language_agrees_with_the_default(mechanism, tmp_path):
    log, module = _program(mechanism, {}, tmp_path / "default")
    default = _sweep(log, module)
    for options in COMBINATIONS:
        folder = tmp_path / "_".join(str(v) for v in options.values())
        built, program = _program(mechanism, options, folder)
        rows = _sweep(built, program)
        _check_against_default(log, default, rows, options["strategy"] == "fixed-point")
        csv = _languages(built, folder)
        assert parse(csv["Python"])[2] == [r["status"] for r in rows], options
        for lang in ("Python", "Octave"):
            compare(built, csv["C"], csv[lang])


@pytest.mark.long
@pytest.mark.parametrize("options", TOLERANCE_AND_CAP, ids=lambda o: "_".join(map(str, o)))
def test_the_tolerance_and_the_cap_act_in_every_language(options, tmp_path):
    log, module = _program(FIG14, {}, tmp_path / "default")
    built, program = _program(FIG14, options, tmp_path / "built")
    rows = _sweep(built, program)
    _check_against_default(built, _sweep(log, module), rows, False)
    csv = _languages(built, tmp_path / "built")
    assert parse(csv["Python"])[2] == [r["status"] for r in rows]
    for lang in ("Python", "Octave"):
        compare(built, csv["C"], csv[lang])


@pytest.mark.long
def test_a_float_fixed_point_build_compiles_without_a_diagnostic(tmp_path):
    log = build_log(str(FIG14), options={"real": "float", "strategy": "fixed-point", "predictor": 2, "polish": False})
    write_all(render_all(log), str(tmp_path))
    for cc in ("gcc", "clang"):
        done = subprocess.run([need(cc), *STRICT, "-O2", "-Wdouble-promotion", "-c", f"{log.name}.c", "-o",
                               f"{cc}.o"], cwd=tmp_path, capture_output=True, text=True)
        assert done.returncode == 0 and not done.stderr and not done.stdout, f"{cc}: {done.stderr}"


