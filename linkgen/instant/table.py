"""Every instant centre of a mechanism at one row (``linkgen ic``, the manual's table): its class
from the topology, its place from the in-process evaluation of the ``instant_centre`` steps."""

from __future__ import annotations

import json
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ..evaluate import evaluate
from ..model import Mechanism
from ..steplog import CentreAt, StepLog
from ..table import columns
from ..units import from_file, to_file
from .classify import Centre, classify

STATES = ("finite", "at infinity", "links move alike")  # the centre's status 0, 1, 2


@dataclass(frozen=True)
class Located:
    """One centre at a row: its class, and its place (x, y nan at infinity), direction, status and sigma."""

    centre: Centre
    x: float
    y: float
    ux: float
    uy: float
    status: int  # 0 finite, 1 at infinity, 2 the links move alike; -1 where the row has no velocities
    sigma: float


@dataclass(frozen=True)
class Table:
    inputs: tuple[float, ...]  # in the file's units, as given (degrees where the file's angles are)
    rates: tuple[float, ...]
    row_status: int
    centres: tuple[Located, ...]


def centre_outputs(m: Mechanism) -> tuple[str, ...]:
    """Every centre's output name, in the classification's order."""
    return tuple(c.name for c in classify(m))


def locate(log: StepLog, m: Mechanism, values: Sequence[float] | None = None,
           rates: Sequence[float] | None = None) -> Table:
    """Every centre of a log built with every centre as an output (``centre_outputs``), at the input
    values and rates in the file's units (default: the sketch and the inputs' speeds); the table
    keeps them as given."""
    here = tuple(i.sketch for i in log.inputs) if values is None else from_file(log, values)
    speeds = tuple(i.speed for i in log.inputs) if rates is None else from_file(log, rates)
    result = evaluate(log, np.array([here], dtype=float), np.array([speeds], dtype=float), np.zeros((1, len(here))),
                      order=1)
    names, data = columns(log, result)
    row = dict(zip(names, data[0]))
    out = []
    for c in classify(m):
        st, x, y, ux, uy, sigma = (float(row[f"{c.name}.{f}"]) for f in ("status", "x", "y", "ux", "uy", "sigma"))
        out.append(Located(c, x, y, ux, uy, int(st) if math.isfinite(st) else -1, sigma))
    shown = (to_file(log, here) if values is None else tuple(map(float, values)),
             to_file(log, speeds) if rates is None else tuple(map(float, rates)))
    return Table(*shown, int(result.status[0]), tuple(out))


def _g(x: float) -> str:
    text = f"{x:.6g}"
    return "0" if text == "-0" else text


def where(c: Located) -> str:
    """The place of a centre in words: (x, y), or at infinity in the direction (ux, uy)."""
    if c.status == 1:
        return f"at infinity, direction ({_g(c.ux)}, {_g(c.uy)})"
    if c.status < 0:
        return "not known (the row has no velocities)"
    text = f"({_g(c.x)}, {_g(c.y)})"
    return text + (" (the links move alike)" if c.status == 2 else "")


def text(log: StepLog, table: Table) -> str:
    """The table of centres as ``linkgen ic`` prints it."""
    units = ", ".join(f"{i.column} = {_g(v)}" for i, v in zip(log.inputs, table.inputs))
    rates = ", ".join(_g(r) for r in table.rates)
    lines = [f"Instant centres of {log.name} ({len(table.centres)}): class from the topology, place at {units} "
             f"moving at {rates} per second (the file's units; row status {table.row_status})"]
    width = max(len(c.centre.name) for c in table.centres)
    for c in table.centres:
        how = f"pair {c.centre.pair}" if c.centre.pair else (
            "Kennedy lines via " + ", ".join(c.centre.lines) if c.centre.lines else "on no Kennedy line")
        lines.append(f"  {c.centre.name:<{width}}  {c.centre.kind:<9}  {where(c):<40}  sigma {_g(c.sigma):<10}  {how}")
    return "\n".join(lines) + "\n"


def _num(x: float) -> float | None:
    return x if math.isfinite(x) else None


def to_json(log: StepLog, table: Table) -> str:
    rows = [{"centre": c.centre.name, "links": list(c.centre.links), "class": c.centre.kind, "pair": c.centre.pair,
             "placed_by_theorem": c.centre.placed, "lines": list(c.centre.lines), "x": _num(c.x), "y": _num(c.y),
             "ux": _num(c.ux), "uy": _num(c.uy), "status": c.status, "sigma": _num(c.sigma)} for c in table.centres]
    doc = {"mechanism": log.name, "inputs": list(table.inputs),
           "rates": list(table.rates),
           "row_status": table.row_status, "centres": rows}
    return json.dumps(doc, indent=2) + "\n"


def at_sketch(log: StepLog, m: Mechanism) -> tuple[CentreAt, ...]:
    """Every centre at the sketch, the inputs at their speeds, as the step log keeps them (``log``
    built with every centre as an output)."""
    table = locate(log, m)

    def num(x: float) -> float | None:
        return x if math.isfinite(x) else None

    return tuple(CentreAt(c.centre.name, c.centre.links, c.centre.kind, c.centre.pair, c.centre.lines,
                          c.centre.placed, num(c.x), num(c.y), num(c.ux), num(c.uy), c.status, c.sigma)
                 for c in table.centres)
