"""Two-channel copies of the primitives a resolver block calls (NAME_2), for the C program.

A block's last Newton pass measures the Jacobian column (the Add-link's unit rate, the records read
from outside still) and the rates pass after it the residuals' rates at zero Add-link rate (those
records live): the same positions twice.  A two-channel copy computes the positions once and each
channel's velocity statements as the order-1 copy does, the second channel's on records named
NAME_t: the same operations, so the same bits as the two passes, for one pass's positions.

The pass at the solved Add-link rates after it is at the same positions again: the two-channel copy
keeps the position values the rates and accelerations read (tape), and the rates copy (NAME_r) takes
them as parameters instead of computing them (the same operations on the same values: the same bits,
without a third placing of the positions; Fig. 14 5422 -> 5243 instructions a row).
"""

from __future__ import annotations

from dataclasses import replace

from ...primitives.dsl import (
    RECORD_FIELDS,
    Binary,
    Call,
    Cmp,
    Expr,
    Let,
    Neg,
    Num,
    Param,
    Primitive,
    Select,
    Sym,
    symbols,
)

SUFFIX = "_t"  # the second channel's records and velocity statements
TAPED_STATUS = "st_taped"  # the status a two-channel copy kept, a rates copy's parameter


def _renamed(e: Expr, names: dict[str, str]) -> Expr:
    """The expression with the symbols of ``names`` renamed."""
    if isinstance(e, Sym):
        return Sym(names.get(e.name, e.name))
    if isinstance(e, Binary):
        return type(e)(e.op, _renamed(e.a, names), _renamed(e.b, names))
    if isinstance(e, Neg):
        return Neg(_renamed(e.a, names))
    if isinstance(e, Call):
        return Call(e.fn, tuple(_renamed(a, names) for a in e.args))
    if isinstance(e, Select):
        return Select(_renamed(e.cond, names), _renamed(e.a, names), _renamed(e.b, names))
    return e


def two_channel(prim: Primitive) -> Primitive:
    """NAME_2: the order-1 primitive with a second velocity channel: a record parameter's copy p_t
    whose rates the second channel reads (its positions are p's), an output's copy o_t it writes."""
    records = [p for p in prim.params if p.is_record]
    lets = prim.live(1)
    names = {f"{p.name}_{f}": f"{p.name}{SUFFIX}_{f}" for p in records for f in RECORD_FIELDS[p.kind][1]}
    names |= {let.name: let.name + SUFFIX for let in lets if let.order == 1}
    second = tuple(Let(names[let.name], _renamed(let.expr, names), 1) for let in lets if let.order == 1)
    results = dict(prim.results)
    for o in prim.outputs:
        results[o.name + SUFFIX] = {f: _renamed(e, names) for f, e in prim.results[o.name].items()}
    return replace(prim, name=f"{prim.name}_2",
                   params=(*prim.params, *(Param(p.name + SUFFIX, p.kind) for p in records)),
                   outputs=(*prim.outputs, *(Param(o.name + SUFFIX, o.kind) for o in prim.outputs)),
                   body=(*lets, *second), results=results)


def tape(prim: Primitive) -> tuple[str, ...]:
    """The position values (order-0 definitions) the rates and accelerations read, and the results: what a
    two-channel copy keeps for the rates copy (from_tape), the status after them where there is one.  Found
    once per primitive (the C program asks for it at every call of a block's pass it prints)."""
    return prim._memo("tape", 2, True, lambda order, with_sigma: _tape(prim))


def _tape(prim: Primitive) -> tuple[str, ...]:
    live = prim.live(2)
    read: set[str] = set()
    for let in live:
        if let.order >= 1:
            read |= symbols(let.expr)
    for fields in prim.results.values():
        for e in fields.values():
            read |= symbols(e)
    first = {let.name for let in prim.live(1)}
    names = tuple(let.name for let in live if let.order == 0 and let.name in read and let.name in first)
    return (*names, TAPED_STATUS) if prim.status is not None else names


def from_tape(prim: Primitive) -> Primitive:
    """NAME_r: the order-2 primitive with the position values a two-channel copy kept (tape) as parameters: the
    rates and accelerations at the positions of the pass before, without computing them again (the same
    operations on the same values: the same bits).  Its status is the kept one."""
    kept = tape(prim)
    values = tuple(n for n in kept if n != TAPED_STATUS)
    status: Expr | None = None
    if prim.status is not None:
        status = Num(0)
        for code in sorted(prim.codes(), reverse=True):
            status = Select(Cmp("==", Sym(TAPED_STATUS), Num(code)), Num(code), status)
    params = (*prim.params, *(Param(n, "REAL") for n in values),
              *((Param(TAPED_STATUS, "INT"),) if prim.status is not None else ()))
    return replace(prim, name=f"{prim.name}_r", params=params,
                   body=tuple(let for let in prim.body if let.name not in values), status=status, sigma=None, fail=None)
