"""The Python printer of a DSL primitive: standard-library functions on tuples of floats (the
generated programs and the evaluator's scalar runtime; the numpy twin is backends/np/printer.py)."""

from __future__ import annotations

import math
import re
import sys
from collections import OrderedDict
from typing import NamedTuple

from ... import status
from ...primitives.dsl import Param, Primitive, field_order, record_fields
from ...primitives.printers import MASKS, ExprPrinter

_LITERAL = re.compile(r"-?[0-9][0-9.e+-]*")  # a number as printers.literal writes it


class PythonExprs(ExprPrinter):
    consts = {"eps": "EPS", "nan": "NAN", "pi": "PI"}
    compares = True  # as max() and min() choose, without their call

    def select(self, cond: str, a: str, b: str) -> str:
        return f"{a} if {cond} else {b}"


class InlineExprs(PythonExprs):
    """A primitive's expressions inside the calling function: its names with a leading underscore
    (no template name has one), a scalar argument given as a literal in its place."""

    consts = {**PythonExprs.consts, "eps": repr(sys.float_info.epsilon), "pi": repr(math.pi)}  # folded with literals

    def __init__(self, literals: dict[str, str]):
        self.literals = literals

    def sym(self, name: str) -> str:
        return self.literals.get(name, f"_{name}")


def _field_names(p: Param, order: int) -> list[str]:
    return [f"{p.name}_{f}" for f in record_fields(p.kind, order)]


def parameter_lines(prim: Primitive, order: int) -> list[str]:
    """The record parameters unpacked into their fields (those not read named _)."""
    used = prim.params_used(order)
    lines = []
    for p in prim.params:
        if p.is_record:
            names = [n if n in used else "_" for n in _field_names(p, order)]
            if any(n != "_" for n in names):
                lines.append(f"    {', '.join(names)}{',' if len(names) == 1 else ''} = {p.name}")
    return lines


def inline_lines(prim: Primitive, order: int, args: list[str | list[str]], targets: list[str], sigma: str,
                 failed: list[str]) -> list[str]:
    """A call of a primitive as the caller's own statements (no call, no tuples but the output records).

    A record argument is an expression (unpacked into locals) or the literals of its fields (a constant
    record: read in place, as is a scalar given as a literal; another scalar is bound once); then the
    body, ``st`` and the conditioning into ``sigma``, and each output record into its target (the fields
    a failing status makes nan, nan), with the lines ``failed`` where the chain cannot close (st 1).
    The primitive's expressions are printed once (``_printed``) and their names filled in here.
    """
    used = prim.params_used(order)
    literals: dict[str, str] = {}
    lines = []
    for p, arg in zip(prim.params, args):
        fields = _field_names(p, order) if p.is_record else [p.name]
        if isinstance(arg, list) or _LITERAL.fullmatch(arg):
            values = arg if isinstance(arg, list) else [arg]
            literals.update((n, f"({x})" if x.startswith("-") else x) for n, x in zip(fields, values) if n in used)
        elif p.is_record:
            names = [f"_{n}" if n in used else "_" for n in fields]
            if any(n != "_" for n in names):
                lines.append(f"{', '.join(names)}{',' if len(names) == 1 else ''} = {arg}")
        elif p.name in used:
            lines.append(f"_{p.name} = {arg}")
    printed = _printed(prim, order)

    def fill(text: str) -> str:
        return _MARKED.sub(lambda m: literals.get(m[1], f"_{m[1]}"), text)

    lines += [f"_{name} = {fill(text)}" for name, text in printed.lets]
    if printed.status is not None:
        lines.append(f"st = {fill(printed.status)}")
    if printed.sigma is not None:
        lines.append(f"{sigma} = {fill(printed.sigma)}")
    cases = [(code, nan_from) for code, nan_from in MASKS if nan_from <= order and code in prim.codes()]
    full = [f"{t} = {fill(v)}" for t, v in zip(targets, printed.results[None])]
    if not cases:
        return lines + full
    for k, (code, nan_from) in enumerate(cases):
        lines.append(f"{'el' if k else ''}if st == {code}:")
        lines += [f"    {t} = {fill(v)}" for t, v in zip(targets, printed.results[nan_from])]
        lines += [f"    {line}" for line in failed if code == status.CANNOT_CLOSE]
    return lines + ["else:"] + [f"    {line}" for line in full]


_MARKED = re.compile("\x00(\\w+)\x00")  # a name as _Marked prints it


class _Marked(InlineExprs):
    """InlineExprs with every name marked (NUL name NUL), to be filled in per call: a name is a leaf of
    the printed text wherever it stands, so the text filled in is the text printed with the names."""

    def __init__(self) -> None:
        super().__init__({})

    def sym(self, name: str) -> str:
        return f"\x00{name}\x00"


class _Printed(NamedTuple):
    """A primitive's expressions at an order as inline_lines writes them, their names marked."""

    lets: list[tuple[str, str]]
    status: str | None
    sigma: str | None
    results: dict[int | None, list[str]]  # the output tuples: all fields (None), or nan from an order


_printed_by_id: OrderedDict[tuple[int, int], tuple[Primitive, _Printed]] = OrderedDict()
KEPT = 64  # primitives whose printed expressions are kept (the last few programs')


def _printed(prim: Primitive, order: int) -> _Printed:
    """The primitive's expressions printed once per object and order (a resolver's blocks inline the same
    primitive dozens of times; hashing a primitive's expression trees costs as much as printing them)."""
    hit = _printed_by_id.get((id(prim), order))
    if hit is not None and hit[0] is prim:
        _printed_by_id.move_to_end((id(prim), order))
        return hit[1]
    exprs = _Marked()
    printed = _Printed([(let.name, exprs.expr(let.expr)) for let in prim.live(order)],
                       None if prim.status is None else exprs.expr(prim.status),
                       None if prim.sigma is None else exprs.expr(prim.sigma),
                       {nan_from: _result_tuples(prim, order, exprs, nan_from)
                        for nan_from in (None, *(n for _, n in MASKS if n <= order))})
    _printed_by_id[id(prim), order] = (prim, printed)
    if len(_printed_by_id) > KEPT:
        _printed_by_id.popitem(last=False)
    return printed


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
    lines = [f"def {prim.name}({', '.join(p.name for p in prim.params)}):", f'    """{prim.doc}"""']
    lines += parameter_lines(prim, order)
    lines += [f"    {let.name} = {exprs.expr(let.expr)}" for let in prim.live(order)]
    head = [name for name, e in (("st", prim.status), ("sigma", prim.sigma)) if e is not None]
    if prim.status is not None:
        lines.append(f"    st = {exprs.expr(prim.status)}")
        if prim.sigma is not None and exprs.expr(prim.sigma) != "sigma":
            lines.append(f"    sigma = {exprs.expr(prim.sigma)}")
        for code, nan_from in MASKS:
            if nan_from <= order and code in prim.codes():
                values = ", ".join(head + _result_tuples(prim, order, exprs, nan_from))
                lines.append(f"    if st == {code}:")
                lines.append(f"        return {values}")
    values = ", ".join(head + _result_tuples(prim, order, exprs, None))
    lines.append(f"    return {values}")
    return "\n".join(lines) + "\n"
