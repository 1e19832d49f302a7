"""Every step's conditioning over the sweep, and the input values where it reaches zero.

Along the sweep (all inputs moving together, lambda from 0 to 1) every step's
conditioning is recorded; where a chain reaches a singular position the input value is
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
from .sweep import SMALL, Array, closes, local_minima, run, warm_after, zoom_edge, zoom_min


def conditioning(log: StepLog) -> tuple[Conditioning, ...]:
    """The conditioning of every step that has one, over the log's sweep (its change points
    and reach found)."""
    grid = np.linspace(0.0, 1.0, log.samples)
    result = run(log, grid)
    inner = {n for g in log.groups for b in (g, *g.variants) for n in b.steps}
    out = []
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
        for k in range(len(grid) - 1):
            # a resolver block's chain fails only as its group does: the group's step has the limit
            if usable[k] != usable[k + 1] and fine[k] != fine[k + 1] and number not in inner:
                found.append(_limit(log, result, grid, k if usable[k] else k + 1, k + 1 if usable[k] else k, number))
        for k in local_minima(sigma, usable):
            if sigma[k] >= SMALL or step.change_points:
                continue
            lam, low = zoom_min(log, grid[k - 1], grid[k + 1], partial(_sigma, number),
                                warm_after(result, k - 1))
            found.append(Singular(_input_values(log, lam), "minimum", float(f"{low:.3g}")))
        found.sort(key=lambda s: s.inputs)
        out.append(Conditioning(number, float(f"{sigma[usable].min():.3g}"), float(f"{sigma[usable].max():.3g}"),
                                tuple(found)))
    return tuple(out)


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
