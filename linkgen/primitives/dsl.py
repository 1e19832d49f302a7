"""A tiny straight-line language in which every runtime primitive is written once.

Each primitive (``RRR_links``, ``crank_input``, ...) is a list of scalar assignments over the
fields of its record arguments.  Printers turn that one definition into Python (``math``), NumPy
(the evaluator), C99 and MATLAB/Octave, and ``to_sympy`` turns it into sympy expressions so the
tests can prove the derivative formulas.  Every assignment carries the derivative order it
belongs to (0 displacement, 1 velocity, 2 acceleration) so a program built for a lower order
contains none of the higher-order code.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import TypeVar

from ..status import CANNOT_CLOSE

# Record kinds and their scalar fields, by derivative order (mech.cpp's POINT,
# ANGLE and VARIABLE records).
RECORD_FIELDS: dict[str, tuple[tuple[str, ...], ...]] = {
    "POINT": (("x", "y"), ("dx", "dy"), ("ddx", "ddy")),
    "ANGLE": (("the",), ("dthe",), ("ddthe",)),
    "VARIABLE": (("v",), ("dv",), ("ddv",)),
    # an instant centre (linkgen.instant): known from velocities, so its fields are all of order 1
    "CENTRE": ((), ("x", "y", "ux", "uy", "status", "sigma"), ()),
}


def record_fields(kind: str, order: int) -> tuple[str, ...]:
    """The scalar fields of a record kind up to a derivative order."""
    return tuple(f for level in RECORD_FIELDS[kind][: order + 1] for f in level)


def field_order(kind: str, name: str) -> int:
    """The derivative order of one field of a record kind."""
    for level, names in enumerate(RECORD_FIELDS[kind]):
        if name in names:
            return level
    raise KeyError(f"{kind} has no field {name}")


_T = TypeVar("_T")
Operator = Callable[["Expr", object], "Expr"]


def _arithmetic(op: str) -> tuple[Operator, Operator]:
    """An arithmetic operator and its reflected form (``2 * x`` as well as ``x * 2``)."""
    return (lambda a, b: Bin(op, a, wrap(b))), (lambda a, b: Bin(op, wrap(b), a))


def _comparison(op: str) -> Operator:
    return lambda a, b: Cmp(op, a, wrap(b))


class Expr:
    """An expression node; Python operators build new nodes (``eq`` stands for ``==``,
    which dataclasses and sets need as identity)."""

    __add__, __radd__ = _arithmetic("+")
    __sub__, __rsub__ = _arithmetic("-")
    __mul__, __rmul__ = _arithmetic("*")
    __truediv__, __rtruediv__ = _arithmetic("/")
    __lt__, __le__, __gt__, __ge__ = (_comparison(op) for op in ("<", "<=", ">", ">="))
    eq = _comparison("==")

    def __neg__(self) -> Expr:
        return Neg(self)


@dataclass(frozen=True, eq=False)
class Sym(Expr):
    name: str


@dataclass(frozen=True, eq=False)
class Num(Expr):
    value: float | int


@dataclass(frozen=True, eq=False)
class Const(Expr):
    """A named mathematical constant: ``eps`` (machine epsilon), ``nan``, ``pi``."""

    name: str


@dataclass(frozen=True, eq=False)
class Binary(Expr):
    """An operator on two operands; the subclass says which kind."""

    op: str
    a: Expr
    b: Expr


class Bin(Binary):
    """Arithmetic: + - * /."""


class Cmp(Binary):
    """A comparison: < <= > >= ==."""


class Logic(Binary):
    """``or`` (``either``) or ``and``."""


@dataclass(frozen=True, eq=False)
class Neg(Expr):
    a: Expr


@dataclass(frozen=True, eq=False)
class Call(Expr):
    """A math function: sqrt, atan2, cos, sin, abs, max, min."""

    fn: str
    args: tuple[Expr, ...]


@dataclass(frozen=True, eq=False)
class Select(Expr):
    """``a`` where ``cond`` holds, else ``b``."""

    cond: Expr
    a: Expr
    b: Expr


def wrap(value: object) -> Expr:
    if isinstance(value, Expr):
        return value
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise TypeError(f"cannot use {value!r} in an expression")
    return Num(value)


def sqrt(a: Expr) -> Expr:
    return Call("sqrt", (a,))


def atan2(y: Expr, x: Expr) -> Expr:
    return Call("atan2", (y, x))


def cos(a: Expr) -> Expr:
    return Call("cos", (a,))


def sin(a: Expr) -> Expr:
    return Call("sin", (a,))


def fabs(a: Expr) -> Expr:
    return Call("abs", (a,))


def _operands(fn: str, a: object, b: object) -> Expr:
    """max or min of two names or numbers: b where it is the larger (the smaller), else a, as
    Python's max and min choose (a nan b gives a).  The operands are names or numbers, so a
    printer may spell the choice as a comparison without computing either twice."""
    args = (wrap(a), wrap(b))
    if not all(isinstance(x, (Sym, Num, Const)) for x in args):
        raise TypeError(f"{fn}() takes names or numbers (let-bind an expression first)")
    return Call(fn, args)


def fmax(a: object, b: object) -> Expr:
    return _operands("max", a, b)


def fmin(a: object, b: object) -> Expr:
    return _operands("min", a, b)


def either(a: Expr, b: Expr) -> Expr:
    return Logic("or", a, b)


def select(cond: Expr, a: object, b: object) -> Expr:
    return Select(cond, wrap(a), wrap(b))


EPS = Const("eps")
NAN = Const("nan")
PI = Const("pi")


@dataclass(frozen=True)
class Param:
    name: str
    kind: str  # a RECORD_FIELDS key, or REAL or INT for a scalar

    @property
    def is_record(self) -> bool:
        return self.kind in RECORD_FIELDS


class Record:
    """A record argument seen from inside a primitive: ``j1.x``, ``j1.dx``, ..."""

    def __init__(self, name: str, kind: str):
        self._name = name
        self._kind = kind

    def __getattr__(self, fieldname: str) -> Sym:
        if fieldname.startswith("_"):
            raise AttributeError(fieldname)
        field_order(self._kind, fieldname)  # raises on a wrong field
        return Sym(f"{self._name}_{fieldname}")


@dataclass(frozen=True)
class Let:
    name: str
    expr: Expr
    order: int


def children(e: Expr) -> tuple[Expr, ...]:
    if isinstance(e, Binary):
        return (e.a, e.b)
    if isinstance(e, Neg):
        return (e.a,)
    if isinstance(e, Call):
        return e.args
    if isinstance(e, Select):
        return (e.cond, e.a, e.b)
    return ()


def symbols(e: Expr) -> set[str]:
    """Names of the symbols an expression reads."""
    if isinstance(e, Sym):
        return {e.name}
    out: set[str] = set()
    for c in children(e):
        out |= symbols(c)
    return out


@dataclass(frozen=True)
class Primitive:
    """One runtime function: parameters, straight-line body, record outputs.

    ``results`` maps each output record to its fields' expressions.  ``status``
    is 0 (done), 1 (the chain cannot close: every output nan), 3 (singular:
    displacements valid, derivatives nan) or 4 (near singular: values valid);
    None when the function cannot fail.  ``sigma`` is the dimensionless
    conditioning reported with the status (None when there is none); ``fail``
    the condition of status 1 alone (``unchecked``).
    """

    name: str
    doc: str
    params: tuple[Param, ...]
    outputs: tuple[Param, ...]
    body: tuple[Let, ...]
    results: dict[str, dict[str, Expr]] = field(hash=False)
    status: Expr | None = None
    sigma: Expr | None = None
    fail: Expr | None = None

    def unchecked(self) -> Primitive:
        """The function without its checks (options.checks off): status 1 where it cannot
        give an answer (``fail``: its outputs nan), else 0; no conditioning, no singular codes."""
        if self.fail is not None:
            status: Expr | None = Select(self.fail, Num(CANNOT_CLOSE), Num(0))
        else:  # a status that is a failure alone stays
            status = self.status if self.codes() <= {CANNOT_CLOSE} else None
        return replace(self, status=status, sigma=None)

    def codes(self) -> frozenset[int]:
        """The status codes the function can return besides 0."""
        found: set[int] = set()

        def walk(e: Expr) -> None:
            if isinstance(e, Select):
                for branch in (e.a, e.b):
                    if isinstance(branch, Num) and branch.value:
                        found.add(int(branch.value))
                    walk(branch)

        if self.status is not None:
            walk(self.status)
        return frozenset(found)

    def result_fields(self, order: int) -> list[tuple[Param, str, Expr]]:
        """(output, field, expression) for every output field up to ``order``."""
        return [
            (out, f, self.results[out.name][f])
            for out in self.outputs
            for f in record_fields(out.kind, order)
        ]

    def live(self, order: int, with_sigma: bool = True) -> tuple[Let, ...]:
        """The assignments needed for the outputs up to ``order`` (dead code dropped)."""
        return self._memo("live", order, with_sigma, self._live)

    def params_used(self, order: int, with_sigma: bool = True) -> set[str]:
        """Parameter fields (``j1_x``) and scalars read at ``order``."""
        return set(self._memo("used", order, with_sigma, self._params_used))

    def _memo(self, what: str, order: int, with_sigma: bool, compute: Callable[[int, bool], _T]) -> _T:
        """A walk of the body computed once per primitive (the printers ask for it per call they print)."""
        memo = self.__dict__.setdefault("_walks", {})  # not a field: replace() and == ignore it
        if (what, order, with_sigma) not in memo:
            memo[what, order, with_sigma] = compute(order, with_sigma)
        return memo[what, order, with_sigma]  # type: ignore[no-any-return]

    def _live(self, order: int, with_sigma: bool) -> tuple[Let, ...]:
        roots = [e for _, _, e in self.result_fields(order)]
        roots += [e for e in (self.status, self.sigma if with_sigma else None) if e is not None]
        needed: set[str] = set()
        for e in roots:
            needed |= symbols(e)
        kept = []
        for let in reversed(self.body):
            if let.name in needed:
                kept.append(let)
                needed |= symbols(let.expr)
        return tuple(reversed(kept))

    def _params_used(self, order: int, with_sigma: bool) -> frozenset[str]:
        used: set[str] = set()
        for let in self.live(order, with_sigma):
            used |= symbols(let.expr)
        for e in [e for _, _, e in self.result_fields(order)] + [self.status, self.sigma if with_sigma else None]:
            if e is not None:
                used |= symbols(e)
        return frozenset(used - {let.name for let in self.body})


class Builder:
    """Collects the statements of one primitive in the order they are written.

    The derivative order of each assignment is inferred from what it reads.
    """

    def __init__(self, name: str, doc: str):
        self.name = name
        self.doc = doc
        self.params: list[Param] = []
        self.outputs: list[Param] = []
        self.body: list[Let] = []
        self.results: dict[str, dict[str, Expr]] = {}
        self._orders: dict[str, int] = {}

    def record(self, name: str, kind: str) -> Record:
        self.params.append(Param(name, kind))
        for f in record_fields(kind, 2):
            self._orders[f"{name}_{f}"] = field_order(kind, f)
        return Record(name, kind)

    def scalar(self, name: str, kind: str = "REAL") -> Sym:
        self.params.append(Param(name, kind))
        self._orders[name] = 0
        return Sym(name)

    def scalars(self, *names: str) -> tuple[Sym, ...]:
        """Several REAL parameters, in this order."""
        return tuple(self.scalar(name) for name in names)

    def order_of(self, e: Expr) -> int:
        return max((self._orders[s] for s in symbols(e)), default=0)

    def let(self, name: str, expr: object) -> Sym:
        if name in self._orders:
            raise ValueError(f"{self.name}: {name} assigned twice")
        e = wrap(expr)
        order = self.order_of(e)
        self.body.append(Let(name, e, order))
        self._orders[name] = order
        return Sym(name)

    def output(self, name: str, kind: str, **fields: Expr) -> None:
        self.outputs.append(Param(name, kind))
        self.results[name] = {k: wrap(v) for k, v in fields.items()}

    def build(self, status: Expr | None = None, sigma: Expr | None = None, fail: Expr | None = None) -> Primitive:
        names = {p.name for p in self.params} | {p.name for p in self.outputs}
        clash = names & {let.name for let in self.body}
        if clash:
            raise ValueError(f"{self.name}: locals named like arguments: {sorted(clash)}")
        for out in self.outputs:
            wanted = set(record_fields(out.kind, 2))
            got = self.results[out.name]
            if set(got) != wanted:
                raise ValueError(f"{self.name}: output {out.name} needs fields {sorted(wanted)}")
            for f, e in got.items():
                if self.order_of(e) > field_order(out.kind, f):
                    raise ValueError(f"{self.name}: {out.name}.{f} reads a higher derivative")
        for flag in (status, sigma, fail):
            if flag is not None and self.order_of(flag) > 0:
                raise ValueError(f"{self.name}: status and sigma must come from displacements")
        return Primitive(
            self.name, self.doc, tuple(self.params), tuple(self.outputs), tuple(self.body),
            self.results, status, sigma, fail,
        )
