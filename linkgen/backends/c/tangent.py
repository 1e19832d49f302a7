"""Two-channel copies of the primitives a resolver block calls (NAME_2), for the C program.

A block's last Newton pass measures the Jacobian column (the Add-link's unit rate, the records read
from outside still) and the rates pass after it the residuals' rates at zero Add-link rate (those
records live): the same positions twice.  A two-channel copy computes the positions once and each
channel's velocity statements as the order-1 copy does, the second channel's on records named
NAME_t: the same operations, so the same bits as the two passes, for one pass's positions.
"""

from __future__ import annotations

from dataclasses import replace

from ...primitives.dsl import RECORD_FIELDS, Binary, Call, Expr, Let, Neg, Param, Primitive, Select, Sym

SUFFIX = "_t"  # the second channel's records and velocity statements


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
