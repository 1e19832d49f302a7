"""The Python printers of a DSL primitive: standard-library functions on tuples of floats (the
generated programs and the evaluator's scalar runtime) and their numpy twins (the evaluator's
vectorised runtime)."""

from __future__ import annotations

from ...primitives.dsl import Logic, Param, Primitive, field_order, record_fields
from ...primitives.printers import MASKS, ExprPrinter


class PythonExprs(ExprPrinter):
    consts = {"eps": "EPS", "nan": "NAN", "pi": "PI"}

    def select(self, cond: str, a: str, b: str) -> str:
        return f"{a} if {cond} else {b}"


class NumpyExprs(PythonExprs):
    calls = {**{f: f"np.{f}" for f in ExprPrinter.calls}, "atan2": "np.arctan2", "max": "np.maximum",
             "min": "np.minimum"}
    and_op = "&"
    or_op = "|"

    def select(self, cond: str, a: str, b: str) -> str:
        return f"np.where({cond}, {a}, {b})"

    def logic(self, e: Logic) -> str:
        op = self.and_op if e.op == "and" else self.or_op
        return f"({self.expr(e.a)}) {op} ({self.expr(e.b)})"


def _field_names(p: Param, order: int) -> list[str]:
    return [f"{p.name}_{f}" for f in record_fields(p.kind, order)]


def _python_lines(prim: Primitive, order: int, exprs: ExprPrinter) -> list[str]:
    """Body shared by the math and numpy flavours (they differ in leaves and masking)."""
    used = prim.params_used(order)
    lines = [f'    """{prim.doc}"""']
    for p in prim.params:
        if p.is_record:
            names = [n if n in used else "_" for n in _field_names(p, order)]
            if any(n != "_" for n in names):
                lines.append(f"    {', '.join(names)}{',' if len(names) == 1 else ''} = {p.name}")
    for let in prim.live(order):
        lines.append(f"    {let.name} = {exprs.expr(let.expr)}")
    return lines


def _result_tuples(prim: Primitive, order: int, exprs: ExprPrinter, nan_from: int | None) -> list[str]:
    """One tuple per output; fields of order >= nan_from are nan."""
    out = []
    for p in prim.outputs:
        fields = []
        for f in record_fields(p.kind, order):
            if nan_from is not None and field_order(p.kind, f) >= nan_from:
                fields.append(exprs.consts["nan"])
            else:
                fields.append(exprs.expr(prim.results[p.name][f]))
        out.append("(" + ", ".join(fields) + ("," if len(fields) == 1 else "") + ")")
    return out


def python_function(prim: Primitive, order: int) -> str:
    """A standard-library Python function: records are tuples of floats.

    Returns ``outputs`` (one record, or a tuple of them); functions that can fail
    return ``(status, [sigma,] outputs...)``.
    """
    exprs = PythonExprs()
    lines = [f"def {prim.name}({', '.join(p.name for p in prim.params)}):"]
    lines += _python_lines(prim, order, exprs)
    head = [name for name, e in (("st", prim.status), ("sigma", prim.sigma)) if e is not None]
    if prim.status is not None:
        lines.append(f"    st = {exprs.expr(prim.status)}")
        if prim.sigma is not None and exprs.expr(prim.sigma) != "sigma":
            lines.append(f"    sigma = {exprs.expr(prim.sigma)}")
        for code, nan_from in MASKS:
            if nan_from <= order:
                values = ", ".join(head + _result_tuples(prim, order, exprs, nan_from))
                lines.append(f"    if st == {code}:")
                lines.append(f"        return {values}")
    values = ", ".join(head + _result_tuples(prim, order, exprs, None))
    lines.append(f"    return {values}")
    return "\n".join(lines) + "\n"


def numpy_function(prim: Primitive, order: int) -> str:
    """The evaluator's vectorised twin: same formulas over numpy arrays.

    Always returns ``(status, sigma, outputs...)``: status 0 and sigma 1 where
    the function cannot fail.
    """
    exprs = NumpyExprs()
    lines = [f"def {prim.name}({', '.join(p.name for p in prim.params)}):"]
    lines += _python_lines(prim, order, exprs)
    status = exprs.expr(prim.status) if prim.status is not None else "0"
    sigma = exprs.expr(prim.sigma) if prim.sigma is not None else "1.0"
    lines.append(f"    st = np.asarray({status})")
    lines.append(f"    sigma = np.asarray({sigma}, dtype=float)")
    outs = []
    for p in prim.outputs:
        fields = []
        for f in record_fields(p.kind, order):
            value = exprs.expr(prim.results[p.name][f])
            bad = "(st == 1)" if field_order(p.kind, f) == 0 else "(st == 1) | (st == 3)"
            fields.append(f"np.where({bad}, np.nan, {value})")
        outs.append("(" + ", ".join(fields) + ("," if len(fields) == 1 else "") + ")")
    lines.append(f"    return st, sigma, {', '.join(outs)}")
    return "\n".join(lines) + "\n"
