"""analysis.change_points: where a chain's two assemblies cross, against the closed form."""

from __future__ import annotations

import math

import numpy as np
import pytest
from linkages import four_bar

from linkgen.evaluate import evaluate
from linkgen.pipeline import build_log
from linkgen.rows import input_rows


def test_a_parallelogram_flips_where_its_pivots_are_in_line(tmp_path):
    """A parallelogram (crank = rocker, coupler = ground) with its ground at 30 degrees: its
    pivots are in line, and its chain's assemblies cross, with the crank along the ground line,
    at 30 and 210 degrees."""
    log = build_log(str(four_bar(tmp_path, "parallelogram", 20, 60, 20, 60, 45, ground=30)), sweep=False)
    (chain,) = [s for s in log.steps if s.change_points]
    assert chain.function == "RRR_links"
    assert chain.change_points == pytest.approx([math.radians(30), math.radians(210)], abs=1e-10)
    assert "flips at each of them" in chain.branch_reason and "branch_at" in log.runtime


def test_the_flipping_branch_keeps_the_coupler_parallel_to_the_ground(tmp_path):
    """Over a whole turn, across both change points, B - A stays O2 - O1 (a parallelogram's
    coupler moves parallel to its ground): to rounding, and to sqrt(eps) of the length on the
    rows at the change points (a double root); a branch kept from the sketch folds it, by the
    length of the links."""
    log = build_log(str(four_bar(tmp_path, "parallelogram", 20, 60, 20, 60, 45, ground=30)), sweep=False)
    result = evaluate(log, *input_rows(log, 721))
    pos = {v.entity: v.name for v in log.variables if v.role == "pair"}
    a, b = (np.stack(result.values[pos[j]][:2]) for j in ("A", "B"))
    ground = np.array([60 * math.cos(math.radians(30)), 60 * math.sin(math.radians(30))])
    error = np.abs(b - a - ground[:, None]).max(axis=0)
    at = np.isin(np.round(np.degrees(result.inputs[:, 0]), 9), (30.0, 210.0))
    assert at.sum() == 2 and error[~at].max() < 1e-12 * 60 and error[at].max() < 1e-7 * 60


def test_a_crank_rocker_has_none(tmp_path):
    """A Grashof crank-rocker (a=20, b=70, c=50, d=60): |A O2| stays within [40, 80], inside
    [b - c, b + c] = [20, 120], so the chain never reaches a toggle, let alone a double one."""
    log = build_log(str(four_bar(tmp_path, "crank_rocker", 20, 70, 50, 60, 60)), sweep=False)
    assert not any(s.change_points for s in log.steps) and "branch_at" not in log.runtime
