"""The LJ-matrix (the paper's Table 1) and its state after each step.

Rows are pairs, columns links after rules (i) and (ii): truss members, input
links and actuators, then the Add-links as they are installed.  An entry is 0
when the pair is not on the link, -1/-2 for a known revolute/prismatic pair and
1/2 for an unknown one.

A step changes only the rows of the pairs it determines and adds the column of
the Add-link it installs, so the states share one record of when each pair
became known and each column came, and a state works out its entries only when
they are read: the states of a long procedure cost one record, not one matrix
per step, and ``change`` gives the rows and columns a step touches.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from functools import cached_property

from .steplog import LJColumn, StepLog

DENSE_COLUMNS = 32  # a matrix this wide or narrower is shown whole; a wider one by its nonzero entries


@dataclass(frozen=True)
class LJTable:
    """Some rows and columns of the LJ-matrix with their entries."""

    columns: tuple[LJColumn, ...]
    rows: tuple[str, ...]
    entries: tuple[tuple[int, ...], ...]


@dataclass(frozen=True)
class History:
    """When each pair became known and each column came, for all the states of a step log."""

    rows: tuple[str, ...]
    slides: frozenset[str]  # the prismatic pairs (entries 2 rather than 1)
    columns: tuple[LJColumn, ...]  # every column, in matrix order
    known: Mapping[str, int]  # pair -> the step that determines it (0: known before step 1)
    installed: Mapping[str, int]  # column -> the step that installs it (0: from the start)

    @cached_property
    def by_step(self) -> dict[int, tuple[list[str], list[int]]]:
        """step -> (the pairs it determines, the indices of the columns it installs)."""
        out: dict[int, tuple[list[str], list[int]]] = {}
        for r, k in self.known.items():
            out.setdefault(k, ([], []))[0].append(r)
        for i, c in enumerate(self.columns):
            out.setdefault(self.installed[c.name], ([], []))[1].append(i)
        return out

    @cached_property
    def on(self) -> dict[str, list[int]]:
        """pair -> the indices of the columns it is on."""
        out: dict[str, list[int]] = {r: [] for r in self.rows}
        for i, c in enumerate(self.columns):
            for p in c.pairs:
                out[p].append(i)
        return out

    @cached_property
    def row_index(self) -> dict[str, int]:
        return {r: i for i, r in enumerate(self.rows)}

    def value(self, row: str, step: int) -> int:
        """The row's entry on the links the pair is on, after the step."""
        value = 2 if row in self.slides else 1
        return -value if self.known.get(row, step + 1) <= step else value

    def entry(self, row: str, column: LJColumn, step: int) -> int:
        return self.value(row, step) if row in column.pairs else 0


@dataclass(frozen=True)
class LJState:
    """The LJ-matrix before step 1 (step 0) or after a step."""

    step: int
    history: History

    @property
    def rows(self) -> tuple[str, ...]:
        return self.history.rows

    @cached_property
    def columns(self) -> tuple[LJColumn, ...]:
        return tuple(c for c in self.history.columns if self.history.installed[c.name] <= self.step)

    @cached_property
    def entries(self) -> tuple[tuple[int, ...], ...]:
        return tuple(tuple(self.history.entry(r, c, self.step) for c in self.columns) for r in self.rows)

    @property
    def dense(self) -> bool:
        """Narrow enough to be read whole (else read it by its nonzero entries)."""
        return len(self.columns) <= DENSE_COLUMNS

    def table(self) -> LJTable:
        return LJTable(self.columns, self.rows, self.entries)

    def nonzero(self) -> list[tuple[str, int, list[str]]]:
        """Row by row, the entry that is not 0 (one per row: a pair is known or not) and the
        columns where it is: (pair, entry, [column, ...]), in matrix order."""
        h = self.history
        out = []
        for r in self.rows:
            names = [c.name for c in (h.columns[i] for i in h.on[r]) if h.installed[c.name] <= self.step]
            out.append((r, h.value(r, self.step) if names else 0, names))
        return out

    def change(self, before: LJState) -> LJTable | None:
        """The rows and columns that differ from ``before``: the rows of the pairs determined
        since, the columns installed since, and the columns and rows those cross that are not
        zero there (None when nothing changed)."""
        h = self.history
        rows: set[str] = set()
        new: set[int] = set()
        for k in range(before.step + 1, self.step + 1):
            determined, installed = h.by_step.get(k, ([], []))
            rows.update(determined)
            new.update(installed)
        if not rows and not new:
            return None
        cols = new | {i for r in rows for i in h.on[r] if h.installed[h.columns[i].name] <= self.step}
        rows |= {p for i in new for p in h.columns[i].pairs}
        columns = tuple(h.columns[i] for i in sorted(cols))
        order = tuple(sorted(rows, key=h.row_index.__getitem__))
        return LJTable(columns, order, tuple(tuple(h.entry(r, c, self.step) for c in columns) for r in order))


def history(log: StepLog) -> History:
    lj = log.lj
    known = dict.fromkeys(lj.known, 0)
    for step in log.steps:
        known.update((p, step.number) for p in step.determines if p not in known)
    added = {a.name: a.step for a in log.add_links}
    base = [c for c in lj.columns if c.kind != "addlink"]
    extra = sorted((c for c in lj.columns if c.name in added), key=lambda c: added[c.name])
    installed = {**dict.fromkeys((c.name for c in base), 0), **{c.name: added[c.name] for c in extra}}
    slides = frozenset(r for r, s in zip(lj.rows, lj.prismatic) if s)
    return History(lj.rows, slides, tuple(base + extra), known, installed)


def states(log: StepLog) -> list[LJState]:
    """The LJ-matrix before step 1 and after every step."""
    h = history(log)
    return [LJState(0, h)] + [LJState(step.number, h) for step in log.steps]


def text(table: LJState | LJTable) -> str:
    """A fixed-width table of a state or of some of its rows and columns."""
    head = [""] + [c.name for c in table.columns]
    body = [[r] + [str(e) for e in es] for r, es in zip(table.rows, table.entries)]
    widths = [max(len(line[i]) for line in [head] + body) for i in range(len(head))]
    lines = ["  ".join(cell.rjust(w) if i else cell.ljust(w) for i, (cell, w) in enumerate(zip(line, widths))).rstrip()
             for line in [head] + body]
    return "\n".join(lines) + "\n"
