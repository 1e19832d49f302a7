"""What the languages' spellings (linkgen.backends.<lang>.spelling) are checked against: the samples without
a resolver, their procedure run at one input row by the Python printer's functions of the primitives each step
calls (with the sketch's records held still, linkgen.backends.still: no spelling involved), record by record."""

from __future__ import annotations

import math
import sys
from functools import cache
from pathlib import Path

from linkgen.backends.py.printer import python_function
from linkgen.backends.still import held_params, variant
from linkgen.pipeline import build_log
from linkgen.primitives.dsl import Primitive, record_fields
from linkgen.primitives.interpret import Record, constant_record
from linkgen.render.view import View, build_view
from linkgen.status import CANNOT_CLOSE

ROOT = Path(__file__).resolve().parents[1]
# every kind of call between them: the five chains, crank, slider and distance inputs, points, angles
NAMES = ("fourbar", "slider_crank", "inverted_slider", "cross_slot", "scotch_yoke", "actuator", "fivebar",
         "sixbar_slider", "jansen_foot")


@cache
def view(name: str) -> View:
    log = build_log(str(ROOT / "samples" / name / f"{name}.yaml"), None, None, sweep=False)
    assert not log.groups and not any(s.change_points for s in log.steps), name
    return build_view(log)


def row(v: View) -> tuple[list[float], list[float], list[float]]:
    """An input row a little off the sketch: values, rates, accelerations."""
    n = len(v.inputs)
    values = [i.sketch + 0.01 for i in v.log.inputs]
    return values, [1.0 + 0.25 * k for k in range(n)], [0.5 - 0.125 * k for k in range(n)]


def reference(v: View) -> dict[str, Record]:
    """Every record of the procedure at ``row(v)``: constants as the programs hold them, the inputs, the
    steps' outputs."""
    order = v.record_order
    env = {c.name: constant_record(c, order, v.log.origin) for c in v.constants}
    values, rates, accelerations = row(v)
    for k, var in enumerate(v.inputs):
        env[var.name] = (values[k], rates[k], accelerations[k])[: order + 1]
    space = {"sqrt": math.sqrt, "atan2": math.atan2, "cos": math.cos, "sin": math.sin, "EPS": sys.float_info.epsilon,
             "NAN": math.nan, "PI": math.pi}
    exec("\n\n".join(python_function(p, order) for p in called(v)), space)
    for step, prim in zip((s for s in v.run if s.function), calls(v), strict=True):
        args = [env[a.var] if a.kind == "var" else int(a.value) if a.kind == "int" else float(a.value)
                for a in step.args]
        res = space[prim.name](*args)
        if prim.status is not None:
            assert res[0] != CANNOT_CLOSE, step.number
            res = res[2:] if prim.sigma is not None else res[1:]
        env.update(zip(step.outputs, res if prim.status is not None or len(prim.outputs) > 1 else (res,)))
    return env


def calls(v: View) -> list[Primitive]:
    """The primitive each step of the run calls, in order: with the sketch's records held still where the
    programs hold them (with its checks: the samples keep theirs)."""
    return [variant(s.function, True, held_params(v.log, v.record_order, s)) for s in v.run if s.function]


def called(v: View) -> list[Primitive]:
    """The primitives the run calls, each once."""
    return list({p.name: p for p in calls(v)}.values())


def computed(v: View) -> list[tuple[str, str]]:
    """(record, field) of every record the procedure computes, in the view's order."""
    return [(r.name, f) for r in v.records for f in record_fields(r.kind, v.record_order)]


def same(a: float, b: float) -> bool:
    return (math.isnan(a) and math.isnan(b)) or (a == b and math.copysign(1.0, a) == math.copysign(1.0, b))
