"""The loop strategy (options: strategy loop, issue 20): the literature's fixed-point iteration on one
assumed angle of a class-III group, in every program language.

Checked against independent routes: the 50-digit reference (tests/reference.py) over the sample's sweep,
C = Python = Octave bit for bit, and the contraction check on a loop built to have |g'| > 1 (the
reverse loop then contracts, its slope the reciprocal)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from programs import compare, different_bits, parse, run_c, run_numpy, run_octave, run_python
from reference import Reference

from linkgen import loopmap
from linkgen.assemblies import assemblies, whole_log
from linkgen.cli import cli
from linkgen.evaluate import evaluate
from linkgen.pipeline import build_log
from linkgen.render import render_all
from linkgen.rowsolver import RowSolver, runtime
from linkgen.writer import write_all

ROOT = Path(__file__).resolve().parents[1]
FIG14 = ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"
TRIADS = ROOT / "samples" / "double_triad" / "double_triad.yaml"


def _built(path: Path, outdir: Path, **options: object):
    log = build_log(str(path), options={"strategy": "loop", **options}, sweep=False)
    write_all(render_all(log), str(outdir))
    return log


def _against_reference(path: Path, log, text: str, every: int) -> float:
    """The worst distance of the program's pairs from the 50-digit reference (started from each row)."""
    ref = Reference(str(path))
    names, data, statuses = parse(text)
    assert statuses == [0] * log.samples
    worst = 0.0
    for r in range(0, log.samples, every):
        row = dict(zip(names, data[r]))
        want = ref.solve(data[r][:1], [ref.m.inputs[0].speed], ref.guess(row)).columns
        for name, x in row.items():
            if name in want and name.endswith((".x", ".y")):
                worst = max(worst, abs(x - float(want[name])) / log.length_scale)
    return worst


def test_the_step_log_has_a_forward_and_a_reverse_loop_per_class_three_group(tmp_path):
    log = _built(FIG14, tmp_path)
    (g,) = log.groups
    loops = [b for b in g.variants if log.variable(b.add_links[0]).role == "loop"]
    assert len(loops) == 2 and log.policy.max_iterations == 60
    functions = [[log.step(n).function for n in b.steps] for b in loops]
    assert functions == [["loop_point", "RRR_links", "RRR_links", "RRR_links", "loop_turn",
                          "loop_residual"]] * 2
    # the forward loop places the body's pairs one way round, the reverse the other, X1 again last
    forward, reverse = ([log.step(n).target for n in b.steps[1:4]] for b in loops)
    assert forward[2] == reverse[2] == log.step(loops[0].steps[0]).target and forward[:2] == reverse[1::-1]
    assert "strategy loop" in log.step(g.step).reason
    assert "resolver loop" in (tmp_path / "sixbar_fig14.py").read_text().splitlines()[0]


@pytest.mark.parametrize("path", [FIG14, pytest.param(TRIADS, marks=pytest.mark.long)], ids=lambda p: p.stem)
def test_python_agrees_with_the_50_digit_reference(tmp_path, path):
    log = _built(path, tmp_path)
    assert _against_reference(path, log, run_python(log, tmp_path), 15) <= 1e-9


@pytest.mark.long
@pytest.mark.parametrize("path", [FIG14, TRIADS], ids=lambda p: p.stem)
def test_every_language_is_the_same_bits_and_the_reference(tmp_path, path):
    log = _built(path, tmp_path)
    py = run_python(log, tmp_path)
    assert different_bits(py, run_c(log, tmp_path)) == []
    assert different_bits(py, run_octave(log, tmp_path)) == []
    assert different_bits(py, run_numpy(log, tmp_path)) == []  # the kernel solves such rows through NAME.py
    assert _against_reference(path, log, py, 1) <= 1e-9
    newton = build_log(str(path), sweep=False)
    write_all(render_all(newton), str(tmp_path / "newton"))
    compare(log, py, run_python(newton, tmp_path / "newton"))


def _loop(g_slope: float):
    """A loop block whose map is the line theta' = theta* + g (theta - theta*) (the group function's
    residual f = l (theta' - theta) as the runtime reads it, with its rate for the Jacobian)."""
    arm, star = 2.0, 0.3

    def group(a, da, dda, live):
        theta = a[0] / arm
        back = star + g_slope * (theta - star)
        return 0, [(arm * (back - theta), (g_slope - 1) * da[0], 0.0)]
    return group, arm * star


@pytest.mark.parametrize("slope", [0.5, -0.8, 1.5, -2.0])
def test_the_contraction_check_fires_where_the_loop_does_not_contract(slope):
    loop_iteration = runtime()["loop_iteration"]
    group, fixed = _loop(slope)
    ok, a, its, jac = loop_iteration(group, [fixed + 0.1], 1e-12, 200, 1.0, 1)
    if abs(slope) < 1:
        assert ok == 1 and abs(a[0] - fixed) <= 1e-11 and abs(1 + jac[0][0] - slope) <= 1e-12
    else:  # the check fires; the reverse loop (the inverse map, slope 1/g) contracts
        assert ok == -1 and its == 1
        inverse, fixed = _loop(1 / slope)
        ok, a, its, jac = loop_iteration(inverse, [fixed + 0.1], 1e-12, 200, 1.0, 1)
        assert ok == 1 and abs(a[0] - fixed) <= 1e-11


@pytest.mark.parametrize(("path", "at"), [(FIG14, 90.0)] + [pytest.param(p, at, marks=pytest.mark.long) for p, at in
                                                      [(FIG14, 30.0), (FIG14, 250.0), (TRIADS, 90.0), (TRIADS, 30.0),
                                                       (TRIADS, 250.0)]], ids=str)
def test_the_fixed_points_per_branch_combination_are_the_certified_assemblies(path, at):
    """Over the 2^3 branch combinations of each group's loop, the fixed points (mirror images of the body
    left out) are the group's assemblies linkgen assemblies counts, to 1e-9 of the length scale; the group's
    assemblies combine across groups (the census counts their product)."""
    log = build_log(str(path), order=0, sweep=False, options={"strategy": "loop"})
    found = [loopmap.fixed_points(loop) for loop in loopmap.loops(log, [math.radians(at)])]
    census = assemblies(str(path), whole_log(str(path)), [at])
    assert math.prod(len(points) for points in found) == len(census.assemblies)
    for points in found:
        names = sorted(points[0].pairs)
        want = {tuple(round(a.values[f"{n}.{c}"] / log.length_scale, 9) for n in names for c in "xy")
                for a in census.assemblies}
        got = {tuple(round(p.pairs[n][i] / log.length_scale, 9) for n in names for i in (0, 1)) for p in points}
        assert got == want
        assert all(abs(p.slope) != 1 for p in points)  # one of the two loops contracts at each


def test_the_sweep_turns_to_the_reverse_loop_where_the_forward_one_stops_contracting():
    """Fig. 14's forward loop contracts at the sketch (|g'| 0.49) and not everywhere: over the sweep the check
    fires and the reverse loop solves rows (on every row the fixed point is the 50-digit reference's:
    test_python_agrees_with_the_50_digit_reference)."""
    log = build_log(str(FIG14), sweep=False, options={"strategy": "loop"})
    forward, reverse = (b.variant for b in log.groups[0].variants[-2:])
    values = np.radians(np.arange(0.0, 361.0, 5.0))[:, None]
    result = evaluate(log, values, np.ones_like(values), np.zeros_like(values))
    used = [w[4][0] for w in result.warm]
    assert forward in used and reverse in used
    assert all(code == 0 for code in result.status)


def _beside_newton(path: Path) -> tuple[list[int], list[int], float]:
    """The loop's and Newton's failing rows over 121 rows of the sweep, and the loop's worst pair distance from
    Newton's on the rows both solve (over the length scale)."""
    loop, newton = (build_log(str(path), sweep=False, options=o) for o in ({"strategy": "loop"}, {}))
    values = np.linspace(loop.inputs[0].start, loop.inputs[0].stop, 121)[:, None]
    a, b = (evaluate(log, values, np.ones_like(values), np.zeros_like(values)) for log in (loop, newton))
    both = (a.status <= 0) & (b.status <= 0)
    worst = max(float(np.max(np.abs(a.values[v.name][k] - b.values[v.name][k])[both]))
                for v in newton.variables if v.role == "pair" and not v.constant for k in (0, 1))
    return [i for i, c in enumerate(a.status) if c > 0], [i for i, c in enumerate(b.status) if c > 0], \
        worst / loop.length_scale


TRIAD_FILES = sorted((ROOT / "tests" / "mechanisms").glob("triad_*.yaml"))


@pytest.mark.parametrize("path", [pytest.param(p, marks=[] if p.stem == "triad_sharp_turn" else [pytest.mark.long])
                                  for p in TRIAD_FILES], ids=lambda p: p.stem)
def test_the_loop_solves_the_rows_newton_solves_and_the_same_assembly(path):
    """Every triad test mechanism: the loop strategy fails exactly Newton's rows (past a reach, ...) and
    lands on Newton's assembly within its tolerance; triad_sharp_turn's assumed leg passes its sketch
    angle's zero, where an arc length must not be reflected as an Add-link length is."""
    loop_fails, newton_fails, worst = _beside_newton(path)
    assert loop_fails == newton_fails and worst <= 1e-9


@pytest.mark.long
def test_assemblies_lists_the_loops_with_the_census():
    """`linkgen assemblies --loops --at 30`: the census, then one line per fixed point (as many as the census
    counts, the sketch's turn of the crank moved to 30 deg)."""
    result = CliRunner().invoke(cli, ["assemblies", str(FIG14), "--at", "30", "--loops"])
    assert result.exit_code == 0, result.output
    counted = int(result.output.split(": ", 1)[1].split(" assemblies")[0])
    lines = [line for line in result.output.splitlines() if line.startswith("  branches ")]
    assert len(lines) == counted == 4 and f"{counted} fixed points" in result.output
    assert all("|g'|" in line and "loop contracts" in line for line in lines)


@pytest.mark.long
def test_a_loop_refuses_the_bodys_mirror_image_where_it_would_contract():
    """Fig. 14 at the sketch's input: the body turned over is a fixed point of the loop 5 deg from the drawn pose
    (loopmap without its mirror filter: theta 94.99 deg, |g'| 4.36, so the reverse loop contracts to it at
    0.23 a step); started there the reverse block gives up (loop_turn), started at the drawn pose it solves."""
    log = build_log(str(FIG14), sweep=False, options={"strategy": "loop"})
    solver = RowSolver(log, 1)
    row = solver.solve([math.pi / 2], [1.0], [0.0])
    forward, reverse = log.groups[0].variants[-2:]
    (loop,) = loopmap.loops(log, [math.pi / 2])
    turned = loopmap.Loop(loop.group, loop.names, loop.ks, loop.legs, loop.sides, -loop.turn)
    (mirror,) = [p for p in loopmap.fixed_points(turned) if abs(math.degrees(p.theta) - 95) < 1]
    assert abs(1 / mirror.slope) < 1  # the reverse loop contracts to the mirror image
    arm, rt = loop.legs[0], runtime()
    for block, start, solved in ((reverse, mirror.theta + 1e-3, 0), (forward, math.pi / 2 + 1e-3, 1)):
        group = solver._group(block, dict(row.env), dict(row.env), {}, [0.0])
        ok, a, _, _ = rt["loop_iteration"](group, [arm * start], 1e-10 * log.length_scale, 60,
                                           0.1 * log.length_scale, 1)
        assert ok == solved
    assert abs(a[0] - arm * math.pi / 2) < 1e-9 * log.length_scale
