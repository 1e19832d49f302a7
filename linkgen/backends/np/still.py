"""The primitives as the kernel prints them: once per setting, and with the sketch's records held
still where a call passes them (their rates are 0: a rate subtracted is not subtracted)."""

from __future__ import annotations

import functools
from typing import TYPE_CHECKING

from ...primitives import PRIMITIVES
from ...textcache import kept
from .printer import held_still, numpy_function

if TYPE_CHECKING:
    from ...steplog import Step, StepLog


@functools.cache
def printed(name: str, order: int, suffix: str = "", checks: bool = True, still: tuple[str, ...] = ()) -> str:
    """A primitive on arrays of rows at an order (named with the suffix), with its checks or without,
    with the record parameters named in still held still (see held_still; named with
    still_suffix): printed once, the evaluator renders many logs."""
    def make() -> str:
        prim = PRIMITIVES[name] if checks else PRIMITIVES[name].unchecked()
        if still:
            return numpy_function(held_still(prim, still)[0], order, suffix, name + still_suffix(still))
        return numpy_function(prim, order, suffix)

    return kept("numpy primitive", (name, order, suffix, checks, still), make)  # printing: 13 ms a build


def still_suffix(still: tuple[str, ...]) -> str:
    """The suffix of a primitive with record parameters held still: link_angle_still_j1."""
    return "".join(f"_still_{'_'.join(still)}" for _ in still[:1])


def held_params(log: StepLog, order: int, step: Step) -> tuple[str, ...]:
    """The record parameters of a step's call that hold still (the sketch's constant records,
    their rates 0) where that saves the kernel a subtraction on every row: outside resolver
    groups, at records with rates; () for the primitive as it is."""
    if log.groups or order == 0 or not step.function:
        return ()
    prim = PRIMITIVES[step.function]
    return tuple(p.name for p, a in zip(prim.params, step.args) if p.is_record and a.kind == "var"
                 and log.variable(a.var).constant and _saves(step.function, p.name))


@functools.cache
def _saves(name: str, param: str) -> int:
    """The subtractions a primitive leaves out with one record parameter held still (found once per
    user, as the printed primitives are: 5 ms of a build found them anew)."""
    return int(kept("numpy still saves", (name, param), lambda: str(held_still(PRIMITIVES[name], (param,))[1])))
