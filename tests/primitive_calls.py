"""Calling the runtime primitives as the generated Python does (linkgen.primitives.python_backend):
arguments by field name or by position, results as (status, sigma, outputs)."""

from __future__ import annotations

import math

import pytest

from linkgen.primitives import PRIMITIVES, python_backend
from linkgen.primitives.dsl import RECORD_FIELDS, record_fields

PI = math.pi
STILL = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)  # a point at the origin, at rest


def args_of(name: str, order: int, values: dict) -> list:
    """Records as tuples of their fields up to ``order``, scalars as they are."""
    args = []
    for p in PRIMITIVES[name].params:
        if p.is_record:
            args.append(tuple(values[f"{p.name}_{f}"] for f in record_fields(p.kind, order)))
        else:
            args.append(values[p.name])
    return args


def call_python(name: str, order: int, values: dict):
    """(status, sigma, outputs) from the generated math function; None where it has none."""
    prim = PRIMITIVES[name]
    res = python_backend(order)[name](*args_of(name, order, values))
    if prim.status is None:
        return None, None, ((res,) if len(prim.outputs) == 1 else tuple(res))
    st, *rest = res
    sigma = rest.pop(0) if prim.sigma is not None else None
    return st, sigma, tuple(rest)


def named(name: str, args) -> dict:
    """Positional arguments (records as tuples, possibly short of the higher orders) by field name."""
    out = {}
    for p, a in zip(PRIMITIVES[name].params, args):
        if p.is_record:
            out.update({f"{p.name}_{f}": x for f, x in zip(record_fields(p.kind, 2), a)})
        else:
            out[p.name] = a
    return out


def py2(name: str, *args):
    """(status, sigma, outputs) at order 2 from positional arguments."""
    return call_python(name, 2, dict(named(name, args)))


def approx(values):
    return pytest.approx(values, rel=1e-14, abs=1e-14)


def all_outputs(name: str, row: dict, order: int):
    """(status, sigma, [(output, field, value), ...])."""
    prim = PRIMITIVES[name]
    st, sigma, outs = call_python(name, order, row)
    levels = [record_fields(o.kind, order) for o in prim.outputs]
    return st, sigma, [(o.name, f, x) for o, fs, rec in zip(prim.outputs, levels, outs) for f, x in zip(fs, rec)]


def field_level(kind: str, f: str) -> int:
    """The derivative order of a field."""
    return next(i for i, names in enumerate(RECORD_FIELDS[kind]) if f in names)
