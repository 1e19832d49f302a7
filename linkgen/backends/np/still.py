"""The primitives as the kernel prints them: once per setting, and with the sketch's records held
still where a call passes them (their rates are 0: ../still.py)."""

from __future__ import annotations

import functools

from ...primitives import PRIMITIVES
from ...textcache import kept
from ..still import held_params, held_still, still_suffix
from .printer import numpy_function


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


__all__ = ["held_params", "printed", "still_suffix"]
