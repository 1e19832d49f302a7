"""Print a DSL primitive as source code of one language.

The expression printer keeps the evaluation order written in the DSL exactly
(a right operand of the same precedence is always parenthesised), so every
language rounds the same way.  Each language subclass says how to spell
symbols, constants, calls and selections, and how a function is laid out.
"""

from __future__ import annotations

from .dsl import (
    RECORD_FIELDS,
    Bin,
    Call,
    Cmp,
    Const,
    Expr,
    Logic,
    Neg,
    Num,
    Param,
    Primitive,
    Select,
    Sym,
    record_fields,
)

_PREC = {"select": 1, "or": 2, "and": 3, "cmp": 5, "+": 6, "-": 6, "*": 7, "/": 7, "neg": 8, "atom": 10}
_MASKS = ((1, 0), (3, 1))  # status -> first derivative order that is nan


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
    calls: dict[str, str] = {}
    consts: dict[str, str] = {}

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

    def logic(self, e: Logic) -> str:
        p = self.prec(e)
        op = self.and_op if e.op == "and" else self.or_op
        left = self.wrapped(e.a, self.prec(e.a) < p)
        right = self.wrapped(e.b, self.prec(e.b) <= p)
        return f"{left} {op} {right}"


class PythonExprs(ExprPrinter):
    calls = {
        "sqrt": "sqrt", "atan2": "atan2", "cos": "cos", "sin": "sin",
        "abs": "abs", "max": "max", "min": "min",
    }
    consts = {"eps": "EPS", "nan": "NAN", "pi": "PI"}

    def select(self, cond: str, a: str, b: str) -> str:
        return f"{a} if {cond} else {b}"


class NumpyExprs(PythonExprs):
    calls = {
        "sqrt": "np.sqrt", "atan2": "np.arctan2", "cos": "np.cos",
        "sin": "np.sin", "abs": "np.abs", "max": "np.maximum", "min": "np.minimum",
    }
    and_op = "&"
    or_op = "|"

    def select(self, cond: str, a: str, b: str) -> str:
        return f"np.where({cond}, {a}, {b})"

    def logic(self, e: Logic) -> str:
        op = self.and_op if e.op == "and" else self.or_op
        return f"({self.expr(e.a)}) {op} ({self.expr(e.b)})"


def _field_names(p: Param, order: int) -> list[str]:
    return [f"{p.name}_{f}" for f in record_fields(p.kind, order)]


def _python_lines(prim: Primitive, order: int, exprs: ExprPrinter, with_sigma: bool) -> list[str]:
    """Body shared by the math and numpy flavours (they differ in leaves and masking)."""
    used = prim.params_used(order, with_sigma)
    lines = [f'    """{prim.doc}"""']
    for p in prim.params:
        if p.is_record:
            names = [n if n in used else "_" for n in _field_names(p, order)]
            if any(n != "_" for n in names):
                lines.append(f"    {', '.join(names)}{',' if len(names) == 1 else ''} = {p.name}")
    for let in prim.live(order, with_sigma):
        lines.append(f"    {let.name} = {exprs.expr(let.expr)}")
    return lines


def _result_tuples(prim: Primitive, order: int, exprs: ExprPrinter, nan_from: int | None) -> list[str]:
    """One tuple per output; fields of order >= nan_from are nan."""
    out = []
    for p in prim.outputs:
        fields = []
        for f in record_fields(p.kind, order):
            level = next(i for i, names in enumerate(RECORD_FIELDS[p.kind]) if f in names)
            if nan_from is not None and level >= nan_from:
                fields.append(exprs.consts["nan"])
            else:
                fields.append(exprs.expr(prim.results[p.name][f]))
        out.append("(" + ", ".join(fields) + ("," if len(fields) == 1 else "") + ")")
    return out


def _head(prim: Primitive, with_sigma: bool) -> list[str]:
    head = ["st"] if prim.status is not None else []
    if with_sigma and prim.sigma is not None:
        head.append("sigma")
    return head


def python_function(prim: Primitive, order: int, with_sigma: bool = False) -> str:
    """A standard-library Python function: records are tuples of floats.

    Returns ``outputs`` (one record, or a tuple of them); functions that can fail
    return ``(status, [sigma,] outputs...)``.
    """
    exprs = PythonExprs()
    lines = [f"def {prim.name}({', '.join(p.name for p in prim.params)}):"]
    lines += _python_lines(prim, order, exprs, with_sigma)
    head = _head(prim, with_sigma)
    if prim.status is not None:
        lines.append(f"    st = {exprs.expr(prim.status)}")
        if with_sigma and prim.sigma is not None and exprs.expr(prim.sigma) != "sigma":
            lines.append(f"    sigma = {exprs.expr(prim.sigma)}")
        for code, nan_from in _MASKS:
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
    lines += _python_lines(prim, order, exprs, True)
    status = exprs.expr(prim.status) if prim.status is not None else "0"
    sigma = exprs.expr(prim.sigma) if prim.sigma is not None else "1.0"
    lines.append(f"    st = np.asarray({status})")
    lines.append(f"    sigma = np.asarray({sigma}, dtype=float)")
    outs = []
    for p in prim.outputs:
        fields = []
        for f in record_fields(p.kind, order):
            level = next(i for i, names in enumerate(RECORD_FIELDS[p.kind]) if f in names)
            value = exprs.expr(prim.results[p.name][f])
            bad = "(st == 1)" if level == 0 else "(st == 1) | (st == 3)"
            fields.append(f"np.where({bad}, np.nan, {value})")
        outs.append("(" + ", ".join(fields) + ("," if len(fields) == 1 else "") + ")")
    lines.append(f"    return st, sigma, {', '.join(outs)}")
    return "\n".join(lines) + "\n"


def _is_int(e: Expr, ints: set[str]) -> bool:
    """Whether an expression is integer-valued in C (flags, comparisons, status codes)."""
    if isinstance(e, (Cmp, Logic)):
        return True
    if isinstance(e, Num):
        return isinstance(e.value, int)
    if isinstance(e, Sym):
        return e.name in ints
    if isinstance(e, Select):
        return _is_int(e.a, ints) and _is_int(e.b, ints)
    return False


_C_FIELD = {"x": "P.x", "y": "P.y", "dx": "DP.x", "dy": "DP.y", "ddx": "DDP.x", "ddy": "DDP.y"}


class CExprs(ExprPrinter):
    calls = {
        "sqrt": "sqrt", "atan2": "atan2", "cos": "cos", "sin": "sin",
        "abs": "fabs", "max": "fmax", "min": "fmin",
    }
    consts = {"eps": "DBL_EPSILON", "nan": "NAN", "pi": "3.141592653589793"}
    and_op = "&&"
    or_op = "||"

    def __init__(self, prim: Primitive):
        self.fields: dict[str, str] = {}
        for p in prim.params:
            if p.is_record:
                for f in record_fields(p.kind, 2):
                    self.fields[f"{p.name}_{f}"] = f"{p.name}.{_C_FIELD[f] if p.kind == 'POINT' else f}"

    def sym(self, name: str) -> str:
        return self.fields.get(name, name)

    def select(self, cond: str, a: str, b: str) -> str:
        return f"{cond} ? {a} : {b}"


def _c_type(kind: str) -> str:
    return {"REAL": "double", "INT": "int"}.get(kind, kind)


def c_function(prim: Primitive, order: int) -> str:
    """A static C99 function shaped like mech.cpp: records by value, outputs by pointer,
    the status as return value (void when the function cannot fail)."""
    exprs = CExprs(prim)
    params = [f"{_c_type(p.kind)} {p.name}" for p in prim.params]
    params += [f"{p.kind} *{p.name}" for p in prim.outputs]
    if prim.sigma is not None:
        params.append("double *sigma_out")
    head = "static int" if prim.status is not None else "static void"
    lines = [f"/* {prim.doc} */", f"{head} {prim.name}({', '.join(params)})", "{"]
    used = prim.params_used(order)
    for p in prim.params:
        touched = used & ({f"{p.name}_{f}" for f in record_fields(p.kind, order)} if p.is_record else {p.name})
        if not touched:
            lines.append(f"    (void){p.name};")
    ints = {p.name for p in prim.params if p.kind == "INT"}
    for let in prim.live(order):
        ctype = "int" if _is_int(let.expr, ints) else "double"
        if ctype == "int":
            ints.add(let.name)
        lines.append(f"    const {ctype} {let.name} = {exprs.expr(let.expr)};")
    if prim.status is not None:
        lines.append(f"    const int st = {exprs.expr(prim.status)};")
    if prim.sigma is not None and exprs.expr(prim.sigma) != "sigma":
        lines.append(f"    const double sigma = {exprs.expr(prim.sigma)};")
    for p, f, e in prim.result_fields(order):
        field = _C_FIELD[f] if p.kind == "POINT" else f
        lines.append(f"    {p.name}->{field} = {exprs.expr(e)};")
    if prim.sigma is not None:
        lines.append("    *sigma_out = sigma;")
    if prim.status is not None:
        for code, nan_from in _MASKS:
            fields = [(p, f) for p, f, _ in prim.result_fields(order)
                      if nan_from <= next(i for i, n in enumerate(RECORD_FIELDS[p.kind]) if f in n)]
            if fields:
                cond = "st == 1" if code == 1 else "st == 1 || st == 3"
                sets = " ".join(f"{p.name}->{_C_FIELD[f] if p.kind == 'POINT' else f} = NAN;" for p, f in fields)
                lines.append(f"    if ({cond}) {{ {sets} }}")
        lines.append("    return st;")
    lines.append("}")
    return "\n".join(lines) + "\n"


class OctaveExprs(ExprPrinter):
    calls = {
        "sqrt": "sqrt", "atan2": "atan2", "cos": "cos", "sin": "sin",
        "abs": "abs", "max": "max", "min": "min",
    }
    consts = {"eps": "eps", "nan": "NaN", "pi": "pi"}
    and_op = "&&"
    or_op = "||"

    def __init__(self, prim: Primitive):
        self.fields: dict[str, str] = {}
        for p in prim.params:
            if p.is_record:
                for f in record_fields(p.kind, 2):
                    self.fields[f"{p.name}_{f}"] = f"{p.name}.{f}"

    def sym(self, name: str) -> str:
        return self.fields.get(name, name)

    def select(self, cond: str, a: str, b: str) -> str:
        raise ValueError("MATLAB has no conditional expression; selections are statements")

    def assign(self, target: str, e: Expr, indent: str = "    ") -> list[str]:
        """``target = e`` where e may be a chain of selections: if / elseif / else."""
        if not isinstance(e, Select):
            return [f"{indent}{target} = {self.expr(e)};"]
        out = []
        keyword = "if"
        while isinstance(e, Select):
            out.append(f"{indent}{keyword} {self.expr(e.cond)}")
            out.append(f"{indent}    {target} = {self.expr(e.a)};")
            keyword = "elseif"
            e = e.b
        out += [f"{indent}else", f"{indent}    {target} = {self.expr(e)};", f"{indent}end"]
        return out


def octave_function(prim: Primitive, order: int) -> str:
    """A MATLAB/Octave subfunction: records are structs, outputs then status and sigma."""
    exprs = OctaveExprs(prim)
    outs = [p.name for p in prim.outputs]
    if prim.status is not None:
        outs.append("st")
    if prim.sigma is not None:
        outs.append("sigma")
    ret = f"[{', '.join(outs)}]" if len(outs) > 1 else outs[0]
    lines = [f"function {ret} = {prim.name}({', '.join(p.name for p in prim.params)})", f"    % {prim.doc}"]
    for let in prim.live(order):
        lines += exprs.assign(let.name, let.expr)
    if prim.status is not None:
        lines += exprs.assign("st", prim.status)
    if prim.sigma is not None and exprs.expr(prim.sigma) != "sigma":
        lines += exprs.assign("sigma", prim.sigma)
    for p, f, e in prim.result_fields(order):
        lines += exprs.assign(f"{p.name}.{f}", e)
    if prim.status is not None:
        for code, nan_from in _MASKS:
            fields = [(p, f) for p, f, _ in prim.result_fields(order)
                      if nan_from <= next(i for i, n in enumerate(RECORD_FIELDS[p.kind]) if f in n)]
            if fields:
                cond = "st == 1" if code == 1 else "st == 1 || st == 3"
                lines.append(f"    if {cond}")
                lines += [f"        {p.name}.{f} = NaN;" for p, f in fields]
                lines.append("    end")
    lines.append("end")
    return "\n".join(lines) + "\n"
