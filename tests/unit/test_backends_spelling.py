"""linkgen.backends.spelling, the rules every language's spelling shares, checked through the Python one by
evaluating what it writes: a chain's branch measure is the cross or dot product worked out by hand, a
published output adds the origin back, branch_at and reach_at (the runtime's own) flip and stop where the
change points and the reach say, the status codes are linkgen.status's, the conditioning compares with the
policy's thresholds, constants are held relative to the origin."""

from __future__ import annotations

import math
import random
from functools import cache
from importlib import resources
from types import SimpleNamespace

import pytest
from spelled import ROOT

from linkgen import status
from linkgen.backends.py.spelling import Python
from linkgen.backends.spelling import Spelling, Syntax
from linkgen.pipeline import build_log
from linkgen.render.view import View, build_view
from linkgen.steplog import Arg, BranchSign


@cache
def view_of(path: str) -> View:
    return build_view(build_log(str(ROOT / path), None, None, sweep=False))


def runtime(*names: str) -> dict:
    """The Python runtime's hand-written helpers, exec'd as the program has them."""
    space = {"floor": math.floor, "PI": math.pi, "NAN": math.nan}
    for name in names:
        exec(resources.files("linkgen.backends.py").joinpath("runtime", f"{name}.py").read_text(encoding="utf-8"),
             space)
    return space


def test_a_branch_measure_is_the_cross_or_dot_product():
    v = view_of("samples/fourbar/fourbar.yaml")
    spell = Python(v)
    rng = random.Random(1)
    a, b, c = ((rng.uniform(-9, 9), rng.uniform(-9, 9)) for _ in range(3))
    t = rng.uniform(-3, 3)
    w = SimpleNamespace(p_A=(*a, 0, 0, 0, 0), p_B=(*b, 0, 0, 0, 0), p_P=(*c, 0, 0, 0, 0), phi_coupler=(t, 0, 0))
    side = spell.sign_measure(BranchSign(3, "side", ("p_A", "p_B", "p_P"), "", 1))
    along = spell.sign_measure(BranchSign(3, "along", ("p_A", "p_P"), "phi_coupler", 1))
    space = {"w": w, "cos": math.cos, "sin": math.sin}
    assert eval(side, space) == pytest.approx((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]), rel=1e-14)
    assert eval(along, space) == pytest.approx((c[0] - a[0]) * math.cos(t) + (c[1] - a[1]) * math.sin(t), rel=1e-14)


def test_a_published_output_is_drawn_or_computed_with_the_origin_added_back():
    v = view_of("samples/fourbar/fourbar.yaml")
    spell = Python(v)
    log = v.log
    ox, oy = log.origin
    assert (ox, oy) != (0.0, 0.0)
    w = SimpleNamespace(p_A=(1.5, -2.25, 3.0, 4.0, 5.0, 6.0))
    for c in log.columns:
        text = spell.published(c)
        if c.variable == "p_O2":  # a constant pair: its drawn value, rates 0
            assert float(text) == {"x": 90.0, "y": 0.0}.get(c.field, 0.0), c.name
        elif c.variable == "p_A":
            want = dict(zip(("x", "y", "dx", "dy", "ddx", "ddy"), (1.5 + ox, -2.25 + oy, 3.0, 4.0, 5.0, 6.0)))
            assert eval(text, {"w": w}) == want[c.field], c.name
    negative = Python(build_view(build_log(str(ROOT / "samples/actuator/actuator.yaml"), None, None, sweep=False)))
    assert negative.log.origin[0] < 0  # the offset is subtracted as a positive literal
    x = next(c for c in negative.log.columns if c.field == "x" and not negative.log.drawn(c))
    assert f" - {negative.lit(-negative.log.origin[0])}" in negative.published(x)


@pytest.mark.parametrize("turns, flips", [(0.0, 0), (0.5, 1), (1.0, 2), (-0.5, 1), (1.75, 3), (-2.25, 5)])
def test_branch_at_flips_at_every_change_point_passed(turns: float, flips: int):
    """The parallelogram's chain flips at 0 and pi (its change points); from the sketch at pi/4, a turn of
    x turns passes the change points counted by hand."""
    v = view_of("tests/mechanisms/parallelogram.yaml")
    spell = Python(v)
    step = next(s for s in v.log.steps if s.change_points)
    b0 = int(next(a for a in step.args if a.label == "minv").value)
    sketch = v.log.inputs[0].sketch
    call = spell.arg(next(a for a in step.args if a.label == "minv"), None, step)
    assert call == spell.branch(step, b0) and call.startswith("branch_at(")
    space = {**runtime("branch"), "w": SimpleNamespace(**{v.inputs[0].name: (sketch + 2 * math.pi * turns, 0, 0)})}
    assert eval(call, space) == b0 * (-1) ** flips


def test_reach_at_is_called_with_the_logs_reach_and_nan_where_none():
    v = view_of("tests/mechanisms/cylinder_triad.yaml")
    spell = Python(v)
    r = v.log.reach
    assert r is not None and r.high is None and not r.periodic
    assert spell.reach_call("x") == f"reach_at(x, {spell.lit(r.low)}, NAN, 0)"
    assert spell.reach_low() == spell.lit(r.low)
    space = runtime("reach")
    assert [eval(spell.reach_call(repr(x)), space) for x in (r.low - 1, r.low + 1, 1e9)] == [-1, 0, 0]
    plain = Python(view_of("samples/fourbar/fourbar.yaml"))
    assert plain.reach_check() == [] and plain.reach_low() == "NAN"
    with pytest.raises(ValueError, match="has no reach"):
        plain.reach_call("x")


def test_status_codes_and_notes_are_linkgen_statuss():
    v = view_of("samples/fourbar/fourbar.yaml")
    spell = Python(v)
    step = next(s for s in v.log.steps if s.fails)
    assert spell.status_code(step, status.CANNOT_CLOSE) == status.code(step.number, status.CANNOT_CLOSE)
    singular, near = (int(x) for x in spell.note_codes(step).split(", "))
    assert (status.step(singular), status.reason(singular)) == (step.number, status.SINGULAR)
    assert (status.step(near), status.reason(near), near < 0) == (step.number, status.NEAR_SINGULAR, True)


@pytest.mark.parametrize("sigma, want", [(0.5e-7, 3), (0.5e-3, 4), (0.5, 0)])
def test_a_resolvers_conditioning_against_the_policys_thresholds(sigma: float, want: int):
    v = view_of("tests/mechanisms/cylinder_triad.yaml")
    spell = Python(v)
    step = v.log.step(v.log.groups[0].step)
    notes: list[tuple] = []
    w = SimpleNamespace(sigma={step.number: sigma}, note=lambda *a: notes.append(a))
    line = spell.note_sigma(step)
    assert isinstance(line, str)  # one expression in Python
    eval(line, {"w": w})
    assert notes == [(want, status.code(step.number, 3), status.code(step.number, 4))]
    assert v.log.policy.singular < 0.5e-3 < v.log.policy.near_singular  # the middle case is between them


def test_constants_are_held_relative_to_the_origin_with_zero_rates():
    v = view_of("samples/fourbar/fourbar.yaml")
    spell = Python(v)
    o2 = v.log.variable("p_O2")
    assert spell.padded(o2) == (90.0 - 44.0, 0.0 - 36.0, 0.0, 0.0, 0.0, 0.0)  # origin (44, 36)
    assert spell.padded(v.log.variable("l_coupler")) == (v.log.variable("l_coupler").value[0], 0.0, 0.0)
    assert spell.zero_record() == "0.0, 0.0, 0.0" and spell.flag(True) == "True" and spell.flag(False) == "False"


def test_arguments_and_references():
    v = view_of("tests/mechanisms/cylinder_triad.yaml")
    spell = Python(v)
    g = v.groups[0]
    read = g.reads[0].name
    assert spell.ref(read, g) == read and spell.ref(read, None) == f"w.{read}"  # a block's copy of what it reads
    const = v.constants[0].name
    assert spell.ref(const, None) == const  # Python holds constants as the file's names
    assert spell.arg(Arg("real", value=0.1, label="gsi"), None) == "0.1"
    assert spell.arg(Arg("int", value=-1, label="sgn"), None) == "-1"
    measured = next(s for s in v.log.steps if s.number in v.measured)
    minv = next(a for a in measured.args if a.label == "minv")
    assert spell.arg(minv, g, measured) == f"w.br{measured.number}"  # read off the last solution


def test_the_base_leaves_the_language_to_the_subclass():
    v = view_of("samples/fourbar/fourbar.yaml")
    assert Spelling.syntax == Syntax() and Spelling.order_of(v) == v.record_order
    with pytest.raises(NotImplementedError):
        Spelling(v).member("POINT", "x")
    with pytest.raises(NotImplementedError):
        Spelling(v).reach_fail(1, 2)
