"""linkgen.primitives.directions, a link's direction as a unit vector (angles: unit): hand-calculated
unit vectors and rates, the sketch offset, and the status where the two points coincide.  (The sympy
oracle, the constraints and the backends' bits are in tests/test_primitives.py.)"""

from __future__ import annotations

import math

import pytest
from primitive_calls import PI, STILL, approx, py2

from linkgen.primitives.directions import angle_direction, link_direction
from linkgen.primitives.dsl import Call, Expr, children

# j1 at rest at (1, 2); j2 = j1 + (3, 4) turning about it at omega = 2: v = 2 (-4, 3), a = -4 (3, 4)
J1 = (1.0, 2.0, 0.0, 0.0, 0.0, 0.0)
J2 = (4.0, 6.0, -8.0, 6.0, -12.0, -16.0)


@pytest.mark.parametrize(
    ("c", "s", "u"),
    [
        (1.0, 0.0, (0.6, 0.8)),  # along j1 -> j2: (3, 4) / 5
        (0.0, 1.0, (-0.8, 0.6)),  # a quarter turn on
        (-1.0, 0.0, (-0.6, -0.8)),  # half a turn
    ],
)
def test_the_direction_of_a_turning_link_and_its_rates(c: float, s: float, u: tuple[float, float]):
    """u' = omega (-uy, ux), u'' = -omega^2 u at constant omega (alpha = 0)."""
    st, sigma, (got,) = py2("link_direction", J1, J2, c, s)
    assert (st, sigma) == (0, None)
    assert got == approx((*u, -2 * u[1], 2 * u[0], -4 * u[0], -4 * u[1]))


def test_an_angular_acceleration_adds_its_tangential_term():
    """j2 with the tangential acceleration of alpha = 1 added: u'' = alpha n - omega^2 u."""
    j2 = (4.0, 6.0, -8.0, 6.0, -12.0 - 4.0, -16.0 + 3.0)
    (got,) = py2("link_direction", J1, j2, 1.0, 0.0)[2]
    assert got[4:] == approx((-0.8 - 4 * 0.6, 0.6 - 4 * 0.8))


def test_the_direction_needs_no_trigonometry():
    """Only arithmetic and one square root: no atan2, cos or sin anywhere in its body."""
    calls: set[str] = set()
    todo: list[Expr] = [let.expr for let in link_direction.body]
    while todo:
        e = todo.pop()
        if isinstance(e, Call):
            calls.add(e.fn)
        todo += children(e)
    assert calls == {"sqrt"}


def test_coincident_points_have_no_direction():
    st, _, (got,) = py2("link_direction", STILL, STILL, 1.0, 0.0)
    assert st == 1 and all(math.isnan(x) for x in got)


def test_the_direction_of_an_angle():
    st, _, (got,) = py2("angle_direction", (PI / 6, 2.0, 3.0))
    c, s = math.sqrt(3) / 2, 0.5
    assert st is None and angle_direction.status is None
    assert got == approx((c, s, -2 * s, 2 * c, -3 * s - 4 * c, 3 * c - 4 * s))
