"""linkgen.rows: the sweep's input rows together and on a grid, and the lines a grid restarts at,
against rows written out by hand and itertools.product."""

from __future__ import annotations

import dataclasses
import itertools
import math
from pathlib import Path

import numpy as np

from linkgen.pipeline import build_log
from linkgen.rows import input_rows, line_length

SAMPLES = Path(__file__).resolve().parents[2] / "samples"


def _log(name: str):
    return build_log(str(SAMPLES / name / f"{name}.yaml"), sweep=False)


def test_together_moves_every_input_in_step():
    log = _log("fivebar")  # two cranks, in degrees in the file
    values, rates, accs = input_rows(log, 5, grid=False)
    for k in range(5):
        assert values[k].tolist() == [i.start + k * (i.stop - i.start) / 4 for i in log.inputs]
    assert rates.tolist() == [[i.speed for i in log.inputs]] * 5 and not accs.any()
    assert line_length(log, 5) == 0


def test_a_grid_is_every_combination_the_first_input_slowest():
    log = dataclasses.replace(_log("fivebar"), sweep="grid")
    values, rates, _ = input_rows(log, 3)
    axes = [[i.start + j * (i.stop - i.start) / 2 for j in range(3)] for i in log.inputs]
    assert values.tolist() == [list(row) for row in itertools.product(*axes)]
    assert rates.shape == (9, 2) and line_length(log, 3) == 3


def test_a_grid_of_one_input_is_the_together_sweep():
    log = dataclasses.replace(_log("fourbar"), sweep="grid")
    assert np.array_equal(input_rows(log, 7)[0], input_rows(log, 7, grid=False)[0])
    assert line_length(log, 7) == 0


def test_the_ranges_as_a_program_takes_them():
    log = _log("fourbar")
    degrees = {"start": [0.0], "stop": [360.0], "speed": [36.0]}
    values, rates, _ = input_rows(log, 5, degrees)
    assert values[:, 0].tolist() == [0.0, 90.0, 180.0, 270.0, 360.0] and rates[:, 0].tolist() == [36.0] * 5
    assert input_rows(log, 5)[0][-1, 0] == 2 * math.pi
