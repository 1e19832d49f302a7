"""Trigonometry of sketch quantities, correctly rounded on every machine.

Constants written into generated files (local coordinates, offsets, sketch
angles) must not depend on the platform's libm, whose last digit differs
between systems.  They are evaluated in binary fixed point on Python's
integers, with PREC bits of the result's own size (77 digits; the doubles
given are exact rationals), and rounded once to the nearest double (an
integer over a power of two, divided as Python divides integers: correctly
rounded).  mpmath at 40 digits did this before: its import took 13-18 ms of
every build.
"""

from __future__ import annotations

import functools
import math
from fractions import Fraction

PREC = 256  # bits of a result that are computed (its error is a few units of the last of them)
GUARD = 16  # bits more that absorb the rounding of every operation of a series


def atan2(y: float, x: float) -> float:
    """The angle of (x, y), in (-pi, pi]; 0 at (0, 0) (a zero has no sign here: atan2(-0.0, -1.0) is pi)."""
    if y == 0 and x == 0:
        return 0.0
    ay, ax = abs(Fraction(y)), abs(Fraction(x))
    t = min(ay, ax) / max(ay, ax)
    deeper = max(0, t.denominator.bit_length() - t.numerator.bit_length())  # t about 2^-deeper, or more
    bits = PREC + GUARD + 2 + deeper  # an angle near an axis is about t: its bits are the fraction's deeper ones
    angle = _atan(t, bits)  # the angle from the nearer axis, at most pi/4
    if ay > ax:
        angle = (_pi(bits) >> 1) - angle
    if x < 0:
        angle = _pi(bits) - angle
    return (-angle if y < 0 else angle) / (1 << bits)


def cos(a: float) -> float:
    return _sin_cos(a)[1]


def sin(a: float) -> float:
    return _sin_cos(a)[0]


def local(rx: float, ry: float, dx: float, dy: float) -> tuple[float, float]:
    """(gsi, eta) with r = gsi e + eta n, e = d / |d| and n = e turned a quarter turn left:
    (r.d, d x r) / |d|."""
    x, y, u, v = (Fraction(t) for t in (rx, ry, dx, dy))
    square = u * u + v * v
    return _over_root(x * u + y * v, square), _over_root(u * y - v * x, square)


def along_across(rx: float, ry: float, dx: float, dy: float) -> tuple[float, float]:
    """(a, b) with r = a d + b n, n = (-dy, dx) the base d turned a quarter turn left:
    (r.d, d x r) / |d|^2."""
    x, y, u, v = (Fraction(t) for t in (rx, ry, dx, dy))
    d2 = u * u + v * v
    return float((x * u + y * v) / d2), float((u * y - v * x) / d2)


def _over_root(n: Fraction, square: Fraction) -> float:
    """n / sqrt(square), the nearest double."""
    if square == 0:
        raise ZeroDivisionError("a base of length zero")
    if n == 0:
        return 0.0
    value = n * n / square  # the result squared, exact
    shift = PREC + GUARD + max(0, (value.denominator.bit_length() - value.numerator.bit_length()) // 2 + 1)
    root = math.isqrt((value.numerator << (2 * shift)) // value.denominator)
    return (root if n > 0 else -root) / (1 << shift)


def _sin_cos(a: float) -> tuple[float, float]:
    """sin a and cos a, the nearest doubles: a reduced by the multiple of pi/2 nearest it, then
    the Taylor series of both on the rest (at most pi/4), each at PREC bits of its own size."""
    if a == 0:
        return 0.0, 1.0
    size = math.frexp(a)[1]  # a lies in [2^(size-1), 2^size)
    bits = PREC + GUARD + max(0, -size) + 2  # below 1: sin a is about a, its bits are the fraction's deeper ones
    wide = bits + max(0, size) + 2  # the reduction takes the integer bits of a/(pi/2) from pi
    n, d = a.as_integer_ratio()
    fixed = (n << wide) // d  # exact: d is a power of two not above 2^1074, wide covers it where it matters
    quarter = _pi(wide) >> 1
    turns = (2 * fixed + quarter) // (2 * quarter)  # the nearest multiple of pi/2
    rest = (fixed - turns * quarter) >> (wide - bits)
    s, c = _series(rest, bits)
    s, c = ((s, c), (c, -s), (-s, -c), (-c, s))[turns % 4]
    return s / (1 << bits), c / (1 << bits)


def _series(r: int, bits: int) -> tuple[int, int]:
    """sin and cos of r / 2^bits (at most about pi/4), times 2^bits: their Taylor series."""
    r2 = r * r >> bits
    s = term = r
    k = 1
    while term:
        term = -(term * r2 >> bits) // ((k + 1) * (k + 2))
        s += term
        k += 2
    c = term = 1 << bits
    k = 0
    while term:
        term = -(term * r2 >> bits) // ((k + 1) * (k + 2))
        c += term
        k += 2
    return s, c


def _atan(t: Fraction, bits: int) -> int:
    """atan t for 0 <= t <= 1, times 2^bits: t halved in angle twice (atan t = 2 atan(t / (1 +
    sqrt(1 + t^2)))), then the series."""
    one = 1 << bits
    u = (t.numerator << bits) // t.denominator
    for _ in range(2):
        u = (u << bits) // (one + math.isqrt(one * one + u * u))
    u2 = u * u >> bits
    total = term = u
    k = 1
    while term:
        term = -(term * u2 >> bits)
        total += term // (2 * k + 1)
        k += 1
    return 4 * total


@functools.cache
def _pi(bits: int) -> int:
    """pi times 2^bits (Machin: pi = 16 atan(1/5) - 4 atan(1/239))."""
    work = bits + GUARD

    def atan_inverse(n: int) -> int:
        total = term = (1 << work) // n
        k, n2 = 1, n * n
        while term:
            term = -term // n2
            total += term // (2 * k + 1)
            k += 1
        return total

    return (16 * atan_inverse(5) - 4 * atan_inverse(239)) >> GUARD
