"""linkgen.directions (angles: unit): which step gives each output link's direction, under which
number, from which records; constant directions as drawn; the fallback blocks moved up past new steps.
The values are checked against the angle build's programs in tests/test_unit_angles.py."""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import pytest

from linkgen import exact
from linkgen.directions import renumbered, source, unit_directions
from linkgen.pipeline import analyse_file, draft
from linkgen.steplog import Arg, LJMatrix, Procedure, Step, StepLog, Variable

SAMPLES = Path(__file__).resolve().parents[2] / "samples"
HERE = Path(__file__).resolve().parent  # slotted_coupler.yaml, slotted_triad.yaml


def drafts(name: str, outputs: tuple[str, ...] | None = None) -> tuple[StepLog, StepLog]:
    """The sample's (or this folder's mechanism's) draft (no motion facts) with angles, and with unit vectors."""
    path = SAMPLES / name / f"{name}.yaml"
    _, topo, proc = analyse_file(str(path if path.exists() else HERE / f"{name}.yaml"))
    return draft(topo, proc, outputs), draft(topo, proc, outputs, options={"angles": "unit"})


def calls(log: StepLog) -> list[tuple[int, str, tuple[str, ...], tuple[str, ...]]]:
    """(number, function, records read, records written) of every step."""
    return [(s.number, s.function, tuple(a.var for a in s.args if a.kind == "var"), s.outputs) for s in log.steps]


def test_an_angle_only_the_outputs_read_becomes_its_direction_under_its_number():
    """The four-bar: the crank's, coupler's and rocker's angles (steps 5-7) are read by the outputs only
    (P is placed from A and B, without an angle)."""
    angle, unit = drafts("fourbar")
    assert calls(unit)[:4] == calls(angle)[:4]
    assert calls(unit)[4:] == [(5, "link_direction", ("p_O1", "p_A"), ("u_crank",)),
                               (6, "link_direction", ("p_A", "p_B"), ("u_coupler",)),
                               (7, "link_direction", ("p_O2", "p_B"), ("u_rocker",))]


def test_an_angle_another_step_reads_stays_and_its_direction_is_a_step_of_its_own():
    """The slotted coupler: the coupler's angle (step 4) turns the slot S, so it stays and the coupler's
    direction is step 12, after the procedure's last (the crank's, rocker's, block's and rod's directions
    take their angles' numbers, 8-11)."""
    angle, unit = drafts("slotted_coupler")
    assert calls(unit)[:7] == calls(angle)[:7] and calls(unit)[3][1:] == ("link_angle", ("p_A", "p_B"),
                                                                          ("phi_coupler",))
    step = unit.step(12)
    assert calls(unit)[11] == (12, "link_direction", ("p_A", "p_B"), ("u_coupler",))
    assert (step.action, step.target, step.pairs, step.links, step.fails) == ("direction", "coupler", ("A", "B"),
                                                                              ("coupler",), True)
    assert [a.value for a in step.args[2:]] == [1.0, 0.0]  # no offset: the link's direction is A to B


def test_the_output_columns_read_the_directions_and_the_inputs_stay_angles():
    angle, unit = drafts("fourbar", ("rocker", "P"))
    assert [c.name for c in unit.columns] == ["theta_O1", "rocker.ux", "rocker.uy", "rocker.dux", "rocker.duy",
                                              "rocker.ddux", "rocker.dduy", *(c.name for c in angle.columns[4:])]
    assert unit.columns[0] == angle.columns[0]
    assert {(c.variable, c.field, c.quantity) for c in unit.columns[1:3]} == {("u_rocker", "x", "angle"),
                                                                              ("u_rocker", "y", "angle")}
    v = unit.variable("u_rocker")
    assert (v.kind, v.role, v.entity, v.value) == ("POINT", "direction", "rocker", ())
    assert v.sketch == (exact.cos(angle.variable("phi_rocker").sketch[0]),
                        exact.sin(angle.variable("phi_rocker").sketch[0]))


def test_a_fixed_link_and_a_link_at_a_constant_angle_to_it_have_constant_directions():
    """The slider-crank's frame and its block (at a constant angle to the frame: offset_angle of a
    constant): (cos, sin) of their sketch angles, no step; the block's offset step is read by nobody."""
    angle, unit = drafts("slider_crank")
    for link in ("frame", "block"):
        v = unit.variable(f"u_{link}")
        sketch = next(k.angle for k in unit.links if k.name == link)
        assert v.value == pytest.approx((math.cos(sketch), math.sin(sketch)), abs=2e-16)
        assert not any(f"u_{link}" in s.outputs for s in unit.steps)
    assert calls(unit) == calls(angle)[:3] + [(4, "link_direction", ("p_O", "p_A"), ("u_crank",)),
                                              (5, "link_direction", ("p_A", "p_B"), ("u_rod",)), calls(angle)[5]]


def test_a_chains_line_angle_is_turned_into_its_direction_by_cos_and_sin():
    """The inverted slider's lever and block turn with the RPR chain's line angle psi_S: one
    angle_direction step after the procedure gives both links' columns."""
    _, unit = drafts("inverted_slider")
    assert calls(unit)[-1] == (6, "angle_direction", ("psi_S",), ("u_S",))
    assert unit.step(6).target == "lever, block" and not unit.step(6).fails
    assert {c.variable for c in unit.columns if c.name.startswith(("lever.", "block."))} == {"u_S"}


def test_a_direction_after_a_resolver_moves_the_fallback_blocks_up():
    """The Fig. 14 six-bar with a slot on its ternary (slotted_triad.yaml): the ternary's angle, once the
    resolver has placed it, turns the slot, so its direction is step 19, after the procedure; the
    fallback blocks (19-50) become 20-51, with their groups' records, and nothing else changes."""
    angle, unit = drafts("slotted_triad")
    assert calls(unit)[18] == (19, "link_direction", ("p_J2", "p_J4"), ("u_ternary",))
    fallbacks = [s for s in angle.steps if s.variant]
    assert [replace(s, number=s.number + 1) for s in fallbacks] == [s for s in unit.steps if s.variant]
    (g,), (h,) = angle.groups, unit.groups
    assert h == replace(g, variants=tuple(replace(v, steps=tuple(n + 1 for n in v.steps),
                                                  branches=tuple(replace(b, step=b.step + 1) for b in v.branches))
                                          for v in g.variants))
    assert angle.add_links == unit.add_links and angle.residuals == unit.residuals


def _record(name: str, kind: str = "ANGLE", value: tuple[float, ...] = ()) -> Variable:
    return Variable(name, kind, "link", name, value, (0.0,) * (2 if kind == "POINT" else 1))


def _step(number: int, function: str, args: list[Arg], out: str) -> Step:
    return Step(number, "angle", function, tuple(args), (out,), out, "", (), (), 0, "", "", (), 0, False)


def test_offsets_add_up_to_the_base_link_angle_and_a_chains_angle_is_its_own_source():
    var = Arg("var")
    steps = (_step(1, "link_angle", [replace(var, var="a"), replace(var, var="b"), Arg("real", value=0.25)], "t1"),
             _step(2, "offset_angle", [replace(var, var="t1"), Arg("real", value=0.5)], "t2"),
             _step(3, "offset_angle", [replace(var, var="t2"), Arg("real", value=1.0)], "t3"),
             _step(4, "RPR_links", [replace(var, var="a"), replace(var, var="b")], "psi"),
             _step(5, "offset_angle", [replace(var, var="psi"), Arg("real", value=1.0)], "t5"),
             _step(6, "offset_angle", [replace(var, var="c0"), Arg("real", value=1.0)], "t6"))
    records = [_record(n) for n in ("t1", "t2", "t3", "psi", "t5", "t6")] + [_record("c0", value=(0.5,))]
    records += [_record("a", "POINT"), _record("b", "POINT")]
    proc = Procedure(tuple(records), steps, LJMatrix((), (), (), ()), (), (), ())
    producer = {s.outputs[0]: s for s in steps}
    t3 = source(proc, producer, "t3")
    assert (t3.kind, t3.points, t3.off, t3.step) == ("link_direction", ("a", "b"), 1.75, steps[0])
    assert (source(proc, producer, "t5").kind, source(proc, producer, "t5").angle) == ("angle_direction", "t5")
    assert (source(proc, producer, "t6").kind, source(proc, producer, "t6").off) == ("constant", 1.5)
    assert (source(proc, producer, "c0").kind, source(proc, producer, "c0").off) == ("constant", 0.5)


def test_no_new_step_renumbers_nothing():
    _, topo, proc = analyse_file(str(SAMPLES / "sixbar_fig14" / "sixbar_fig14.yaml"))
    assert renumbered(proc, 13, 0) is proc
    assert unit_directions(proc, (), 0) == (proc, ())
