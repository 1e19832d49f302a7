"""linkgen.rowsolver: the row status rule against codes worked out by hand, and the row driver
the evaluator runs against the generated Python program's: the same numbers handed to the
runtime, the same rows out (status, Newton steps, positions to the bit)."""

from __future__ import annotations

import importlib.util
import math
from pathlib import Path

import numpy as np
import pytest

from linkgen.options import runtime_policy
from linkgen.pipeline import build_log
from linkgen.render import render_all
from linkgen.rows import input_rows
from linkgen.rowsolver import RowSolver, mechanism, row_status
from linkgen.writer import write_all

ROOT = Path(__file__).resolve().parents[2]
RESOLVED = [ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml",
            ROOT / "samples" / "double_triad" / "double_triad.yaml",
            ROOT / "tests" / "mechanisms" / "sixbar_partial.yaml"]  # a crank that meets two limit positions


def test_row_status_takes_the_first_failure_then_the_first_singular_then_the_first_near_singular_step():
    # a step's code is 10 * step + reason; near-singular (reason 4) rows are flagged negative
    near_then_singular = {3: (0, 1.0), 5: (4, 1e-4), 7: (3, 1e-8), 8: (3, 1e-9)}
    assert row_status(near_then_singular) == 73
    assert row_status({**near_then_singular, 9: (1, math.nan), 10: (2, 0.0)}) == 91
    assert row_status({3: (0, 1.0), 5: (4, 1e-4), 8: (4, 1e-4)}) == -54
    assert row_status({3: (0, 1.0), 4: (0, 1.0)}) == 0
    assert row_status({6: (2, 0.0), 2: (1, math.nan)}) == 62  # the order the steps ran, not their numbers


def test_row_status_ranks_a_failure_over_a_singular_step_over_a_near_singular_one():
    rows = [(0, 3, 2), (1, 0, 0), (0, 4, 0), (4, 3, 0)]  # the statuses of steps 3, 5 and 7 on four rows
    codes = [row_status({3: (a, None), 5: (b, None), 7: (c, None)}) for a, b, c in rows]
    assert codes == [72, 31, -54, 53]  # a failure beats a singular step, which beats a near one


@pytest.fixture(scope="module", params=RESOLVED, ids=lambda p: p.stem)
def program(request, tmp_path_factory):
    """The step log and its generated Python module, imported."""
    log = build_log(str(request.param))
    folder = tmp_path_factory.mktemp(request.param.stem)
    write_all(render_all(log), str(folder))
    spec = importlib.util.spec_from_file_location(f"generated_{log.name}", folder / f"{log.name}.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return log, module


def test_the_evaluator_hands_the_driver_the_programs_numbers(program):
    log, module = program
    ours = vars(mechanism(log))
    assert set(ours) == set(vars(module.MECHANISM))
    for name, value in ours.items():
        theirs = getattr(module.MECHANISM, name)
        if name == "sketch_a":  # the program pads every block's state to the largest
            theirs = [g[: len(b)] for g, b in zip(theirs, value)]
            assert all(not any(g[len(b):]) for g, b in zip(getattr(module.MECHANISM, name), value))
        assert np.array_equal(np.asarray(value, dtype=float), np.asarray(theirs, dtype=float), equal_nan=True), name
    policy = runtime_policy(log.policy, log.options)  # the policy's numbers, the strategy, polish and predictor
    for name, value in vars(module.POLICY).items():
        assert getattr(policy, name) == value, name


def test_the_evaluator_solves_each_row_as_the_program_does(program):
    log, module = program
    values, rates, accs = input_rows(log, log.samples)
    solver, state = RowSolver(log, log.order), {}
    points = [v.name for v in log.variables if v.kind == "POINT" and not v.constant]
    for k in range(log.samples):
        row = solver.solve(values[k], rates[k], accs[k])
        out = module.solve(list(values[k]), list(rates[k]), list(accs[k]), log.order, state)
        assert (row.code, list(row.iterations.values())) == (out["status"], out["iterations"]), k
        assert (solver.warm is None) == (state["warm"] is None), k
        if row.ok:
            for c in (c for c in log.columns if c.variable in points and c.field in ("x", "y")):
                assert row.env[c.variable][c.field == "y"] + log.offset(c) == out[c.name], (k, c.name)


def test_the_runtimes_one_by_one_solve_is_the_division_and_its_det_the_entry():
    # a block with one Add-link solves a 1 x 1 system: x = b / d correctly rounded (IEEE), det d itself;
    # elimination with pivoting gives those bits too ((b - 0) / (1.0 * d)), and d == 0 gives nan, det 0
    from linkgen.rowsolver import runtime

    solve_linear = runtime()["solve_linear"]
    rng = np.random.default_rng(19)
    for b, d in [*zip(rng.normal(size=50) * 10.0 ** rng.integers(-8, 8, 50), rng.normal(size=50)),
                 (-0.0, 3.0), (0.0, -2.5), (1.0, 1e-300)]:
        x, det = solve_linear([[float(d)]], [float(b)])
        assert (x[0], det) == (float(b) / float(d), float(d))
        assert math.copysign(1.0, x[0]) == math.copysign(1.0, float(b) / float(d))
    x, det = solve_linear([[-0.0]], [1.0])
    assert math.isnan(x[0]) and det == 0.0
    x, det = solve_linear([[2.0, 1.0], [4.0, 3.0]], [1.0, 2.0])  # two Add-links: elimination, rows swapped
    assert np.allclose(x, [0.5, 0.0], rtol=0, atol=1e-15) and det == 2.0  # by hand: det 2 * 3 - 1 * 4
