"""The LJ-matrix (the paper's Table 1) and its state after each step.

Rows are pairs, columns links after rules (i) and (ii): truss members, input
links and actuators, then the Add-links as they are installed.  An entry is 0
when the pair is not on the link, -1/-2 for a known revolute/prismatic pair and
1/2 for an unknown one.
"""

from __future__ import annotations

from dataclasses import dataclass

from .steplog import LJColumn, StepLog


@dataclass(frozen=True)
class LJState:
    step: int  # 0: before the first step
    columns: tuple[LJColumn, ...]
    rows: tuple[str, ...]
    entries: tuple[tuple[int, ...], ...]


def states(log: StepLog) -> list[LJState]:
    """The LJ-matrix before step 1 and after every step."""
    lj = log.lj
    known: set[str] = set(lj.known)
    added = {a.step: a.name for a in log.add_links}
    base = [c for c in lj.columns if c.kind != "addlink"]
    extra = {c.name: c for c in lj.columns if c.kind == "addlink"}
    columns: list[LJColumn] = list(base)
    out = [_state(0, columns, lj.rows, lj.prismatic, known)]
    for step in log.steps:
        known |= set(step.determines)
        if step.number in added:
            columns.append(extra[added[step.number]])
        out.append(_state(step.number, columns, lj.rows, lj.prismatic, known))
    return out


def _state(step: int, columns: list[LJColumn], rows: tuple[str, ...], prismatic: tuple[bool, ...],
           known: set[str]) -> LJState:
    entries = []
    for row, slide in zip(rows, prismatic):
        value = 2 if slide else 1
        sign = -1 if row in known else 1
        entries.append(tuple(sign * value if row in c.pairs else 0 for c in columns))
    return LJState(step, tuple(columns), rows, tuple(entries))


def text(state: LJState) -> str:
    """A fixed-width table of one state."""
    head = [""] + [c.name for c in state.columns]
    body = [[r] + [str(e) for e in es] for r, es in zip(state.rows, state.entries)]
    widths = [max(len(line[i]) for line in [head] + body) for i in range(len(head))]
    lines = ["  ".join(cell.rjust(w) if i else cell.ljust(w) for i, (cell, w) in enumerate(zip(line, widths))).rstrip()
             for line in [head] + body]
    return "\n".join(lines) + "\n"
