"""analysis.reach: a resolver mechanism's reach ends at limit positions (folds of its input).

At a fold the fastest point's speed grows as one over the square root of the distance to
it, so speed^2 times the distance tends to a constant: measured here at three distances
with the evaluator's row solver, from the sketch, on the log without its reach (the
search uses other distances and a secant; tests/test_reach.py checks the bounds against a
50-digit model)."""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import pytest

from linkgen.analysis.reach import _outward
from linkgen.pipeline import build_log
from linkgen.rowsolver import RowSolver

ROOT = Path(__file__).resolve().parents[2]
PARTIAL = ROOT / "tests" / "mechanisms" / "sixbar_partial.yaml"  # a crank that meets two limit positions


def _speed(log, value: float) -> float | None:
    """The fastest point's speed per unit crank rate at ``value``, reached from the sketch."""
    out = RowSolver(log, 1).solve([value], [1.0], [0.0])
    if not out.ok:
        return None
    return max(math.hypot(*out.env[v.name][2:4]) for v in log.variables if v.kind == "POINT" and not v.constant)


@pytest.mark.parametrize("side", ["low", "high"])
def test_the_reach_ends_where_the_speed_follows_the_law_of_a_fold(side):
    log = build_log(str(PARTIAL), sweep=False)
    reach = log.reach
    assert reach is not None and reach.periodic and getattr(reach, f"{side}_step") == 8
    assert log.step(8).action == "resolve"
    bound, inward = (reach.low, 1.0) if side == "low" else (reach.high, -1.0)
    free = replace(log, reach=None)
    laws = []
    for distance in (1e-4, 1e-5, 1e-6):
        speed = _speed(free, bound + inward * distance)
        assert speed is not None, f"{bound + inward * distance} not reached"
        laws.append(speed * speed * distance)
    assert max(laws) / min(laws) < 1.01, laws
    assert _speed(free, bound - inward * 1e-6) is None


@pytest.mark.parametrize("value", [0.0293539524107123, -3.1844406694587, 22.42935288817, 1e-5 / 3])
@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_a_bound_is_rounded_to_12_digits_away_from_the_sketch(value, sign):
    rounded = _outward(value, sign)
    assert float(f"{rounded:.12g}") == rounded
    assert (rounded - value) * sign >= 0 and abs(rounded - value) <= 1e-11 * abs(value)
