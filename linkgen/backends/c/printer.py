"""The C printer of a DSL primitive: a static C99 function shaped like mech.cpp's."""

from __future__ import annotations

from ...primitives.dsl import (
    Call,
    Cmp,
    Expr,
    Let,
    Logic,
    Num,
    Param,
    Primitive,
    Select,
    Sym,
    field_order,
    record_fields,
    symbols,
)
from ...primitives.printers import MASKS, RecordExprs, statements
from .tangent import TAPED_STATUS

_POINT_FIELD = {"x": "P.x", "y": "P.y", "dx": "DP.x", "dy": "DP.y", "ddx": "DDP.x", "ddy": "DDP.y"}


def field(kind: str, name: str) -> str:
    """A record field as the C structs name it: a POINT's dx is DP.x."""
    return _POINT_FIELD[name] if kind == "POINT" else name


class CExprs(RecordExprs):
    """Record parameters are pointers to const records (``j1->P.x``)."""

    calls = {**RecordExprs.calls, "abs": "fabs", "max": "fmax", "min": "fmin"}
    consts = {"eps": "DBL_EPSILON", "nan": "NAN", "pi": "3.141592653589793"}
    field = staticmethod(field)
    compares = True

    def __init__(self, prim: Primitive):
        self.fields = {f"{p.name}_{f}": f"{p.name}->{field(p.kind, f)}"
                       for p in prim.params if p.is_record for f in record_fields(p.kind, 2)}

    def select(self, cond: str, a: str, b: str) -> str:
        """``cond ? a : b``; a condition of logic() ``(x) & (y)`` in parentheses (clang's
        -Wbitwise-conditional-parentheses)."""
        if " & " in cond or " | " in cond:
            cond = f"({cond})"
        return f"{cond} ? {a} : {b}"

    def logic(self, e: Logic) -> str:
        """Of two truth values (comparisons, and and or of them) ``(a) | (b)`` and ``(a) & (b)``: both sides
        evaluated, no branch (a chain's fail flag: 3 instructions less a chain); else C's || and &&."""
        if not all(isinstance(x, (Cmp, Logic)) for x in (e.a, e.b)):
            return super().logic(e)
        op = "&" if e.op == "and" else "|"

        def side(x: Expr) -> str:
            text = self.expr(x)
            return text if isinstance(x, Logic) and x.op == e.op and f" {op} " in text else f"({text})"

        return f"{side(e.a)} {op} {side(e.b)}"

    def expr(self, e: Expr) -> str:
        """As every language, but a whole number given to a math function is a real literal (0.0):
        in another real type the literal then takes the type's suffix (fmaxf(x, 0.0f), not an int to convert)."""
        if isinstance(e, Call):
            args = tuple(Num(float(a.value)) if isinstance(a, Num) and isinstance(a.value, int) else a for a in e.args)
            e = Call(e.fn, args)
        return super().expr(e)


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


def _c_type(kind: str) -> str:
    return {"REAL": "double", "INT": "int"}.get(kind, kind)


def c_function(prim: Primitive, order: int, tape: tuple[str, ...] = ()) -> str:
    """A static C99 function shaped like mech.cpp: records in by pointer to const (no copy of
    a record per call), outputs by pointer, the status as return value (void when the
    function cannot fail).  Inline, and declared always inline where the compiler has the
    attribute (gcc, clang): a call with the sketch's constants folds them, and a
    chain called from several steps is not left a call (Jansen's leg: 1292 -> 998 instructions
    a row).  With ``tape`` (names of its values, the status st among them) it keeps those values
    into ``double tape[]`` too, before its exits (tangent.from_tape's copy reads them)."""
    exprs = CExprs(prim)
    params = [f"const {p.kind} *{p.name}" if p.is_record else f"{_c_type(p.kind)} {p.name}" for p in prim.params]
    params += [f"{p.kind} *{p.name}" for p in prim.outputs]
    if tape:
        params.append("double tape[]")
    if prim.sigma is not None:
        params.append("double *sigma_out")
    head = "static inline int" if prim.status is not None else "static inline void"
    signature = f"{head} {prim.name}({', '.join(params)})"
    lines = [f"/* {prim.doc} */", "#if defined(__GNUC__)", f"{signature} __attribute__((always_inline));", "#endif",
             signature, "{"]
    used = prim.params_used(order)
    for p in prim.params:
        touched = used & ({f"{p.name}_{f}" for f in record_fields(p.kind, order)} if p.is_record else {p.name})
        if not touched:
            lines.append(f"    (void){p.name};")
    lines += [f"    (void){p.name};" for p in prim.outputs if not record_fields(p.kind, order)]  # no field yet
    ints = {p.name for p in prim.params if p.kind == "INT"}

    def define(name: str, e: Expr, ctype: str) -> list[str]:
        ctype = ctype or ("int" if _is_int(e, ints) else "double")
        if ctype == "int":
            ints.add(name)
        return [f"    const {ctype} {name} = {exprs.expr(e)};"]

    stores: list[str] = []

    def store(p: Param, f: str, e: Expr) -> list[str]:
        stores.append(f"{p.name}->{field(p.kind, f)} = {exprs.expr(e)};")
        return []

    body = statements(prim, order, exprs, define, store)
    split = None if tape else _branch(prim, order, exprs)
    lines += _branched(body, split, prim, order) if split else body
    if prim.sigma is not None:
        lines.append("    *sigma_out = sigma;")
    lines += [f"    tape[{k}] = {'st' if name == TAPED_STATUS else name};" for k, name in enumerate(tape)]
    if prim.status is not None:
        lines += _masked_exits(prim, order, exprs)
    lines += [f"    {s}" for s in stores]
    lines.append("    return st;" if prim.status is not None else "}")
    if prim.status is not None:
        lines.append("}")
    return "\n".join(lines) + "\n"


def _masked_exits(prim: Primitive, order: int, exprs: CExprs) -> list[str]:
    """Per failing status (printers.MASKS), an early return that writes the results with the fields it makes nan
    nan: ``if (st == 1) { ... return st; }`` before the results' stores.  The values the other languages write,
    but a store is never overwritten: where the caller leaves on the status (a failed chain ends the row), the
    compiler keeps the records in registers (a mask after the stores cost a checks-off four-bar 10% of its time,
    more than the conditioning it leaves out)."""
    out = []
    returned = prim.codes()
    for code, nan_from in MASKS:
        fields = prim.result_fields(order)
        if code not in returned or not any(nan_from <= field_order(p.kind, f) for p, f, _ in fields):
            continue
        sets = " ".join(f"{p.name}->{field(p.kind, f)} = "
                        f"{'NAN' if nan_from <= field_order(p.kind, f) else exprs.expr(e)};" for p, f, e in fields)
        out.append(f"    if (st == {code}) {{ {sets} return st; }}")
    return out


Place = dict[str, str]  # let name -> "pre", "then", "else", "split" or "post"


def _branch(prim: Primitive, order: int, exprs: CExprs) -> tuple[Expr, Place] | None:
    """Where each live definition goes when the function branches on the condition that selects most of its
    definitions (RRR_links' open test), or None where it does not pay or cannot be: "split" for a selection on
    it (its two sides assigned in the two branches), "then" and "else" for a value read only on that side, "pre"
    before the branch, "post" after it.  The same values as straight-line code, each side computing only what it
    reads (the open four-bar: 469 -> 412 instructions a row, the same bits)."""
    live = prim.live(order)
    tests: dict[str, list[Let]] = {}
    for let in live:
        if isinstance(let.expr, Select):
            tests.setdefault(exprs.expr(let.expr.cond), []).append(let)
    if not tests or max(len(v) for v in tests.values()) < 2:
        return None
    cond = max(tests.values(), key=len)[0].expr.cond  # type: ignore[attr-defined]
    split = {let.name for let in tests[exprs.expr(cond)]}
    side: dict[str, str] = {}  # where a name is read: "then", "else" or "both"

    def read(e: Expr, where: str) -> None:
        for name in symbols(e):
            side[name] = where if side.get(name, where) == where else "both"

    for e in [e for _, _, e in prim.result_fields(order)] + [prim.status, prim.sigma]:
        if e is not None:
            read(e, "both")
    place: Place = {}
    for let in reversed(live):
        where = side.get(let.name, "both")
        if let.name in split and where == "both":
            place[let.name] = "split"
            assert isinstance(let.expr, Select)
            read(let.expr.cond, "both")
            read(let.expr.a, "then")
            read(let.expr.b, "else")
        else:
            place[let.name] = where
            read(let.expr, where)
    region = {n for n, p in place.items() if p != "both"}
    after: set[str] = set()
    for let in live:
        if place[let.name] == "both":
            deps = symbols(let.expr)
            if deps & (region | after):
                after.add(let.name)
            place[let.name] = "post" if let.name in after else "pre"
    if any(place.get(n) not in ("pre", None) for n in symbols(cond)):
        return None
    for let in live:  # a branch reads what comes before it, never a value after it
        if place[let.name] in ("then", "else", "split") and any(place.get(n) == "post" for n in symbols(let.expr)):
            return None
    if not any(p in ("then", "else") for p in place.values()):
        return None
    return cond, place


def _branched(body: list[str], split: tuple[Expr, Place], prim: Primitive, order: int) -> list[str]:
    """The definitions of ``body`` laid out by _branch: the ones before, the branch (the selections' names declared
    first, each side's definitions and sides in order), then the rest of ``body``."""
    cond, place = split
    live = prim.live(order)
    named = {let.name: let for let in live}
    by_name = {line.split(" = ", 1)[0].split()[-1]: line for line in body if line.startswith("    const ")}
    lines = [by_name[n] for n in named if place[n] == "pre"]
    decls = {n: by_name[n].split()[1] for n in named if place[n] == "split"}
    for ctype in dict.fromkeys(decls.values()):
        lines.append(f"    {ctype} {', '.join(n for n, t in decls.items() if t == ctype)};")
    exprs = CExprs(prim)
    for k, where in enumerate(("then", "else")):
        lines.append(f"    if ({exprs.expr(cond)}) {{" if k == 0 else "    } else {")
        for name, let in named.items():
            if place[name] == where:
                lines.append("    " + by_name[name])
            elif place[name] == "split":
                assert isinstance(let.expr, Select)
                lines.append(f"        {name} = {exprs.expr(let.expr.a if k == 0 else let.expr.b)};")
    lines.append("    }")
    rest = [line for line in body if not (line.startswith("    const ") and line.split(" = ", 1)[0].split()[-1] in place
                                          and place[line.split(" = ", 1)[0].split()[-1]] != "post")]
    return lines + rest
