"""The C99 backend: NAME.h, NAME.c (the procedure and NAME_solve) and NAME_main.c (the sweep)."""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING

from ...policy import REAL_TYPES
from ...primitives.dsl import RECORD_FIELDS
from ...primitives.dsl import record_fields as record_fields_of
from .. import Backend, Runtime, Template
from ..program import input_lists, program_primitive, runtime_sources, sensitivity_count, sketch_states
from .printer import c_function, field
from .real import retype, typedef
from .spelling import C
from .tangent import from_tape, tape, two_channel
from .words import WORDS

if TYPE_CHECKING:
    from ...render.view import View

RUNTIME = Runtime(__name__, "runtime", ".c")


def render(view: View, spell: C, template: Template) -> dict[str, bytes]:
    """The three files, in the log's real type (real.py; render gives the policy of that type)."""
    files = _render(view, spell, template)
    real, name = view.log.options.real, view.log.name
    files = {k: retype(v.decode("utf-8"), real, name).encode("utf-8") if k != "NAME_main.c" else v
             for k, v in files.items()}
    files["NAME.h"] = typedef(files["NAME.h"].decode("utf-8"), real, name).encode("utf-8")
    return files


def _reads_reasons(view: View) -> bool:
    """Whether NAME.c reads a status code's reason (reason_of): the resolvers' row driver and
    publish() do, the latter where a singular row's rates are nan."""
    return bool(view.groups) or (view.checks and view.log.order > 0)


def velocity_variants(view: View) -> list[str]:
    """Order-1 copies (NAME_1) of the primitives the resolver blocks call, for a program of order 2: the
    passes that measure residuals and the Jacobian need no accelerations (the same statements, fewer)."""
    if not view.groups or view.record_order < 2:
        return []
    return [c_function(replace(program_primitive(view, n), name=f"{n}_1"), 1) for n in _block_functions(view)]


def two_channel_variants(view: View) -> list[str]:
    """Two-channel copies (NAME_2, tangent.py) of the primitives the resolver blocks call: a block's
    last Newton pass measures its Jacobian column and the residuals' rates at zero Add-link rate at once,
    and keeps its position values (tangent.tape) for the rates copies."""
    return [c_function(two_channel(program_primitive(view, n)), 1, tape(program_primitive(view, n)))
            for n in _block_functions(view)]


def rates_variants(view: View) -> list[str]:
    """Rates copies (NAME_r, tangent.from_tape) of the primitives the resolver blocks call: the pass at the
    solved Add-link rates reads the positions the last Newton pass kept instead of computing them again."""
    return [c_function(from_tape(program_primitive(view, n)), view.record_order) for n in _block_functions(view)]


def _block_functions(view: View) -> list[str]:
    """The primitives the resolver blocks call, by name."""
    return sorted({s.function for b in view.blocks for s in b.steps if s.function})


def tape_size(view: View) -> int:
    """The values a block's last Newton pass keeps for its rates pass, the most of any block (work.tape)."""
    return max((sum(len(tape(program_primitive(view, s.function))) for s in b.steps if s.function)
                for b in view.blocks), default=0)


def bends(view: View) -> dict[str, list[tuple[str, str]]]:
    """Per resolver block (its suffix): the fields of its bent records (Group.bent) as C names them,
    each a (rate, acceleration) pair: w->NAME.DP.x and w->NAME.DDP.x of a POINT."""
    return {b.suffix: [(f"{name}.{field(kind, d)}", f"{name}.{field(kind, dd)}")
                       for name, kind in b.bent for d, dd in zip(*RECORD_FIELDS[kind][1:])]
            for b in view.blocks}


def conditioned_steps(view: View) -> tuple[int, ...]:
    """The steps of the run whose call writes its conditioning (its primitive's sigma) into the state."""
    return tuple(s.number for s in view.run if s.function and program_primitive(view, s.function).sigma is not None)


def _render(view: View, spell: C, template: Template) -> dict[str, bytes]:
    log = view.log
    upper = log.name.upper()
    order = view.record_order
    levels = ("P", "DP", "DDP")[: order + 1]
    record_fields = {
        "POINT": f"VEC2 {', '.join(levels)};",
        "ANGLE": f"double {', '.join(('the', 'dthe', 'ddthe')[: order + 1])};",
        "VARIABLE": f"double {', '.join(('v', 'dv', 'ddv')[: order + 1])};",
    }
    if any(v.kind == "CENTRE" for v in view.records):  # instant centres: every field a velocity's
        record_fields["CENTRE"] = f"double {', '.join(record_fields_of('CENTRE', order))};"
    per_kind = {"point": ("x", "y", "vx", "vy", "ax", "ay"), "angle": ("phi", "omega", "alpha"),
                "slide": ("s", "ds", "dds"), "direction": ("ux", "uy", "dux", "duy", "ddux", "dduy")}
    width = {"point": 2, "angle": 1, "slide": 1, "direction": 2}
    fields = {k: per_kind[k][: width[k] * (log.order + 1)] for k in per_kind}
    columns = [c.name for c in log.columns]
    lists = input_lists(view, spell)
    return {
        "NAME.h": template("NAME.h.j2", upper=upper, n_columns=len(columns), point_fields=fields["point"],
                           angle_fields=fields["angle"], slide_fields=fields["slide"],
                           direction_fields=fields["direction"], columns=columns, inputs=lists),
        "NAME.c": template("NAME.c.j2", upper=upper,
                           runtime=runtime_sources(view, c_function, RUNTIME, status=_reads_reasons(view))
                           + velocity_variants(view) + two_channel_variants(view) + rates_variants(view),
                           record_fields=record_fields, sketch_in=lists["sketch"],
                           sketch_a=", ".join("{" + a + "}" for a in sketch_states(view, spell)),
                           column_fields=[f"{spell.ident(c.owner)}.{c.field}" for c in view.cells],
                           limits=lists["limits"], slack=spell.lit(log.policy.path_slack),
                           periodic=lists["periodic"], conditioned=conditioned_steps(view), bends=bends(view),
                           nsens=sensitivity_count(view), tape_size=tape_size(view)),
        "NAME_main.c": template("NAME_main.c.j2", upper=upper, columns=columns, inputs=lists),
    }


BACKEND = Backend("c", "C", templates="c", files=("NAME.h", "NAME.c", "NAME_main.c"), comment=("/*", " */"),
                  spelling=C, render=render, filters={"cbody": lambda text: str(text).replace("*/", "* /")},
                  printer=c_function, runtime=RUNTIME, words=WORDS, reals=REAL_TYPES)
