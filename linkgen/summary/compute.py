"""The engineering summary of a step log: its motion facts (linkgen.analysis) read in the
file's units, and what one sweep of the procedure shows (transmission angles, strokes and
swings, time ratios, the rows that fail), each extreme located by grid refinement."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import replace
from functools import partial
from typing import Any

import numpy as np

from .. import status
from ..analysis.sweep import Pending, Zooms, found, margin, own, warm_after
from ..evaluate import Result, evaluate
from ..options import reference
from ..steplog import Gap, StepLog
from ..sweepdata import file_rows
from .grashof import four_bars
from .records import Failure, InputRange, Position, Summary, Transmission, Travel

Array = np.ndarray[Any, np.dtype[Any]]
TURN = 2 * math.pi
EDGE_ROUNDS = 12  # refinements of a limit position, each to 1/32 of the last
EDGE_GRID = 33
STRIDE = math.pi / 8  # rows of an angle farther apart than this are not refined between
NEWTON = 12  # Newton steps on an output's rate before its bracket is searched instead
EPS = float(np.finfo(float).eps)
STILL = 1e-12  # an output whose travel is below this (radians, or of the length scale) does not move


def summarize(log: StepLog) -> Summary:
    """The summary of the log over its sweep (log.samples rows, all inputs together), found with
    the reference settings (options.reference: every check on), whatever the programs run."""
    log = replace(log, options=reference(log.options))
    result = file_rows(log)  # the plots' sweep too (linkgen.sweepdata): evaluated once
    lam = np.linspace(0.0, 1.0, log.samples)
    units = _Units(log)
    edges = _limits(log)
    st = result.status
    return Summary(
        log.name, log.title, log.length_unit, "deg" if units.deg else "rad", log.grubler, log.mobility, log.redundant,
        _inputs(log, units, edges), four_bars(log), _positions(log, units, edges),
        _transmission(log, result, lam, units, edges), _travels(log, result, lam, units),
        int(len(st)), int(np.count_nonzero(st < 0)), int(np.count_nonzero(status.singular(st))),
        int(np.count_nonzero(status.failed(st))), _failures(log, result, units))


class _Units:
    """Converts the programs' values (radians, length units) to the file's."""

    def __init__(self, log: StepLog) -> None:
        self.log = log
        self.deg = log.angle_unit == "deg"

    def angle(self, x: float) -> float:
        return math.degrees(x) if self.deg else x

    def input(self, k: int, x: float) -> float:
        return self.angle(x) if self.log.inputs[k].kind == "revolute" else x

    def unit(self, k: int) -> str:
        return ("deg" if self.deg else "rad") if self.log.inputs[k].kind == "revolute" else self.log.length_unit

    def at(self, lam: float) -> tuple[float, ...]:
        """The inputs at sweep position lam, in the file's units."""
        return tuple(self.input(k, i.start + lam * (i.stop - i.start)) for k, i in enumerate(self.log.inputs))


def _periodic(log: StepLog) -> bool:
    """One input turning a whole turn: the sweep's last row is its first."""
    return (len(log.inputs) == 1 and log.inputs[0].kind == "revolute"
            and abs(abs(log.inputs[0].stop - log.inputs[0].start) - TURN) <= 1e-12 * TURN)


# limit positions: (step, value) in the programs' units, from the gaps (refined) or the resolvers' reach
Edges = list[tuple[int, float]]


def _limits(log: StepLog) -> Edges:
    out: Edges = []
    for g in log.gaps:
        if g.point:
            continue
        for side, beyond in ((g.low, 1.0), (g.high, -1.0)):
            if side is not None:
                out.append((g.step, _refined_edge(log, g, side, beyond)))
    if log.reach is not None and log.groups:
        out += [(s, x) for s, x in ((log.reach.low_step, log.reach.low), (log.reach.high_step, log.reach.high))
                if x is not None]
    return sorted(out, key=lambda e: (e[1], e[0]))


def _refined_edge(log: StepLog, gap: Gap, value: float, beyond: float) -> float:
    """A gap's side located to rounding: where the chain's closing margin crosses zero, by grid
    refinement of a bracket around the analysis' value (unchanged where it holds no crossing)."""
    step = log.step(gap.step)
    procedure = own(log, step)
    inp = log.inputs[0]
    width = 1e-6 * max(1.0, abs(value)) * (log.length_scale if inp.kind != "revolute" else 1.0)
    good, bad = value - beyond * width, value + beyond * width
    for _ in range(EDGE_ROUNDS):
        xs = np.linspace(good, bad, EDGE_GRID)
        with np.errstate(all="ignore"):
            m = margin(step, evaluate(procedure, xs[:, None], np.zeros((EDGE_GRID, 1)), np.zeros((EDGE_GRID, 1)),
                                      order=0))
        if m is None or not m[0] >= 0 or m[-1] >= 0:
            return value if _ == 0 else float(good)
        k = int(np.argmax(m < 0))
        good, bad = float(xs[k - 1]), float(xs[k])
    return good


def _inputs(log: StepLog, units: _Units, edges: Edges) -> tuple[InputRange, ...]:
    out = []
    for k, i in enumerate(log.inputs):
        low = high = None
        known = len(log.inputs) == 1
        if known and edges:
            shift = (-TURN, 0.0, TURN) if i.kind == "revolute" else (0.0,)
            below = [x + s for _, x in edges for s in shift if x + s < i.sketch]
            above = [x + s for _, x in edges for s in shift if x + s > i.sketch]
            low = units.input(k, max(below)) if below else None
            high = units.input(k, min(above)) if above else None
        out.append(InputRange(i.column, i.kind, units.unit(k), units.input(k, i.start), units.input(k, i.stop),
                              units.input(k, i.sketch), low, high, known))
    return tuple(out)


def _in_sweep(log: StepLog, x: float) -> float:
    """An input angle moved by a whole turn into the sweep's range where it lies outside and a turn
    brings it in (the analysis gives a limit of a periodic motion modulo a turn)."""
    i = log.inputs[0]
    lo, hi = sorted((i.start, i.stop))
    if i.kind != "revolute" or lo <= x <= hi:
        return x
    return next((x + s for s in (-TURN, TURN) if lo <= x + s <= hi), x)


def _positions(log: StepLog, units: _Units, edges: Edges) -> tuple[Position, ...]:
    found = [Position(s, log.step(s).target, "limit", (units.input(0, _in_sweep(log, x)),)) for s, x in edges]
    found += [Position(g.step, log.step(g.step).target, "cannot close", (units.input(0, _in_sweep(log, g.low)),))
              for g in log.gaps if g.point and g.low is not None]
    found += [Position(s.number, s.target, "change point", (units.input(0, x),))
              for s in log.steps if not s.variant for x in s.change_points]
    return tuple(sorted(found, key=lambda p: (p.inputs, p.step)))


def _usable(result: Result) -> Array:
    out: Array = ~status.failed(result.status)
    return out


def _transmission(log: StepLog, result: Result, lam: Array, units: _Units, edges: Edges) -> tuple[Transmission, ...]:
    """Each chain's least and greatest transmission angle over the sweep: 0 at a limit position the
    sweep reaches (a limit outside its range is the mechanism's, not the sweep's)."""
    lo, hi = sorted((log.inputs[0].start, log.inputs[0].stop))
    edges = [(s, x) for s, x in ((s, _in_sweep(log, x)) for s, x in edges) if lo <= x <= hi]
    limited = {s for s, _ in edges}
    added = {a.name for a in log.add_links}  # a chain on an Add-link transmits nothing: the resolver sets it
    out: list[Callable[[], Transmission]] = []  # each made once every zoom is asked for (analysis.sweep.Zooms)
    zooms = Zooms(log)
    for s in log.steps:
        if s.action != "chain" or s.variant or s.number not in result.sigma or set(s.links) & added:
            continue
        sigma = result.sigma[s.number]
        ok = _usable(result) & np.isfinite(sigma)
        if not ok.any():
            continue
        high = units.angle(math.asin(min(1.0, float(np.max(sigma[ok])))))
        if s.number in limited:
            edge = min((x for n, x in edges if n == s.number), key=lambda x: abs(x - log.inputs[0].sketch))
            out.append(partial(Transmission, s.number, s.target, s.chain, s.links, 0.0, (units.input(0, edge),),
                                high, True))
            continue
        k = int(np.argmin(np.where(ok, sigma, np.inf)))
        zoom = _zoomed(log, result, lam, k, lambda r, n=s.number: r.sigma.get(n), zooms)

        def least(s: Any = s, zoom: Any = zoom, row: float = float(sigma[k]), high: float = high) -> Transmission:
            where, value = zoom()
            return Transmission(s.number, s.target, s.chain, s.links, units.angle(math.asin(min(1.0, min(value, row)))),
                                units.at(_folded(log, where)), high, False)
        out.append(least)
    return tuple(make() for make in out)


def _zoomed(log: StepLog, result: Result, lam: Array, k: int, measure: Any, zooms: Zooms) -> Pending:
    """(sweep position, value) of the least ``measure`` around sweep row k, by grid refinement
    (across the seam of a whole turn); the row itself where the rows are more than STRIDE apart
    in an angle (a sweep over many turns: the places between rows are not one motion), at an end
    of the sweep, and with resolvers next to a failing row."""
    h = float(lam[1] - lam[0]) if len(lam) > 1 else 0.0
    apart = any(i.kind == "revolute" and abs(i.stop - i.start) * h > STRIDE for i in log.inputs)
    failed = status.failed(result.status)
    edge = log.groups and any(0 <= j < len(lam) and failed[j] for j in (k - 1, k + 1))
    # an end of the sweep, or with resolvers the last row before a limit position (rows past it
    # fail only after the resolver's whole search): that row
    if apart or edge or (not _periodic(log) and k in (0, len(lam) - 1)):
        v = measure(result)
        return found(float(lam[k]), math.inf if v is None else float(v[k]))
    lo, hi = float(lam[k]) - h, float(lam[k]) + h
    if not _periodic(log):
        lo, hi = max(lo, 0.0), min(hi, 1.0)
    return zooms.ask(lo, hi, measure, warm_after(result, k - 1) if k > 0 else None)


def _folded(log: StepLog, lam: float) -> float:
    """A sweep position of a whole turn in [0, 1) (within the 1e-7 a place is found to of 1:
    the turn's start)."""
    if not _periodic(log):
        return lam
    lam %= 1.0
    return 0.0 if lam > 1.0 - 1e-7 else lam


def _wrapped(x: Array | float) -> Any:
    return (np.asarray(x) + math.pi) % TURN - math.pi


def _travels(log: StepLog, result: Result, lam: Array, units: _Units) -> tuple[Travel, ...]:
    ok = _usable(result)
    out: list[Callable[[], Travel]] = []  # each made once every zoom is asked for (analysis.sweep.Zooms)
    zooms = Zooms(log)
    for c in log.columns[len(log.inputs):]:
        v = log.variable(c.variable)
        if v.constant or not ((v.role == "link" and c.field == "the") or (v.role == "slide" and c.field == "v")):
            continue
        x = np.asarray(result.values[c.variable][0], dtype=float)
        if not (ok & np.isfinite(x)).any():
            continue
        angle = v.role == "link"
        u = _unwrapped(x, ok) if angle else np.where(ok, x, np.nan)
        kh, kl = int(np.nanargmax(u)), int(np.nanargmin(u))
        if u[kh] - u[kl] <= STILL * (1.0 if angle else log.length_scale):
            continue  # computed, but it does not move
        if angle and u[kh] - u[kl] >= TURN * (1 - 1e-9):
            out.append(partial(Travel, c.name, "angle", "deg" if units.deg else "rad", units.angle(u[kl]),
                               units.angle(u[kh]), units.at(float(lam[kl])), units.at(float(lam[kh])),
                               units.angle(float(u[kh] - u[kl])), True, None))
            continue
        high_zoom = _extreme(log, result, lam, kh, c.variable, float(x[kh]), float(u[kh]), angle, -1.0, zooms)
        low_zoom = _extreme(log, result, lam, kl, c.variable, float(x[kl]), float(u[kl]), angle, 1.0, zooms)
        out.append(partial(_travel, log, result, units, c.name, angle, u, high_zoom, low_zoom))
    return tuple(make() for make in out)


def _travel(log: StepLog, result: Result, units: _Units, name: str, angle: bool, u: Array, high_zoom: Pending,
            low_zoom: Pending) -> Travel:
    """An output's travel from its extremes (found by their zooms)."""
    (high_at, high), (low_at, low) = high_zoom(), low_zoom()
    if angle:  # the unwrapped sweep may start a turn away: the swing's middle in (-pi, pi]
        turns = TURN * math.ceil((low + high) / 2 / TURN - 0.5)
        low, high = low - turns, high - turns
    scale = units.angle if angle else (lambda t: t)
    return Travel(name, "angle" if angle else "slide", ("deg" if units.deg else "rad") if angle else log.length_unit,
                  scale(low), scale(high), units.at(_folded(log, low_at)), units.at(_folded(log, high_at)),
                  scale(high) - scale(low), False, _time_ratio(log, result, u, low_at, high_at))


def _unwrapped(x: Array, ok: Array) -> Array:
    """An angle along the sweep without its jumps of a turn, nan where rows fail."""
    out = np.full_like(x, np.nan)
    good = ok & np.isfinite(x)
    out[good] = np.unwrap(x[good])
    return out


def _extreme(log: StepLog, result: Result, lam: Array, k: int, variable: str, wrapped: float, unwrapped: float,
             angle: bool, sign: float, zooms: Zooms) -> Pending:
    """(sweep position, value) of the output's extreme near row k: its least (sign 1) or
    greatest (sign -1) value, an angle measured from its value at row k."""

    def measure_at(y: Array | float) -> Array:
        out: Array = sign * (_wrapped(np.asarray(y) - wrapped) if angle else np.asarray(y) - wrapped)
        return out

    def measure(r: Result) -> Array:  # a row that fails further on has no motion: never an extreme
        return np.where(status.failed(r.status), np.inf, measure_at(np.asarray(r.values[variable][0], dtype=float)))

    at = _stationary(log, result, lam, k, variable) if log.groups else None
    zoom = _zoomed(log, result, lam, k, measure, zooms) if at is None else found(at[0], float(measure_at(at[1])))

    def extreme() -> tuple[float, float]:
        where, value = zoom()
        return where, unwrapped + sign * min(value, 0.0)
    return extreme


def _stationary(log: StepLog, result: Result, lam: Array, k: int, variable: str) -> tuple[float, float] | None:
    """(sweep position, value) where the output's rate is zero near sweep row k, by Newton's
    method on the rate with its acceleration (a row at order 2 per step, from the warm start the
    step before left: a resolver solves rows one by one), or None where it does not converge
    inside the rows either side of k (the caller then searches the bracket)."""
    per = {round(i.speed / (i.stop - i.start), 12) for i in log.inputs if i.stop != i.start}
    if len(per) != 1 or len(lam) < 3 or not 0 < k < len(lam) - 1:
        return None
    rate = next(iter(per))  # d lam / dt: every input's speed over its span, the same for all
    lo, hi = float(lam[k - 1]), float(lam[k + 1])
    at, warm = float(lam[k]), warm_after(result, k - 1)
    start = np.array([i.start for i in log.inputs])
    span = np.array([i.stop - i.start for i in log.inputs])
    speeds = np.array([[i.speed for i in log.inputs]], dtype=float)
    for _ in range(NEWTON):
        with np.errstate(all="ignore"):
            row = evaluate(log, (start + at * span)[None, :], speeds, np.zeros_like(speeds), order=2, warm=warm)
        if status.failed(row.status[0]):
            return None
        warm = row.warm[-1] if row.warm else None
        y, dy, ddy = (float(f[0]) for f in row.values[variable][:3])
        if not (math.isfinite(dy) and math.isfinite(ddy)) or ddy == 0:
            return None
        step = -dy / ddy * rate
        if abs(step) <= 4 * EPS * max(1.0, abs(at)):
            return at, y
        at += step
        if not lo <= at <= hi:
            return None
    return None


def _time_ratio(log: StepLog, result: Result, u: Array, low_at: float, high_at: float) -> float | None:
    """The slower stroke's input angle over the faster's, where one input turns a whole turn,
    every row assembles and the output has one maximum and one minimum a turn."""
    if not _periodic(log) or status.failed(result.status).any():
        return None
    d = np.diff(u[:-1])
    turns = np.count_nonzero(np.sign(d) != np.sign(np.roll(d, 1)))
    if turns != 2:
        return None
    forward = ((high_at - low_at) % 1.0) * TURN
    faster = min(forward, TURN - forward)
    return max(forward, TURN - forward) / faster if faster > 0 else None


def _failures(log: StepLog, result: Result, units: _Units) -> tuple[Failure, ...]:
    st = result.status
    failed = status.failed(st)
    meaning = {c.code: c.meaning for c in log.status_codes}
    out = []
    for code in sorted({int(c) for c in st[failed]}):
        rows = np.flatnonzero(st == code)
        runs = np.split(rows, np.flatnonzero(np.diff(rows) > 1) + 1)
        first = result.inputs[:, 0]
        ranges = tuple((units.input(0, float(first[r[0]])), units.input(0, float(first[r[-1]]))) for r in runs)
        out.append(Failure(code, int(status.step(code)), meaning.get(code, ""), len(rows), ranges))
    return tuple(out)
