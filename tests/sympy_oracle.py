"""sympy as the source of truth for the DSL primitives.

Two views of a :class:`~linkgen.primitives.dsl.Primitive`:

* ``to_sympy(name)``: every ``Let``, result field, status and sigma as one sympy
  expression in the parameter symbols (``j1_x``, ``l1_dv``, ``minv``, ...), the
  lets substituted away.  ``time_derivative(name, expr)`` differentiates such an
  expression with respect to time literally: each record parameter's displacement
  field becomes a function of t (``j1_x -> J1_X(t)``) whose derivatives are the
  record's rate fields (``j1_dx = J1_X'(t)``, ``j1_ddx = J1_X''(t)``), REAL and
  INT parameters are constants, ``sympy.diff`` does the work and the result is
  written in the parameter symbols again.

* ``program(name)``: the same primitive as a straight-line sympy program, one
  symbol per ``Let``.  ``Program.rate`` differentiates it with the chain rule, one
  assignment at a time (``d/dt L = sum over s of dL/ds * ds/dt``, each partial
  derivative taken by sympy), so a derivative of the 3R chain's velocity takes
  milliseconds instead of the tens of seconds ``sympy.diff`` spends on the
  substituted expression.  ``Program.expand`` writes any of its expressions in the
  parameter symbols; the tests check both routes agree.

``oracle_rates`` gives, for every velocity and acceleration field of every output,
the primitive's own expression next to the time derivative of the field one
order below and the first/second time derivative of the displacement field.
``Program.compile`` (program expressions) and ``numeric`` (expressions in the
parameter symbols) evaluate lists of expressions with mpmath; call them inside
``mpmath.workdps(50)`` for 50 digits.
"""

from __future__ import annotations

import functools
import sys
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import mpmath
import sympy as sp
from sympy.printing.pycode import MpmathPrinter

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

# The DSL's nan marks a value that must not be used (a division by zero avoided).
# sympy's own nan cannot sit in a Piecewise whose condition is compared again
# (``sigma < 1e-7`` with sigma built on ``1/q``): piecewise_fold raises "Invalid
# NaN comparison".  So it is a constant symbol here, set to mpmath's nan when
# evaluated; being constant, its time derivative is 0, right for a branch that is
# never taken where the chain is assembled.
NAN = sp.Symbol("NAN_", real=True)

CONSTANTS = {
    "eps": sp.Rational(sys.float_info.epsilon),  # the binary value the programs use, exactly
    "nan": NAN,
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


Prim = str | Primitive  # a library name, or a Primitive object (a test's mutant, say)


def resolve(prim: Prim) -> Primitive:
    return PRIMITIVES[prim] if isinstance(prim, str) else prim


def rate_chains(prim: Primitive) -> list[tuple[str, str, str]]:
    """(displacement, velocity, acceleration) names of every time-varying parameter field."""
    chains = []
    for p in prim.params:
        if p.is_record:
            d0, d1, d2 = RECORD_FIELDS[p.kind]
            chains += [(f"{p.name}_{a}", f"{p.name}_{b}", f"{p.name}_{c}") for a, b, c in zip(d0, d1, d2)]
    return chains


# --------------------------------------------------------------------------- literal view


@dataclass(frozen=True)
class SympyPrimitive:
    prim: Primitive
    symbols: dict[str, sp.Symbol]
    lets: dict[str, sp.Basic]
    results: dict[str, dict[str, sp.Basic]]
    status: sp.Basic | None
    sigma: sp.Basic | None


@functools.cache
def to_sympy(p: Prim) -> SympyPrimitive:
    """A primitive as sympy expressions in its parameter symbols."""
    prim = resolve(p)
    name = prim.name
    syms = param_symbols(prim)
    env: dict[str, sp.Basic] = dict(syms)
    lets: dict[str, sp.Basic] = {}
    for let in prim.body:
        if let.name in env:
            raise ValueError(f"{name}: {let.name} shadows a name")
        lets[let.name] = env[let.name] = convert(let.expr, env)
    results = {out: {f: convert(e, env) for f, e in fields.items()} for out, fields in prim.results.items()}
    status = convert(prim.status, env) if prim.status is not None else None
    sigma = convert(prim.sigma, env) if prim.sigma is not None else None
    return SympyPrimitive(prim, syms, lets, results, status, sigma)


@functools.cache
def _time_maps(p: Prim) -> tuple[dict, dict]:
    """Symbol -> function-of-t substitutions and their inverse for one primitive."""
    prim = resolve(p)
    syms = param_symbols(prim)
    forward: dict[sp.Basic, sp.Basic] = {}
    back: dict[sp.Basic, sp.Basic] = {}
    for x, dx, ddx in rate_chains(prim):
        f = sp.Function(x.upper(), real=True)(T)
        df, ddf = f.diff(T), f.diff(T, 2)
        forward.update({syms[x]: f, syms[dx]: df, syms[ddx]: ddf})
        back.update({ddf: syms[ddx], df: syms[dx], f: syms[x]})
    return forward, back


def time_derivative(p: Prim, expr: sp.Basic) -> sp.Basic:
    """d/dt of an expression in the parameter symbols of a primitive, in those symbols again.

    An expression that already reads an acceleration field cannot be
    differentiated: its derivative would need a third derivative.
    """
    forward, back = _time_maps(p)
    derivative = sp.diff(expr.xreplace(forward), T).xreplace(back)
    if derivative.has(T):
        raise ValueError(f"{resolve(p).name}: the derivative needs a rate the records do not carry")
    return derivative


# --------------------------------------------------------------------------- program view


@dataclass
class Program:
    """A primitive as ordered sympy assignments ``symbol = expression`` over the parameter symbols."""

    prim: Primitive
    symbols: dict[str, sp.Symbol]
    assignments: dict[sp.Symbol, sp.Basic]
    results: dict[str, dict[str, sp.Basic]]
    status: sp.Basic | None
    sigma: sp.Basic | None
    _rates: dict[sp.Symbol, sp.Basic] = field(default_factory=dict)

    @property
    def name(self) -> str:
        return self.prim.name

    def __post_init__(self) -> None:
        for x, dx, ddx in rate_chains(self.prim):
            self._rates[self.symbols[x]] = self.symbols[dx]
            self._rates[self.symbols[dx]] = self.symbols[ddx]
        for p in self.prim.params:
            if not p.is_record:
                self._rates[self.symbols[p.name]] = sp.Integer(0)
        self._rates[NAN] = sp.Integer(0)

    def _rate_of(self, s: sp.Symbol) -> sp.Basic:
        if s in self._rates:
            return self._rates[s]
        if s not in self.assignments:
            raise ValueError(f"{self.name}: no rate for {s}: it is an acceleration or unknown")
        d = self._fresh(f"d__{s.name}")
        self.assignments[d] = self.rate(self.assignments[s], s.name)  # its dependencies come first
        self._rates[s] = d
        return d

    def _fresh(self, name: str) -> sp.Symbol:
        sym = sp.Symbol(name, real=True)
        if sym in self.assignments or name in self.symbols:
            raise ValueError(f"{self.name}: {name} exists already")
        return sym

    def rate(self, expr: sp.Basic, tag: str | None = None) -> sp.Basic:
        """d/dt of an expression of the program, by the chain rule over its assignments.

        ``d/dt f(s1, ..., sn) = sum of df/dsi * dsi/dt``: sympy takes each partial
        derivative; with ``tag``, a partial that is not a number or a symbol gets an
        assignment of its own (``p__tag__si``) so that second derivatives stay small.
        """
        terms = []
        for s in sorted(expr.free_symbols, key=lambda s: s.name):
            ds = self._rate_of(s)
            if ds == 0:
                continue
            partial = sp.diff(expr, s)
            if tag is not None and not (partial.is_Number or partial.is_Symbol):
                p = self._fresh(f"p__{tag}__{s.name}")
                self.assignments[p] = partial
                partial = p
            terms.append(partial * ds)
        return sp.Add(*terms)

    def expand(self, expr: sp.Basic) -> sp.Basic:
        """The expression in the parameter symbols only (can be large)."""
        for s, e in reversed(list(self.assignments.items())):
            if s in expr.free_symbols:
                expr = expr.xreplace({s: e})
        return expr

    def compile(self, exprs: Sequence[sp.Basic]) -> Callable[[dict[str, object]], list]:
        """A function of {parameter name: value} giving the expressions' values with mpmath."""
        assignments = list(self.assignments.items())
        args = [*self.symbols.values(), NAN]
        fn = sp.lambdify(
            args, list(exprs), modules=_MPMATH, cse=lambda e: (assignments, e), docstring_limit=0,
            printer=_printer(),
        )
        names = list(self.symbols)

        def call(values: dict[str, object]) -> list:
            return fn(*(values[n] for n in names), mpmath.nan)

        return call


@functools.cache
def program(p: Prim) -> Program:
    """A primitive as a straight-line sympy program."""
    prim = resolve(p)
    name = prim.name
    syms = param_symbols(prim)
    env: dict[str, sp.Basic] = dict(syms)
    assignments: dict[sp.Symbol, sp.Basic] = {}
    for let in prim.body:
        s = sp.Symbol(let.name, real=True)
        if let.name in env or s in assignments:
            raise ValueError(f"{name}: {let.name} shadows a name")
        assignments[s] = convert(let.expr, env)
        env[let.name] = s
    results = {out: {f: convert(e, env) for f, e in fields.items()} for out, fields in prim.results.items()}
    status = convert(prim.status, env) if prim.status is not None else None
    sigma = convert(prim.sigma, env) if prim.sigma is not None else None
    return Program(prim, syms, assignments, results, status, sigma)


@dataclass(frozen=True)
class Rate:
    """One rate field of one output and its oracles (program expressions)."""

    output: str
    field: str
    order: int  # 1 velocity, 2 acceleration
    dsl: sp.Basic  # the primitive's own expression for the field
    from_lower: sp.Basic  # d/dt of the primitive's field one order below
    from_displacement: sp.Basic  # d^order/dt^order of the displacement field


@functools.cache
def oracle_rates(p: Prim) -> tuple[Rate, ...]:
    """The time derivative of every output field, next to the primitive's own rate fields."""
    prog = program(p)
    rates = []
    for out in prog.prim.outputs:
        levels = RECORD_FIELDS[out.kind]
        res = prog.results[out.name]
        for f0, f1, f2 in zip(*levels):
            d1 = prog.rate(res[f0])
            rates.append(Rate(out.name, f1, 1, res[f1], d1, d1))
            rates.append(Rate(out.name, f2, 2, res[f2], prog.rate(res[f1]), prog.rate(d1)))
    return tuple(rates)


def numeric(p: Prim, exprs: Sequence[sp.Basic]) -> Callable[[dict[str, object]], list]:
    """A function of {parameter name: value} giving expressions in the parameter symbols with mpmath."""
    syms = param_symbols(resolve(p))
    fn = sp.lambdify([*syms.values(), NAN], list(exprs), modules=_MPMATH, docstring_limit=0, printer=_printer())
    names = list(syms)

    def call(values: dict[str, object]) -> list:
        return fn(*(values[n] for n in names), mpmath.nan)

    return call


def _printer() -> MpmathPrinter:
    # terms in their stored order: sorting them is most of lambdify's time on these programs
    # Heaviside and DiracDelta (derivatives of Max, Min, Abs) are called by name, not
    # rewritten as Piecewise over their (large) arguments first.
    return MpmathPrinter({
        "fully_qualified_modules": False, "inline": True, "allow_unknown_functions": True,
        "user_functions": {"Heaviside": "Heaviside", "DiracDelta": "DiracDelta"}, "order": "none",
    })


def _heaviside(x, h0=None):
    if x > 0:
        return mpmath.mpf(1)
    if x < 0:
        return mpmath.mpf(0)
    return mpmath.mpf(h0) if h0 is not None else mpmath.nan


def _dirac(x, k=0):
    # derivatives of Max, Min and Abs: zero away from the switch, undefined on it
    return mpmath.mpf(0) if x != 0 else mpmath.nan


_MPMATH = [{"Heaviside": _heaviside, "DiracDelta": _dirac}, "mpmath"]
