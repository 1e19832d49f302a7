"""The programs' units (options.units): SI radians, or the file's units.

With ``units: file`` and a file that writes angles in degrees, every program takes its angle
inputs in degrees (their rates in degrees per second, per second squared) and writes its angle
outputs so: the conversion is at the boundary only, each angle input divided by DEGREE on the way
in and each angle output multiplied by it on the way out, so the computation between is the SI
one.  Lengths are the file's in either case; unit-vector directions (angles: unit) are unchanged.

``from_file`` and ``to_file`` convert the input values and rates the commands take and print
(--at, --rates: the file's units, whatever the programs' units are) to radians and back.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from .steplog import Column, StepLog

DEGREE = 57.295779513082323  # 180 / pi: degrees per radian, the one factor every language writes as a literal
ANGULAR = ("angle", "angular_velocity", "angular_acceleration")  # the column quantities it converts


def factor(log: StepLog) -> float | None:
    """DEGREE where the programs work in degrees (units: file, angles in degrees), else None."""
    return DEGREE if log.options.units == "file" and log.angle_unit == "deg" else None


def converted(log: StepLog, c: Column) -> bool:
    """Whether an output column is written in degrees: an angle or its rate (not a direction's components)."""
    return factor(log) is not None and c.quantity in ANGULAR and log.variable(c.variable).kind == "ANGLE"


def angular_inputs(log: StepLog) -> tuple[int, ...]:
    """The indices of the inputs that take degrees (the revolute ones, where the programs work in degrees)."""
    if factor(log) is None:
        return ()
    return tuple(k for k, i in enumerate(log.inputs) if i.kind == "revolute")


def sweep_lists(log: StepLog) -> dict[str, list[float]]:
    """Each input's start, stop and speed as the programs take them (degrees for an angle in degrees)."""
    scale = [DEGREE if k in angular_inputs(log) else 1.0 for k in range(len(log.inputs))]
    return {key: [getattr(i, key) * s if s != 1.0 else getattr(i, key) for i, s in zip(log.inputs, scale)]
            for key in ("start", "stop", "speed")}


def to_si(log: StepLog, values: np.ndarray, rates: np.ndarray,
          accs: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Rows of inputs, rates and accelerations in the programs' units, in SI: the angle ones over DEGREE."""
    return _radians(log, values), _radians(log, rates), _radians(log, accs)


def _radians(log: StepLog, rows: np.ndarray) -> np.ndarray:
    out = np.array(rows, dtype=float)
    for k in angular_inputs(log):
        out[:, k] = out[:, k] / DEGREE
    return out


def outputs_from_si(log: StepLog, data: np.ndarray) -> np.ndarray:
    """The output columns of rows (the CSV's, inputs first) in the programs' units: the angle ones times DEGREE."""
    for k, c in enumerate(log.columns):
        if k >= len(log.inputs) and converted(log, c):
            data[:, k] = data[:, k] * DEGREE
    return data


def from_file(log: StepLog, values: Sequence[float]) -> tuple[float, ...]:
    """One value per input in the file's units, as the procedure takes them."""
    scale = math.pi / 180 if log.angle_unit == "deg" else 1.0
    return tuple(v * scale if i.kind == "revolute" else float(v) for i, v in zip(log.inputs, values))


def to_file(log: StepLog, values: Sequence[float]) -> tuple[float, ...]:
    """One value per input as the procedure takes it, in the file's units."""
    scale = 180 / math.pi if log.angle_unit == "deg" else 1.0
    return tuple(v * scale if i.kind == "revolute" else float(v) for i, v in zip(log.inputs, values))
