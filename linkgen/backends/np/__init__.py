"""The numpy backend: NAME_np.py, the procedure vectorised over rows and designs (numpy only)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ...primitives import PRIMITIVES
from ...units import sweep_lists
from .. import Backend, Runtime, Template
from ..program import LEVEL, used_primitives
from ..still import carried
from .printer import numpy_function
from .spelling import Numpy
from .still import printed

if TYPE_CHECKING:
    from ...render.view import View

RUNTIME = Runtime(__name__, "runtime", ".py")
REALS = {"float": "float32", "double": "float64"}  # the real types of options.real it computes in, as numpy's


FAST = "_1"  # the suffix of the primitives and resolver blocks at order 1 (a resolver's Newton passes)


def fast(view: View) -> str:
    """The suffix of the order-1 primitives and blocks the resolvers' Newton passes run: none where
    the records are of order 1 anyway."""
    return FAST if view.groups and view.record_order > 1 else ""


def fast_primitives(view: View) -> list[str]:
    """The primitives the resolver blocks and their states call, at order 1 (none where the
    records are of order 1 anyway)."""
    if not fast(view):
        return []
    names = {s.function for b in view.blocks for s in b.steps if s.function}
    return [p for p in PRIMITIVES if p in names]


def runtime_sources(view: View) -> list[str]:
    """The kernel's runtime: the primitives the procedure calls, printed, then the status rule,
    branch_at and reach_at where the procedure needs them, and the row driver; with resolver
    groups the resolver on lanes of rows and the sweep that solves the rows in order."""
    log = view.log
    texts = [printed(p, view.record_order, "", view.measures, still)
             for p, still in carried(log, view.record_order, used_primitives(view))]
    texts += [printed(p, 1, FAST, view.measures) for p in fast_primitives(view)]
    if any("cos_sin(" in text for text in texts):
        texts.append(RUNTIME.source("trig"))
    texts.append(RUNTIME.source("status"))
    texts += [RUNTIME.source(name) for name, needed in (
        ("branch", "branch_at" in log.runtime), ("reach", "reach_at" in log.runtime)) if needed]
    texts.append(RUNTIME.source("driver"))
    if view.groups:
        texts += [RUNTIME.source(name) for name in ("resolver", "group", "sweep")]
    return [text.rstrip("\n") for text in texts]


def render(view: View, spell: Numpy, template: Template) -> dict[str, bytes]:
    log = view.log
    params = spell.params()
    example = next((name for name, _, _ in params if name.startswith("step")), params[0][0] if params else "")
    return {"NAME_np.py": template(
        "NAME_np.py.j2", runtime=runtime_sources(view), columns=[c.name for c in log.columns],
        levels=[str(LEVEL[cell.column.quantity]) for cell in view.cells],
        values=[spell.published(cell.column) for cell in view.cells],
        inputs=[", ".join(spell.lit(x) for x in row) for row in zip(*sweep_lists(log).values())],
        params=params, example=example, fast=fast(view), real=REALS.get(log.options.real, REALS["double"]))}


BACKEND = Backend("np", "numpy", templates="np", files=("NAME_np.py",), comment=("#", ""), spelling=Numpy,
                  render=render, printer=numpy_function, runtime=RUNTIME, reals=tuple(REALS))
