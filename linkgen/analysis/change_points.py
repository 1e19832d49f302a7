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
from .sweep import SMALL, TOUCH, Array, Zoom, at_once, local_minima, margin, rows, span, spanning, zoom_mins
from .union import Readers, Union

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
    each found in its own procedure with the change points of the chains before it.

    The chains are searched together (see union), with the change points found so far; a
    chain that reads from one whose change points were found along with it is searched
    again, with them."""
    grid = np.linspace(0.0, 1.0, rows(draft))
    readers = Readers(draft)
    pending = [s for s in draft.steps if s.branch != 0 and not s.group and not readers.grouped(s)]
    found: dict[int, tuple[float, ...]] = {}
    while pending:
        new = _search(Union(spanning(with_change_points(draft, found)), pending, grid, readers), pending)
        stale = {n for number in new for n in readers.after(number) if n != number}
        found.update((n, points) for n, points in new.items() if n not in stale)
        pending = [s for s in pending if s.number in stale]
    return tuple(sorted(found.items()))


def _search(union: Union, chains: list[Step]) -> dict[int, tuple[float, ...]]:
    """The change points of the chains, each in its own procedure as the union has it."""
    lo, hi, periodic = span(union.log)
    grid, scale = union.grid, union.log.length_scale
    zooms = []
    for step in chains:
        m = margin(step, union.result)
        if m is None:
            continue
        usable = union.closes(step, step.number - 1) & np.isfinite(m)
        zooms += [Zoom(step, grid[k] - grid[1], grid[k] + grid[1], partial(margin, step),
                       (-TOUCH * scale, TOUCH * scale), TOUCH * scale)
                  for k in local_minima(m, usable, periodic) if m[k] <= SMALL * scale]
    touching = [(z, lam) for z, (lam, low) in zip(zooms, zoom_mins(union.log, zooms)) if abs(low) <= TOUCH * scale]
    delta = grid[1] / 8
    found: dict[int, list[float]] = {}
    at = at_once(union.log, [(z.step, np.array([lam - delta, lam, lam + delta]), z.value) for z, lam in touching])
    for (z, lam), v in zip(touching, at):
        assert v is not None
        value = lo + _vertex(lam, delta, v) * (hi - lo)
        found.setdefault(z.step.number, []).append(0.0 if abs(value) < SNAP * (hi - lo) else float(f"{value:.12g}"))
    return {n: tuple(sorted(set(points))) for n, points in found.items()}


def _vertex(lam: float, delta: float, v: Array) -> float:
    """The vertex of the parabola through v at lam - delta, lam, lam + delta.

    A double root's margin is smooth and quadratic: its vertex locates the root to
    rounding / (curvature * delta), where the minimum itself is only good to sqrt(eps).
    """
    lo, mid, hi = (float(x) for x in v)
    curve = lo - 2 * mid + hi
    return lam if not curve > 0 else lam + delta * (lo - hi) / (2 * curve)
