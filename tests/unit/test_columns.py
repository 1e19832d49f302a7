"""linkgen.columns: the CSV's columns in the order the generated-programs spec gives (inputs, then the
outputs with the columns their kind and the order give)."""

from __future__ import annotations

import pytest

from linkgen.columns import direction_columns, plan
from linkgen.loader import parse
from linkgen.model import Mechanism
from linkgen.primitives.dsl import record_fields
from linkgen.validate import validate

TEXT = """linkgen: 1
name: slider_crank
joints:
  O: [0, 0]
  A: [10, 8]
  B: [45, -5]
  S: {type: prismatic, at: [45, -5], axis: 0}
links:
  frame: {joints: [O, S], fixed: true}
  crank: [O, A]
  rod: {joints: [A, B], points: {P: [30, 10]}}
  block: [B, S]
inputs:
  - {joint: O, link: crank, relative_to: frame, range: [0, 360]}
"""
POINT = ["x", "y", "vx", "vy", "ax", "ay"]
ANGLE = ["phi", "omega", "alpha"]
SLIDE = ["s", "ds", "dds"]


@pytest.fixture(scope="module")
def m() -> Mechanism:
    return validate(parse(TEXT, "m.yaml"), "m.yaml")


def columns(m: Mechanism, order: int, outputs: tuple[str, ...] = ()):
    """The plan with every record named after its pair, point or link (VAR_NAME)."""
    named = {n: f"VAR_{n}" for n in [*m.positions, *(lk.name for lk in m.links)]}
    return plan(m, order, outputs, named, named, named, ["VAR_theta"])


def test_the_default_outputs_at_order_2(m: Mechanism):
    """Every pair in joints order, every point, every link (the frame too), then each prismatic pair's slide."""
    expected = ["theta_O"]
    expected += [f"{n}.{c}" for n in ("O", "A", "B", "S", "P") for c in POINT]
    expected += [f"{n}.{c}" for n in ("frame", "crank", "rod", "block") for c in ANGLE]
    expected += [f"S.{c}" for c in SLIDE]
    assert [c.name for c in columns(m, 2)] == expected


@pytest.mark.parametrize("order, point, angle, slide", [
    (0, ["x", "y"], ["phi"], ["s"]),
    (1, ["x", "y", "vx", "vy"], ["phi", "omega"], ["s", "ds"]),
])
def test_the_order_limits_the_derivatives(m: Mechanism, order: int, point: list, angle: list, slide: list):
    expected = ["theta_O"] + [f"B.{c}" for c in point] + [f"rod.{c}" for c in angle]
    expected += [f"S.{c}" for c in point] + [f"S.{c}" for c in slide]
    assert [c.name for c in columns(m, order, ("B", "rod", "S"))] == expected


def test_given_outputs_keep_their_order(m: Mechanism):
    assert [c.name for c in columns(m, 0, ("rod", "P", "O"))] == ["theta_O", "rod.phi", "P.x", "P.y", "O.x", "O.y"]


def test_each_column_reads_its_records_field_and_has_its_quantity(m: Mechanism):
    """The quantity sets the spec's scale S of a column (positions, velocities, ..., angular accelerations);
    a record holds its value, then its first and second derivatives (x, y, dx, dy, ddx, ddy for a point)."""
    spec = {"x": ("POINT", 0, "position"), "y": ("POINT", 0, "position"), "vx": ("POINT", 1, "velocity"),
            "vy": ("POINT", 1, "velocity"), "ax": ("POINT", 2, "acceleration"), "ay": ("POINT", 2, "acceleration"),
            "phi": ("ANGLE", 0, "angle"), "omega": ("ANGLE", 1, "angular_velocity"),
            "alpha": ("ANGLE", 2, "angular_acceleration"), "s": ("VARIABLE", 0, "position"),
            "ds": ("VARIABLE", 1, "velocity"), "dds": ("VARIABLE", 2, "acceleration")}
    for c in columns(m, 2)[1:]:
        name, suffix = c.name.split(".")
        record, derivative, quantity = spec[suffix]
        fields = record_fields(record, 2)
        per = 2 if record == "POINT" else 1
        assert (c.variable, c.quantity) == (f"VAR_{name}", quantity)
        assert fields.index(c.field) == per * derivative + (suffix in ("y", "vy", "ay"))


def test_an_input_column_is_the_input_record_value():
    m = validate(parse(TEXT.replace("{joint: O, link: crank, relative_to: frame, range: [0, 360]}",
                                    "{joint: S, range: [0, 5]}"), "m.yaml"), "m.yaml")
    (column,) = plan(m, 2, ("B",), {"B": "p"}, {}, {}, ["VAR_s"])[:1]
    assert (column.name, column.variable, column.quantity) == ("s_S", "VAR_s", "position")


@pytest.mark.parametrize("order, names", [
    (0, ["ux", "uy"]), (1, ["ux", "uy", "dux", "duy"]), (2, ["ux", "uy", "dux", "duy", "ddux", "dduy"])])
def test_a_direction_takes_the_place_and_quantity_of_its_angle(m: Mechanism, order: int, names: list):
    """angles: unit: each angle column becomes the direction record's x and y of the same order
    (the unit vector, its rate, its acceleration); points, slides and the input stay."""
    angle = columns(m, order, ("B", "rod", "crank"))
    unit = direction_columns(angle, {"VAR_rod": "U_rod", "VAR_crank": "U_crank"}, 1)
    point = [c for c in angle if c.name.startswith("B.")]
    assert [c.name for c in unit] == ["theta_O", *(c.name for c in point), *(f"rod.{n}" for n in names),
                                      *(f"crank.{n}" for n in names)]
    assert unit[: 1 + len(point)] == angle[: 1 + len(point)]
    fields, quantities = record_fields("POINT", order), ("angle", "angular_velocity", "angular_acceleration")
    for k, c in enumerate(unit[1 + len(point):]):
        assert (c.variable, c.field, c.quantity) == ("U_rod" if k < len(names) else "U_crank",
                                                     fields[k % len(names)], quantities[(k % len(names)) // 2])


def test_an_input_column_stays_an_angle_even_where_its_record_has_a_direction(m: Mechanism):
    angle = columns(m, 0, ("rod",))
    assert direction_columns(angle, {"VAR_theta": "U", "VAR_rod": "U_rod"}, 1)[0] == angle[0]
