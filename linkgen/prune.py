"""Backward slice of the step log: keep only the steps the chosen outputs depend on.

A step is kept when a kept step or an output column reads what it writes.  A resolver
group is kept whole (its Add-link, the steps it iterates, its fallback blocks) when,
and only when, something kept reads what it computes.  Kept steps keep their numbers,
so status codes and the manual's step numbers mean the same in every build.

A step's motion facts (change points, gaps, conditioning) depend only on the steps it
reads from, so the kept steps keep theirs; the reach is their gaps' (see
``motion.reach_between``), or, while a resolver group is kept, the resolver's.
"""

from __future__ import annotations

from dataclasses import replace

from .motion import reach_between
from .steplog import Omitted, Step, StepLog


def _reads(step: Step) -> set[str]:
    return {a.var for a in step.args if a.kind == "var"}


def _needed(log: StepLog, names: set[str]) -> tuple[set[int], set[int]]:
    """The steps, and the resolver groups, that compute ``names``."""
    groups = {g.number: g for g in log.groups}
    needed = set(names)
    kept_groups: set[int] = set()
    kept: set[int] = set()
    for s in reversed([s for s in log.steps if not s.variant]):
        if s.action == "resolve":
            g = groups[s.group]
            blocks = (g, *g.variants)
            if not needed & {name for b in blocks for name in b.writes}:
                continue
            kept_groups.add(g.number)
            for b in blocks:
                needed |= set(b.reads)
        elif s.group:
            if s.group not in kept_groups:
                continue
        elif s.outputs and not needed & set(s.outputs):
            continue
        kept.add(s.number)
        if not s.group:
            needed |= _reads(s)
    return kept, kept_groups


def keep(log: StepLog, names: set[str]) -> StepLog:
    """The step log with only the steps that compute ``names`` (unchanged when all do)."""
    kept, kept_groups = _needed(log, names)
    if len(kept) == sum(1 for s in log.steps if not s.variant):
        return log
    steps = tuple(s for s in log.steps if s.number in kept or (s.variant and s.group in kept_groups))
    numbers = {s.number for s in steps}
    used = {name for s in steps for name in (*_reads(s), *s.outputs)} | {c.variable for c in log.columns}
    gaps = tuple(g for g in log.gaps if g.step in numbers)
    groups = tuple(g for g in log.groups if g.number in kept_groups)
    periodic = bool(log.inputs) and log.inputs[0].kind == "revolute"
    return replace(
        log,
        variables=tuple(v for v in log.variables if v.name in used or v.role in ("input", "point")),
        steps=steps,
        add_links=tuple(a for a in log.add_links if a.step in numbers),
        residuals=tuple(r for r in log.residuals if r.step in numbers),
        groups=groups,
        conditioning=tuple(c for c in log.conditioning if c.step in numbers),
        omitted=tuple(Omitted(s.number, s.target) for s in log.steps if not s.variant and s.number not in kept),
        reach=log.reach if groups else reach_between(gaps, log.inputs[0].sketch, periodic) if gaps else None,
        gaps=gaps,
    )


def prune(log: StepLog) -> StepLog:
    """The step log with only the steps its columns need (unchanged when all are needed)."""
    return keep(log, {c.variable for c in log.columns})
