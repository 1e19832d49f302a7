"""The numpy kernel of a resolver mechanism against NAME.py, the standard-library program, which solves
the same rows one after another: the kernel solves them on lanes, chunks of the sweep side by side
seeded by the same sweep one level up, and hands NAME.py the rows it cannot solve as NAME.py would.
On the file's sweep and on one of 2000 rows (chunks seeded two levels deep): the same status and the
same Newton steps on every row, positions within the resolver's tolerance (of the length scale) over
the row's worst conditioning sigma, rates and accelerations within 1e-9 of their quantity's scale (1e-6
on near-singular rows; the programs' agreement) over sigma and sigma squared: the kernel's positions
differ from NAME.py's in the last bits (numpy's arctan2, cos_sin), which the derivatives magnify so
(measured: 1.8e-9 of the scale at sigma 0.0096 in triad_straight_through's accelerations).

The kernel in float32 (options: real float) against the kernel in double: the same status on every row
and values within test_real_type's bound (32 eps of float over the worst sigma)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from programs import ROOT, SAMPLES, noise_floors, parse
from test_real_type import BOUND_EPS, _worst_eps

from linkgen.kernel import kernel
from linkgen.pipeline import analyse_file, build_log
from linkgen.policy import EPSILON
from linkgen.render import render_all
from linkgen.rows import input_rows
from linkgen.writer import write_all

DENSE = 2000  # rows of the second sweep
QUICK = ("sixbar_fig14", "file"), ("double_triad", "file"), ("sixbar_fig14", DENSE)  # make test; the rest: long
RESOLVERS = [pytest.param(p, rows, id=f"{p.stem}-{rows}", marks=() if (p.stem, rows) in QUICK else pytest.mark.long)
             for p in [*SAMPLES, *sorted((ROOT / "tests" / "mechanisms").glob("*.yaml"))]
             if analyse_file(str(p))[2].groups for rows in ("file", DENSE)]
DERIVATIVES = 1e-9  # the programs' agreement (docs/generated-programs.md), 1e-6 near a singular position


def _one_by_one(rows_module, values, rates, accs, order):
    """NAME.py's solve on each row in order, one state through the sweep."""
    state: dict = {}
    return [rows_module.solve(list(x), list(r), list(a), order, state) for x, r, a in zip(values, rates, accs)]


@pytest.mark.parametrize(("mechanism", "rows"), RESOLVERS)
def test_the_lanes_solve_what_the_standard_library_program_solves(mechanism: Path, rows):
    _check_lanes(build_log(str(mechanism)), rows)


def test_the_lanes_run_the_first_order_predictor_too():
    """The default's lanes run the second-order predictor (the parabola through the row before, which a
    seed of the call's chunks holds as the one-by-one rows do); built with the first order, theirs."""
    log = build_log(str(ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"), options={"predictor": 1})
    _check_lanes(log, DENSE)


def _check_lanes(log, rows):
    """The kernel's sweep against NAME.py's rows one by one (see the module's docstring)."""
    module = kernel(log, log.order)
    assert module._MODULE.lanes  # on lanes, not NAME.py's rows
    values, rates, accs = input_rows(log, log.samples if rows == "file" else rows)
    out = module.solve(values, rates, accs)
    ref = _one_by_one(module.ROWS, values, rates, accs, log.order)
    status = np.array([r["status"] for r in ref])
    assert np.array_equal(out["status"], status), np.flatnonzero(out["status"] != status)[:5]
    assert np.array_equal(out["iterations"].T, [r["iterations"] for r in ref])
    fine = status <= 0
    worst = np.array([min(r["sigma"]) for r in ref])
    largest: dict[str, float] = {}
    for c in log.columns[len(log.inputs):]:
        size = np.nanmax(np.abs([r[c.name] for r in ref]), initial=0.0)
        largest[c.quantity] = max(largest.get(c.quantity, 0.0), float(size))
    floors = noise_floors(largest, log.length_scale)
    for c in log.columns[len(log.inputs):]:
        got, want = out[c.name][fine], np.array([r[c.name] for r in ref])[fine]
        assert np.array_equal(np.isnan(got), np.isnan(want)), c.name
        diff = np.abs(got - want)[~np.isnan(want)]
        sigma = np.maximum(worst[fine], log.policy.singular)
        if c.quantity in ("position", "angle"):
            bound = log.policy.tolerance * log.length_scale / sigma
        else:  # a rate divides by sigma, an acceleration by its square
            level = 2 if "acceleration" in c.quantity else 1
            bound = np.where(status[fine] == 0, DERIVATIVES, 1e-6) * np.maximum(np.abs(want), floors[c.quantity])
            bound = bound / sigma**level
        assert (diff <= bound[~np.isnan(want)]).all(), (c.name, diff.max())


def test_refused_rows_an_earlier_calls_arrays_and_no_design_parameters():
    log = build_log(str(ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"))
    module = kernel(log, 2)
    values, rates, accs = input_rows(log, 40)
    bad = values.copy()
    bad[3, 0] = np.inf
    out = module.solve(bad, rates, accs)
    assert out["status"][3] == 5 and np.isnan(out["J6.x"][3]) and np.isnan(out["sigma"][:, 3]).all()
    ref = _one_by_one(module.ROWS, np.delete(bad, 3, 0), np.delete(rates, 3, 0), np.delete(accs, 3, 0), 2)
    assert np.array_equal(np.delete(out["status"], 3), [r["status"] for r in ref])  # the row left out
    again = module.solve(values, rates, accs, out=out)
    assert np.shares_memory(again["J6.x"], out["J6.x"]) and (again["status"] == 0).all()
    with pytest.raises(ValueError, match="design parameters need a mechanism without resolver groups"):
        module.solve(values, rates, accs, params={"step2.l": 1.0})


FLOAT = ("fourbar", "jansen", "sixbar_fig14")  # make test; the other samples in the long tier


@pytest.mark.parametrize("mechanism", [pytest.param(p, id=p.stem, marks=() if p.stem in FLOAT else pytest.mark.long)
                                       for p in SAMPLES])
def test_the_kernel_in_float32_agrees_with_double_to_its_bound(mechanism: Path, tmp_path: Path):
    runs = {}
    for real in ("double", "float"):
        log = build_log(str(mechanism), options={"real": real})
        write_all(render_all(log), str(tmp_path / real))
        runs[real] = subprocess.run([sys.executable, f"{log.name}_np.py"], cwd=tmp_path / real, check=True,
                                    capture_output=True, text=True).stdout
    worst = _worst_eps(log, runs["double"], runs["float"], EPSILON["float"])
    print(f"{log.name}: numpy float32 {worst:.3g} eps / sigma")
    assert worst <= BOUND_EPS
    assert runs["float"] != runs["double"]  # computed in float32 indeed
    assert parse(runs["float"])[0] == parse(runs["double"])[0]


@pytest.mark.parametrize("rows", [30, 400])
def test_without_the_checks_the_rows_handed_to_the_standard_library_program_give_no_sigma(rows):
    """Regression (docs/performance.md, "checks off": KeyError: 'sigma'): a kernel built without the
    checks hands NAME.py the rows of a short sweep (all of them) and the row after a jump of the
    input (the sweep rolled by half: no warm start there), and NAME.py's rows carry no sigma.  The
    same statuses and Newton steps as NAME.py row after row, positions within the resolver's
    tolerance over the worst conditioning the checked build measures."""
    path = str(ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml")
    log = build_log(path, options={"checks": False})
    module = kernel(log, log.order)
    values, rates, accs = input_rows(log, rows)
    values = np.roll(values, rows // 2, axis=0)
    out = module.solve(values, rates, accs)
    assert "sigma" not in out
    ref = _one_by_one(module.ROWS, values, rates, accs, log.order)
    assert np.array_equal(out["status"], [r["status"] for r in ref])
    assert np.array_equal(out["iterations"].T, [r["iterations"] for r in ref])
    checked = build_log(path)
    sigma = np.maximum(kernel(checked, checked.order).solve(values, rates, accs)["sigma"].min(axis=0),
                       log.policy.singular)
    for c in log.columns[len(log.inputs):]:
        if c.quantity in ("position", "angle"):
            diff = np.abs(out[c.name] - [r[c.name] for r in ref])
            assert (diff <= log.policy.tolerance * log.length_scale / sigma).all(), (c.name, diff.max())


def test_refused_rows_amid_the_lanes_leave_the_others_as_the_standard_library_program_solves_them():
    """Refused rows in the middle of a sweep the lanes solve (rows not consecutive: the outputs go
    through the flush's mask): the other rows as NAME.py solves them without the refused ones."""
    log = build_log(str(ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"))
    module = kernel(log, 2)
    values, rates, accs = input_rows(log, 403)
    bad = values.copy()
    bad[[7, 200, 201]] = np.nan
    out = module.solve(bad, rates, accs)
    keep = ~np.isnan(bad[:, 0])
    assert (out["status"][~keep] == 5).all()
    ref = _one_by_one(module.ROWS, values[keep], rates[keep], accs[keep], 2)
    assert np.array_equal(out["status"][keep], [r["status"] for r in ref])
    assert np.array_equal(out["iterations"][:, keep].T, [r["iterations"] for r in ref])
    sigma = np.maximum([min(r["sigma"]) for r in ref], log.policy.singular)
    for c in log.columns[len(log.inputs):]:
        if c.quantity in ("position", "angle"):
            diff = np.abs(out[c.name][keep] - [r[c.name] for r in ref])
            assert (diff <= log.policy.tolerance * log.length_scale / sigma).all(), (c.name, diff.max())
