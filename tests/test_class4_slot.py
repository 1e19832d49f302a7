"""A class-IV group with one prismatic pair (issue 20): tests/regressions/class4_slot.yaml, two
ternary links on their own pivots (left on O1, right on the crank tip O2) tied by the link upper
and a block on C in a slot of right.

Extraction used to refuse it ("an Add-link group is left open"): the Solver placed B by the 3R
chain O1-B-E, C followed as a point of left, and the one constraint left unused was C's slot, which
gives no residual (residuals are link lengths).  Extraction now tries such a mechanism again with
chains on a slide first inside the group: an Add-link, then the inverted slider-crank chain
(RPR_links) for the second ternary, upper's length the residual.  Its sweep, in every language
and in process, is the 50-digit reference (tests/reference.py) continued from the sketch.
"""

from __future__ import annotations

import csv as csvlib
import io
import math
from pathlib import Path

import pytest
from programs import compare, run_c, run_numpy, run_octave, run_python
from reference import Reference, wrap

from linkgen.evaluate import evaluate
from linkgen.pipeline import build_log
from linkgen.render import render_all
from linkgen.rows import input_rows
from linkgen.steplog import StepLog
from linkgen.table import csv
from linkgen.writer import write_all

ROOT = Path(__file__).resolve().parents[1]
SLOT = ROOT / "tests" / "regressions" / "class4_slot.yaml"


@pytest.fixture(scope="module")
def log() -> StepLog:
    return build_log(str(SLOT), sweep=False)


def _sweep(log: StepLog):
    values, rates, accs = input_rows(log, log.samples)
    return values, rates, evaluate(log, values, rates, accs)


def test_one_add_link_and_an_inverted_slider_crank_close_the_group(log):
    (group,) = log.groups
    assert len(group.add_links) == 1 and len(group.residuals) == 1
    block = [log.step(n) for n in group.steps]
    assert [s.function for s in block].count("RPR_links") == 1
    assert [s.target for s in block if s.function == "link_residual"] == ["upper"]
    assert group.variants  # the other usable candidates are fallback blocks


def test_every_row_solves(log):
    assert _sweep(log)[2].status.tolist() == [0] * log.samples


@pytest.mark.long  # four programs over the sweep: a few seconds
def test_every_language_gives_the_same_bits_and_the_evaluator(log, tmp_path):
    write_all(render_all(log), str(tmp_path))
    own = csv(log, _sweep(log)[2])
    c = run_c(log, tmp_path)
    assert [int(r.rsplit(",", 1)[1]) for r in c.splitlines()[1:]] == [0] * log.samples
    assert run_python(log, tmp_path) == c
    assert run_octave(log, tmp_path) == c
    compare(log, c, own)
    compare(log, run_numpy(log, tmp_path), own)


ORDER = {"x": 0, "y": 0, "s": 0, "phi": 0, "vx": 1, "vy": 1, "ds": 1, "omega": 1, "ax": 2, "ay": 2, "dds": 2,
         "alpha": 2}  # the time derivative a CSV column holds
TOL = 1e-12  # times the length scale (1 for angles) and the input speed to the column's order
ANGULAR = ("phi", "omega", "alpha")


@pytest.mark.long  # the reference's continuation over the turn: about ten seconds
def test_the_sweep_is_the_reference(log):
    """Every row's positions, angles, slides and their first and second derivatives are the 50-digit
    reference continued from the sketch in steps of at most 1 degree (the way the sweep goes: to its
    first row the shorter way, then row by row); measured: 1e-13 L for positions, 2e-12 L w^2 for
    accelerations."""
    values, rates, result = _sweep(log)
    rows = list(csvlib.DictReader(io.StringIO(csv(log, result))))
    ref = Reference(str(SLOT))
    u, q = ref.sketch_inputs()[0], ref.sketch_pose()
    first = float(values[0][0])
    turn = 2 * math.pi * math.floor((first - u) / (2 * math.pi) + 0.5)  # the sweep's value less the walk's
    checked = set()
    for k, row in enumerate(rows):
        target = float(values[k][0]) - turn
        steps = max(1, math.ceil(abs(target - u) / math.radians(1)))
        for j in range(1, steps + 1):
            q = ref.newton(q, ref.turned_inputs(q, [u + (target - u) * j / steps]), exact=False)[0]
        u = target
        speed = abs(float(rates[k][0]))
        for name, x in ref.solve([target], [float(rates[k][0])], q).columns.items():
            what = name.rsplit(".", 1)[-1]
            if name not in row or what not in ORDER:
                continue
            diff = float(row[name]) - float(x)
            if what == "phi":
                diff = float(wrap(diff))
            scale = (1.0 if what in ANGULAR else log.length_scale) * max(speed, 1.0) ** ORDER[what]
            assert abs(diff) <= TOL * scale, (k, name, row[name], float(x))
            checked.add(what)
    assert checked == set(ORDER)
