"""Every step's conditioning over the sweep, and the input values where it reaches zero.

Along the sweep (all inputs moving together, lambda from 0 to 1: the file's rows, as the CSV
has them, evaluated once for the summary and the plots too, linkgen.sweepdata.file_rows) every
step's conditioning is recorded; where a chain reaches a singular position the input value is
located by zooming in on it: a limit position (the chain cannot close beyond it), a
change point (its two assemblies cross and the motion goes on), or a near-singular
minimum.
"""

from __future__ import annotations

from functools import partial

import numpy as np

from ..evaluate import Result, reach_side
from ..motion import Conditioning, Singular
from ..primitives import PRIMITIVES
from ..steplog import StepLog
from ..sweepdata import file_rows
from .sweep import SMALL, Array, Zoom, closes, local_minima, warm_after, zoom_edge, zoom_min, zoom_mins


def conditioning(log: StepLog) -> tuple[Conditioning, ...]:
    """The conditioning of every step that has one, over the log's sweep (its change points
    and reach found); without resolvers the minima of all steps are zoomed in on together."""
    grid = np.linspace(0.0, 1.0, log.samples)
    result = file_rows(log)
    inner = {n for g in log.groups for b in (g, *g.variants) for n in b.steps}
    steps: list[tuple[int, Array, list[Singular]]] = []  # (step, its usable sigma, what it passes)
    zooms, warms, owners = [], [], []
    for number in sorted(result.sigma):
        step = log.step(number)
        if step.action != "resolve" and PRIMITIVES[step.function].sigma is None:
            continue
        sigma = result.sigma[number]
        fine = closes(result, number)
        usable = fine & np.isfinite(sigma)
        if not usable.any():
            continue
        found = [Singular((p,), "change point", 0.0) for p in step.change_points]
        # a resolver block's chain fails only as its group does: the group's step has the limit
        edges = np.flatnonzero((usable[:-1] != usable[1:]) & (fine[:-1] != fine[1:])) if number not in inner else ()
        for k in (int(k) for k in edges):
            found.append(_limit(log, result, grid, k if usable[k] else k + 1, k + 1 if usable[k] else k, number))
        for k in local_minima(sigma, usable):
            if sigma[k] < SMALL and not step.change_points:
                zooms.append(Zoom(step, grid[k - 1], grid[k + 1], partial(_sigma, number)))
                warms.append(warm_after(result, k - 1))
                owners.append(len(steps))
        steps.append((number, sigma[usable], found))
    lows = (zoom_mins(log, zooms) if not log.groups
            else [zoom_min(log, z.lo, z.hi, z.value, warm) for z, warm in zip(zooms, warms)])
    for owner, (lam, low) in zip(owners, lows):
        steps[owner][2].append(Singular(_input_values(log, lam), "minimum", float(f"{low:.3g}")))
    return tuple(Conditioning(number, float(f"{sigma.min():.3g}"), float(f"{sigma.max():.3g}"),
                              tuple(sorted(found, key=lambda s: s.inputs)))
                 for number, sigma, found in steps)


def _limit(log: StepLog, result: Result, grid: Array, good: int, bad: int, number: int) -> Singular:
    """The limit position of step number between sweep rows good (it closes) and bad."""
    lam = _reach_limit(log, float(grid[good]), float(grid[bad]))
    if lam is not None:  # located when the reach was: sigma is 0 there
        return Singular(_input_values(log, lam), "limit", 0.0)
    lam, s = zoom_edge(log, float(grid[good]), float(grid[bad]), number, float(result.sigma[number][good]),
                       warm_after(result, good))
    return Singular(_input_values(log, lam), "limit", float(f"{s:.3g}"))


def _sigma(number: int, result: Result) -> Array | None:
    return result.sigma.get(number)


def _input_values(log: StepLog, lam: float) -> tuple[float, ...]:
    return tuple(float(f"{i.start + lam * (i.stop - i.start):.10g}") for i in log.inputs)


def _reach_limit(log: StepLog, good: float, bad: float) -> float | None:
    """The sweep position of the resolver mechanism's limit position between sweep positions
    good (reached) and bad (past the reach), or None (no resolver, or the reach not between)."""
    reach = log.reach
    if not log.groups or reach is None or log.inputs[0].start == log.inputs[0].stop:
        return None
    inp = log.inputs[0]
    before, after = (inp.start + lam * (inp.stop - inp.start) for lam in (good, bad))
    if reach_side(reach, np.array([before]))[0] or not reach_side(reach, np.array([after]))[0]:
        return None
    bound = reach.high if after > before else reach.low
    assert bound is not None, "a row past a side of the reach that has no bound"
    if reach.periodic and reach.low is not None:  # the bound's turn between the two
        bound += 2 * np.pi * np.floor((before - reach.low) / (2 * np.pi))
    return float((bound - inp.start) / (inp.stop - inp.start))
