"""The numpy backend: NAME_np.py, the procedure vectorised over rows and designs (numpy only)."""

from __future__ import annotations

import functools
from typing import TYPE_CHECKING

from ...primitives import PRIMITIVES
from .. import Backend, Runtime, Template
from ..program import LEVEL, used_primitives
from .printer import numpy_function
from .spelling import Numpy

if TYPE_CHECKING:
    from ...render.view import View

RUNTIME = Runtime(__name__, "runtime", ".py")


@functools.cache
def printed(name: str, order: int, checks: bool = True) -> str:
    """A primitive on arrays of rows at an order, with its checks or without (printed once: the
    evaluator renders many logs)."""
    return numpy_function(PRIMITIVES[name] if checks else PRIMITIVES[name].unchecked(), order)


def runtime_sources(view: View) -> list[str]:
    """The kernel's runtime: without resolver groups the primitives the procedure calls, printed,
    then the status rule, branch_at and reach_at where the procedure needs them, and the row
    driver (with resolver groups, which runs the standard-library module row by row)."""
    log = view.log
    texts = [] if view.groups else [printed(p, view.record_order, view.measures) for p in used_primitives(view)]
    texts.append(RUNTIME.source("status"))
    texts += [RUNTIME.source(name) for name, needed in (
        ("branch", "branch_at" in log.runtime and not view.groups),
        ("reach", "reach_at" in log.runtime and not view.groups)) if needed]
    texts.append(RUNTIME.source("driver"))
    return [text.rstrip("\n") for text in texts]


def render(view: View, spell: Numpy, template: Template) -> dict[str, bytes]:
    log = view.log
    params = [] if view.groups else spell.params()
    example = next((name for name, _, _ in params if name.startswith("step")), params[0][0] if params else "")
    return {"NAME_np.py": template(
        "NAME_np.py.j2", runtime=runtime_sources(view), columns=[c.name for c in log.columns],
        levels=[str(LEVEL[cell.column.quantity]) for cell in view.cells],
        values=[spell.published(cell.column) for cell in view.cells],
        inputs=[f"{spell.lit(i.start)}, {spell.lit(i.stop)}, {spell.lit(i.speed)}" for i in log.inputs],
        params=params, example=example)}


BACKEND = Backend("np", "numpy", templates="np", files=("NAME_np.py",), comment=("#", ""), spelling=Numpy,
                  render=render, printer=numpy_function, runtime=RUNTIME)
