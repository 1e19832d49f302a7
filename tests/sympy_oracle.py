"""sympy as the source of truth for the DSL primitives.

``to_sympy`` turns a :class:`~linkgen.primitives.dsl.Primitive` into sympy
expressions in its parameter symbols (``j1_x``, ``l1_dv``, ``minv``, ...), every
``Let`` substituted away.  ``time_derivative`` differentiates such an expression
with respect to time, treating each record parameter's displacement fields as
functions of t whose derivatives are the record's rate fields (``j1_x -> X(t)``,
``j1_dx = X'(t)``, ``j1_ddx = X''(t)``); REAL and INT parameters are constants.
``oracle_rates`` applies it to every output: the derivative of each displacement
field, the derivative of the primitive's own velocity field, and the second
derivative of the displacement field.

``numeric`` lambdifies a list of those expressions for mpmath so the tests can
evaluate them at 50 digits (the expressions are far too big for ``evalf``).
"""

from __future__ import annotations

import functools
import sys
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import mpmath
import sympy as sp

from linkgen.primitives import PRIMITIVES
from linkgen.primitives.dsl import (
    RECORD_FIELDS,
    Bin,
    Call,
    Cmp,
    Const,
    Expr,
    Logic,
    Neg,
    Num,
    Primitive,
    Select,
    Sym,
    record_fields,
)

T = sp.Symbol("t", real=True)

CONSTANTS = {
    # the binary value the generated programs use, exactly
    "eps": sp.Rational(sys.float_info.epsilon),
    "nan": sp.nan,
    "pi": sp.pi,
}


def _number(value: float | int) -> sp.Expr:
    if isinstance(value, bool):
        raise TypeError("booleans are not numbers")
    if isinstance(value, int):
        return sp.Integer(value)
    return sp.Rational(value)  # the exact binary value of the literal


def _call(fn: str, args: list[sp.Expr]) -> sp.Expr:
    if fn == "sqrt":
        return sp.sqrt(args[0])
    if fn == "hypot":
        return sp.sqrt(args[0] ** 2 + args[1] ** 2)
    if fn == "atan2":
        return sp.atan2(args[0], args[1])
    if fn == "cos":
        return sp.cos(args[0])
    if fn == "sin":
        return sp.sin(args[0])
    if fn == "abs":
        return sp.Abs(args[0])
    if fn == "max":
        return sp.Max(*args)
    if fn == "min":
        return sp.Min(*args)
    raise ValueError(f"unknown function {fn}")


_CMP = {"<": sp.Lt, "<=": sp.Le, ">": sp.Gt, ">=": sp.Ge, "==": sp.Eq}
_BIN = {
    "+": lambda a, b: a + b,
    "-": lambda a, b: a - b,
    "*": lambda a, b: a * b,
    "/": lambda a, b: a / b,
}


def convert(e: Expr, env: dict[str, sp.Basic]) -> sp.Basic:
    """One DSL expression as sympy; ``env`` maps symbol names (params and lets) to sympy."""
    if isinstance(e, Sym):
        return env[e.name]
    if isinstance(e, Num):
        return _number(e.value)
    if isinstance(e, Const):
        return CONSTANTS[e.name]
    if isinstance(e, Bin):
        return _BIN[e.op](convert(e.a, env), convert(e.b, env))
    if isinstance(e, Neg):
        return -convert(e.a, env)
    if isinstance(e, Call):
        return _call(e.fn, [convert(a, env) for a in e.args])
    if isinstance(e, Cmp):
        return _CMP[e.op](convert(e.a, env), convert(e.b, env))
    if isinstance(e, Logic):
        op = sp.And if e.op == "and" else sp.Or
        return op(convert(e.a, env), convert(e.b, env))
    if isinstance(e, Select):
        cond = convert(e.cond, env)
        a, b = convert(e.a, env), convert(e.b, env)
        if cond is sp.true:
            return a
        if cond is sp.false:
            return b
        return sp.Piecewise((a, cond), (b, True))
    raise TypeError(f"cannot convert {e!r}")


def param_symbols(prim: Primitive) -> dict[str, sp.Symbol]:
    """Every parameter field and scalar of a primitive, in parameter order."""
    out: dict[str, sp.Symbol] = {}
    for p in prim.params:
        names = [f"{p.name}_{f}" for f in record_fields(p.kind, 2)] if p.is_record else [p.name]
        for n in names:
            out[n] = sp.Symbol(n, real=True)
    return out


@dataclass(frozen=True)
class SympyPrimitive:
    prim: Primitive
    symbols: dict[str, sp.Symbol]
    lets: dict[str, sp.Basic]
    results: dict[str, dict[str, sp.Basic]]
    status: sp.Basic | None
    sigma: sp.Basic | None


@functools.cache
def to_sympy(name: str) -> SympyPrimitive:
    """The primitive ``name`` of the library as sympy expressions in its parameter symbols."""
    prim = PRIMITIVES[name]
    syms = param_symbols(prim)
    env: dict[str, sp.Basic] = dict(syms)
    lets: dict[str, sp.Basic] = {}
    for let in prim.body:
        if let.name in env:
            raise ValueError(f"{name}: {let.name} shadows a name")
        lets[let.name] = env[let.name] = convert(let.expr, env)
    results = {
        out: {f: convert(e, env) for f, e in fields.items()} for out, fields in prim.results.items()
    }
    status = convert(prim.status, env) if prim.status is not None else None
    sigma = convert(prim.sigma, env) if prim.sigma is not None else None
    return SympyPrimitive(prim, syms, lets, results, status, sigma)


def _chains(prim: Primitive) -> list[tuple[str, str | None, str | None]]:
    """(displacement, velocity, acceleration) symbol names of every time-varying parameter field."""
    chains = []
    for p in prim.params:
        if not p.is_record:
            continue
        d0, d1, d2 = RECORD_FIELDS[p.kind]
        for a, b, c in zip(d0, d1, d2):
            chains.append((f"{p.name}_{a}", f"{p.name}_{b}", f"{p.name}_{c}"))
    return chains


@functools.cache
def _time_maps(name: str) -> tuple[dict, dict]:
    """Symbol -> function-of-t substitutions and their inverse for one primitive."""
    sprim = to_sympy(name)
    forward: dict[sp.Basic, sp.Basic] = {}
    back: dict[sp.Basic, sp.Basic] = {}
    for x, dx, ddx in _chains(sprim.prim):
        f = sp.Function(x.upper(), real=True)(T)
        df, ddf = f.diff(T), f.diff(T, 2)
        forward.update({sprim.symbols[x]: f, sprim.symbols[dx]: df, sprim.symbols[ddx]: ddf})
        back.update({ddf: sprim.symbols[ddx], df: sprim.symbols[dx], f: sprim.symbols[x]})
    return forward, back


def time_derivative(name: str, expr: sp.Basic) -> sp.Basic:
    """d/dt of an expression in the parameter symbols of primitive ``name``, in those symbols again.

    The displacement fields of every record parameter are functions of t, their
    rate fields are its derivatives; scalar parameters are constant.  An
    expression that already reads an acceleration field cannot be differentiated
    (its derivative would need a third derivative).
    """
    forward, back = _time_maps(name)
    as_functions = expr.xreplace(forward)
    derivative = sp.diff(as_functions, T)
    out = derivative.xreplace(back)
    if out.has(T):
        raise ValueError(f"{name}: the derivative reads a rate the records do not carry: {out.free_symbols}")
    return out


@dataclass(frozen=True)
class Rate:
    """One rate field of one output and its oracles."""

    output: str
    field: str
    order: int  # 1 velocity, 2 acceleration
    dsl: sp.Basic  # the primitive's own expression for the field
    from_lower: sp.Basic  # d/dt of the field one order below (the primitive's expression)
    from_displacement: sp.Basic  # d^order/dt^order of the displacement field


@functools.cache
def oracle_rates(name: str) -> tuple[Rate, ...]:
    """The sympy time derivative of every output field, next to the primitive's rate fields."""
    sprim = to_sympy(name)
    rates = []
    for out in sprim.prim.outputs:
        levels = RECORD_FIELDS[out.kind]
        res = sprim.results[out.name]
        for i, f0 in enumerate(levels[0]):
            f1, f2 = levels[1][i], levels[2][i]
            d1 = time_derivative(name, res[f0])
            rates.append(Rate(out.name, f1, 1, res[f1], d1, d1))
            rates.append(Rate(out.name, f2, 2, res[f2], time_derivative(name, res[f1]), time_derivative(name, d1)))
    return tuple(rates)


def _heaviside(x, h0=None):
    if x > 0:
        return mpmath.mpf(1)
    if x < 0:
        return mpmath.mpf(0)
    return mpmath.mpf(h0) if h0 is not None else mpmath.nan


_MPMATH = [{"Heaviside": _heaviside}, "mpmath"]


def numeric(name: str, exprs: Sequence[sp.Basic]) -> Callable[[dict[str, object]], list]:
    """A function of {parameter name: value} giving the expressions' values with mpmath.

    Evaluate it inside ``mpmath.workdps(50)`` for 50-digit results.
    """
    sprim = to_sympy(name)
    args = list(sprim.symbols.values())
    fn = sp.lambdify(args, list(exprs), modules=_MPMATH, cse=True)
    names = list(sprim.symbols)

    def call(values: dict[str, object]) -> list:
        return fn(*(values[n] for n in names))

    return call
