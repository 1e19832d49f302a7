"""NAME_np.py, the vectorised kernel (the numpy backend).

Run as a script with numpy alone (python -I, linkgen not importable) it writes the evaluator's CSV
bit for bit (the evaluator runs this very module) and C's to 1e-12; with resolver groups the
statuses of the evaluator and of C (tests/test_np_resolver.py holds its values against
NAME.py's).  A design sweep in one call (the four-bar's crank length as 1000 values
against 360 rows) equals separate builds of the four-bar with that crank and the four-bar's closed
form; calls it cannot answer are refused as the C program refuses them.
"""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest
from programs import ROOT, SAMPLES, build, compare, parse, run_c

from linkgen.backends.py import BACKEND as PYTHON
from linkgen.evaluate import evaluate
from linkgen.kernel import kernel, source
from linkgen.pipeline import build_log
from linkgen.rows import input_rows
from linkgen.table import csv

MECHANISMS = [pytest.param(p, id=p.stem) for p in SAMPLES] + [
    pytest.param(p, id=p.stem, marks=pytest.mark.long) for p in sorted((ROOT / "tests" / "mechanisms").glob("*.yaml"))]
# runs NAME_np.py as a script with linkgen made unimportable; fails naming any module it loads beyond
# numpy and the standard library
ALONE = """import contextlib, io, runpy, sys
loaded = set(sys.modules)
sys.modules["linkgen"] = None
sys.argv = [sys.argv[1]]
out = io.StringIO()
with contextlib.redirect_stdout(out):
    runpy.run_path(sys.argv[0], run_name="__main__")
extra = {m.partition(".")[0] for m in set(sys.modules) - loaded} - set(sys.stdlib_module_names) - {"numpy", "linkgen"}
if extra:
    sys.exit("imports " + ", ".join(sorted(extra)))
sys.stdout.write(out.getvalue())
"""


@pytest.mark.parametrize("mechanism", MECHANISMS)
def test_the_kernel_alone_writes_the_evaluators_bits_and_agrees_with_c(mechanism: Path, tmp_path: Path):
    """With resolver groups the evaluator solves the rows one by one as NAME.py does: the same
    statuses (the values as tests/test_np_resolver.py bounds them)."""
    log = build(mechanism, tmp_path)
    done = subprocess.run([sys.executable, "-I", "-c", ALONE, f"{log.name}_np.py"], cwd=tmp_path,
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    evaluator = csv(log, evaluate(log, *input_rows(log, log.samples)))
    if log.groups:
        assert parse(done.stdout)[2] == parse(evaluator)[2] == parse(run_c(log, tmp_path))[2]
        return
    assert done.stdout == evaluator
    # the spec's 1e-9: the kernel's cos_sin rounds otherwise than libm by up to 2 eps, magnified near a
    # change point (4.7e-11 measured on the parallelogram, 1.1e-12 on grashof_near_change)
    compare(log, done.stdout, run_c(log, tmp_path))


# -- a design sweep: the four-bar's crank length ------------------------------

FOURBAR = ROOT / "samples" / "fourbar" / "fourbar.yaml"
O2, COUPLER, ROCKER = np.array([90.0, 0.0]), math.hypot(60, 50), math.hypot(10, 50)  # as fourbar.yaml draws them
ROWS = 360


def _theta() -> np.ndarray:
    return 2 * np.pi * np.arange(ROWS) / ROWS


def _sweep(module: ModuleType, lengths: np.ndarray) -> dict[str, np.ndarray]:
    """Every crank length against every row in one call: arrays of shape (designs, rows)."""
    inputs = _theta()[:, None]
    return module.solve(inputs, [2 * np.pi], [0.0], params={"step2.l": lengths[:, None]})


def _closed_form(lengths: np.ndarray) -> dict[str, np.ndarray]:
    """The four-bar by hand: A on the crank, B where the circles about A (coupler) and O2 (rocker)
    meet left of A -> O2, B's velocity from the two links' rigidity; h2 < 0 where they do not meet."""
    t, crank = _theta()[None, :], lengths[:, None]
    a = np.stack([crank * np.cos(t), crank * np.sin(t)])
    d = O2[:, None, None] - a
    q = np.hypot(d[0], d[1])
    along = (COUPLER**2 - ROCKER**2 + q**2) / (2 * q)
    h2 = COUPLER**2 - along**2
    h = np.sqrt(np.maximum(h2, 0))
    b = a + (along * d + h * np.stack([-d[1], d[0]])) / q
    va = 2 * np.pi * np.stack([-a[1], a[0]])
    ab, ob = b - a, b - O2[:, None, None]  # (B - A).(vB - vA) = 0 and (B - O2).vB = 0
    det = ab[0] * ob[1] - ab[1] * ob[0]
    rhs = ab[0] * va[0] + ab[1] * va[1]
    with np.errstate(divide="ignore", invalid="ignore"):  # B's velocity at a limit position (det 0)
        vb = np.stack([rhs * ob[1] / det, -rhs * ob[0] / det])
    return {"A.x": a[0], "A.y": a[1], "B.x": b[0], "B.y": b[1], "B.vx": vb[0], "B.vy": vb[1],
            "rocker.phi": np.arctan2(ob[1], ob[0]), "h2": h2}


def test_a_design_sweep_in_one_call_is_the_closed_form_of_the_four_bar():
    """Cranks from 5 to 60: up to 39 the crank turns round, beyond it the chain cannot close
    where A is too far from O2 or too near (status 31 exactly there)."""
    lengths = np.linspace(5.0, 60.0, 1000)
    out, hand = _sweep(kernel(build_log(str(FOURBAR)), 2), lengths), _closed_form(lengths)
    assert out["B.x"].shape == out["status"].shape == (1000, ROWS)
    clear = np.abs(hand["h2"]) > 1e-6 * COUPLER**2  # not at a limit position
    assert np.array_equal((out["status"] == 31)[clear], (hand["h2"] < 0)[clear])
    assert (out["status"][hand["h2"] > 0] != 31).all()
    assert 0 < (out["status"] == 31).sum() < out["status"].size / 4
    fine = (out["status"] == 0) & clear
    for name in ("A.x", "A.y", "B.x", "B.y", "rocker.phi"):
        assert np.max(np.abs(out[name] - hand[name])[fine]) < 1e-11 * 100, name
    speed = np.max(np.abs(hand["B.vx"][fine]))
    for name in ("B.vx", "B.vy"):
        assert np.max(np.abs(out[name] - hand[name])[fine]) < 1e-9 * speed, name
    assert np.isnan(out["B.x"][out["status"] == 31]).all()


def _fourbar_with_crank(length: float, path: Path) -> Path:
    """fourbar.yaml with a crank of this length: A at (length, 0), B where coupler and rocker keep
    their lengths, P where it keeps its place on the coupler."""
    b = _closed_form(np.array([length]))
    bx, by = float(b["B.x"][0, 0]), float(b["B.y"][0, 0])
    u = np.array([bx - length, by]) / COUPLER
    gsi, eta = 75.54175916040862, 28.168113585237116  # P in the coupler's frame (fourbar_np.PARAMS)
    px, py = float(length + gsi * u[0] - eta * u[1]), float(gsi * u[1] + eta * u[0])
    text = FOURBAR.read_text(encoding="utf-8")
    text = text.replace("A: [20, 0]", f"A: [{length!r}, 0]").replace("B: [80, 50]", f"B: [{bx!r}, {by!r}]")
    path.write_text(text.replace("P: [60, 70]", f"P: [{px!r}, {py!r}]"), encoding="utf-8")
    return path


@pytest.mark.parametrize("every", [pytest.param(50, id="every_50th"),
                                   pytest.param(1, id="all", marks=pytest.mark.long)])
def test_a_design_sweep_in_one_call_is_the_separate_builds(every: int, tmp_path: Path):
    """Cranks from 5 to 38 (each turns round): row k of the sweep is what the four-bar built with
    crank k computes, to the rounding of its sketch's numbers (its coupler length and P's place come
    back through the sketch's coordinates)."""
    lengths = np.linspace(5.0, 38.0, 1000)
    out = _sweep(kernel(build_log(str(FOURBAR)), 2), lengths)
    assert (out["status"] == 0).all()
    for k in range(0, len(lengths), every):
        log = build_log(str(_fourbar_with_crank(float(lengths[k]), tmp_path / f"fourbar_{k}.yaml")), sweep=False)
        alone = kernel(log, 2).solve(_theta()[:, None], [2 * np.pi], [0.0])
        assert (alone["status"] == 0).all()
        for c in log.columns[1:]:
            scale = max(np.max(np.abs(alone[c.name])), 1.0)
            assert np.max(np.abs(out[c.name][k] - alone[c.name])) <= 1e-11 * scale, (k, c.name)


def _fourbar_moved(o2: tuple[float, float], rocker: float, path: Path) -> Path:
    """fourbar.yaml with O2 at o2 and B where the coupler keeps its length and the rocker has this
    one (left of A -> O2, as drawn), P where it keeps its place on the coupler."""
    a, o = np.array([20.0, 0.0]), np.array(o2)  # A as drawn
    d = np.hypot(*(o - a))
    along = (COUPLER**2 - rocker**2 + d**2) / (2 * d)
    b = a + (along * (o - a) + np.sqrt(COUPLER**2 - along**2) * np.array([a[1] - o[1], o[0] - a[0]])) / d
    u = (b - a) / COUPLER
    gsi, eta = 75.54175916040862, 28.168113585237116  # P in the coupler's frame (fourbar_np.PARAMS)
    p = a + gsi * u + eta * np.array([-u[1], u[0]])
    text = FOURBAR.read_text(encoding="utf-8").replace("O2: [90, 0]", f"O2: [{float(o[0])!r}, {float(o[1])!r}]")
    text = text.replace("B: [80, 50]", f"B: [{float(b[0])!r}, {float(b[1])!r}]")
    path.write_text(text.replace("P: [60, 70]", f"P: [{float(p[0])!r}, {float(p[1])!r}]"), encoding="utf-8")
    return path


def test_sketch_coordinates_and_a_length_broadcast_as_the_scalar_program_computes_them(tmp_path: Path):
    """O2's place and the rocker's length as arrays of five designs against 36 rows in one call:
    each design's rows are bit for bit the call with that design's numbers alone, and its points
    what the standard-library fourbar.py of the four-bar drawn so computes, one row at a time, to
    the rounding of its sketch's numbers (its angles keep their own sketch's offsets)."""
    module = kernel(build_log(str(FOURBAR)), 2)
    o2x, o2y = O2[0] + np.linspace(-3.0, 3.0, 5), O2[1] + np.linspace(2.0, -2.0, 5)
    rocker = ROCKER + np.linspace(-1.0, 1.0, 5)
    theta = _theta()[::10]
    out = module.solve(theta[:, None], [2 * np.pi], [0.0],
                       params={"O2.x": o2x[:, None], "O2.y": o2y[:, None], "l_rocker": rocker[:, None]})
    assert out["B.x"].shape == out["status"].shape == (5, len(theta)) and (out["status"] == 0).all()
    points = [c for c in out if c.split(".")[0] in ("A", "B", "P")]
    for d in range(5):
        alone = module.solve(theta[:, None], [2 * np.pi], [0.0],
                             params={"O2.x": o2x[d], "O2.y": o2y[d], "l_rocker": rocker[d]})
        for name in alone:
            assert np.array_equal(out[name][d] if name != "sigma" else out[name][:, d], alone[name]), (d, name)
        log = build_log(str(_fourbar_moved((o2x[d], o2y[d]), rocker[d], tmp_path / f"fourbar_{d}.yaml")), sweep=False)
        scalar = ModuleType(f"fourbar_{d}")
        exec(compile(source(PYTHON, log, 2), f"fourbar_{d}.py", "exec"), scalar.__dict__)
        rows = [scalar.solve([float(t)], [2 * np.pi], [0.0]) for t in theta]
        assert [r["status"] for r in rows] == out["status"][d].tolist()
        for name in points:
            want = np.array([r[name] for r in rows])
            assert np.max(np.abs(out[name][d] - want)) <= 1e-11 * max(np.max(np.abs(want)), 1.0), (d, name)


# -- calls it cannot answer ----------------------------------------------------

def test_a_row_the_kernel_cannot_answer_is_refused_and_the_others_are_solved():
    log = build_log(str(FOURBAR))
    module = kernel(log, 2)
    values, rates, accs = input_rows(log, 7)
    values[2, 0], rates[4, 0], accs[5, 0] = math.nan, 1e31, -math.inf
    out = module.solve(values, rates, accs)
    good = evaluate(log, *input_rows(log, 7))
    refused = np.isin(np.arange(7), (2, 4, 5))
    assert (out["status"][refused] == 5).all() and np.isnan(out["sigma"][:, refused]).all()
    assert all(np.isnan(out[c.name][refused]).all() for c in log.columns[1:])
    assert np.array_equal(out["status"][~refused], good.status[~refused])
    assert np.array_equal(out["B.x"][~refused], good.values["p_B"][0][~refused] + log.origin[0])
    with pytest.raises(ValueError, match="last axis of inputs must hold the 1 inputs"):
        module.solve(np.zeros((3, 2)), [1.0], [0.0])
    with pytest.raises(ValueError, match="'crank' is not a design parameter"):
        module.solve(values, rates, accs, params={"crank": 3.0})
    assert set(module.solve(values, rates, accs, order=0)) == {
        c.name for c in log.columns[1:] if c.quantity in ("position", "angle")} | {"status", "sigma"}


def test_one_row_and_no_rows_are_calls_like_the_others():
    """A call of one row (every array of the call a number) keeps its conditioning and its
    values as the same row of a sweep has them; a call of no rows gives empty arrays."""
    log = build_log(str(FOURBAR))
    module = kernel(log, 2)
    values, rates, accs = input_rows(log, 7)
    sweep = module.solve(values, rates, accs)
    one = module.solve(values[3], rates[3], accs[3])
    assert one["status"].shape == () and one["sigma"].shape == (log.steps[-1].number + 1,)
    assert np.array_equal(one["sigma"], sweep["sigma"][:, 3]) and (one["sigma"][3] < 1.0)
    for c in log.columns[1:]:
        assert np.array_equal(one[c.name], sweep[c.name][3]), c.name
    none = module.solve(values[:0], rates[:0], accs[:0])
    assert none["B.x"].shape == none["status"].shape == (0,) and none["sigma"].shape[1:] == (0,)


def test_a_call_fills_the_arrays_of_an_earlier_one():
    log = build_log(str(FOURBAR))
    module = kernel(log, 2)
    values, rates, accs = input_rows(log, 11)
    bad = values.copy()
    bad[4, 0] = math.nan
    last = module.solve(bad, rates, accs)
    again = module.solve(values, rates, accs, out=last)
    fresh = module.solve(values, rates, accs)
    assert all(np.shares_memory(again[k], last[k]) for k in fresh)
    for k in fresh:
        assert np.array_equal(again[k], fresh[k], equal_nan=True), k
    with pytest.raises(ValueError, match=r"out has no float64 array of shape \(10,\) for 'O1.x'"):
        module.solve(values[:10], rates[:10], accs[:10], out=last)


def test_the_kernels_branch_and_reach_are_the_python_runtimes_on_every_row():
    """branch_at and reach_at on arrays (the kernel's runtime) against the Python runtime's, one value
    at a time, on values around change points and gaps, turns away included."""
    from linkgen.kernel import runtime as numpy_runtime
    from linkgen.rowsolver import runtime as python_runtime

    scalar, vector = python_runtime(), numpy_runtime()
    rng = np.random.default_rng(19)
    theta = np.concatenate([rng.uniform(-20, 20, 2000), [-np.pi, 0.0, np.pi, 0.5, 1.25, 2 * np.pi + 0.5]])
    for points, periodic in (((0.5,), True), ((0.5, 1.25), True), ((0.5, 1.25), False), ((), True)):
        for b0, theta0 in ((1, 0.0), (-1, 3.0)):
            got = np.broadcast_to(vector["branch_at"](theta, b0, theta0, points, periodic), theta.shape)
            assert got.tolist() == [scalar["branch_at"](float(t), b0, theta0, points, periodic) for t in theta]
    for low, high, periodic in ((0.5, 1.25, True), (-1.0, 2.0, False), (math.nan, 2.0, False), (-1.0, math.nan, False)):
        got = vector["reach_at"](theta, low, high, periodic)
        assert got.tolist() == [scalar["reach_at"](float(t), low, high, periodic) for t in theta]
