"""Calling the runtime primitives as the generated Python does (linkgen.primitives.python_backend):
arguments by field name or by position, results as (status, sigma, outputs)."""

from __future__ import annotations

import math

import pytest

from linkgen.primitives import PRIMITIVES, python_backend
from linkgen.primitives.dsl import RECORD_FIELDS, record_fields

PI = math.pi
STILL = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)  # a point at the origin, at rest
# The primitives that give motions (each output a displacement with its rates): every one but
# instant_centre, whose record is of velocities alone (tests/test_instant_centres.py tests it).
MOTIONS = tuple(n for n, p in PRIMITIVES.items() if all(RECORD_FIELDS[o.kind][0] for o in p.outputs))


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


def special_inputs(name: str) -> list[tuple[str, int | None, dict]]:
    """(what, expected status, float parameter values) at the status branches: toggles, failures, degeneracies."""

    def pt(pname, x, y, dx=0.5, dy=-0.25, ddx=0.125, ddy=1.0):
        return {f"{pname}_{k}": v for k, v in zip(("x", "y", "dx", "dy", "ddx", "ddy"), (x, y, dx, dy, ddx, ddy))}

    def var(pname, v, dv=0.5, ddv=-0.5, kind="VARIABLE"):
        names = RECORD_FIELDS[kind]
        return {f"{pname}_{names[i][0]}": x for i, x in enumerate((v, dv, ddv))}

    cases: list[tuple[str, int, dict]] = []
    if name == "RRR_links":
        for what, st, l1, l2, q in (("toggle", 3, 2.0, 3.0, 5.0), ("toggle", 3, 7.0, 2.0, 5.0),
                                    ("fail", 1, 3.0, 4.0, 10.0), ("coincident", 1, 3.0, 4.0, 0.0),
                                    ("fail", 1, 0.0, 5.0, 5.0)):
            for minv in (1, -1):
                cases.append((what, st, {**pt("j1", 0.0, 0.0), **pt("j2", q, 0.0, 1.0, 2.0, -1.0, 0.5),
                                         **var("l1", l1), **var("l2", l2), "minv": minv}))
    elif name == "PRR_links":
        for what, st, ln, y in (("toggle", 3, 3.0, 3.0), ("toggle", 3, 3.0, -3.0), ("fail", 1, 2.0, 3.0),
                                ("fail", 1, 0.0, 0.0)):
            cases.append((what, st, {**pt("jr", 0.0, y), **var("l", ln), **pt("pg", 0.0, 0.0),
                                     **var("psig", 0.0, 1.0, 0.5, "ANGLE"), "gsi": 0.0, "eta": 0.0, "minv": 1}))
    elif name == "RPR_links":
        for what, st, bg, q in (("toggle", 3, 3.0, 3.0), ("toggle", 3, -3.0, 3.0), ("fail", 1, 4.0, 3.0),
                                ("coincident", 1, 0.0, 0.0)):
            cases.append((what, st, {**pt("jg", 0.0, 0.0), **pt("js", q, 0.0, 0.0, 1.0),
                                     "ag": 0.0, "bg": bg, "as_": 0.0, "bs": 0.0, "minv": 1}))
    elif name == "PRP_links":
        cases.append(("parallel", 1, {**pt("pg1", 0.0, 0.0), **var("psig1", 0.0, kind="ANGLE"), "gsi1": 0.0,
                                      "eta1": 0.0, **pt("pg2", 0.0, 1.0), **var("psig2", 0.0, kind="ANGLE"),
                                      "gsi2": 0.0, "eta2": 0.0}))
    elif name == "PPR_links":
        cases.append(("parallel", 1, {**pt("jr", 1.0, 2.0), **pt("pg", 0.0, 0.0), **var("psig", 0.0, kind="ANGLE"),
                                      "xa": 0.0, "ya": 0.0, "xb": 0.0, "yb": 0.0, "cx": 0.0, "sgn": 1}))
    elif name == "link_angle":
        cases.append(("coincident", 1, {**pt("j1", 1.0, 2.0), **pt("j2", 1.0, 2.0), "off": 0.5}))
    elif name in ("link_point", "pair_point"):  # a point placed from coincident pairs is undefined
        cases.append(("coincident", 1, {**pt("j1", 1.0, 2.0), **pt("j2", 1.0, 2.0), **dict(zip(
            [q.name for q in PRIMITIVES[name].params[2:]], (0.5, 0.25)))}))
    elif name == "link_direction":
        cases.append(("coincident", 1, {**pt("j1", 1.0, 2.0), **pt("j2", 1.0, 2.0), "c": 0.6, "s": 0.8}))
    elif name == "link_residual":
        cases.append(("coincident", None, {**pt("j1", 1.0, 2.0), **pt("j2", 1.0, 2.0), **var("l", 1.0)}))
        cases.append(("parting", None, {**pt("j1", 1.0, 2.0), **pt("j2", 1.0, 2.0, 3.5, 3.75), **var("l", 1.0)}))
    elif name == "loop_residual":  # no angle comes back where the pairs coincide
        cases.append(("coincident", 1, {**pt("j1", 1.0, 2.0), **pt("j2", 1.0, 2.0), **var("l", 1.0, 0.0, 0.0),
                                        **var("s", 0.5)}))
    elif name == "loop_turn":  # the body turned over (its mirror image), and flat: either turn fails
        for what, j3, turn in (("turned over", (0.0, -1.0), 1), ("turned over", (0.0, 1.0), -1),
                               ("flat", (2.0, 0.0), 1), ("flat", (2.0, 0.0), -1)):
            cases.append((what, 1, {**pt("j1", 0.0, 0.0), **pt("j2", 1.0, 0.0), **pt("j3", *j3), "turn": turn}))
    return cases
