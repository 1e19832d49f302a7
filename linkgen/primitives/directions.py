"""The runtime functions that give a link's direction as a unit vector (``angles: unit``).

A direction is a POINT record: the unit vector u = (cos, sin) of the link's angle in x and
y, its rate du/dt = omega n in dx and dy, and d2u/dt2 = alpha n - omega^2 u in ddx and ddy
(n the left normal of u).  ``link_direction`` takes it straight from two points of the link,
with no trigonometry: u = (j2 - j1) / |j2 - j1| turned by the sketch offset (c, s) = (cos,
sin) of off; its rate is (I - e e^T) (j2' - j1') / |j2 - j1| = omega n for e the unit vector
along j2 - j1, omega = (d x d') / |d|^2 and alpha = (d x d'' - 2 omega d.d') / |d|^2 as for the
segment's angle (d = j2 - j1).
``angle_direction`` takes it from an angle that a chain computes (cos and sin of it).
"""

from __future__ import annotations

from .. import status
from .dsl import NAN, Primitive, select, sqrt
from .vectors import PlaneBuilder, primitive


@primitive
def link_direction(b: PlaneBuilder) -> Primitive:
    """Unit vector u of a link from two of its points j1, j2, turned by the sketch offset (c, s) = (cos, sin) of off."""
    j1, j2 = b.points("j1", "j2")
    c, s = b.scalars("c", "s")
    d = b.difference(j1, j2)
    r2 = b.let("r2", d.p.dot(d.p))
    ir = b.let("ir", select(r2.eq(0), NAN, 1 / sqrt(r2)))
    e = b.vec("e", d.p.scaled(ir))
    u = b.local("u", e, c, s)
    om, al = b.angle_rates(d, r2)
    b.output_point("u", b.rotating("u", u, om, al))
    return b.build(status=select(r2.eq(0), status.CANNOT_CLOSE, 0), fail=r2.eq(0))


@primitive
def angle_direction(b: PlaneBuilder) -> Primitive:
    """Unit vector u of the angle phi (cos phi, sin phi), with its rates."""
    phi = b.record("phi", "ANGLE")
    u = b.direction("p", phi.the)
    b.output_point("u", b.rotating("u", u, phi.dthe, phi.ddthe))
    return b.build()
