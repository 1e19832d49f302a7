"""The DSL's own evaluation: a primitive's expression trees walked node by node on Python floats, the
route the printers' outputs are checked against (no printer involved), and rows of arguments to walk.

Semantics as the DSL documents them: a selection evaluates only the branch it takes; max(a, b) is b where
b > a, else a, and min with < (Python's choice: a nan b gives a); sqrt of a negative number and a division
by zero give what IEEE arithmetic gives.  A primitive's status masks its outputs: 1 makes every field nan, 3 every rate.
"""

from __future__ import annotations

import math
import random
import sys
from collections.abc import Mapping

from primitive_calls import special_inputs

from linkgen.primitives import PRIMITIVES
from linkgen.primitives.dsl import Bin, Call, Cmp, Const, Expr, Logic, Neg, Num, Primitive, Select, Sym, field_order
from linkgen.primitives.dsl import record_fields as fields_of
from linkgen.primitives.printers import MASKS

CONSTANTS = {"eps": sys.float_info.epsilon, "nan": math.nan, "pi": math.pi}


def _divide(a: float, b: float) -> float:
    if b != 0:
        return a / b
    if a != a or a == 0:
        return math.nan
    return math.copysign(math.inf, a) * math.copysign(1.0, b)


def _fmax(a: float, b: float) -> float:
    if b > a:
        return b
    return a


def _fmin(a: float, b: float) -> float:
    if b < a:
        return b
    return a


CALLS = {"sqrt": lambda x: math.sqrt(x) if x >= 0 else math.nan, "atan2": math.atan2, "cos": math.cos,
         "sin": math.sin, "abs": abs, "max": _fmax, "min": _fmin}
ARITHMETIC = {"+": lambda a, b: a + b, "-": lambda a, b: a - b, "*": lambda a, b: a * b, "/": _divide}
COMPARE = {"<": lambda a, b: a < b, "<=": lambda a, b: a <= b, ">": lambda a, b: a > b, ">=": lambda a, b: a >= b,
           "==": lambda a, b: a == b}


def walk(e: Expr, env: Mapping[str, float]) -> float:
    """The value of an expression in ``env`` (symbols by name)."""
    if isinstance(e, Sym):
        return env[e.name]
    if isinstance(e, Num):
        return e.value
    if isinstance(e, Const):
        return CONSTANTS[e.name]
    if isinstance(e, Neg):
        return -walk(e.a, env)
    if isinstance(e, Bin):
        return ARITHMETIC[e.op](walk(e.a, env), walk(e.b, env))
    if isinstance(e, Cmp):
        return COMPARE[e.op](walk(e.a, env), walk(e.b, env))
    if isinstance(e, Logic):
        a = bool(walk(e.a, env))
        return (a or bool(walk(e.b, env))) if e.op == "or" else (a and bool(walk(e.b, env)))
    if isinstance(e, Call):
        return CALLS[e.fn](*(walk(a, env) for a in e.args))
    if isinstance(e, Select):
        return walk(e.a, env) if walk(e.cond, env) else walk(e.b, env)
    raise TypeError(f"cannot walk {e!r}")


def evaluate(prim: Primitive, order: int, values: Mapping[str, float]) -> tuple[int | None, float | None, list[float]]:
    """(status, sigma, every output field up to ``order`` in output order), masked by the status."""
    env = dict(values)
    for let in prim.live(order):
        env[let.name] = walk(let.expr, env)
    st = None if prim.status is None else int(walk(prim.status, env))
    sigma = None if prim.sigma is None else float(walk(prim.sigma, env))
    out = []
    for p, f, e in prim.result_fields(order):
        masked = any(st == code and field_order(p.kind, f) >= first for code, first in MASKS)
        out.append(math.nan if masked else float(walk(e, env)))
    return st, sigma, out


def _ulps(x: float, k: int) -> float:
    """x moved k ulps (down for k < 0)."""
    for _ in range(abs(k)):
        x = math.nextafter(x, math.copysign(math.inf, k))
    return x


def slack_rows(name: str) -> list[dict[str, float]]:
    """A chain short of closing by a few ulps of its sides (about 3): within the toggle slack of 8 eps
    times its longest side (5 for the 3R chain: 20 ulps of 3, else 3: 12 ulps), and past it."""
    still = {f: 0.0 for f in ("dx", "dy", "ddx", "ddy")}

    def point(p: str, x: float, y: float) -> dict[str, float]:
        return {f"{p}_x": x, f"{p}_y": y, **{f"{p}_{f}": v for f, v in still.items()}}

    def record(p: str, kind: str, v: float) -> dict[str, float]:
        return {f"{p}_{f}": (v if i == 0 else 0.0) for i, f in enumerate(fields_of(kind, 2))}

    out = []
    for k in ((16, 24) if name == "RRR_links" else (8, 16)):
        if name == "RRR_links":
            out.append({**point("j1", 0.0, 0.0), **point("j2", 5.0, 0.0), **record("l1", "VARIABLE", 2.0),
                        **record("l2", "VARIABLE", _ulps(3.0, -k)), "minv": 1})
        elif name == "PRR_links":
            out.append({**point("jr", 0.0, 3.0), **record("l", "VARIABLE", _ulps(3.0, -k)), **point("pg", 0.0, 0.0),
                        **record("psig", "ANGLE", 0.0), "gsi": 0.0, "eta": 0.0, "minv": 1})
        elif name == "RPR_links":
            out.append({**point("jg", 0.0, 0.0), **point("js", 3.0, 0.0), "ag": 0.0, "bg": _ulps(3.0, k), "as_": 0.0,
                        "bs": 0.0, "minv": 1})
    return out


def thin_rows(name: str) -> list[dict[str, float]]:
    """The 3R chain over a base of 2 with jb far up at (1, h), its sides growing: sigma = 2 h / (1 + h^2),
    5e-8 (singular: the rates, finite as computed, masked) and 2e-5 (near singular: all given)."""
    if name != "RRR_links":
        return []
    out = []
    for sigma in (5e-8, 2e-5):
        side = math.hypot(1.0, 2 / sigma)
        base = {"j1_x": 0.0, "j1_y": 0.0, "j2_x": 2.0, "j2_y": 0.0, "minv": 1}
        rates = {f"j{i}_{f}": 0.0 for i in (1, 2) for f in ("dx", "dy", "ddx", "ddy")}
        out.append({**base, **rates, "l1_v": side, "l1_dv": 0.5, "l1_ddv": 0.25, "l2_v": side, "l2_dv": -0.5,
                    "l2_ddv": 0.125})
    return out


def rows(name: str, count: int, seed: int = 0) -> list[dict[str, float]]:
    """Arguments of a primitive by field name at order 2: ``count`` random ones (lengths positive, flags +1
    or -1), then the toggles, failures and coincidences of primitive_calls.special_inputs, the chains
    short of closing by about their toggle slack, and thin 3R chains (singular and near singular)."""
    prim = PRIMITIVES[name]
    rng = random.Random(f"{name} {seed}")
    out: list[dict[str, float]] = []
    for _ in range(count):
        row: dict[str, float] = {}
        for p in prim.params:
            if p.kind == "INT":
                row[p.name] = rng.choice((1, -1))
            elif p.kind == "REAL":
                row[p.name] = rng.uniform(-2.0, 2.0)
            else:
                for f in fields_of(p.kind, 2):
                    length = p.kind == "VARIABLE" and field_order(p.kind, f) == 0
                    row[f"{p.name}_{f}"] = rng.uniform(0.5, 4.0) if length else rng.uniform(-3.0, 3.0)
        out.append(row)
    return out + [row for _, _, row in special_inputs(name)] + slack_rows(name) + thin_rows(name)


def same(a: float | None, b: float | None) -> bool:
    """Bit for bit (the sign of a zero too), any nan equal to any nan."""
    if a is None or b is None:
        return a is b
    if math.isnan(a) or math.isnan(b):
        return math.isnan(a) and math.isnan(b)
    return a == b and math.copysign(1.0, a) == math.copysign(1.0, b)
