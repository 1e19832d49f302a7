"""Gaps: where a chain with two assemblies cannot close, over the span of the one input.

Each chain outside the resolver groups is searched in its own procedure (it and the steps
it reads from), so what is found holds in every procedure that contains the chain: rows
where it is the first step to fail make runs, whose ends are located by root finding
(of a run cut by a sliding input's span, its failing row next to the rows that close),
and where its closing margin dips below zero between two rows that close, the deepest
point is a gap of its own.  A chain with one assembly (PRP, PPR) fails only where it is
singular, and passes through.
"""

from __future__ import annotations

from functools import partial

import numpy as np

from .. import status
from ..motion import Gap
from ..steplog import Step, StepLog
from .sweep import TOUCH, Array, closes, local_minima, margin, own, rows, run, span, spanning, zoom_edge, zoom_min

TWO_ASSEMBLIES = ("RRR_links", "PRR_links", "RPR_links")  # the chains margin() measures


def gaps(log: StepLog) -> tuple[Gap, ...]:
    """Every gap of every chain outside the resolver groups with two assemblies, by step (a
    dip found from two rows, once)."""
    grid = np.linspace(0.0, 1.0, rows(log) | 1)
    spanned = spanning(log)
    out: list[Gap] = []
    for step in log.steps:
        if step.group or step.function not in TWO_ASSEMBLIES:
            continue
        procedure = own(spanned, step)
        if not procedure.groups:
            out += _gaps(procedure, step, grid)
    return tuple(dict.fromkeys(out))


def _gaps(log: StepLog, step: Step, grid: Array) -> list[Gap]:
    """The runs of rows where ``step`` fails first, then the dips of its margin."""
    lo, hi, periodic = span(log)
    result = run(log, grid)
    st = result.status
    fails = status.failed(st) & (status.step(st) == step.number)
    n = len(grid) - 1 if periodic else len(grid)  # a full turn: the last row is the first

    def value(lam: float) -> float:
        return float(lo + lam * (hi - lo))

    def lam(j: int) -> float:  # grid position of row j, counted on past the end of a turn
        return float(grid[j % n] + j // n)

    def edge(good: int, bad: int) -> float:  # the last value from row good towards row bad that closes
        return value(zoom_edge(log, lam(good), lam(bad), step.number, 0.0)[0])

    out = []
    for k in range(n):
        if not fails[k] or (fails[(k - 1) % n] if periodic else k > 0 and fails[k - 1]):
            continue  # not the first row of a run of failing rows
        end = k
        while fails[(end + 1) % n] and (end + 1 < k + n if periodic else end + 1 < n):
            end += 1
        opens, ends = periodic or k > 0, periodic or end < n - 1  # whether the run has each end in the span
        if opens and ends:
            out.append(Gap(step.number, edge(k - 1, k), edge(end + 1, end)))
        else:
            out.append(Gap(step.number, value(lam(k)), None) if opens else Gap(step.number, None, value(lam(end))))
    m = margin(step, result)
    assert m is not None
    for k in local_minima(m, closes(result, step.number) & np.isfinite(m), periodic):
        deepest, low = zoom_min(log, grid[k] - grid[1], grid[k] + grid[1], partial(margin, step))
        if low < -TOUCH * log.length_scale:
            out.append(Gap(step.number, value(deepest), value(deepest)))
    return out
