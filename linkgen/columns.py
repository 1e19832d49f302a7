"""The CSV column plan: inputs, then the chosen outputs, then status (generated-programs spec)."""

from __future__ import annotations

from .model import Mechanism
from .steplog import Column

_POINT = (("x", "x", "position"), ("y", "y", "position"), ("vx", "dx", "velocity"), ("vy", "dy", "velocity"),
          ("ax", "ddx", "acceleration"), ("ay", "ddy", "acceleration"))
_ANGLE = (("phi", "the", "angle"), ("omega", "dthe", "angular_velocity"), ("alpha", "ddthe", "angular_acceleration"))
# an instant centre (ic:LINK1:LINK2, linkgen.instant): known from velocities, so every column is of order 1
_CENTRE = (("x", "x", "centre"), ("y", "y", "centre"), ("ux", "ux", "centre_direction"),
           ("uy", "uy", "centre_direction"), ("status", "status", "centre_status"), ("sigma", "sigma", "centre_sigma"))
_SLIDE = (("s", "v", "position"), ("ds", "dv", "velocity"), ("dds", "ddv", "acceleration"))
# a link's direction (angles: unit): the unit vector (cos, sin) of its angle and its rates, as a
# POINT record's fields; each takes the place, and the quantity, of the angle column of its order
_DIRECTION = {"the": (("ux", "x"), ("uy", "y")), "dthe": (("dux", "dx"), ("duy", "dy")),
              "ddthe": (("ddux", "ddx"), ("dduy", "ddy"))}


def _take(spec: tuple[tuple[str, str, str], ...], per: int, order: int) -> tuple[tuple[str, str, str], ...]:
    """The fields of a record up to the order: ``per`` a derivative."""
    return spec[: per * (order + 1)]


def plan(m: Mechanism, order: int, outputs: tuple[str, ...], positions: dict[str, str], angles: dict[str, str],
         slides: dict[str, str], input_vars: list[str], centres: dict[str, str] | None = None) -> tuple[Column, ...]:
    """Columns in the spec's order for the given outputs (empty: the default set); ``centres``
    maps each instant centre among the outputs to its record."""
    cols = []
    for inp, var in zip(m.inputs, input_vars):
        field, quantity = ("the", "angle") if inp.kind == "revolute" else ("v", "position")
        cols.append(Column(inp.column, var, field, quantity))

    def point(name: str) -> None:
        cols.extend(Column(f"{name}.{c}", positions[name], f, q) for c, f, q in _take(_POINT, 2, order))

    def slide(name: str) -> None:
        cols.extend(Column(f"{name}.{c}", slides[name], f, q) for c, f, q in _take(_SLIDE, 1, order))

    def angle(name: str) -> None:
        cols.extend(Column(f"{name}.{c}", angles[name], f, q) for c, f, q in _take(_ANGLE, 1, order))

    prismatic = [j.name for j in m.joints if not j.revolute]
    links = [lk.name for lk in m.links]
    if not outputs:
        for j in m.joints:
            point(j.name)
        for p in m.points:
            point(p.name)
        for name in links:
            angle(name)
        for name in prismatic:
            slide(name)
    else:
        for name in outputs:
            if centres and name in centres:
                cols.extend(Column(f"{name}.{c}", centres[name], f, q) for c, f, q in _CENTRE)
            elif name in links:
                angle(name)
            else:
                point(name)
                if name in prismatic:
                    slide(name)
    return tuple(cols)


def direction_columns(columns: tuple[Column, ...], directions: dict[str, str], inputs: int) -> tuple[Column, ...]:
    """The columns with each output angle's (phi, omega, alpha) replaced by its direction's (ux, uy,
    dux, duy, ddux, dduy): ``directions`` maps the angle records to the direction records.  The
    first ``inputs`` columns, the inputs, stay as they are."""
    out = list(columns[:inputs])
    for c in columns[inputs:]:
        if c.variable not in directions:
            out.append(c)
            continue
        owner = c.name.split(".", 1)[0]
        out.extend(Column(f"{owner}.{name}", directions[c.variable], f, c.quantity) for name, f in _DIRECTION[c.field])
    return tuple(out)
