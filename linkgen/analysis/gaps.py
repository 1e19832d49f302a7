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

from ..motion import Gap
from ..steplog import Step, StepLog
from .sweep import TOUCH, Zoom, local_minima, margin, own, rows, span, spanning, zoom_edge, zoom_mins
from .union import Readers, Union

TWO_ASSEMBLIES = ("RRR_links", "PRR_links", "RPR_links")  # the chains margin() measures


def gaps(log: StepLog) -> tuple[Gap, ...]:
    """Every gap of every chain outside the resolver groups with two assemblies, by step (a
    dip found from two rows, once); the chains searched together (see union)."""
    grid = np.linspace(0.0, 1.0, rows(log) | 1)
    spanned = spanning(log)
    readers = Readers(spanned)
    chains = [s for s in log.steps if not s.group and s.function in TWO_ASSEMBLIES and not readers.grouped(s)]
    if not chains:
        return ()
    union = Union(spanned, chains, grid, readers)
    lo, hi, periodic = span(log)
    scale = log.length_scale
    found = {step.number: _runs(union, step) for step in chains}
    dips = []
    for step in chains:
        m = margin(step, union.result)
        assert m is not None
        dips += [Zoom(step, grid[k] - grid[1], grid[k] + grid[1], partial(margin, step),
                      (-np.inf, -TOUCH * scale), TOUCH * scale)
                 for k in local_minima(m, union.closes(step, step.number) & np.isfinite(m), periodic)]
    for z, (deepest, low) in zip(dips, zoom_mins(union.log, dips)):
        if low < -TOUCH * scale:
            value = float(lo + deepest * (hi - lo))
            found[z.step.number].append(Gap(z.step.number, value, value))
    return tuple(dict.fromkeys(g for step in chains for g in found[step.number]))


def _runs(union: Union, step: Step) -> list[Gap]:
    """The runs of rows where ``step`` fails first in its own procedure."""
    lo, hi, periodic = span(union.whole)
    grid = union.grid
    fails = union.fails_first(step)
    if not fails.any():
        return []
    n = len(grid) - 1 if periodic else len(grid)  # a full turn: the last row is the first

    def value(lam: float) -> float:
        return float(lo + lam * (hi - lo))

    def lam(j: int) -> float:  # grid position of row j, counted on past the end of a turn
        return float(grid[j % n] + j // n)

    procedure = own(union.whole, step)

    def edge(good: int, bad: int) -> float:  # the last value from row good towards row bad that closes
        return value(zoom_edge(procedure, lam(good), lam(bad), step.number, 0.0)[0])

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
    return out
