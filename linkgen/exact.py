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
