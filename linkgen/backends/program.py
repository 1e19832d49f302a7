"""What the program backends (C, Python, MATLAB/Octave) build alike from the view."""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import TYPE_CHECKING

from ..instant.names import CENTRE_QUANTITIES
from ..primitives import PRIMITIVES
from ..primitives.dsl import Primitive
from ..textcache import kept
from ..units import sweep_lists
from . import Runtime
from .still import carried, held_params, variant

if TYPE_CHECKING:
    from ..render.view import View
    from .spelling import Spelling

# The derivative order of each output quantity.
LEVEL = {"position": 0, "angle": 0, "velocity": 1, "angular_velocity": 1, "acceleration": 2,
         "angular_acceleration": 2, **{q: 1 for q in CENTRE_QUANTITIES}}


def used_primitives(view: View) -> list[str]:
    """The runtime primitives the procedure calls, in the library's order."""
    return [name for name in PRIMITIVES if name in view.log.runtime]


def program_primitive(view: View, name: str) -> Primitive:
    """A runtime primitive as the view's program carries it: without its checks where the
    program has none and no resolver picks a block by the chains' conditioning."""
    return PRIMITIVES[name] if view.measures else PRIMITIVES[name].unchecked()


def step_primitives(view: View) -> dict[int, Primitive]:
    """The primitive each step calls, by the step's number (its name the function's): outside resolver
    blocks its variant with the sketch's records held still where it has one (still.py)."""
    return {s.number: variant(s.function, view.measures, held_params(view.log, view.record_order, s))
            for s in view.log.steps if s.function}


def sensitivity_count(view: View) -> int:
    """The most sensitivities of one block's records (Group.bent: a POINT two, others one)."""
    return max((sum(2 if kind == "POINT" else 1 for _, kind in b.bent) for b in view.blocks), default=1)


def _printed(printer: Callable[[Primitive, int], str], view: View, name: str, order: int,
             still: tuple[str, ...]) -> str:
    return printer(variant(name, view.measures, still), order)


def runtime_sources(view: View, printer: Callable[[Primitive, int], str], runtime: Runtime,
                    status: bool = True) -> list[str]:
    """The runtime a program carries: the primitives it calls (each variant with records held still,
    still.py, that a call takes), printed, then the hand-written
    status helpers (where ``status``) and, where the procedure needs them, branch_at, reach_at, the resolver
    (with the closure strategy's where it is chosen) and the row driver."""
    order = view.record_order
    texts = [kept("program primitive", (printer.__module__, printer.__qualname__, p, view.measures, order, still),
                  functools.partial(_printed, printer, view, p, order, still))  # printed once per user (textcache)
             for p, still in carried(view.log, order, used_primitives(view))]
    if status:
        texts.append(runtime.source("status"))
    texts += [runtime.source(name) for name, needed in (
        ("branch", "branch_at" in view.log.runtime), ("reach", "reach_at" in view.log.runtime),
        ("resolver", bool(view.groups)), ("closure", "closure" in view.log.runtime),
        ("driver", bool(view.groups))) if needed]
    return texts


def sketch_states(view: View, spell: Spelling) -> list[str]:
    """Every resolver block's state in the sketch: its Add-link lengths, its chains' branches
    and its orientation (unknown: 0), padded to the largest block."""
    out = []
    for b in view.blocks:
        state = [spell.lit(x) for x in b.group.start()]
        out.append(", ".join(state + ["0.0"] * (view.nmax - len(state))))
    return out


def input_lists(view: View, spell: Spelling) -> dict[str, str]:
    """The inputs' sweep (start, stop, speed), sketch values, step limits and periodicity, as lists of literals."""
    log = view.log
    lists = {k: ", ".join(spell.lit(x) for x in xs) for k, xs in sweep_lists(log).items()}  # the programs' units
    lists["sketch"] = ", ".join(spell.lit(i.sketch) for i in log.inputs)
    lists["limits"] = ", ".join(spell.lit(x) for x in log.step_limits())
    lists["periodic"] = ", ".join(spell.flag(i.kind == "revolute") for i in log.inputs)
    return lists
