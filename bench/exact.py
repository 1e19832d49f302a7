"""The 50-digit reference of a sample at rows of its sweep, and the worst errors against it.

The reference is tests/reference.py (constraints from the format spec alone, Newton in mpmath at
50 digits, rates by Taylor jets), started from the in-process evaluator's row so that it follows
the same assembly, as tests/test_accuracy.py does.  A row where the reference's Jacobian is
singular (a change point: no unique motion) is left out.

Errors, the worst over the rows compared and the columns the reference has: positions in units of
the length scale L, angles in radians (so both are "in L"), rates relative to the larger of the
value and its quantity's scale (tests/programs.noise_floors); and the positions of pairs and points
alone, which every peer computes.
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

from programs import noise_floors, parse  # noqa: E402
from reference import Reference, wrap  # noqa: E402

from linkgen.evaluate import evaluate  # noqa: E402
from linkgen.pipeline import build_log  # noqa: E402
from linkgen.rows import input_rows  # noqa: E402
from linkgen.table import columns  # noqa: E402

ROWS = 37  # reference rows spread over the sweep (every 10 degrees of a full turn in 361 rows)
SINGULAR = 1e-9  # the reference's conditioning below which a row is a change point (tests/test_accuracy.py)
POSITIONS = ("position", "angle")


@dataclass
class Exact:
    """The reference of one sample: columns per row (None where left out), and what scales them."""

    path: str
    length: float  # the length scale L
    values: np.ndarray  # input values of each row
    rates: np.ndarray  # input rates of each row
    rows: list[dict[str, float] | None]
    quantity: dict[str, str]  # column name -> quantity class
    scales: dict[str, float]  # quantity class -> S


def solve(path: str, values: np.ndarray, rates: np.ndarray) -> Exact:
    """The reference at the rows of input values (and rates) given, in the order given."""
    log = build_log(path, outputs=(), order=2, sweep=False)
    result = evaluate(log, values, rates, np.zeros_like(values))
    names, data = columns(log, result)
    ref = Reference(path)
    rows: list[dict[str, float] | None] = []
    for k in range(len(values)):
        if result.status[k] > 0:
            rows.append(None)
            continue
        guess = ref.guess(dict(zip(names, (float(x) for x in data[k]))))
        sol = ref.solve(list(values[k]), list(rates[k]), guess)
        rows.append({n: float(v) for n, v in sol.columns.items()} if sol.cond >= SINGULAR else None)
    largest: dict[str, float] = {}
    quantity = {c.name: c.quantity for c in log.columns}
    for row in rows:
        for name, v in (row or {}).items():
            q = quantity[name]
            largest[q] = max(largest.get(q, 0.0), abs(v))
    return Exact(path, log.length_scale, values, rates, rows, quantity, noise_floors(largest, log.length_scale))


def sweep_rows(samples: int) -> list[int]:
    """The rows of a sweep of ``samples`` rows the reference is computed at."""
    return sorted({round(k * (samples - 1) / (ROWS - 1)) for k in range(ROWS)})


def of_sample(path: str) -> tuple[Exact, list[int]]:
    """The reference at ROWS rows of the file's sweep, and their row numbers."""
    log = build_log(path, outputs=(), order=2, sweep=False)
    values, rates, _ = input_rows(log, log.samples)
    picked = sweep_rows(log.samples)
    return solve(path, values[picked], rates[picked]), picked


def _unit(name: str, row: dict[str, float]) -> tuple[float, str] | None:
    """The reference value and quantity of a unit-vector column (angles: unit; link.ux, .uy and their
    rates .dux, .duy, .ddux, .dduy): cos and sin of the link's angle and their time derivatives."""
    link, _, part = name.rpartition(".")
    if f"{link}.phi" not in row or part not in ("ux", "uy", "dux", "duy", "ddux", "dduy"):
        return None
    phi, omega, alpha = (row.get(f"{link}.{k}", math.nan) for k in ("phi", "omega", "alpha"))
    c, s = math.cos(phi), math.sin(phi)
    return {"ux": (c, "angle"), "uy": (s, "angle"), "dux": (-s * omega, "angular_velocity"),
            "duy": (c * omega, "angular_velocity"),
            "ddux": (-c * omega * omega - s * alpha, "angular_acceleration"),
            "dduy": (-s * omega * omega + c * alpha, "angular_acceleration")}[part]


@dataclass
class Errors:
    """Worst errors of one program or peer against the reference."""

    position: float  # positions / L and angles (rad)
    rate: float  # velocities and accelerations, relative (nan without any)
    points: float  # the positions of pairs and points alone / L (what every peer computes)
    compared: int  # rows compared
    failed: int  # rows the reference solves and the program fails
    unmatched: tuple[str, ...]  # output columns the reference has no value for


def worst(exact: Exact, got: list[dict[str, float] | None]) -> Errors:
    """The worst errors of ``got`` (per reference row: column -> value; None: the row failed)."""
    pos, rate, points, compared, failed = 0.0, math.nan, 0.0, 0, 0
    unmatched: set[str] = set()
    for ref, row in zip(exact.rows, got):
        if ref is None:
            continue
        if row is None:
            failed += 1
            continue
        compared += 1
        for name, value in row.items():
            want, q = ref.get(name), exact.quantity.get(name)
            if want is None:
                want, q = _unit(name, ref) or (None, None)
            if want is None or q is None:
                unmatched.add(name)
                continue
            if q in POSITIONS:
                err = abs(float(wrap(value - want))) if q == "angle" else abs(value - want) / exact.length
                pos = max(pos, err) if math.isfinite(err) else math.inf
                if q == "position":
                    points = max(points, err) if math.isfinite(err) else math.inf
            else:
                err = abs(value - want) / max(abs(want), exact.scales[q])
                rate = err if math.isnan(rate) else max(rate, err) if math.isfinite(err) else math.inf
    return Errors(pos, rate, points, compared, failed, tuple(sorted(unmatched)))


POINT_FIELDS = ("x", "y", "vx", "vy", "ax", "ay")  # the columns of pairs and points


def table(text: str) -> tuple[list[str], list[list[float]], list[int]]:
    """A program's sweep CSV as header, rows and status codes (tests/programs.parse); a CSV without a
    status column (a program built without checks may leave it out) reads as every row solved."""
    header = text.split("\n", 1)[0].split(",")
    if header[-1] == "status":
        return parse(text)
    rows = [[float(x) for x in line.split(",")] for line in text.splitlines()[1:] if line]
    return header, rows, [0] * len(rows)


def csv_errors(exact: Exact, picked: list[int], text: str, points_only: bool = False) -> Errors:
    """The worst errors of a program's sweep CSV at the reference's rows (with ``points_only``, of the
    pairs' and points' columns alone); the input columns are not compared (a float program rounds
    its inputs: that is part of its error)."""
    header, data, status = table(text)
    n_inputs = exact.values.shape[1]
    keep = [k for k, name in enumerate(header) if k >= n_inputs and name != "status"
            and (not points_only or name.rpartition(".")[2] in POINT_FIELDS)]
    got: list[dict[str, float] | None] = []
    for k in picked:
        ok = k < len(status) and status[k] <= 0
        got.append({header[j]: data[k][j] for j in keep} if ok else None)
    return worst(exact, got)
