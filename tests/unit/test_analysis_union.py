"""analysis.union and the zooms taken together: the same as each chain's own procedure, each zoom alone."""

from __future__ import annotations

import math
from functools import partial
from pathlib import Path

import numpy as np
import pytest
from linkages import four_bar

from linkgen import status
from linkgen.analysis import sweep
from linkgen.analysis.change_points import change_points
from linkgen.analysis.sweep import Zoom, closes, local_minima, margin, own, run, spanning, zoom_min, zoom_mins
from linkgen.analysis.union import Readers, Union
from linkgen.pipeline import analyse_file, draft

ROOT = Path(__file__).resolve().parents[2]

# Two parallelograms: O1-A-B-O2 (the crank 20 at 45 degrees, the ground 60 along x), and O2-E-F-O4
# on its rocker (E midway along O2-B, O4 50 above O2).  The rocker turns with the crank while the
# first chain (B) flips at its change points, 0 and pi; the second chain (F) has its pivots E, O4
# in line with the rocker at +-90 degrees.
TWO_PARALLELOGRAMS = """\
linkgen: 1
name: two_parallelograms
units: {length: mm, angle: rad}
joints:
  O1: [0, 0]
  A: [14.142135623730951, 14.142135623730951]
  B: [74.14213562373095, 14.142135623730951]
  O2: [60, 0]
  E: [67.07106781186548, 7.0710678118654755]
  F: [67.07106781186548, 57.071067811865476]
  O4: [60, 50]
links:
  frame: {joints: [O1, O2, O4], fixed: true}
  crank: [O1, A]
  coupler: [A, B]
  rocker: [O2, B, E]
  link: [E, F]
  rocker2: [O4, F]
inputs:
  - {joint: O1, link: crank, relative_to: frame, range: [0, 1]}
"""

# A crank carrying two dyads that do not read from each other: the first (B) fails over a stretch
# of the turn where the second (C) still closes.
TWIN = """\
linkgen: 1
name: twin
units: {length: mm, angle: rad}
joints:
  O1: [-35.233447033367526, -69.83016521509961]
  A: [30.186894607970743, -85.51274266649145]
  B: [7.176400861337839, -26.862216617482886]
  O2: [-88.40021504505864, 1.4871466378840523]
  C: [-92.50086831160303, -13.270863267522827]
  O3: [-86.02891528507621, -81.85739733122699]
links:
  frame: {joints: [O1, O2, O3], fixed: true}
  crank: [O1, A]
  c1: {joints: [A, B], points: {P: [-15.096162171497213, 65.37042493440762]}}
  r1: [O2, B]
  c2: [A, C]
  r2: [O3, C]
inputs:
  - {joint: O1, link: crank, relative_to: frame, range: [-1, 1]}
"""


def _draft(path: Path):
    _, topo, proc = analyse_file(str(path))
    return draft(topo, proc)


def _file(tmp_path: Path, name: str, text: str) -> Path:
    path = tmp_path / f"{name}.yaml"
    path.write_text(text, encoding="utf-8")
    return path


def test_a_chain_downstream_of_a_parallelogram_flips_with_it(tmp_path):
    """F's change point at -90 degrees lies past B's at 0 from the sketch (45 degrees): without B's
    flip there the first loop folds and its rocker no longer turns with the crank.  F is searched
    again once B's change points are found, and has both."""
    found = dict(change_points(_draft(_file(tmp_path, "two_parallelograms", TWO_PARALLELOGRAMS))))
    assert list(found) == [3, 5]
    assert found[3] == pytest.approx((0.0, math.pi), abs=1e-10)
    assert found[5] == pytest.approx((-math.pi / 2, math.pi / 2), abs=1e-10)


@pytest.mark.parametrize("sample", sorted(ROOT.glob("samples/*/*.yaml")), ids=lambda p: p.stem)
def test_which_steps_read_from_which_as_prune_keeps_them(sample):
    """A step's own procedure (prune.keep) holds the steps whose ``after`` holds the step, and a
    resolver group exactly where ``grouped`` says so."""
    log = _draft(sample)
    readers = Readers(log)
    plain = [s for s in log.steps if s.outputs and not s.group and not s.variant]
    for step in plain:
        procedure = own(log, step)
        assert readers.grouped(step) == bool(procedure.groups), step.number
        if not procedure.groups:
            mine = {s.number for s in procedure.steps if s.outputs}
            assert mine == {s.number for s in plain if step.number in readers.after(s.number)}, step.number


@pytest.mark.parametrize("name, text", [("twin", TWIN), ("two_parallelograms", TWO_PARALLELOGRAMS)])
def test_the_union_says_where_each_chain_closes_as_its_own_procedure(tmp_path, name, text):
    log = spanning(_draft(_file(tmp_path, name, text)))
    chains = [s for s in log.steps if s.function == "RRR_links"]
    grid = np.linspace(0.0, 1.0, 721)
    union = Union(log, chains, grid)
    for step in chains:
        alone = run(own(log, step), grid)
        for through in (step.number - 1, step.number):
            assert np.array_equal(union.closes(step, through), closes(alone, through))
        st = alone.status
        assert np.array_equal(union.fails_first(step), status.failed(st) & (status.step(st) == step.number))
        assert np.array_equal(margin(step, union.result), margin(step, alone), equal_nan=True)
    if name == "twin":  # rows the union fails first at B where C's own procedure closes
        st = union.result.status
        assert (status.failed(st) & (status.step(st) == 3) & closes(run(own(log, log.step(4)), grid), 4)).any()


@pytest.mark.parametrize("rows", [sweep.ROWS, 40])
def test_zooms_taken_together_find_what_each_finds_alone(tmp_path, monkeypatch, rows):
    """Each zoom refined in lockstep with the others, some sharing their grids, the positions
    evaluated in parts of at most ROWS: bit for bit what zoom_min finds for it."""
    monkeypatch.setattr(sweep, "ROWS", rows)
    log = spanning(_draft(_file(tmp_path, "two_parallelograms", TWO_PARALLELOGRAMS)))
    grid = np.linspace(0.0, 1.0, 181)
    result = run(log, grid)
    zooms = []
    for step in (log.step(3), log.step(5)):
        m = margin(step, result)
        assert m is not None
        for k in local_minima(m, np.isfinite(m), periodic=True):
            zooms += [Zoom(step, grid[k] - grid[1], grid[k] + grid[1], partial(margin, step))] * 2
    assert len(zooms) >= 6
    assert zoom_mins(log, zooms) == [zoom_min(log, z.lo, z.hi, z.value) for z in zooms]


def test_a_zoom_settles_once_flat_outside_its_band(tmp_path):
    log = _draft(four_bar(tmp_path, "fourbar", 20, 70, 50, 60, 60))
    zoom = Zoom(log.step(3), 0.0, 1.0, partial(margin, log.step(3)), (-1e-6, 1e-6), 1e-6)
    assert zoom.settled(np.array([3e-6, 3.5e-6, 2.5e-6]))  # flat, and more than flat above the band
    assert zoom.settled(np.array([-3e-6, -2.5e-6]))  # flat, below
    assert not zoom.settled(np.array([2.5e-6, 1.5e-6]))  # within flat of the band
    assert not zoom.settled(np.array([3e-6, 5e-6]))  # not flat
    assert not zoom.settled(np.array([3e-6, np.nan]))
    assert not Zoom(log.step(3), 0.0, 1.0, zoom.value).settled(np.array([1.0, 1.0]))  # no band: never
