"""linkgen.backends.md, the manual: text escaped so Markdown shows it as written, the listing one line a step
with the resolver's steps marked, the constants a reader needs per step, the omitted steps in runs, and a
rendered NAME.md that holds each of these and a row per status code."""

from __future__ import annotations

import dataclasses
import re
from functools import cache

import pytest
from spelled import ROOT

from linkgen.backends.md import BACKEND, _constants, _listing, _omitted, markdown_text
from linkgen.backends.md.spelling import Manual, number
from linkgen.pipeline import build_log
from linkgen.render import render_backend
from linkgen.render.view import View, build_view
from linkgen.steplog import Omitted


@cache
def view_of(path: str) -> View:
    return build_view(build_log(str(ROOT / path), None, None, sweep=False))


@pytest.mark.parametrize("text", ["a*b*", "_x_", "[link](u)", "<b>&amp;", "# h", "a|b", "~~s~~", "`c`", "back\\slash",
                                  "plain 四節 text"])
def test_markdown_text_escapes_every_character_that_starts_markup(text: str):
    escaped = markdown_text(text)
    # CommonMark: a backslash before ASCII punctuation shows the character itself
    assert re.sub(r"\\([!-/:-@\[-`{-~])", r"\1", escaped) == text
    assert re.search(r"(?<!\\)[*_\[\]<>&#|~`]", escaped.replace("\\\\", "")) is None


def test_the_listing_marks_the_steps_a_resolver_iterates():
    v = view_of("tests/mechanisms/sixbar_fallback.yaml")
    spell = Manual(v)
    inside = {n for g in v.log.groups for n in g.steps}
    lines = _listing(v, spell, v.main_steps)
    assert len(lines) == len(v.main_steps)
    for line, s in zip(lines, v.main_steps):
        assert line[:3] == f"{s.number:>3}" and line[4] == ("|" if s.number in inside else " ")
        if s.function:
            assert line[6:] == spell.call(s)
    texts = {s.action: line[6:] for line, s in zip(lines, v.main_steps)}
    g = v.log.groups[0]
    assert texts["fixed"] == f"fixed_link({v.log.steps[0].target})"
    assert texts["resolve"] == f"add_link_optimizer({', '.join(g.residuals)} -> {', '.join(g.add_links)})"
    add = next(s for s in v.main_steps if s.action == "add_link")
    assert texts["add_link"] == f"{add.target} = additional_link({', '.join(add.pairs)})"


def test_the_constants_a_reader_needs_per_step():
    log = view_of("samples/fourbar/fourbar.yaml").log
    constants = _constants(log)
    crank = next(s for s in log.steps if s.function == "crank_input")
    length = next(a for a in crank.args if a.kind == "real")
    assert constants[crank.number] == [f"{length.label} = {number(float(length.value))}", "ref_O1 = 0"]
    chain = next(s for s in log.steps if s.function == "RRR_links")
    coupler, rocker = log.variable("l_coupler").value[0], log.variable("l_rocker").value[0]
    assert constants[chain.number] == [f"l_coupler = {number(coupler)}", f"l_rocker = {number(rocker)}"]
    assert abs(coupler - (60.0 ** 2 + 50.0 ** 2) ** 0.5) < 1e-12  # |B - A| in the sketch: (80, 50) - (20, 0)


@pytest.mark.parametrize("numbers, text", [
    ((5,), "step 5 (t5)"),
    ((5, 6, 7, 10), "steps 5-7 (t5, t6, t7) and 10 (t10)"),
    ((2, 4, 5), "steps 2 (t2) and 4-5 (t4, t5)"),
])
def test_omitted_steps_in_runs(numbers: tuple[int, ...], text: str):
    log = dataclasses.replace(view_of("samples/fourbar/fourbar.yaml").log,
                              omitted=tuple(Omitted(n, f"t{n}") for n in numbers))
    assert _omitted(log) == text


def test_the_manual_holds_the_listing_the_codes_and_the_constants():
    v = view_of("tests/mechanisms/sixbar_fallback.yaml")
    (name, text), = render_backend(BACKEND, v).items()
    md = text.decode("utf-8")
    assert name == f"{v.log.name}.md"
    for line in _listing(v, Manual(v), v.main_steps):
        assert line in md
    table = md.split("## Status codes", 1)[1].split("\n## ", 1)[0]
    rows = re.findall(r"^\| (-?\d+) \| (.*) \|$", table, re.M)
    assert rows == [(str(c.code), c.meaning) for c in v.log.status_codes]
    other = dataclasses.replace(v.log, policy=dataclasses.replace(v.log.policy, good_lever=0.3125))
    (text,) = render_backend(BACKEND, build_view(other)).values()
    assert "is at least 0.3125 where there are any" in text.decode("utf-8").replace("\n", " ")
