"""Sweeps of a step log and the root finding on them that the analyses share.

A sweep runs all inputs together, lambda from 0 to 1 between each input's start and
stop; ``spanning`` gives the log whose one input sweeps the span searched for change
points and gaps instead.  ``own`` is the procedure of one step: what a step finds holds
in every procedure that contains it (a pruned one included).  Without resolvers, zooms are
taken together (``zoom_mins``): the rows of a log without resolvers are independent, so
one evaluation serves every zoom's grid.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from functools import partial
from typing import Any

import numpy as np

from .. import status
from ..evaluate import Result, evaluate
from ..numeric import unique
from ..prune import keep
from ..steplog import Step, StepLog

Array = np.ndarray[Any, np.dtype[Any]]
Measure = Callable[[Result], Array | None]

ZOOMS = 10  # refinements of a bracket around a minimum, each to 1/16 of the last
EDGE_ZOOMS = 5  # refinements of a limit position, each to 1/32 of the last
GRID = 33  # points per refinement
TOUCH = 1e-9  # a margin within this of zero, relative to the length scale, touches zero
SMALL = 1e-3  # minima of the margin or of sigma below this are examined
ROWS = 2048  # rows evaluated at once by zooms taken together (a result holds every variable per row)


def rows(log: StepLog) -> int:
    """Rows of a search over the span: twice the samples, 721 (a quarter degree) at least."""
    return max(2 * log.samples, 721)


def span(log: StepLog) -> tuple[float, float, bool]:
    """The input interval searched for change points and gaps: a full turn around the sketch
    for an angle (so what is found is complete modulo 2 pi), else the sweep and the sketch."""
    inp = log.inputs[0]
    if inp.kind == "revolute":
        return inp.sketch - np.pi, inp.sketch + np.pi, True
    return min(inp.start, inp.stop, inp.sketch), max(inp.start, inp.stop, inp.sketch), False


def spanning(log: StepLog) -> StepLog:
    """The log with its one input sweeping ``span``."""
    lo, hi, _ = span(log)
    return replace(log, inputs=(replace(log.inputs[0], start=lo, stop=hi),))


def own(log: StepLog, step: Step) -> StepLog:
    """The procedure of ``step``: it and the steps it reads from."""
    return keep(log, set(step.outputs))


def run(log: StepLog, lam: Array, warm: Any = None, stop: int = 0) -> Result:
    """Evaluate at sweep positions lam (in order); with resolvers, ``stop`` ends the rows at
    the first one that fails at or before that step (the rest of a zoom grid would too)."""
    start = np.array([i.start for i in log.inputs])
    stop_at = np.array([i.stop for i in log.inputs])
    values = start + lam[:, None] * (stop_at - start)
    rates = np.tile([i.speed for i in log.inputs], (len(lam), 1)).astype(float)
    with np.errstate(all="ignore"):
        return evaluate(log, values, rates, np.zeros_like(values), order=0, warm=warm, stop=stop)


def closes(result: Result, step: int) -> Array:
    """Rows where the procedure gets past this step."""
    st = result.status
    out: Array = ~(status.failed(st) & (status.step(st) <= step))
    return out


def warm_after(result: Result, row: int) -> Any:
    """The resolver's warm start after a sweep row (None without resolvers)."""
    return result.warm[row] if result.warm else None


def zoom_min(log: StepLog, lo: float, hi: float, value: Measure, warm: Any = None) -> tuple[float, float]:
    """(lambda, minimum) of value(result) on [lo, hi], by repeated grid refinement."""
    best = (lo, np.inf)
    for _ in range(ZOOMS):
        lam = np.linspace(lo, hi, GRID)
        v = value(run(log, lam, warm))
        if v is None or not np.any(np.isfinite(v)):
            break
        best, (lo, hi) = refined(lo, hi, lam, v)
    return best


def zooms_together(log: StepLog, asked: Sequence[tuple[float, float, Measure]]) -> list[tuple[float, float]]:
    """zoom_min of each (lo, hi, value), in a log without resolvers: each refinement evaluates the
    grids of all of them in one call (rows are independent: the values of one zoom at a time)."""
    assert not log.groups, "rows evaluated together in a log with resolvers"
    bracket = [(lo, hi) for lo, hi, _ in asked]
    best = [(lo, np.inf) for lo, _, _ in asked]
    live = list(range(len(asked)))
    for _ in range(ZOOMS):
        if not live:
            break
        grids = [np.linspace(*bracket[i], GRID) for i in live]
        result = run(log, np.concatenate(grids))
        going = []
        for j, (i, lam) in enumerate(zip(live, grids)):
            v = asked[i][2](result)
            v = None if v is None else v[j * GRID:(j + 1) * GRID]
            if v is None or not np.any(np.isfinite(v)):
                continue
            best[i], bracket[i] = refined(*bracket[i], lam, v)
            going.append(i)
        live = going
    return best


def golden_min(log: StepLog, lo: float, hi: float, measure: Any, warm: Any) -> tuple[float, float]:
    """(sweep position, value) of the least ``measure`` on [lo, hi] by golden-section search, one
    row at a time (a resolver's rows are solved one by one: a grid refinement would take ten
    times the rows), each from the warm start the row before it left (the points close in, so
    the resolver's continuation walks ever shorter), until the bracket is 1e-9 of the sweep:
    the value is then found to rounding (it is flat to second order there)."""
    state = [warm]

    def value(lam: float) -> float:
        result = run(log, np.array([lam]), state[0])
        if result.warm and result.warm[-1] is not None:
            state[0] = result.warm[-1]
        v = measure(result)
        return math.inf if v is None or not np.isfinite(v[0]) else float(v[0])

    ratio = (math.sqrt(5) - 1) / 2
    a, b = lo, hi
    c, d = b - ratio * (b - a), a + ratio * (b - a)
    fc, fd = value(c), value(d)
    while b - a > 1e-9:
        if fc <= fd:
            b, d, fd = d, c, fc
            c = b - ratio * (b - a)
            fc = value(c)
        else:
            a, c, fc = c, d, fd
            d = a + ratio * (b - a)
            fd = value(d)
    return (c, fc) if fc <= fd else (d, fd)


Pending = Callable[[], tuple[float, float]]  # a zoom's (sweep position, value), once found


def found(where: float, value: float) -> Pending:
    return lambda: (where, value)


class Zooms:
    """Grid refinements (zoom_min) of a log without resolvers, asked for first and found together when
    the first is read (zooms_together: every grid of a refinement in one call, the values of one zoom
    at a time); with resolvers each is found when asked (golden_min: row by row)."""

    def __init__(self, log: StepLog) -> None:
        self.log, self.asked, self.found = log, list[tuple[float, float, Any]](), list[tuple[float, float]]()

    def ask(self, lo: float, hi: float, measure: Any, warm: Any) -> Pending:
        if self.log.groups:
            return found(*golden_min(self.log, lo, hi, measure, warm))
        self.asked.append((lo, hi, measure))
        return partial(self._read, len(self.asked) - 1)

    def _read(self, k: int) -> tuple[float, float]:
        if not self.found:
            self.found = zooms_together(self.log, self.asked)
        return self.found[k]


def refined(lo: float, hi: float, lam: Array, v: Array) -> tuple[tuple[float, float], tuple[float, float]]:
    """(lambda, value) of the least finite value of a grid on [lo, hi], and the bracket of
    the next refinement: a grid step either side of it."""
    k = int(np.nanargmin(np.where(np.isfinite(v), v, np.nan)))
    step = (hi - lo) / (GRID - 1)
    return (float(lam[k]), float(v[k])), (max(lo, lam[k] - step), min(hi, lam[k] + step))


@dataclass(frozen=True)
class Zoom:
    """A zoom_min of value over [lo, hi] that reads the step's values.  With a band, what
    matters is only whether the minimum falls inside it: the zoom stops once its grid is
    flat (all within ``flat``) and more than that outside the band, as finer grids around its
    minimum, which lie inside the grid, find only rounding there (or the value is not smooth
    at the scale of the grid)."""

    step: Step
    lo: float
    hi: float
    value: Measure
    band: tuple[float, float] | None = None
    flat: float = 0.0

    def settled(self, v: Array) -> bool:
        if self.band is None or not np.all(np.isfinite(v)) or float(v.max() - v.min()) > self.flat:
            return False
        return float(v.min()) - self.flat > self.band[1] or float(v.max()) + self.flat < self.band[0]


def zoom_mins(log: StepLog, zooms: Sequence[Zoom]) -> list[tuple[float, float]]:
    """zoom_min of each zoom, in a log without resolvers: each refinement evaluates the grids
    of all zooms at once, every sweep position once, in the procedure of their steps."""
    bracket = [(z.lo, z.hi) for z in zooms]
    best = [(z.lo, np.inf) for z in zooms]
    live = list(range(len(zooms)))
    procedures: dict[frozenset[int], StepLog] = {}
    for _ in range(ZOOMS):
        if not live:
            break
        grids = [np.linspace(*bracket[i], GRID) for i in live]
        found = at_once(log, [(zooms[i].step, lam, zooms[i].value) for i, lam in zip(live, grids)], procedures)
        going = []
        for i, lam, v in zip(live, grids, found):
            if v is None or not np.any(np.isfinite(v)):
                continue
            best[i], bracket[i] = refined(*bracket[i], lam, v)
            if not zooms[i].settled(v):
                going.append(i)
        live = going
    return best


def at_once(log: StepLog, asked: Sequence[tuple[Step, Array, Measure]],
            procedures: dict[frozenset[int], StepLog] | None = None) -> list[Array | None]:
    """value(result) at the sweep positions asked for each (step, positions, value), from
    as few evaluations as ROWS allows of the procedure of the steps (a log without resolvers:
    its rows are independent, so each position is evaluated once, in any order).  The
    procedures made are kept in ``procedures``, by their steps asked for."""
    procedures = {} if procedures is None else procedures
    assert not log.groups, "rows evaluated at once in a log with resolvers"
    parts: list[list[int]] = []
    rows_in: set[float] = set()
    for i, (_, positions, _) in enumerate(asked):
        more = rows_in | set(positions.tolist())
        if parts and len(more) <= ROWS:
            parts[-1].append(i)
            rows_in = more
        else:
            parts.append([i])
            rows_in = set(positions.tolist())
    out: list[Array | None] = []
    for part in parts:
        lam, where = unique(np.concatenate([asked[i][1] for i in part]))
        steps = frozenset(asked[i][0].number for i in part)
        if steps not in procedures:
            procedures[steps] = keep(log, {name for n in steps for name in log.step(n).outputs})
        result = run(procedures[steps], lam)
        at = 0
        for i in part:
            v = asked[i][2](result)
            out.append(None if v is None else v[where[at:at + len(asked[i][1])]])
            at += len(asked[i][1])
    return out


def zoom_edge(log: StepLog, good: float, bad: float, number: int, sigma: float,
              warm: Any = None) -> tuple[float, float]:
    """The last lambda from good towards bad where the procedure gets past step number, and
    the step's conditioning there (sigma: at good), by repeated grid refinement."""
    for _ in range(EDGE_ZOOMS):
        lam = np.linspace(good, bad, GRID)
        result = run(log, lam, warm, stop=number)
        fine = closes(result, number)
        if not fine[0]:
            break
        k = int(np.argmin(fine)) if not fine.all() else GRID - 1
        last = result.sigma[number][max(k - 1, 0)] if number in result.sigma else np.nan
        sigma = float(last) if np.isfinite(last) else sigma
        good, bad = float(lam[max(k - 1, 0)]), float(lam[k])
    return good, sigma


def local_minima(v: Array, usable: Array, periodic: bool = False) -> list[int]:
    """Rows where v has a local minimum; across the seam too when the grid closes on itself
    (its last row is its first)."""
    n = len(v)
    if n < 3:
        return []
    k = np.arange(0 if periodic else 1, n - 1)
    before, after = (k - 1) % (n - 1) if periodic else k - 1, k + 1
    found = usable[before] & usable[k] & usable[after] & (v[k] <= v[before]) & (v[k] <= v[after])
    return [int(i) for i in k[found]]


def margin(step: Step, result: Result) -> Array | None:
    """The chain's closing margin per row: zero at a toggle, negative where it cannot close."""
    a = {arg.label or f"#{k}": arg for k, arg in enumerate(step.args)}
    args = step.args

    def rec(var: str, field: int = 0) -> Array:
        out: Array = result.values[var][field]
        return out

    if step.function == "RRR_links":
        x1, y1 = rec(args[0].var), rec(args[0].var, 1)
        x2, y2 = rec(args[1].var), rec(args[1].var, 1)
        sides = np.stack([np.sqrt((x2 - x1) ** 2 + (y2 - y1) ** 2), rec(args[2].var), rec(args[3].var)])
        big, small = sides.max(axis=0), sides.min(axis=0)
        out: Array = small - (big - (sides.sum(axis=0) - big - small))
        return out
    if step.function == "PRR_links":
        jx, jy = rec(args[0].var), rec(args[0].var, 1)
        length = rec(args[1].var)
        px, py = rec(args[2].var), rec(args[2].var, 1)
        psi = rec(args[3].var)
        gsi, eta = float(a["gsi"].value), float(a["eta"].value)
        c, s = np.cos(psi), np.sin(psi)
        wx, wy = px + gsi * c - eta * s - jx, py + gsi * s + eta * c - jy
        out = length - np.abs(wx * s - wy * c)
        return out
    if step.function == "RPR_links":
        dx = rec(args[1].var) - rec(args[0].var)
        dy = rec(args[1].var, 1) - rec(args[0].var, 1)
        out = np.sqrt(dx * dx + dy * dy) - abs(float(a["bg"].value) - float(a["bs"].value))
        return out
    return None
