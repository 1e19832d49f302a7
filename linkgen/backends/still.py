"""The primitives with the sketch's constant records held still: a record whose rates are all
0.0 (a frame pivot, a rigid link's length, a root link's angle) lets a call leave out what its rates
add, subtract or multiply.  Every program (C, Python, MATLAB/Octave, numpy) calls the same variant
at the same step, so they keep giving the same bits as each other."""

from __future__ import annotations

import functools
import math
import sys
from collections import Counter
from dataclasses import replace
from typing import TYPE_CHECKING, Any

from ..primitives import PRIMITIVES, RuntimeFunction
from ..primitives.dsl import RECORD_FIELDS, Bin, Binary, Call, Expr, Let, Neg, Num, Primitive, Select, Sym, children
from ..textcache import kept

if TYPE_CHECKING:
    from ..steplog import Step, StepLog


def rebuilt(e: Expr, kids: list[Expr]) -> Expr:
    """e with other children (e itself where they are its own)."""
    if all(n is c for n, c in zip(kids, children(e))):
        return e
    if isinstance(e, Binary):
        return type(e)(e.op, kids[0], kids[1])
    if isinstance(e, Neg):
        return Neg(kids[0])
    if isinstance(e, Call):
        return Call(e.fn, tuple(kids))
    if isinstance(e, Select):
        return Select(kids[0], kids[1], kids[2])
    return e


def substituted(e: Expr, names: dict[str, Expr], memo: dict[int, Expr]) -> Expr:
    """e with the symbols named in names replaced by their expressions (a node met twice, once)."""
    if id(e) in memo:
        return memo[id(e)]
    memo[id(e)] = names.get(e.name, e) if isinstance(e, Sym) else rebuilt(e, [substituted(c, names, memo)
                                                                                for c in children(e)])
    return memo[id(e)]


# A held record's rate, and what it makes zero: the zeros that fold.  A primitive's own 0.0 stays where it
# is written (instant_centre's ``+ 0.0`` and ``0.0 - gy`` turn a -0.0 into 0.0: folded, they would not).
HELD = Num(0.0)


def _folded(e: Expr, kids: list[Expr]) -> Expr | None:
    """e with a HELD operand folded (x - 0, x + 0, 0 + x: x; 0 - x: -x; 0 * x, x * 0, -0: 0), None where
    nothing folds.  For finite x this is the value IEEE arithmetic gives but for the sign of a
    zero (-0.0 + 0.0 is +0.0, x * 0.0 is -0.0 for a negative x)."""
    if isinstance(e, Bin) and e.op in "+-*":
        a, b = kids
        if e.op == "*" and (a is HELD or b is HELD):
            return HELD
        if b is HELD:
            return a
        if a is HELD:
            return b if e.op == "+" else Neg(b)
    if isinstance(e, Neg) and kids[0] is HELD:
        return HELD
    return None


def held_still(prim: Primitive, still: tuple[str, ...]) -> tuple[Primitive, int]:
    """The primitive where the record parameters named hold still, as a constant record of the
    sketch does (every rate 0.0), with what those zeros make zero folded away (_folded; an
    assignment that folds to HELD folded into those reading it).  Returns it and the operations it
    leaves out."""
    zero: dict[str, Expr] = {f"{p.name}_{f}": HELD for p in prim.params if p.name in still
                             for level in RECORD_FIELDS[p.kind][1:] for f in level}
    memo: dict[int, Expr] = {}
    done: dict[int, Expr] = {}
    saved = Counter[str]()

    def fold(e: Expr) -> Expr:
        if id(e) not in done:
            kids = [fold(c) for c in children(e)]
            out = _folded(e, kids)
            saved["op"] += out is not None
            done[id(e)] = rebuilt(e, kids) if out is None else out
        return done[id(e)]

    def still_(e: Expr) -> Expr:
        return fold(substituted(e, zero, memo))

    body = []
    for let in prim.body:  # a later assignment reads an earlier one only: zero and memo stay true as zero grows
        e = still_(let.expr)
        if e is HELD:
            zero[let.name] = e
        body.append(Let(let.name, e, let.order))
    results = {o: {f: still_(e) for f, e in fields.items()} for o, fields in prim.results.items()}
    held = replace(prim, body=tuple(body), results=results, status=prim.status and still_(prim.status),
                   sigma=prim.sigma and still_(prim.sigma), fail=prim.fail and still_(prim.fail))
    return held, saved["op"]


def still_suffix(still: tuple[str, ...]) -> str:
    """The suffix of a primitive with record parameters held still: link_angle_still_j1."""
    return "".join(f"_still_{'_'.join(still)}" for _ in still[:1])


@functools.cache
def variant(name: str, checks: bool, still: tuple[str, ...]) -> Primitive:
    """A primitive (with its checks or without) with the record parameters named held still, named
    with their still_suffix; the primitive as it is where none are."""
    prim = PRIMITIVES[name] if checks else PRIMITIVES[name].unchecked()
    return replace(held_still(prim, still)[0], name=name + still_suffix(still)) if still else prim


def held_params(log: StepLog, order: int, step: Step) -> tuple[str, ...]:
    """The record parameters of a step's call that hold still (the sketch's constant records,
    their rates 0) where that saves an operation: at steps outside resolver groups (whose blocks
    call their own copies), at records with rates; () for the primitive as it is.  The choice reads
    the step and the mechanism only, never which outputs are kept: a pruned build calls what the
    whole build calls, and gives its bits, signed zeros included."""
    if step.group or step.variant or order == 0 or not step.function:
        return ()
    prim = PRIMITIVES[step.function]
    return tuple(p.name for p, a in zip(prim.params, step.args) if p.is_record and a.kind == "var"
                 and log.variable(a.var).constant and _saves(step.function, p.name))


def carried(log: StepLog, order: int, used: list[str]) -> list[tuple[str, tuple[str, ...]]]:
    """The primitives a program carries, each with the records it holds still: those of ``used`` (in
    the library's order) that a step calls as they are or that no step calls (a resolver block's own),
    then every variant a step calls (held_params), in the library's order."""
    calls = {(s.function, held_params(log, order, s)) for s in log.steps if s.function}
    held = sorted((call for call in calls if call[1]), key=lambda call: (list(PRIMITIVES).index(call[0]), call[1]))
    return [(p, ()) for p in used if (p, ()) in calls or all(p != f for f, _ in held)] + held


def scalar_variants(log: StepLog, order: int) -> dict[str, RuntimeFunction]:
    """The variants the log's steps call (carried), by their names, as Python functions on tuples of
    floats: what the row solver calls where the programs call them (linkgen.rowsolver)."""
    return {name + still_suffix(still): _scalar(name, still, order) for name, still in carried(log, order, [])}


@functools.cache
def _scalar(name: str, still: tuple[str, ...], order: int) -> RuntimeFunction:
    from ..kernel import compiled  # the kernel renders through the backends
    from .py.printer import python_function  # the py backend imports the programs' module, which imports this one

    named = name + still_suffix(still)  # the variant's name: the variant itself made only where printed (held_still)
    space: dict[str, Any] = {"sqrt": math.sqrt, "atan2": math.atan2, "cos": math.cos, "sin": math.sin,
                             "EPS": sys.float_info.epsilon, "NAN": math.nan, "PI": math.pi}  # as python_backend's
    source = kept("python still variant", (name, still, order),  # 3 ms a build
                  lambda: python_function(variant(name, True, still), order))
    exec(compiled(source, f"<linkgen runtime python {named} order {order}>"), space)  # compiled once per user
    function: RuntimeFunction = space[named]
    return function


@functools.cache
def _saves(name: str, param: str) -> int:
    """The operations a primitive leaves out with one record parameter held still (found once per
    user, as the printed primitives are)."""
    return int(kept("still saves", (name, param), lambda: str(held_still(PRIMITIVES[name], (param,))[1])))
