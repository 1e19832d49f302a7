"""The sweep's rows: each row's input values, rates and accelerations, as every program's driver
makes them (together or on a grid), and the lines a grid restarts its resolver at."""

from __future__ import annotations

import numpy as np

from .steplog import StepLog


def input_rows(log: StepLog, samples: int, sweep: dict[str, list[float]] | None = None,
               grid: bool | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The sweep's input values, rates (each input's speed) and accelerations (0), row by row:
    together, row k sets every input to start + k (stop - start) / (samples - 1); on a grid
    (``grid``, default the log's sweep) every combination of the inputs' samples values, the
    first input varying slowest (row k has input m at index k // samples**(n-1-m) % samples).
    ``sweep``: each input's start, stop and speed as the programs take them (units.sweep_lists;
    default the log's, in radians and length units)."""
    grid = log.sweep == "grid" if grid is None else grid
    s = sweep or {key: [getattr(i, key) for i in log.inputs] for key in ("start", "stop", "speed")}
    n = len(log.inputs)
    rows = samples ** n if grid else samples
    k = np.arange(rows)
    index = [(k // samples ** (n - 1 - m) % samples if grid else k).astype(float) for m in range(n)]
    values = np.stack([a + j * (b - a) / (samples - 1) for a, b, j in zip(s["start"], s["stop"], index)], axis=1)
    rates = np.tile(s["speed"], (rows, 1)).astype(float)
    return values, rates, np.zeros_like(values)


def line_length(log: StepLog, samples: int) -> int:
    """Rows of one line of the sweep: a resolver restarts from the sketch at every line's
    first row (a grid's row where the last input is at its start), so every line of a grid is
    solved as a together sweep of the last input is; 0 for a together sweep (one line)."""
    return samples if log.sweep == "grid" and len(log.inputs) > 1 else 0
