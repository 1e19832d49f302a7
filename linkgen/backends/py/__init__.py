"""The Python backend: NAME.py, a module (solve, columns) and a script that prints the sweep."""

from __future__ import annotations

import re
from typing import TYPE_CHECKING

from ...units import sweep_lists
from .. import Backend, Runtime, Template
from ..program import LEVEL, input_lists, runtime_sources, sketch_states
from .printer import python_function
from .spelling import Python, Unpacked
from .words import WORDS

if TYPE_CHECKING:
    from ...render.view import View

RUNTIME = Runtime(__name__, "runtime", ".py")


def python_text(text: str) -> str:
    """Text inside a Python string literal (the module's docstring): \\ and " escaped."""
    return text.replace("\\", "\\\\").replace('"', '\\"')


def render(view: View, spell: Python, template: Template) -> dict[str, bytes]:
    log = view.log
    runtime = [text.rstrip("\n") for text in runtime_sources(view, python_function, RUNTIME)]
    measures = (spell.sign_measure, spell.sign_rate)
    code = runtime + [f(b) for g in view.blocks for b in g.group.branches for f in measures]
    math_names = [f for f in ("atan2", "cos", "floor", "sin", "sqrt")
                  if any(re.search(rf"\b{f}\(", text) for text in code)]
    lists = input_lists(view, spell)
    local = Unpacked(view)
    read = dict.fromkeys(c.column.variable for c in view.cells
                         if log.drawn(c.column) is None and local.ref(c.column.variable, None) != c.column.variable)
    return {"NAME.py": template(
        "NAME.py.j2", runtime=runtime, math_names=math_names, columns=[c.name for c in log.columns],
        levels=[str(LEVEL[cell.column.quantity]) for cell in view.cells],
        values=[(cell.column.name, local.published(cell.column), log.drawn(cell.column) is not None)
                for cell in view.cells],
        unpacked=[spell.unpacked(var) for var in read],
        inputs=[", ".join(spell.lit(x) for x in row) for row in zip(*sweep_lists(log).values())],
        sketch_a=sketch_states(view, spell), limits=lists["limits"], slack=spell.lit(log.policy.path_slack),
        periodic=lists["periodic"])}


BACKEND = Backend("py", "Python", templates="py", files=("NAME.py",), comment=("#", ""), spelling=Python,
                  render=render, filters={"pytext": python_text}, printer=python_function, runtime=RUNTIME, words=WORDS)
