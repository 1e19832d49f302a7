"""The real roots of a polynomial with 50-digit coefficients, isolated by arb (python-flint), for the
class-IV back-substitution (``resultant``): the coefficients of S_1 in t_R at a root t_L, degree 12.

The coefficients (mpmath mpf, exactly) are put into complex balls at ISOLATION_BITS and arb's
``acb_poly.roots`` isolates every complex root; a root whose imaginary part is below 1e-20 of its size
is taken as real (its real part's midpoint).  Where arb cannot isolate them (a multiple root, or the
precision is too low) the answer is None and the caller uses mpmath's ``polyroots`` (ten times
slower: 0.27 s a call against 1 to 30 ms).
"""

from __future__ import annotations

from typing import Any

import flint

ISOLATION_BITS = 200  # about 60 digits, above the coefficients' 50
REAL = 1e-20  # an imaginary part below this (relative) is a real root's


def real_roots(coeffs: list[Any], mp: Any) -> list[Any] | None:
    """The real roots (mpf of the context ``mp``) of the polynomial with coefficients ``coeffs`` (mpf,
    highest first), or None where arb cannot isolate its roots."""
    if not coeffs or coeffs[0] == 0:
        raise ValueError("a leading coefficient of zero")
    old, flint.ctx.prec = flint.ctx.prec, ISOLATION_BITS
    try:
        poly = flint.acb_poly([flint.acb(flint.arb(_pair(mp.mpf(c)._mpf_))) for c in reversed(coeffs)])
        found = poly.roots(tol=flint.arb(2) ** -(ISOLATION_BITS - 40))
    except ValueError:
        return None
    finally:
        flint.ctx.prec = old
    out = []
    for z in found:
        re, im = (mp.mpf(tuple(int(v) for v in part.mid().man_exp())) for part in (z.real, z.imag))
        if abs(im) <= REAL * (1 + abs(re)):
            out.append(re)
    return out


def _pair(raw: Any) -> tuple[int, int]:
    """An mpf's (signed mantissa, exponent), exactly, from its raw (sign, mantissa, exponent, bits)."""
    sign, man, exp, _ = raw
    return (-int(man) if sign else int(man)), int(exp)
