"""linkgen.exact: sketch trigonometry correctly rounded, whatever the machine's libm."""

from __future__ import annotations

import math
import random

import mpmath
import pytest

from linkgen import exact

_REFERENCE = mpmath.mp.clone()
_REFERENCE.dps = 80  # twice exact's precision: an independent evaluation of the true value


def _nearest(true: mpmath.mpf) -> float:
    """The double nearest a value given to 80 digits."""
    return float(true)


def _args(seed: int, count: int = 300) -> list[float]:
    rng = random.Random(seed)
    return ([rng.uniform(-10, 10) for _ in range(count)] + [rng.uniform(-1e6, 1e6) for _ in range(count // 3)]
            + [math.ldexp(rng.random(), -rng.randrange(1, 60)) for _ in range(count // 3)])


@pytest.mark.parametrize("name", ["sin", "cos"])
def test_sin_and_cos_are_the_nearest_double(name: str):
    ours, true = getattr(exact, name), getattr(_REFERENCE, name)
    for a in _args(1):
        value = ours(a)
        assert value == _nearest(true(_REFERENCE.mpf(a))), a
        assert abs(value - getattr(math, name)(a)) <= math.ulp(value)  # libm: within one unit


def test_atan2_is_the_nearest_double_in_every_quadrant():
    args = _args(2)
    for y, x in zip(args, reversed(args)):
        value = exact.atan2(y, x)
        assert value == _nearest(_REFERENCE.atan2(_REFERENCE.mpf(y), _REFERENCE.mpf(x))), (y, x)
        assert abs(value - math.atan2(y, x)) <= math.ulp(value)


def test_values_known_in_closed_form():
    assert exact.sin(0.0) == 0.0 and exact.cos(0.0) == 1.0
    assert exact.atan2(1.0, 1.0) == math.pi / 4  # pi/4 rounds to the double pi rounded, over 4 (exact)
    assert exact.atan2(1.0, 0.0) == math.pi / 2
    assert exact.atan2(0.0, -1.0) == math.pi
    assert exact.atan2(-1.0, -1.0) == -3 * math.pi / 4
    # 0.5 = sin(pi/6) holds for the real pi/6, not the double nearest it, which is a little below
    assert exact.sin(math.pi / 6) == 0.49999999999999994
