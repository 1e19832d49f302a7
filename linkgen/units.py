"""Input values and rates between the file's units (degrees where its angles are in degrees) and
the procedure's (radians; lengths as the file gives them): what --at and --rates take and what the
commands print them in."""

from __future__ import annotations

import math
from collections.abc import Sequence

from .steplog import StepLog


def from_file(log: StepLog, values: Sequence[float]) -> tuple[float, ...]:
    """One value per input in the file's units, as the procedure takes them."""
    scale = math.pi / 180 if log.angle_unit == "deg" else 1.0
    return tuple(v * scale if i.kind == "revolute" else float(v) for i, v in zip(log.inputs, values))


def to_file(log: StepLog, values: Sequence[float]) -> tuple[float, ...]:
    """One value per input as the procedure takes it, in the file's units."""
    scale = 180 / math.pi if log.angle_unit == "deg" else 1.0
    return tuple(v * scale if i.kind == "revolute" else float(v) for i, v in zip(log.inputs, values))
