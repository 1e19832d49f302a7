"""The MATLAB/Octave backend: NAME_solve.m (the procedure as a function) and NAME.m (the sweep script)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from .. import Backend, Runtime, Template
from ..program import LEVEL, input_lists, runtime_sources, sketch_states
from .printer import octave_function
from .spelling import Octave
from .words import WORDS

if TYPE_CHECKING:
    from ...render.view import View

RUNTIME = Runtime(__name__, "runtime", ".m")


def render(view: View, spell: Octave, template: Template) -> dict[str, bytes]:
    log = view.log
    outputs = [{"name": spell.ident(o.name),
                "fields": [(field, spell.published(c), LEVEL[c.quantity]) for field, c, _ in o.fields]}
               for o in view.outputs]
    lists = input_lists(view, spell)
    return {
        "NAME_solve.m": template(
            "NAME_solve.m.j2", runtime=[text.rstrip("\n") for text in runtime_sources(view, octave_function, RUNTIME)],
            outputs=outputs, cells=[f"out.{spell.ident(c.owner)}.{c.field}" for c in view.cells],
            sketch_in=lists["sketch"], sketch_a=", ".join(f"[{a}]'" for a in sketch_states(view, spell)),
            limits=lists["limits"], slack=spell.lit(log.policy.path_slack), periodic=lists["periodic"]),
        "NAME.m": template("NAME.m.j2", columns=[c.name for c in log.columns], inputs=lists),
    }


BACKEND = Backend("m", "MATLAB/Octave", templates="m", files=("NAME_solve.m", "NAME.m"), comment=("%", ""),
                  spelling=Octave, render=render, printer=octave_function, runtime=RUNTIME, words=WORDS)
