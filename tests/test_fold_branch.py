"""A chain inside a resolver group that passes its fold goes on on its other branch, as a chain
outside the groups does at a change point.

tests/mechanisms/quaternary_fold.yaml with its chosen block alone (no fallback block: what a group
of two Add-links had before combinations were ranked): its chain of step 10 (A1 from G1 by leg1
and from A2 by left) passes its fold between 225 and 270 degrees, where leg1 and left come in line
and the chain's branch flips while the mechanism moves on smoothly.  The block's state held the
branch as a sign, so every row from there on the far side failed with status 152 (rows 45-54 of
73, measured before the change, in every language) while the 50-digit reference assembles there.
The state now holds the measure whose sign is the branch, with its rate: the predictor moves it
and the branch flips where it passes zero.
"""

from __future__ import annotations

import csv as csvlib
import io
import math
from dataclasses import replace
from pathlib import Path

import pytest
from programs import compare, run_c, run_numpy, run_octave, run_python
from reference import Reference, walked

from linkgen import status
from linkgen.evaluate import evaluate
from linkgen.pipeline import build_log
from linkgen.render import render_all
from linkgen.rows import input_rows
from linkgen.steplog import StepLog
from linkgen.table import csv
from linkgen.writer import write_all

ROOT = Path(__file__).resolve().parents[1]
QUAD = ROOT / "tests" / "mechanisms" / "quaternary_fold.yaml"
FOLDING = 10  # the step whose chain passes its fold
FAILED = range(45, 55)  # the rows that failed with status 152 before (measured)


def chosen_block_only(log: StepLog) -> StepLog:
    """The log whose groups keep their chosen block only (no fallback block, no conditioning
    table: the table names the fallbacks' steps)."""
    return replace(log, groups=tuple(replace(g, variants=()) for g in log.groups), conditioning=(),
                   steps=tuple(s for s in log.steps if not s.variant))


@pytest.fixture(scope="module")
def log() -> StepLog:
    return chosen_block_only(build_log(str(QUAD), sweep=False))


def _sweep(log: StepLog):
    values, rates, accs = input_rows(log, log.samples)
    return values, rates, evaluate(log, values, rates, accs)


def test_the_chain_passes_its_fold_and_every_row_solves(log):
    (group,) = log.groups
    at = len(group.add_links) + [b.step for b in group.branches].index(FOLDING)
    _, _, result = _sweep(log)
    assert not any(status.failed(int(s)) for s in result.status)
    signs = [1 if w[2][0][at] > 0 else -1 for w in result.warm]
    assert signs[0] == log.step(FOLDING).branch  # the sketch's branch at the first row
    flips = [k for k in range(1, len(signs)) if signs[k] != signs[k - 1]]
    assert flips and flips[0] in FAILED, flips  # the chain passes its fold where the rows failed
    least = min(float(s) for k, s in enumerate(result.sigma[FOLDING]) if k in FAILED)
    assert least < 0.01  # its links come in line there


@pytest.mark.long  # four programs over the sweep: about 10 s
def test_every_language_follows_it(log, tmp_path):
    write_all(render_all(log), str(tmp_path))
    own = csv(log, _sweep(log)[2])
    c = run_c(log, tmp_path)
    assert [int(r.rsplit(",", 1)[1]) for r in c.splitlines()[1:]] == [0] * log.samples
    assert run_python(log, tmp_path) == c
    assert run_octave(log, tmp_path) == c
    compare(log, c, own)
    compare(log, run_numpy(log, tmp_path), own)


@pytest.mark.long  # the reference's continuation over the turn takes about twenty seconds
def test_the_followed_assembly_is_the_reference(log):
    """Every row, the stretch past the fold too, is the 50-digit reference continued from the
    sketch in steps of at most 1 degree (the way the sweep goes: to its first row the shorter
    way, then row by row)."""
    values, rates, result = _sweep(log)
    rows = list(csvlib.DictReader(io.StringIO(csv(log, result))))
    ref = Reference(str(QUAD))
    u, q = ref.sketch_inputs()[0], ref.sketch_pose()
    first = float(values[0][0])
    turn = 2 * math.pi * math.floor((first - u) / (2 * math.pi) + 0.5)  # the sweep's value less the walk's
    for k, row in enumerate(rows):
        target = float(values[k][0]) - turn
        q, u = walked(ref, q, u, target), target
        want = ref.solve([target], [float(rates[k][0])], q).columns
        for name, x in want.items():
            if name.endswith((".x", ".y")):
                assert abs(float(row[name]) - float(x)) <= 1e-9 * log.length_scale, (k, name, row[name], float(x))
