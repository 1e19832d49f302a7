"""The sweep the plots and the page show: the file's rows evaluated in-process.

The output columns are the CSV's (linkgen.table: failed rows nan, rates nan at singular
rows); the positions of every pair and point the procedure computes (fixed ones as
drawn) are there for drawing the mechanism, with nan where a row failed.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import status
from .evaluate import evaluate, input_rows
from .steplog import StepLog
from .table import columns


@dataclass(frozen=True)
class Sweep:
    names: tuple[str, ...]  # the CSV's columns (inputs first), without status
    data: np.ndarray  # rows x columns, as the CSV has them
    status: np.ndarray  # the row status codes
    sigma: dict[int, np.ndarray]  # step -> conditioning per row (nan where the step did not run)
    places: dict[str, tuple[np.ndarray, np.ndarray]]  # pair or point -> x and y per row (nan: failed)

    @property
    def rows(self) -> int:
        return int(self.data.shape[0])

    def column(self, name: str) -> np.ndarray:
        out: np.ndarray = self.data[:, self.names.index(name)]
        return out


def sweep_of(log: StepLog) -> Sweep:
    """The file's sweep (its samples), evaluated at the log's order."""
    values, rates, accs = input_rows(log, log.samples)
    result = evaluate(log, values, rates, accs)
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
    return Sweep(tuple(names), data, result.status.copy(), sigma, places)
