"""linkgen.backends.md.spelling, how the manual writes the procedure: numbers to ten significant digits (the
same double within a part in 1e10), the figure's names for pairs, points and inputs, flags signed and said
how they change, one call a line as the paper lists them."""

from __future__ import annotations

import random
from functools import cache

import pytest
from spelled import ROOT

from linkgen.backends.md.spelling import Manual, number
from linkgen.pipeline import build_log
from linkgen.render.view import View, build_view
from linkgen.steplog import Arg


@cache
def view_of(path: str) -> View:
    return build_view(build_log(str(ROOT / path), None, None, sweep=False))


def test_a_number_has_ten_significant_digits():
    rng = random.Random(3)
    for _ in range(200):
        x = rng.uniform(-1, 1) * 10.0 ** rng.randint(-12, 12)
        text = number(x)
        assert float(text) == pytest.approx(x, rel=5e-10)
        digits = text.lstrip("-").split("e")[0].replace(".", "").lstrip("0")
        assert len(digits) <= 10, text
    assert (number(-0.0), number(0), number(2.0), number(1 / 3), number(1e-20)) == ("0", "0", "2", "0.3333333333",
                                                                                 "1e-20")
    assert Manual.lit(123456789012.0) == "1.23456789e+11"


def test_pairs_points_and_inputs_by_their_names_in_the_figure():
    v = view_of("samples/fourbar/fourbar.yaml")
    spell = Manual(v)
    assert spell.order == v.log.order
    for var in v.log.variables:
        want = var.entity if var.role in ("pair", "point", "input") else var.name
        assert spell.ref(var.name) == want
    assert (spell.ref("p_A"), spell.ref("l_coupler"), spell.ref("in1")) == ("A", "l_coupler", "theta_O1")


def test_a_call_as_the_paper_lists_it():
    v = view_of("samples/fourbar/fourbar.yaml")
    spell = Manual(v)
    step = next(s for s in v.log.steps if s.function == "RRR_links")
    minv = int(next(a for a in step.args if a.label == "minv").value)
    assert spell.call(step) == f"B = RRR_links(A, O2, l_coupler, l_rocker, {minv:+d})"
    crank = next(s for s in v.log.steps if s.function == "crank_input")
    length = next(a for a in crank.args if a.kind == "real")
    assert spell.call(crank) == f"A = crank_input(O1, {number(float(length.value))}, theta_O1, ref_O1)"
    slider = view_of("samples/scotch_yoke/scotch_yoke.yaml")
    several = next(s for s in slider.log.steps if len(s.outputs) > 1)
    outs = [Manual(slider).ref(o) for o in several.outputs]
    assert Manual(slider).call(several).startswith(f"[{', '.join(outs)}] = {several.function}(")


def test_a_branch_that_changes_says_how():
    flipped = view_of("tests/mechanisms/parallelogram.yaml")
    step = next(s for s in flipped.log.steps if s.change_points)
    minv = next(a for a in step.args if a.label == "minv")
    assert Manual(flipped).arg(minv, None, step) == f"{int(minv.value):+d} flipped at change points"
    solved = view_of("tests/mechanisms/sixbar_fallback.yaml")
    step = next(s for s in solved.log.steps if s.number in solved.measured)
    minv = next(a for a in step.args if a.label == "minv")
    assert Manual(solved).arg(minv, None, step) == f"{int(minv.value):+d} then as solved"
    assert Manual(solved).arg(Arg("int", value=-1, label="sgn"), None, step) == "-1"
    assert Manual(solved).arg(Arg("real", value=0.1 + 0.2, label="gsi")) == "0.3"
