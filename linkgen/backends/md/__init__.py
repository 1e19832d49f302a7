"""The manual backend: NAME.md, the procedure as the paper lists it, with its LJ-matrices,
resolvers, singular positions and status codes (the figure NAME.svg is render's)."""

from __future__ import annotations

import re
from collections.abc import Sequence
from typing import TYPE_CHECKING

from ...errors import and_list
from ...ljmatrix import states
from ...policy import EPSILON, REAL_TYPES, SINGULAR_EPS, TOLERANCE_EPS, for_real
from ...steplog import Omitted, Step, StepLog
from ...summary.text import markdown as markdown_summary
from .. import Backend, Template
from ..program import used_primitives
from .spelling import Manual, number

if TYPE_CHECKING:
    from ...render.view import View


def markdown_text(text: str) -> str:
    """Text as itself in Markdown: the characters that start markup, links or HTML backslash-escaped."""
    return re.sub(r"([\\`*_\[\]<>&#|~])", r"\\\1", text)


def _constants(log: StepLog) -> dict[int, list[str]]:
    """Per step, the constants a reader needs: labelled numbers and constant records."""
    out: dict[int, list[str]] = {}
    for s in log.steps:
        items = []
        for a in s.args:
            if a.kind == "real":
                items.append(f"{a.label} = {number(float(a.value))}")
            elif a.kind == "var" and log.variable(a.var).constant:
                v = log.variable(a.var)
                if v.role not in ("pair", "point"):
                    items.append(f"{a.var} = {', '.join(number(x) for x in v.value)}")
        out[s.number] = items
    return out


def _listing(view: View, spell: Manual, steps: Sequence[Step]) -> list[str]:
    """One line per step as the paper's listings; | marks a step the resolver iterates."""
    inside = {n for g in view.log.groups for n in g.steps}
    lines = []
    for s in steps:
        mark = "|" if s.number in inside else " "
        if s.function:
            text = spell.call(s)
        elif s.action == "fixed":
            text = f"fixed_link({s.target})"
        elif s.action == "add_link":
            text = f"{s.target} = additional_link({', '.join(s.pairs)})"
        else:
            g = view.resolver(s.number)
            text = f"add_link_optimizer({', '.join(g.group.residuals)} -> {', '.join(g.group.add_links)})"
        lines.append(f"{s.number:>3} {mark} {text}")
    return lines


def _omitted(log: StepLog) -> str:
    """'steps 5-7 (J5, J6, J7) and 10 (rocker1)': the steps left out, in runs."""
    runs: list[list[Omitted]] = []
    for o in log.omitted:
        if runs and runs[-1][-1].number == o.number - 1:
            runs[-1].append(o)
        else:
            runs.append([o])
    parts = [(f"{r[0].number}-{r[-1].number}" if len(r) > 1 else f"{r[0].number}")
             + f" ({', '.join(o.target for o in r)})" for r in runs]
    return ("steps " if len(log.omitted) > 1 else "step ") + and_list(parts)


def render(view: View, spell: Manual, template: Template) -> dict[str, bytes]:
    from ...assemblies.report import manual  # linkgen.assemblies builds logs: the pipeline imports the backends
    from ...loopmap import sketch_slopes  # the evaluator renders through the backends

    log = view.log
    seq = states(log)
    return {"NAME.md": template(
        "NAME.md.j2", lj=seq[0], lj_after={st.step: st for st in seq[1:]},
        lj_before={b.step: a for a, b in zip(seq, seq[1:])}, omitted=_omitted(log),
        listing=_listing(view, spell, view.main_steps),
        fallbacks={b.index: _listing(view, spell, b.steps) for b in view.blocks if b.group.variant},
        codes=log.status_codes, constants=_constants(log), functions=used_primitives(view),
        slides={p.name for p in log.pairs if p.kind == "prismatic"},
        limits=and_list([f"{number(x)} for {i.column}" for x, i in zip(log.step_limits(), log.inputs)]),
        good_lever=log.policy.good_lever, real_policy=for_real(log.policy, log.options.real),
        tolerance_eps=TOLERANCE_EPS, singular_eps=SINGULAR_EPS, real_eps=EPSILON[log.options.real],
        assemblies=manual(log), loop_slopes=sketch_slopes(log),
        summary=markdown_summary(log.summary, markdown_text) if log.summary else "")}


BACKEND = Backend("md", "Markdown", templates="md", files=("NAME.md",), comment=("<!--", " -->"), spelling=Manual,
                  render=render, filters={"mdtext": markdown_text, "num": number}, reals=REAL_TYPES)
