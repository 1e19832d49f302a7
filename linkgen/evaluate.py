"""Stage 6: evaluate a step log in-process.

Mechanisms without Add-links are evaluated for all rows at once by the log's vectorised
kernel, the numpy backend's NAME_np.py run in-process (linkgen.kernel).
Mechanisms with Add-links are evaluated row by row by the Python runtime the generated
programs carry, run on the step log by ``linkgen.rowsolver.RowSolver``.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from . import status
from .kernel import Records, column, kernel
from .kernel import runtime as numpy_runtime
from .primitives.dsl import record_fields
from .steplog import Reach, StepLog

if TYPE_CHECKING:  # the row solver: imported where a log has resolver groups
    from .rowsolver import Row

BLOCK = 16384  # rows of a chain mechanism evaluated at once (the numpy kernel's own block: solve's)


def reach_side(reach: Reach, theta: Any) -> Any:
    """The numpy runtime's reach_at at every input value of an array: 0 where it is reached
    from the sketch, -1 past the gap below, 1 past the gap above."""
    from .rowsolver import bounds

    side = numpy_runtime()["reach_at"](np.asarray(theta, dtype=float), *bounds(reach), reach.periodic)
    return np.asarray(side, dtype=int)


@dataclass
class Result:
    inputs: np.ndarray  # rows x inputs
    values: Mapping[str, tuple[np.ndarray, ...]]  # variable -> its fields per row (points relative to the origin)
    status: np.ndarray
    sigma: dict[int, np.ndarray]  # step -> conditioning per row
    iterations: dict[int, np.ndarray] = field(default_factory=dict)  # group -> Newton steps per row
    warm: list[Any] = field(default_factory=list)  # resolver warm start after each row (None where it failed)


def evaluate(log: StepLog, values: np.ndarray, rates: np.ndarray, accs: np.ndarray, order: int | None = None,
             warm: Any = None, stop: int = 0, line: int = 0) -> Result:
    """Evaluate the procedure at rows of input values, rates and accelerations.

    With resolvers the rows are solved in order, the first from ``warm`` (a previous
    result's warm start) when given, else from the sketch, and every ``line``-th row
    from the sketch again (line_length; 0: never); ``stop`` (a step number)
    leaves the rows after the first one that fails at or before that step unsolved (nan).
    """
    order = log.order if order is None else order
    if log.groups:
        return _evaluate_rows(log, values, rates, accs, order, warm, stop, line)
    module = kernel(log, order, outputs=False)
    rows = values.shape[0]
    blocks, codes, sigmas = [], [], []
    with np.errstate(all="ignore"):
        for lo in range(0, max(rows, 1), BLOCK):  # a block's arrays stay in the cache: 3-4.7x faster at 1e6 rows
            hi = min(lo + BLOCK, rows)
            w, code, sigma = module._run(list(values[lo:hi].T), list(rates[lo:hi].T), list(accs[lo:hi].T),
                                         dict(module.PARAMS))
            blocks.append((vars(w), hi - lo))
            codes.append(np.broadcast_to(np.asarray(code, dtype=int), (hi - lo,)))
            sigmas.append(sigma)
    steps = [s.number for s in log.steps if s.function]
    if len(blocks) == 1:
        return Result(values, Records(blocks), codes[0].copy(), {n: column(sigmas[0][n], rows) for n in steps})
    return Result(values, Records(blocks), np.concatenate(codes),
                  {n: np.concatenate([column(s[n], b) for s, (_, b) in zip(sigmas, blocks)]) for n in steps})


def _evaluate_rows(log: StepLog, values: np.ndarray, rates: np.ndarray, accs: np.ndarray, order: int, warm: Any,
                   stop: int, line: int) -> Result:
    from .rowsolver import Row
    from .rowsolver import solver as row_solver

    solver = row_solver(log, max(order, 1))  # the resolver's rates start the next row at every order
    solver.warm = warm
    rows: list[Row] = []
    warms: list[Any] = []
    for r in range(values.shape[0]):
        if line and r and r % line == 0:
            solver.warm = None
        failed = {n: rep for n, rep in rows[-1].report.items() if rep[0] in status.FAILED} if rows and stop else {}
        stopped = any(n <= stop for n in failed)
        rows.append(Row({}, failed, {}, rows[-1].code) if stopped else solver.solve(values[r], rates[r], accs[r]))
        warms.append(None if stopped else solver.warm)
    width = {kind: len(record_fields(kind, order)) for kind in {v.kind for v in log.variables}}  # a few kinds
    env = RowRecords(rows, {v.name: width[v.kind] for v in log.variables})
    numbers = sorted({n for row in rows for n in row.report})
    sigma = {n: np.array([row.report.get(n, (0, math.nan))[1] for row in rows], dtype=float) for n in numbers}
    its = {g.number: np.array([row.iterations.get(g.number, 0) for row in rows], dtype=int) for g in log.groups}
    codes = np.array([row.code for row in rows], dtype=int)
    if not log.options.checks:  # as the programs built without checks: a failure's code or 0
        codes = np.where(status.failed(codes), codes, 0)
    return Result(values, env, codes, sigma, its, warms)


class RowRecords(Mapping[str, tuple[np.ndarray, ...]]):
    """The rows' records as a result holds them: each variable's fields as arrays of the rows (nan
    where a row has none), made when first read (the summary's single rows read one or two of a
    hundred variables)."""

    def __init__(self, rows: list[Row], widths: dict[str, int]):
        self._rows, self._widths = rows, widths
        self._made: dict[str, tuple[np.ndarray, ...]] = {}

    def __getitem__(self, name: str) -> tuple[np.ndarray, ...]:
        if name not in self._made:
            nan = (math.nan,) * self._widths[name]
            self._made[name] = tuple(np.array([row.env.get(name, nan)[i] for row in self._rows], dtype=float)
                                     for i in range(len(nan)))
        return self._made[name]

    def __iter__(self) -> Iterator[str]:
        return iter(sorted(self._widths))

    def __len__(self) -> int:
        return len(self._widths)
