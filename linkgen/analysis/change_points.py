"""Change points: input values where a chain's two assemblies cross and the motion goes on.

A change point is a double root of the chain's closing margin (for a 3R chain the Kahan
factor z - (x - y), zero at a toggle): the margin touches zero and comes back, as in a
parallelogram four-bar with all pivots in line.  There the smooth motion continues on
the other branch, so the chain's branch flips at every change point between the sketch
and the input (mechanisms with one input; chains outside resolver groups, whose branch
the resolver reads off each solution instead).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import replace
from functools import partial

import numpy as np

from ..steplog import Step, StepLog
from .sweep import SMALL, TOUCH, closes, local_minima, margin, own, rows, run, span, spanning, vertex, zoom_min

SNAP = 1e-10  # a change point this close to 0, relative to the span, is 0

ChangePoints = tuple[tuple[int, tuple[float, ...]], ...]  # (step, input values), by step


def flipping(step: Step, points: tuple[float, ...]) -> Step:
    """The step whose branch flips at ``points``."""
    note = (f"{step.branch_reason}; the chain passes change points, where its two assemblies cross, at input "
            f"{', '.join(f'{p:.10g}' for p in points)}, and its branch flips at each of them")
    return replace(step, change_points=points, branch_reason=note)


def with_change_points(log: StepLog, found: Mapping[int, tuple[float, ...]]) -> StepLog:
    """The log whose chains flip at the change points found (by step)."""
    if not found:
        return log
    return replace(log, steps=tuple(flipping(s, found[s.number]) if s.number in found else s for s in log.steps))


def change_points(draft: StepLog) -> ChangePoints:
    """The change points of every chain outside the resolver groups with two assemblies,
    each found in its own procedure with the change points of the chains before it."""
    lo, hi, periodic = span(draft)
    grid = np.linspace(0.0, 1.0, rows(draft))
    found: dict[int, tuple[float, ...]] = {}
    for step in draft.steps:
        if step.branch == 0 or step.group:
            continue
        log = own(spanning(with_change_points(draft, found)), step)
        if log.groups:
            continue
        result = run(log, grid)
        m = margin(step, result)
        if m is None:
            continue
        usable = closes(result, step.number - 1) & np.isfinite(m)
        points = []
        for k in local_minima(m, usable, periodic):
            if m[k] > SMALL * draft.length_scale:
                continue
            lam, low = zoom_min(log, grid[k] - grid[1], grid[k] + grid[1], partial(margin, step))
            if abs(low) <= TOUCH * draft.length_scale:
                lam = vertex(log, lam, grid[1] / 8, partial(margin, step))
                value = lo + lam * (hi - lo)
                points.append(0.0 if abs(value) < SNAP * (hi - lo) else float(f"{value:.12g}"))
        if points:
            found[step.number] = tuple(sorted(set(points)))
    return tuple(found.items())
