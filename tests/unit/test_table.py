"""linkgen.table: the sweep as the CSV the programs write, against the four-bar solved by hand
(two circles intersected on the sketch's side), and the spec's nan rules for failed rows."""

from __future__ import annotations

import dataclasses
import math
import random
from pathlib import Path

import numpy as np
import pytest

from linkgen.evaluate import evaluate
from linkgen.pipeline import build_log
from linkgen.rows import input_rows
from linkgen.table import columns, csv, number

FOURBAR = Path(__file__).resolve().parents[2] / "samples" / "fourbar" / "fourbar.yaml"
# The sample: O1 (0, 0), A (20, 0), B (80, 50), O2 (90, 0); P (60, 70) on the coupler AB.
O1, A0, B0, O2, P0 = (0.0, 0.0), (20.0, 0.0), (80.0, 50.0), (90.0, 0.0), (60.0, 70.0)


def hand(theta: float) -> dict[str, tuple[float, float]]:
    """A on the crank circle; B where the coupler's and the rocker's circles meet, left of A->O2 as drawn;
    P turned with the coupler."""
    crank = math.dist(O1, A0)
    a = (O1[0] + crank * math.cos(theta), O1[1] + crank * math.sin(theta))
    r1, r2, d = math.dist(A0, B0), math.dist(O2, B0), math.dist(a, O2)
    along = (r1 * r1 - r2 * r2 + d * d) / (2 * d)
    off = math.sqrt(r1 * r1 - along * along)
    ux, uy = (O2[0] - a[0]) / d, (O2[1] - a[1]) / d
    b = (a[0] + along * ux - off * uy, a[1] + along * uy + off * ux)
    turn = math.atan2(b[1] - a[1], b[0] - a[0]) - math.atan2(B0[1] - A0[1], B0[0] - A0[0])
    px, py = P0[0] - A0[0], P0[1] - A0[1]
    p = (a[0] + px * math.cos(turn) - py * math.sin(turn), a[1] + px * math.sin(turn) + py * math.cos(turn))
    return {"A": a, "B": b, "P": p}


@pytest.fixture(scope="module")
def sweep():
    log = build_log(str(FOURBAR), sweep=False)
    values, rates, accs = input_rows(log, 13)  # every 30 degrees
    return log, evaluate(log, values, rates, accs)


def test_number_is_17_significant_digits_or_nan():
    assert number(0.1) == "0.10000000000000001"  # 0.1000000000000000055511... to 17 digits
    assert number(1.0) == "1" and number(-0.0) == "-0" and number(1e300) == "1.0000000000000001e+300"
    assert number(2.0 ** -1074) == "4.9406564584124654e-324"
    assert [number(x) for x in (math.nan, math.inf, -math.inf)] == ["nan"] * 3
    rng = random.Random(3)
    for _ in range(2000):
        x = math.ldexp(rng.random() - 0.5, rng.randrange(-1070, 1020))
        assert float(number(x)) == x


def test_positions_are_the_hand_solution_and_fixed_pivots_as_drawn(sweep):
    log, result = sweep
    names, data = columns(log, result)
    col = {n: k for k, n in enumerate(names)}
    assert result.status.tolist() == [0] * 13
    for row, theta in zip(data, result.inputs[:, 0]):
        assert row[col["theta_O1"]] == theta
        for name, (x, y) in hand(theta).items():
            assert row[col[f"{name}.x"]] == pytest.approx(x, abs=1e-12 * 90)
            assert row[col[f"{name}.y"]] == pytest.approx(y, abs=1e-12 * 90)
        assert [row[col[f"{p}.{c}"]] for p in ("O1", "O2") for c in ("x", "y", "vx", "vy", "ax", "ay")] == [
            *O1, 0, 0, 0, 0, *O2, 0, 0, 0, 0]


def test_velocities_are_the_rate_of_the_hand_solution(sweep):
    """The crank turns at 360 degrees per second: B's velocity is d(hand)/dtheta times 2 pi."""
    log, result = sweep
    names, data = columns(log, result)
    h = 1e-6
    for row, theta in zip(data, result.inputs[:, 0]):
        ahead, behind = hand(theta + h)["B"], hand(theta - h)["B"]
        for k, c in enumerate(("B.vx", "B.vy")):
            rate = (ahead[k] - behind[k]) / (2 * h) * 2 * math.pi
            assert row[names.index(c)] == pytest.approx(rate, rel=1e-6, abs=1e-6 * 90 * 2 * math.pi)


def test_failed_rows_are_nan_and_singular_rows_lose_their_derivatives(sweep):
    """Reason 1 or 2 (10*step + reason): every output nan; reason 3: velocities and accelerations nan;
    a negative (near-singular) code leaves the row as computed."""
    log, result = sweep
    status = np.zeros(13, dtype=int)
    status[2], status[3], status[4], status[5] = 31, 32, 33, -34
    names, data = columns(log, dataclasses.replace(result, status=status))
    _, computed = columns(log, result)
    derivative = [n.partition(".")[2] in ("vx", "vy", "ax", "ay", "omega", "alpha", "ds", "dds") for n in names]
    assert sum(derivative) == 5 * 4 + 4 * 2  # vx, vy, ax, ay of 5 pairs and points; omega, alpha of 4 links
    assert np.isnan(data[2:4, 1:]).all() and not np.isnan(data[2:4, 0]).any()
    assert np.isnan(data[4, derivative]).all()
    assert (data[4, [not d for d in derivative]] == computed[4, [not d for d in derivative]]).all()
    assert (data[5] == computed[5]).all() and (data[[0, 1, *range(6, 13)]] == computed[[0, 1, *range(6, 13)]]).all()


def test_the_csv_reads_back_exactly(sweep):
    log, result = sweep
    names, data = columns(log, result)
    lines = csv(log, result).splitlines()
    assert lines[0].split(",") == names + ["status"] and len(lines) == 14
    for line, row in zip(lines[1:], data):
        *values, status = line.split(",")
        assert [float(v) for v in values] == row.tolist() and status == "0"
