"""The sweep the plots and the page show: the file's rows evaluated in-process.

The output columns are the CSV's (linkgen.table: failed rows nan, rates nan at singular
rows); the positions of every pair and point the procedure computes (fixed ones as
drawn) are there for drawing the mechanism, with nan where a row failed.  ``file_rows``
evaluates the file's sweep once for a build: the engineering summary (linkgen.summary, with the
reference settings) and the plots (with the log's: the same unless the file or the command line
changes the resolver's iteration or the checks) read one result, and the conditioning over the
sweep (linkgen.analysis, of the whole procedure) reads it too where no step was pruned.  ``thin`` keeps
a long sweep's figures and page to a size a reader opens: every k-th row, and the first and
last row of every run of rows with a nan, so that every gap stays a gap.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, replace

import numpy as np

from . import status
from .evaluate import Result, evaluate
from .rows import input_rows
from .steplog import StepLog
from .table import columns


@dataclass(frozen=True)
class Sweep:
    names: tuple[str, ...]  # the CSV's columns (inputs first), without status
    data: np.ndarray  # rows x columns, as the CSV has them
    status: np.ndarray  # the row status codes
    sigma: dict[int, np.ndarray]  # step -> conditioning per row (nan where the step did not run)
    places: dict[str, tuple[np.ndarray, np.ndarray]]  # pair or point -> x and y per row (nan: failed)
    index: np.ndarray  # the file's row number of each row

    @property
    def rows(self) -> int:
        return int(self.data.shape[0])

    def column(self, name: str) -> np.ndarray:
        out: np.ndarray = self.data[:, self._index[name]]
        return out

    @functools.cached_property
    def _index(self) -> dict[str, int]:
        """Each column's place (names.index scans them: the plots of a 1000-dyad chain read 48,000)."""
        return {name: k for k, name in reversed(list(enumerate(self.names)))}


def file_rows(log: StepLog) -> Result:
    """The file's sweep (its samples, all inputs together, the CSV's rows; with ``sweep: grid``
    the inputs together still, the diagonal the plots and summary follow) evaluated at the log's
    order with its settings: once for the steps and settings asked for last.  The conditioning
    over the sweep (linkgen.analysis), the summary and the plots of a build read the one result
    where their logs compute the same steps with the same settings (the facts found from it, the
    manual's centres and the assemblies listed at the sketch do not change it).  A result is read,
    never changed."""
    return _rows(replace(log, conditioning=(), centres=(), summary=None, assemblies=None))


@functools.lru_cache(maxsize=1)
def _rows(log: StepLog) -> Result:
    values, rates, accs = input_rows(log, log.samples, grid=False)  # a grid's plots: its together sweep
    with np.errstate(all="ignore"):
        return evaluate(log, values, rates, accs)


def sweep_of(log: StepLog) -> Sweep:
    """The file's sweep (its samples), evaluated at the log's order."""
    result = file_rows(log)
    values = result.inputs
    names, data = columns(log, result)
    failed = status.failed(result.status)
    places: dict[str, tuple[np.ndarray, np.ndarray]] = {}
    for v in log.variables:
        if v.role not in ("pair", "point") or v.kind != "POINT":
            continue
        if v.constant:
            x, y = (np.full(values.shape[0], float(c)) for c in v.value[:2])
        elif v.name in result.values:
            x, y = (np.where(failed, np.nan, result.values[v.name][k] + log.origin[k]) for k in (0, 1))
        else:
            continue
        places[v.entity] = (x, y)
    at = status.step(result.status)
    sigma = {n: np.where(failed & (n >= at), np.nan, s) for n, s in result.sigma.items()}  # a failed step: a gap
    return Sweep(tuple(names), data, result.status.copy(), sigma, places, np.arange(values.shape[0]))


MAX_ROWS = 1441  # rows drawn at most (a sweep of 0.25 degrees over a turn is drawn whole)


def thin(sweep: Sweep, limit: int = MAX_ROWS) -> Sweep:
    """The sweep at every k-th row (k the least that keeps about ``limit`` rows), the last row,
    and the rows that bound a run of rows with a nan anywhere (so no curve is drawn across a
    row that has none); the sweep itself when it is not longer than ``limit``."""
    if sweep.rows <= limit:
        return sweep
    stride = -(-(sweep.rows - 1) // (limit - 1))
    keep = np.zeros(sweep.rows, dtype=bool)
    keep[::stride] = True
    keep[-1] = True
    blank = ~np.isfinite(sweep.data).all(axis=1)
    for s in sweep.sigma.values():
        blank |= ~np.isfinite(s)
    for x, y in sweep.places.values():
        blank |= ~(np.isfinite(x) & np.isfinite(y))
    edge = blank & ~(np.concatenate([[False], blank[:-1]]) & np.concatenate([blank[1:], [False]]))
    keep |= edge
    return Sweep(sweep.names, sweep.data[keep], sweep.status[keep], {n: s[keep] for n, s in sweep.sigma.items()},
                 {n: (x[keep], y[keep]) for n, (x, y) in sweep.places.items()}, sweep.index[keep])
