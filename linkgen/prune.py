"""Backward slice of the step log: keep only the steps the chosen outputs depend on.

A step is kept when a kept step or an output column reads what it writes.  A resolver
group is kept whole (its Add-link, the steps it iterates, its fallback blocks) when,
and only when, something kept reads what it computes.  Kept steps keep their numbers,
so status codes and the manual's step numbers mean the same in every build.
"""

from __future__ import annotations

from dataclasses import replace

from .steplog import Omitted, StepLog


def _reads(step) -> set[str]:
    return {a.var for a in step.args if a.kind == "var"}


def prune(log: StepLog) -> StepLog:
    """The step log with only the steps its columns need (unchanged when all are needed)."""
    groups = {g.number: g for g in log.groups}
    needed = {c.variable for c in log.columns}
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
    if len(kept) == sum(1 for s in log.steps if not s.variant):
        return log
    steps = tuple(s for s in log.steps if s.number in kept or (s.variant and s.group in kept_groups))
    omitted = tuple(Omitted(s.number, s.target) for s in log.steps if not s.variant and s.number not in kept)
    used = {name for s in steps for name in (*_reads(s), *s.outputs)} | {c.variable for c in log.columns}
    runtime = {s.function for s in steps if s.function}
    if kept_groups:
        runtime |= {"resolver", "link_residual"}
    if any(s.change_points for s in steps):
        runtime.add("branch_at")
    numbers = {s.number for s in steps}
    return replace(
        log,
        variables=tuple(v for v in log.variables if v.name in used or v.role in ("input", "point")),
        steps=steps,
        add_links=tuple(a for a in log.add_links if a.step in numbers),
        residuals=tuple(r for r in log.residuals if r.step in numbers),
        groups=tuple(g for g in log.groups if g.number in kept_groups),
        status_codes=tuple(c for c in log.status_codes if not c.step or c.step in numbers),
        runtime=tuple(sorted(runtime)),
        omitted=omitted,
    )
