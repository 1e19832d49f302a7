"""The reach of resolver mechanisms, the cost of rows past it, and builds that end.

A resolver mechanism with one input gets the reach a closed-form one has: the limit
positions nearest the sketch, found when building by following the sketch's assembly.
They agree with the folds of tests/reference.py's 50-digit constraint model (Newton on
the constraints and a vanishing Jacobian determinant).  Rows past them fail at once with
the resolve step's reason 1 in the evaluator and in every language: one pass of the
procedure, no Newton step.  Builds end for any range the format allows.
"""

from __future__ import annotations

import math
import subprocess
import sys
from types import SimpleNamespace

import numpy as np
import pytest
import sketches as sk
from programs import CFLAGS, ROOT, SAMPLES, build, need
from reference import MP, Reference

from linkgen.evaluate import evaluate
from linkgen.pipeline import build_log
from linkgen.policy import POLICY
from linkgen.rows import input_rows
from linkgen.rowsolver import RowSolver, runtime

MECHANISMS = SAMPLES + sorted((ROOT / "tests" / "mechanisms").glob("*.yaml"))
PARTIAL = ROOT / "tests" / "mechanisms" / "sixbar_partial.yaml"  # a crank that meets two limit positions
# its resolve step is 8 (frame, input, Add-link, two chains, link_point, residual, resolve): reason 1 there is 81


def _fold(ref: Reference, q: list, value: float) -> float:
    """The input value of the limit position next to the pose q at ``value``: Newton at 50
    digits on the constraints together with det(dC/dq) = 0 (a fold of the input), the
    derivatives by differences of 1e-30."""
    x = [MP.mpf(v) for v in q] + [MP.mpf(value)]
    h = MP.mpf(10) ** -30

    def residual(x: list) -> list:
        q, u = x[:-1], [x[-1]]
        return ref.constraints(q, u) + [MP.det(MP.matrix(ref.jacobian(q, u)))]

    for _ in range(20):
        now = residual(x)
        columns = []
        for k in range(len(x)):
            moved = list(x)
            moved[k] += h
            columns.append([(a - b) / h for a, b in zip(residual(moved), now)])
        dx = MP.lu_solve(MP.matrix(columns).T, -MP.matrix(now))
        x = [a + b for a, b in zip(x, dx)]
        if abs(dx[len(x) - 1]) < MP.mpf(10) ** -30:
            return float(x[-1])
    raise ArithmeticError("Newton on the fold did not converge")


def test_resolver_reach_is_at_the_reference_limit_positions():
    """Both ends of sixbar_partial's reach are the folds of the reference model (found from a
    pose the reference walks to, a thousandth of a radian inside each end), to 1e-10."""
    log = build_log(str(PARTIAL), sweep=False)
    reach, ref = log.reach, Reference(str(PARTIAL))
    assert reach is not None and reach.periodic and (reach.low_step, reach.high_step) == (8, 8)
    start = ref.sketch_inputs()[0]
    for bound, inward in ((reach.high, -1.0), (reach.low, 1.0)):
        near = bound + inward * 1e-3
        q = sk.walk(ref, ref.sketch_pose(), start, near)
        assert q is not None, f"the reference does not reach {near} from the sketch"
        assert bound == pytest.approx(_fold(ref, q, near), abs=1e-10)


def test_rows_past_the_reach_take_one_pass_and_no_newton_step(monkeypatch):
    """In the evaluator every row of sixbar_partial's sweep that fails (past a limit position)
    fails with 81 after one pass of the procedure, which stops at the reach check (before, each
    took a continuation of dozens of passes from the sketch and reported 92)."""
    log = build_log(str(PARTIAL), sweep=False)
    passes = []
    run = RowSolver.run

    def counted(self, *args):
        passes[-1] += 1
        return run(self, *args)

    monkeypatch.setattr(RowSolver, "run", counted)
    solver = RowSolver(log, log.order)
    values, rates, accs = input_rows(log, log.samples)
    status, newton = [], []
    for k in range(log.samples):
        passes.append(0)
        out = solver.solve(values[k], rates[k], accs[k])
        status.append(max((10 * n + st for n, (st, _) in out.report.items() if st in (1, 2)), default=0))
        newton.append(sum(out.iterations.values()))
    failed = [k for k, st in enumerate(status) if st]
    assert len(failed) > log.samples // 3 and {status[k] for k in failed} == {81}
    assert all(passes[k] == 1 and newton[k] == 0 for k in failed), [(k, passes[k], newton[k]) for k in failed]
    assert any(code.code == 81 and "limit position" in code.meaning for code in log.status_codes)


C_DRIVER = r"""
#include <stdio.h>
#include "sixbar_partial.h"

int main(void)
{
    static const double values[] = { @VALUES@ };
    sixbar_partial_state st;
    double in[1], din[1] = {1.0}, ddin[1] = {0.0};
    unsigned k;
    sixbar_partial_init(&st);
    for (k = 0; k < sizeof values / sizeof values[0]; k++) {
        in[0] = values[k];
        sixbar_partial_solve(in, din, ddin, &st);
        printf("%d %d\n", st.status, st.iterations[0]);
    }
    return 0;
}
"""

PY_DRIVER = r"""
import sys
sys.path.insert(0, ".")
import sixbar_partial as m
state = {}
for value in [@VALUES@]:
    out = m.solve([value], [1.0], [0.0], 2, state)
    print(out["status"], out["iterations"][0])
"""

M_DRIVER = r"""
warm = [];
for value = [@VALUES@]
    [out, status, warm] = sixbar_partial_solve(value, 1, 0, warm);
    fprintf('%d %d\n', status, out.iterations(1));
end
"""


def test_rows_past_the_reach_fail_at_once_in_every_language(tmp_path):
    """The programs check the reach before the resolver: rows past sixbar_partial's limit
    positions give 81 with no Newton step, in C, Python and Octave, rows inside are solved,
    whatever the row before (inside or past, from a warm start or not)."""
    log = build(PARTIAL, tmp_path)
    low, high = log.reach.low, log.reach.high
    values = [0.0, 1.0, 2.0, high - 1e-6, high + 1e-6, low + 2 * math.pi - 1e-6, 3.5, -2.0, 1.5, 0.01]
    past = [not (low < v < high or low < v - 2 * math.pi < high) for v in values]
    text = ", ".join(repr(v) for v in values)
    (tmp_path / "driver.c").write_text(C_DRIVER.replace("@VALUES@", text))
    subprocess.run([need("gcc"), *CFLAGS, "sixbar_partial.c", "driver.c", "-lm", "-o", "driver"], cwd=tmp_path,
                   check=True, capture_output=True)
    outputs = {"C": subprocess.run(["./driver"], cwd=tmp_path, check=True, capture_output=True, text=True).stdout,
               "Python": subprocess.run([sys.executable, "-I", "-c", PY_DRIVER.replace("@VALUES@", text)],
                                        cwd=tmp_path, check=True, capture_output=True, text=True).stdout}
    (tmp_path / "driver_m.m").write_text(M_DRIVER.replace("@VALUES@", text))
    done = subprocess.run([need("octave-cli"), "--no-gui", "--no-init-file", "--quiet", "driver_m.m"], cwd=tmp_path,
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    outputs["Octave"] = done.stdout
    for lang, text in outputs.items():
        rows = [tuple(int(x) for x in line.split()) for line in text.splitlines()]
        assert [st for st, _ in rows] == [81 if p else 0 for p in past], (lang, rows)
        assert all((its == 0) == p for (_, its), p in zip(rows, past)), (lang, rows)


def test_every_status_of_a_sweep_is_in_the_manual():
    """Each code a sample's or test mechanism's sweep reports is explained in its status-code
    table (81 of a resolver's limit position included)."""
    missing = []
    for path in MECHANISMS:
        log = build_log(str(path), sweep=False)
        known = {c.code for c in log.status_codes}
        codes = set(evaluate(log, *input_rows(log, log.samples)).status.tolist()) - {0}
        missing += [(path.stem, code) for code in sorted(codes - known)]
    assert not missing


def test_walk_gives_up_after_its_passes():
    """The continuation's walk stops after the policy's walk_passes passes, and at once where its
    path needs more steps than that (a sliding input 1e30 away): a build sweeping a huge range ends."""
    calls = []

    def run(inputs, rates, order, a):
        calls.append(inputs[0])
        return True, a, [[0.0, 0.0]]

    limit, passes = 0.05, POLICY.walk_passes
    mechanism = SimpleNamespace(length_scale=1.0, limits=[limit], sizes=[1], loops=[0])
    for steps, reached, count in ((512, True, 513), (passes, False, passes), (1e30, False, 0)):
        calls.clear()
        out = runtime()["walk"](run, [0.0], [[1.0, 0.0]], [steps * limit], mechanism, POLICY)
        assert (out is not None, len(calls)) == (reached, count)


HUGE = [("fourbar", "samples/fourbar/fourbar.yaml", "[0, 360]", "[0, 1e12]"),
        ("sixbar_partial", "tests/mechanisms/sixbar_partial.yaml", "[0, 360]", "[0, 1e12]"),
        ("actuator", "samples/actuator/actuator.yaml", "[1300, 2050]", "[0, 1e30]")]


@pytest.mark.parametrize(("name", "path", "drawn", "huge"), HUGE, ids=[h[0] for h in HUGE])
def test_build_of_a_huge_range_ends(tmp_path, name, path, drawn, huge):
    """A range of 1e12 degrees (the nearest turn of the sketch was a loop over every turn in
    it) or of 1e30 mm builds, and its programs' sweeps, in a subprocess with a generous limit."""
    text = (ROOT / path).read_text()
    assert text.count(f"range: {drawn}") == 1
    mechanism = tmp_path / f"{name}.yaml"
    mechanism.write_text(text.replace(f"range: {drawn}", f"range: {huge}"))
    done = subprocess.run([sys.executable, "-m", "linkgen", "build", str(mechanism), "-o", str(tmp_path / "out")],
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "out" / f"{name}.c").exists()


def test_sketch_angle_of_a_huge_range_is_its_first_turn(tmp_path):
    """The slider-crank's crank drawn at atan2(3, 4) with a range 2.8e9 turns wide starts at the
    turn of that angle inside the range nearest its start: atan2(3, 4) itself for [0, 1e12]
    degrees, within a turn above -1e12 degrees for [-1e12, 0] (to the rounding of 1.7e10)."""
    sample = ROOT / "samples/slider_crank/slider_crank.yaml"
    path = tmp_path / "slider_crank.yaml"
    drawn = math.atan2(3, 4)
    path.write_text(sample.read_text().replace("range: [0, 360]", "range: [0, 1e12]"))
    assert build_log(str(path), sweep=False).inputs[0].sketch == drawn
    path.write_text(sample.read_text().replace("range: [0, 360]", "range: [-1e12, 0]"))
    sketch, start = build_log(str(path), sweep=False).inputs[0].sketch, math.radians(-1e12)
    assert start <= sketch < start + 2 * math.pi
    assert abs(math.remainder(sketch - drawn, 2 * math.pi)) <= 1e-5


def test_reach_of_a_sliding_resolver_input_is_a_limit_position(tmp_path):
    """tests/mechanisms/cylinder_triad.yaml, a triad driven by a cylinder (a sliding input and an
    Add-link): the cylinder's shortest length it reaches from the sketch is a fold of the
    reference model, to 1e-10 of its size, and a build of its range set to [0, 1e30] mm ends."""
    path = ROOT / "tests" / "mechanisms" / "cylinder_triad.yaml"
    log = build_log(str(path), sweep=False)
    assert log.reach is not None and log.reach.high is None and not log.reach.periodic
    ref = Reference(str(path))
    near = log.reach.low + 1e-3 * log.length_scale
    q = _slide_walk(ref, ref.sketch_pose(), ref.sketch_inputs()[0], near)
    assert log.reach.low == pytest.approx(_fold(ref, q, near), abs=1e-10 * log.length_scale)
    huge = tmp_path / "cylinder_triad.yaml"
    huge.write_text(path.read_text().replace("range: [10, 100]", "range: [0, 1e30]"))
    done = subprocess.run([sys.executable, "-m", "linkgen", "build", str(huge), "-o", str(tmp_path / "out")],
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr


def _slide_walk(ref: Reference, q: list, start: float, stop: float, steps: int = 200) -> list:
    """The reference's pose at a sliding input's value stop, followed from start in float Newton steps."""
    for value in np.linspace(start, stop, steps + 1)[1:]:
        q, _, _ = ref.newton(q, [float(value)], exact=False)
    return q
