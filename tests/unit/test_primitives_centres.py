"""linkgen.primitives.centres, instant_centre: worked cases by hand, and on random rows the two links'
velocities equal at the centre (computed here from each link's point and angular velocity), sigma as
defined, a centre at infinity across the relative motion."""

from __future__ import annotations

import math
import random

from linkgen.primitives import python_backend

CENTRE = python_backend(1)["instant_centre"]


def velocity(point: tuple, omega: float, at: tuple) -> tuple[float, float]:
    """The velocity at ``at`` of the body whose point (x, y, vx, vy) moves at angular velocity omega."""
    x, y, vx, vy = point
    return vx - omega * (at[1] - y), vy + omega * (at[0] - x)


def test_by_hand():
    # a = (0, 0) moving at (1, 0) on a link turning at 1; b fixed: v = (1 - y, x) = 0 at (0, 1)
    assert CENTRE((0.0, 0.0, 1.0, 0.0), (0.0, 1.0), (1.0, 0.0, 0.0, 0.0), (0.0, 0.0)) == (0.0, 1.0, 0.0, 1.0, 0.0,
                                                                                          1.0 / 2.0)
    # equal rates 0.5, a's velocity relative to the other link at a: (0, -1) - 0.5 k x (-3, 0) = (0, 0.5)
    x, y, ux, uy, st, sigma = CENTRE((0.0, 0.0, 2.0, 0.0), (0.0, 0.5), (3.0, 0.0, 2.0, 1.0), (0.0, 0.5))
    assert st == 1.0 and math.isnan(x) and math.isnan(y) and (ux, uy) == (1.0, 0.0) and sigma == 0.0
    # one pair both links carry, the links turning alike: every point moves alike, the pair is given
    a = (4.0, 5.0, 1.0, 2.0)
    x, y, ux, uy, st, sigma = CENTRE(a, (0.0, 1.0), a, (0.0, 1.0))
    assert (x, y, st, sigma) == (4.0, 5.0, 2.0, 0.0) and math.isnan(ux)
    # both at rest, apart: nothing moves, every point is a centre
    assert CENTRE((0.0, 0.0, 0.0, 0.0), (0.0, 0.0), (1.0, 0.0, 0.0, 0.0), (0.0, 0.0))[4] == 2.0


def test_random_rows():
    rng = random.Random(21)
    for _ in range(500):
        a = tuple(rng.uniform(-50, 50) for _ in range(4))
        b = tuple(rng.uniform(-50, 50) for _ in range(4))
        w1, w2 = rng.uniform(-3, 3), rng.uniform(-3, 3)
        x, y, ux, uy, st, sigma = CENTRE(a, (0.0, w1), b, (0.0, w2))
        e = math.hypot(a[0] - b[0], a[1] - b[1])
        g = [p - q for p, q in zip(velocity(a, w1, a[:2]), velocity(b, w2, a[:2]))]
        assert sigma == abs(w1 - w2) / (abs(w1) + abs(w2) + math.hypot(*g) / e) or math.isclose(
            sigma, abs(w1 - w2) / (abs(w1) + abs(w2) + math.hypot(*g) / e), rel_tol=1e-15)
        assert st == 0.0
        v1, v2 = velocity(a, w1, (x, y)), velocity(b, w2, (x, y))
        scale = math.hypot(*velocity(a, w1, a[:2])) + math.hypot(*velocity(b, w2, b[:2])) + 3 * (50 + math.hypot(x, y))
        assert math.hypot(v1[0] - v2[0], v1[1] - v2[1]) <= 1e-13 * scale / sigma
        assert abs(math.hypot(ux, uy) - 1) < 1e-15 and (ux > 0 or (ux == 0 and uy > 0))
        assert abs((x - a[0]) * uy - (y - a[1]) * ux) <= 1e-9 * (1 + math.hypot(x - a[0], y - a[1]))  # along u
