"""The chains' own procedures swept together: one evaluation of their union.

What a chain finds holds in every procedure that contains it, so each chain is searched in
its own procedure (``sweep.own``: it and the steps it reads from).  Evaluating each of those
is quadratic in a chain of N chains; their union is evaluated once instead.  A chain's
values are the same there (a step's values depend only on the steps it reads from); where
its own procedure closes is read off the union's row status, the first step that fails: a
row that fails first at a step of the chain's own procedure, or past the step asked about,
says the same of the chain's own procedure.  Only a row that fails first at a step outside
it, before the step asked about, could say otherwise; then the chain's own procedure is
evaluated after all.
"""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np

from .. import status
from ..evaluate import Result
from ..prune import keep
from ..steplog import Step, StepLog
from .sweep import Array, closes, own, run


class Readers:
    """Which steps read from which, in a step log (steps outside resolver groups)."""

    def __init__(self, log: StepLog):
        self.log = log
        self._readers: dict[str, list[int]] = {}
        grouped = {name for s in log.steps if s.group or s.variant for name in s.outputs}
        grouped |= {name for g in log.groups for b in (g, *g.variants) for name in b.writes}
        self._grouped: set[int] = set()
        for s in log.steps:
            if s.group or s.variant:
                continue
            reads = {a.var for a in s.args if a.kind == "var"}
            for name in reads:
                self._readers.setdefault(name, []).append(s.number)
            if reads & grouped:  # reads from a resolver group, or from a step that does
                self._grouped.add(s.number)
                grouped |= set(s.outputs)
        self._after: dict[int, frozenset[int]] = {}

    def grouped(self, step: Step) -> bool:
        """Whether the step's own procedure holds a resolver group."""
        return step.number in self._grouped

    def after(self, number: int) -> frozenset[int]:
        """The steps whose own procedure holds step ``number`` (it included)."""
        if number not in self._after:
            found, todo = {number}, [number]
            while todo:
                for name in self.log.step(todo.pop()).outputs:
                    for reader in self._readers.get(name, ()):
                        if reader not in found:
                            found.add(reader)
                            todo.append(reader)
            self._after[number] = frozenset(found)
        return self._after[number]


class Union:
    """The union of the own procedures of ``chains`` (steps of ``log`` whose own procedures
    hold no resolver group), evaluated at sweep positions ``grid``."""

    def __init__(self, log: StepLog, chains: Iterable[Step], grid: Array, readers: Readers | None = None):
        self.whole, self.grid = log, grid
        self.readers = readers or Readers(log)
        self.log = keep(log, {name for s in chains for name in s.outputs})
        assert not self.log.groups, "a chain whose own procedure holds a resolver group"
        self.result = run(self.log, grid)
        st = self.result.status
        self._first: Array = np.where(status.failed(st), status.step(st), 0)
        self._own: dict[int, Result] = {}

    def _outside(self, step: Step, before: int) -> tuple[Array, Array]:
        """(rows that fail first at a step of the chain's own procedure numbered at most
        ``before``, rows that fail first at a step outside it numbered at most ``before``)."""
        first = self._first
        early = (first > 0) & (first <= before)
        inside = np.zeros(len(first), dtype=bool)
        for number in sorted(set(first[early].tolist())):  # not np.unique: it imports numpy.ma (7 ms)
            if step.number in self.readers.after(number):
                inside |= first == number
        return early & inside, early & ~inside

    def own_result(self, step: Step) -> Result:
        """The chain's own procedure evaluated at the grid."""
        if step.number not in self._own:
            self._own[step.number] = run(own(self.whole, step), self.grid)
        return self._own[step.number]

    def closes(self, step: Step, through: int) -> Array:
        """Rows where the chain's own procedure gets past step ``through``."""
        inside, outside = self._outside(step, through)
        if outside.any():
            return closes(self.own_result(step), through)
        out: Array = ~inside
        return out

    def fails_first(self, step: Step) -> Array:
        """Rows where the chain is the first step of its own procedure to fail."""
        if self._outside(step, step.number - 1)[1].any():
            st = self.own_result(step).status
            mine: Array = status.failed(st) & (status.step(st) == step.number)
            return mine
        out: Array = self._first == step.number
        return out
