"""Trigonometry of sketch quantities, correctly rounded on every machine.

Constants written into generated files (local coordinates, offsets, sketch
angles) must not depend on the platform's libm, whose last digit differs
between systems; mpmath (sympy's own dependency) evaluates them with 40 digits
and they are rounded once to the nearest double.
"""

from __future__ import annotations

import mpmath

_CTX = mpmath.mp.clone()
_CTX.dps = 40


def atan2(y: float, x: float) -> float:
    return float(_CTX.atan2(_CTX.mpf(y), _CTX.mpf(x)))


def cos(a: float) -> float:
    return float(_CTX.cos(_CTX.mpf(a)))


def sin(a: float) -> float:
    return float(_CTX.sin(_CTX.mpf(a)))


def local(rx: float, ry: float, dx: float, dy: float) -> tuple[float, float]:
    """(gsi, eta) with r = gsi e + eta n, e = d / |d| and n = e turned a quarter turn left:
    (r.d, d x r) / |d|."""
    x, y, u, v = (_CTX.mpf(t) for t in (rx, ry, dx, dy))
    d = _CTX.sqrt(u * u + v * v)
    return float((x * u + y * v) / d), float((u * y - v * x) / d)


def along_across(rx: float, ry: float, dx: float, dy: float) -> tuple[float, float]:
    """(a, b) with r = a d + b n, n = (-dy, dx) the base d turned a quarter turn left:
    (r.d, d x r) / |d|^2."""
    x, y, u, v = (_CTX.mpf(t) for t in (rx, ry, dx, dy))
    d2 = u * u + v * v
    return float((x * u + y * v) / d2), float((u * y - v * x) / d2)
