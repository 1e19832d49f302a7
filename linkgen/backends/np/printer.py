"""The numpy printer of a DSL primitive: the same formulas as the standard-library Python
function, on arrays of rows (NAME_np.py and the evaluator run it).

Array code pays for every operation on every row, so what the DSL writes twice (one node
read in two places, as the angle wrap's ``atan2(dy, dx) + off``) is computed once into a
temporary, and each failure mask once.  Neither changes a bit: the same operations run on
the same numbers.
"""

from __future__ import annotations

from collections import Counter

from ...primitives.dsl import (
    Binary,
    Call,
    Const,
    Expr,
    Let,
    Logic,
    Num,
    Primitive,
    Select,
    Sym,
    children,
    field_order,
    record_fields,
)
from ...primitives.printers import ATOM, ExprPrinter
from ..py.printer import PythonExprs, parameter_lines
from ..still import rebuilt as _rebuilt
from ..still import substituted as _substituted


class NumpyExprs(PythonExprs):
    calls = {**{f: f"np.{f}" for f in ExprPrinter.calls}, "atan2": "np.arctan2", "max": "np.maximum",
             "min": "np.minimum"}
    and_op = "&"
    or_op = "|"
    compares = False

    def __init__(self) -> None:
        self.names: dict[int, str] = {}  # id of a node computed into a temporary -> its name

    def expr(self, e: Expr) -> str:
        return self.names.get(id(e)) or super().expr(e)

    def prec(self, e: Expr) -> int:
        return ATOM if id(e) in self.names else super().prec(e)

    def select(self, cond: str, a: str, b: str) -> str:
        return f"np.where({cond}, {a}, {b})"

    def logic(self, e: Logic) -> str:
        op = self.and_op if e.op == "and" else self.or_op
        return f"({self.expr(e.a)}) {op} ({self.expr(e.b)})"


def _shared(roots: list[Expr]) -> set[int]:
    """Nodes (not symbols or numbers) reached more than once from the roots."""
    seen: Counter[int] = Counter()

    def walk(e: Expr) -> None:
        if isinstance(e, (Sym, Num)) or not children(e):
            return
        seen[id(e)] += 1
        if seen[id(e)] == 1:
            for c in children(e):
                walk(c)

    for root in roots:
        walk(root)
    return {k for k, n in seen.items() if n > 1}


class _Lines:
    """Statements of one function, each preceded by the shared nodes it is the first to read."""

    def __init__(self, exprs: NumpyExprs, shared: set[int]):
        self.exprs, self.shared, self.lines = exprs, shared, []  # type: ignore[var-annotated]
        self.made = 0  # names made for conditions and selections

    def temporaries(self, e: Expr) -> None:
        for c in children(e):
            self.temporaries(c)
        if id(e) in self.shared and id(e) not in self.exprs.names:
            text = self.exprs.expr(e)
            self.exprs.names[id(e)] = name = f"_t{len(self.exprs.names) + 1}"
            self.lines.append(f"    {name} = {text}")

    def assign(self, name: str, e: Expr) -> None:
        """``name = e``, after the temporaries e is the first to read."""
        self.temporaries(e)
        self.lines.append(f"    {name} = {self.exprs.expr(e)}")

    def branched(self, name: str, e: Expr, indent: str = "    ") -> None:
        """``name = e`` where e selects (anywhere in it): only the branch every row takes where
        they all take one (each row gets what np.where gives it), both where the rows part."""
        if indent == "    ":
            self.temporaries(e)
        if not isinstance(e, Select) or id(e) in self.exprs.names:
            self._hoisted(e, indent)
            self.lines.append(f"{indent}{name} = {self.exprs.expr(e)}")
            return
        self._hoisted(e.cond, indent)
        self.made += 1
        cond = f"_c{self.made}"
        self.lines.append(f"{indent}{cond} = np.asarray({self.exprs.expr(e.cond)})")
        for test, branch in ((f"if not {cond}.any():", e.b), (f"elif {cond}.all():", e.a)):
            self.lines.append(f"{indent}{test}")
            scope = dict(self.exprs.names)  # what a branch names is not there in the others
            self.branched(name, branch, indent + "    ")
            self.exprs.names = scope
        self.lines.append(f"{indent}else:")
        self.lines.append(f"{indent}    {name} = np.where({cond}, {self.exprs.expr(e.a)}, {self.exprs.expr(e.b)})")

    def _hoisted(self, e: Expr, indent: str) -> None:
        """The selections inside e (outside any selection's branch) computed first, branched."""
        for c in children(e):
            if id(c) in self.exprs.names or isinstance(c, (Sym, Num)):
                continue
            if isinstance(c, Select):
                self.made += 1
                tmp = f"_s{self.made}"
                self.branched(tmp, c, indent)
                self.exprs.names[id(c)] = tmp
            else:
                self._hoisted(c, indent)


def _selects(e: Expr) -> bool:
    """Whether e holds a selection."""
    return isinstance(e, Select) or any(_selects(c) for c in children(e))


def _cos_sin_pairs(lets: tuple[Let, ...]) -> dict[str, tuple[str, str]]:
    """{cos let: (its name, the sin let's)} of a cosine and a sine of the same symbol (taken from one
    half-angle tangent by the runtime's cos_sin, within an eps of numpy's own)."""
    calls: dict[tuple[str, str], str] = {}
    for let in lets:
        e = let.expr
        if isinstance(e, Call) and e.fn in ("cos", "sin") and isinstance(e.args[0], Sym):
            calls[e.fn, e.args[0].name] = let.name
    return {c: (c, calls["sin", arg]) for (fn, arg), c in calls.items() if fn == "cos" and ("sin", arg) in calls}


def _own(e: Expr) -> tuple[object, ...]:
    """What a node is besides its children: a symbol's or a constant's name, a number's type and
    value, a call's function, an operator."""
    if isinstance(e, (Sym, Const)):
        return (e.name,)
    if isinstance(e, Num):
        return (type(e.value).__name__, repr(e.value))
    if isinstance(e, Call):
        return (e.fn,)
    if isinstance(e, Binary):
        return (e.op,)
    return ()


def _merged(roots: list[Expr]) -> list[Expr]:
    """The roots with the nodes written alike (the same operations on the same operands) made one
    node where one of them is read outside every selection's branch: computed once then, at no
    cost to a row that takes a branch, with the same bits."""
    keys: dict[int, tuple[object, ...]] = {}

    def key(e: Expr) -> tuple[object, ...]:
        if id(e) not in keys:
            keys[id(e)] = (type(e).__name__, *_own(e), *(key(c) for c in children(e)))
        return keys[id(e)]

    outside: set[tuple[object, ...]] = set()

    def walk(e: Expr, inside: bool) -> None:
        if not inside:
            outside.add(key(e))
        for k, c in enumerate(children(e)):
            walk(c, inside or (isinstance(e, Select) and k > 0))

    for root in roots:
        walk(root, False)
    one: dict[tuple[object, ...], Expr] = {}
    memo: dict[int, Expr] = {}

    def rebuild(e: Expr) -> Expr:
        if id(e) not in memo:
            node = _rebuilt(e, [rebuild(c) for c in children(e)])
            memo[id(e)] = one.setdefault(key(e), node) if key(e) in outside else node
        return memo[id(e)]

    return [rebuild(root) for root in roots]


def _uses(exprs: list[Expr]) -> tuple[Counter[str], set[str]]:
    """How often each symbol is read (a shared node counted at each reading), and the symbols read
    in a branch of a selection."""
    count: Counter[str] = Counter()
    branch: set[str] = set()

    def walk(e: Expr, inside: bool) -> None:
        if isinstance(e, Sym):
            count[e.name] += 1
            if inside:
                branch.add(e.name)
        for k, c in enumerate(children(e)):
            walk(c, inside or (isinstance(e, Select) and k > 0))

    for e in exprs:
        walk(e, False)
    return count, branch


def _record(fields: list[str]) -> str:
    return "(" + ", ".join(fields) + ("," if len(fields) == 1 else "") + ")"


def numpy_function(prim: Primitive, order: int, suffix: str = "", name: str = "") -> str:
    """A primitive on arrays of rows (records are tuples of arrays or numbers).

    Returns ``(status, sigma, outputs...)`` always: status 0 and sigma 1 where the function
    cannot fail.  A chain that cannot close (status 1) gives nan in every output field, a
    singular position (3) in the derivatives.  With a suffix it is named name + suffix and
    takes records of any higher order too (their first fields); name (the primitive's unless
    given) is what it is called by before the suffix.
    """
    exprs = NumpyExprs()
    # a selection read once, and what a branch alone reads once, is computed where it is read: then
    # only in the branch the rows take
    lets, fields = prim.live(order), prim.result_fields(order)
    tails = [e for _, _, e in fields] + [e for e in (prim.status, prim.sigma) if e is not None]
    uses, in_branch = _uses([let.expr for let in lets] + tails)
    inline: dict[str, Expr] = {}
    memo: dict[int, Expr] = {}
    body: list[Let] = []
    for let in lets:
        e = _substituted(let.expr, inline, memo)
        if uses[let.name] == 1 and (isinstance(e, Select) or let.name in in_branch):
            inline[let.name] = e
        else:
            body.append(Let(let.name, e, let.order))
    lets = tuple(body)
    fields = [(o, f, _substituted(e, inline, memo)) for o, f, e in fields]
    status, sigma_of = (None if e is None else _substituted(e, inline, memo) for e in (prim.status, prim.sigma))
    tails = [e for e in (status, sigma_of) if e is not None]
    merged = iter(_merged([let.expr for let in lets] + [e for _, _, e in fields] + tails))
    lets = tuple(Let(let.name, next(merged), let.order) for let in lets)
    fields = [(o, f, next(merged)) for o, f, _ in fields]
    status, sigma_of = (None if e is None else next(merged) for e in (status, sigma_of))
    roots = [let.expr for let in lets] + [e for _, _, e in fields] + [e for e in (status, sigma_of) if e is not None]
    out = _Lines(exprs, _shared(roots))
    unpack = parameter_lines(prim, order)
    if suffix:
        unpack = [f"{line}[:{line.split(' = ')[0].count(',') + 1}]" for line in unpack]
    out.lines = [f"def {name or prim.name}{suffix}({', '.join(p.name for p in prim.params)}):", f'    """{prim.doc}"""',
                 *unpack]
    pairs = _cos_sin_pairs(lets) if prim.status is None else {}  # no status decided on a rounded cosine
    sines = {s for _, s in pairs.values()}
    for let in lets:
        if let.name in pairs:  # one tangent for both: numpy's sin and cos are scalar library calls
            assert isinstance(let.expr, Call)
            out.lines.append(f"    {', '.join(pairs[let.name])} = cos_sin({exprs.expr(let.expr.args[0])})")
        elif let.name not in sines:
            out.branched(let.name, let.expr)
    if status is None:
        out.lines += ["    _st = np.asarray(0)", "    _sigma = np.asarray(1.0, dtype=REAL)"]
    else:
        out.branched("_st", status)
        out.branched("_sigma", sigma_of if sigma_of is not None else Num(1.0))
        out.lines += ["    _st = np.asarray(_st)", "    _sigma = np.asarray(_sigma, dtype=REAL)",
                      "    _fails = _st == 1"]
        if order > 0:
            out.lines.append("    _singular = _fails | (_st == 3)")
    for _, _, e in fields:
        out.temporaries(e)
    by_field = {(o.name, f): e for o, f, e in fields}
    for k, (_, _, e) in enumerate(fields):
        if _selects(e) and id(e) not in exprs.names:  # a field that selects: its own statement
            out.branched(f"_f{k + 1}", e)
            exprs.names[id(e)] = f"_f{k + 1}"
    for p in prim.outputs:
        fields_of = [exprs.expr(by_field[p.name, f]) for f in record_fields(p.kind, order)]
        out.lines.append(f"    _{p.name} = {_record(fields_of)}")
    if prim.status is not None:
        out.lines.append(f"    if {'_singular' if order > 0 else '_fails'}.any():  # nan where the rows failed")
        for p in prim.outputs:
            masked = [f"np.where({'_fails' if field_order(p.kind, f) == 0 else '_singular'}, np.nan, _{p.name}[{k}])"
                      for k, f in enumerate(record_fields(p.kind, order))]
            out.lines.append(f"        _{p.name} = {_record(masked)}")
    out.lines.append(f"    return _st, _sigma, {', '.join(f'_{p.name}' for p in prim.outputs)}")
    return "\n".join(out.lines) + "\n"
