"""The sweep as CSV, exactly as the generated programs write it."""

from __future__ import annotations

import math

import numpy as np

from . import status
from .evaluate import Result
from .instant.names import CENTRE_QUANTITIES
from .primitives.dsl import record_fields
from .steplog import StepLog

_DERIVATIVES = {"velocity", "acceleration", "angular_velocity", "angular_acceleration", *CENTRE_QUANTITIES}


def number(x: float) -> str:
    """%.17g for finite values; the literal nan for the rest (as every language writes it)."""
    return "%.17g" % x if math.isfinite(x) else "nan"


def columns(log: StepLog, result: Result) -> tuple[list[str], np.ndarray]:
    """Header and a rows x columns array with the spec's nan rules applied (status excluded):
    constant records as drawn, computed points with the origin added back."""
    names = [c.name for c in log.columns]
    data = np.empty((result.inputs.shape[0], len(names)))
    n_inputs = len(log.inputs)
    for k, c in enumerate(log.columns):
        if k < n_inputs:
            data[:, k] = result.inputs[:, k]
            continue
        drawn, offset = log.drawn(c), log.offset(c)
        if drawn is not None:
            data[:, k] = drawn
            continue
        fields = record_fields(log.variable(c.variable).kind, 2)
        data[:, k] = result.values[c.variable][fields.index(c.field)]
        if offset:
            data[:, k] += offset
    fail = status.failed(result.status)
    singular = status.singular(result.status)
    data[fail, n_inputs:] = np.nan
    for k, c in enumerate(log.columns):
        if k >= n_inputs and c.quantity in _DERIVATIVES:
            data[singular, k] = np.nan
    return names, data


def csv(log: StepLog, result: Result) -> str:
    names, data = columns(log, result)
    lines = [",".join(names + ["status"])]
    for row, st in zip(data, result.status):
        lines.append(",".join([number(x) for x in row] + [str(int(st))]))
    return "\n".join(lines) + "\n"
