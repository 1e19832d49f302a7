"""The numpy printer of a DSL primitive: the same formulas as the standard-library Python
function, on arrays of rows (NAME_np.py and the evaluator run it).

Array code pays for every operation on every row, so what the DSL writes twice (one node
read in two places, as the angle wrap's ``atan2(dy, dx) + off``) is computed once into a
temporary, and each failure mask once.  Neither changes a bit: the same operations run on
the same numbers.
"""

from __future__ import annotations

from collections import Counter

from ...primitives.dsl import Expr, Logic, Num, Primitive, Sym, children, field_order, record_fields
from ...primitives.printers import ATOM, ExprPrinter
from ..py.printer import PythonExprs, parameter_lines


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


def _record(fields: list[str]) -> str:
    return "(" + ", ".join(fields) + ("," if len(fields) == 1 else "") + ")"


def numpy_function(prim: Primitive, order: int) -> str:
    """A primitive on arrays of rows (records are tuples of arrays or numbers).

    Returns ``(status, sigma, outputs...)`` always: status 0 and sigma 1 where the function
    cannot fail.  A chain that cannot close (status 1) gives nan in every output field, a
    singular position (3) in the derivatives.
    """
    exprs = NumpyExprs()
    fields = prim.result_fields(order)
    roots = [let.expr for let in prim.live(order)] + [e for _, _, e in fields]
    roots += [e for e in (prim.status, prim.sigma) if e is not None]
    out = _Lines(exprs, _shared(roots))
    out.lines = [f"def {prim.name}({', '.join(p.name for p in prim.params)}):", f'    """{prim.doc}"""',
                 *parameter_lines(prim, order)]
    for let in prim.live(order):
        out.assign(let.name, let.expr)
    if prim.status is None:
        out.lines += ["    _st = np.asarray(0)", "    _sigma = np.asarray(1.0, dtype=float)"]
    else:
        out.assign("_st", prim.status)
        out.lines[-1] = f"    _st = np.asarray({exprs.expr(prim.status)})"
        sigma = exprs.expr(prim.sigma) if prim.sigma is not None else "1.0"
        out.lines += [f"    _sigma = np.asarray({sigma}, dtype=float)", "    _fails = _st == 1"]
        if order > 0:
            out.lines.append("    _singular = _fails | (_st == 3)")
    for _, _, e in fields:
        out.temporaries(e)
    for p in prim.outputs:
        fields_of = [exprs.expr(prim.results[p.name][f]) for f in record_fields(p.kind, order)]
        out.lines.append(f"    _{p.name} = {_record(fields_of)}")
    if prim.status is not None:
        out.lines.append(f"    if np.any({'_singular' if order > 0 else '_fails'}):  # nan where the rows failed")
        for p in prim.outputs:
            masked = [f"np.where({'_fails' if field_order(p.kind, f) == 0 else '_singular'}, np.nan, _{p.name}[{k}])"
                      for k, f in enumerate(record_fields(p.kind, order))]
            out.lines.append(f"        _{p.name} = {_record(masked)}")
    out.lines.append(f"    return _st, _sigma, {', '.join(f'_{p.name}' for p in prim.outputs)}")
    return "\n".join(out.lines) + "\n"
