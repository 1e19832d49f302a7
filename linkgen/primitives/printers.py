"""What every language's printer of a DSL primitive shares (linkgen/backends/<lang>/printer.py print).

The expression printer keeps the evaluation order written in the DSL exactly
(a right operand of the same precedence is always parenthesised), so every
language rounds the same way.  Each language subclass says how to spell
symbols, constants, calls and selections, and how a function is laid out.
"""

from __future__ import annotations

from collections.abc import Callable

from .. import status
from .dsl import Bin, Call, Cmp, Const, Expr, Logic, Neg, Num, Param, Primitive, Select, Sym, field_order, record_fields

_PREC = {"select": 1, "or": 2, "and": 3, "cmp": 5, "+": 6, "-": 6, "*": 7, "/": 7, "neg": 8, "atom": 10}
ATOM = _PREC["atom"]  # a name, a number or a call: never parenthesised
MASKS = ((status.CANNOT_CLOSE, 0), (status.SINGULAR, 1))  # a chain's status -> first derivative order that is nan


def literal(value: float | int) -> str:
    """Shortest round-trip spelling of a number, valid in Python, C and MATLAB."""
    if isinstance(value, bool):
        raise TypeError("booleans are not numbers here")
    if isinstance(value, int):
        return str(value)
    if value != value or value in (float("inf"), float("-inf")):
        raise ValueError("non-finite literal")
    return repr(float(value))


class ExprPrinter:
    """Language-neutral expression layout; subclasses spell the leaves."""

    and_op = "and"
    or_op = "or"
    calls = {f: f for f in ("sqrt", "atan2", "cos", "sin", "abs", "max", "min")}  # the DSL's functions by their names
    consts: dict[str, str] = {}
    compares = False  # max and min as a comparison and a conditional expression (else as calls)

    def sym(self, name: str) -> str:
        return name

    def select(self, cond: str, a: str, b: str) -> str:
        raise NotImplementedError

    def prec(self, e: Expr) -> int:
        if isinstance(e, Bin):
            return _PREC[e.op]
        if isinstance(e, Neg) or (isinstance(e, Num) and e.value < 0):
            return _PREC["neg"]
        if isinstance(e, Cmp):
            return _PREC["cmp"]
        if isinstance(e, Logic):
            return _PREC[e.op]
        if isinstance(e, Select):
            return _PREC["select"]
        return _PREC["atom"]

    def wrapped(self, e: Expr, parens: bool) -> str:
        text = self.expr(e)
        return f"({text})" if parens else text

    def expr(self, e: Expr) -> str:
        if isinstance(e, Sym):
            return self.sym(e.name)
        if isinstance(e, Num):
            return literal(e.value)
        if isinstance(e, Const):
            return self.consts[e.name]
        if isinstance(e, Call):
            if self.compares and e.fn in ("max", "min"):
                return self.choice(e)
            return f"{self.calls[e.fn]}({', '.join(self.expr(a) for a in e.args)})"
        if isinstance(e, Neg):
            return "-" + self.wrapped(e.a, self.prec(e.a) <= _PREC["neg"])
        if isinstance(e, (Bin, Cmp)):
            p = self.prec(e)
            left = self.wrapped(e.a, self.prec(e.a) < p)
            right = self.wrapped(e.b, self.prec(e.b) <= p)
            return f"{left} {e.op} {right}"
        if isinstance(e, Logic):
            return self.logic(e)
        if isinstance(e, Select):
            p = _PREC["select"]
            return self.select(
                self.wrapped(e.cond, self.prec(e.cond) <= p),
                self.wrapped(e.a, self.prec(e.a) <= p),
                self.wrapped(e.b, self.prec(e.b) < p),
            )
        raise TypeError(f"cannot print {e!r}")

    def choice(self, e: Call) -> str:
        """max(a, b) as ``b > a ? b : a`` (min with <), parenthesised: Python's choice, a compare
        and a move in C where fmax is a library call (its operands are names or numbers)."""
        a, b = (self.expr(x) for x in e.args)
        op = ">" if e.fn == "max" else "<"
        return f"({self.select(f'{b} {op} {a}', b, a)})"

    def logic(self, e: Logic) -> str:
        p = self.prec(e)
        op = self.and_op if e.op == "and" else self.or_op
        left = self.wrapped(e.a, self.prec(e.a) < p)
        right = self.wrapped(e.b, self.prec(e.b) <= p)
        return f"{left} {op} {right}"


class RecordExprs(ExprPrinter):
    """A printer of a function whose record parameters are structs (``j1_dx`` is ``j1.<field>``) in
    a language that writes and and or as && and || (C, MATLAB)."""

    and_op = "&&"
    or_op = "||"

    def __init__(self, prim: Primitive):
        self.fields = {f"{p.name}_{f}": f"{p.name}.{self.field(p.kind, f)}"
                       for p in prim.params if p.is_record for f in record_fields(p.kind, 2)}

    @staticmethod
    def field(kind: str, name: str) -> str:
        """A record field as the language's structs name it."""
        return name

    def sym(self, name: str) -> str:
        return self.fields.get(name, name)


def statements(prim: Primitive, order: int, exprs: ExprPrinter,
               assign: Callable[[str, Expr, str], list[str]], store: Callable[[Param, str, Expr], list[str]]
               ) -> list[str]:
    """A function body in statements: the live definitions, the status and the conditioning
    (``assign(name, expression, type)``, type int, double or '' to infer), then every result
    field (``store``)."""
    lines = [line for let in prim.live(order) for line in assign(let.name, let.expr, "")]
    if prim.status is not None:
        lines += assign("st", prim.status, "int")
    if prim.sigma is not None and exprs.expr(prim.sigma) != "sigma":
        lines += assign("sigma", prim.sigma, "double")
    return lines + [line for p, f, e in prim.result_fields(order) for line in store(p, f, e)]


def masks(prim: Primitive, order: int, or_op: str) -> list[tuple[str, list[tuple[Param, str]]]]:
    """Per failing status, the condition on ``st`` and the result fields it makes nan: a chain
    that cannot close (1) every field, a singular position (3) the derivatives."""
    out = []
    returned = prim.codes()
    for code, nan_from in MASKS:
        fields = [(p, f) for p, f, _ in prim.result_fields(order) if nan_from <= field_order(p.kind, f)]
        if fields and code in returned:
            codes = [c for c, n in MASKS if n <= nan_from and c in returned]
            out.append((f" {or_op} ".join(f"st == {c}" for c in codes), fields))
    return out
