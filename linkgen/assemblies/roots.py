"""A triad's assemblies at one position of its bases (``polynomial.solve``'s answer), kept across processes.

``polynomial`` needs python-flint and mpmath, whose imports take 30-45 ms, and its solve a few ms
more per position; a build's census solves the same triads at the same sketch every time the file is
built.  ``solve`` keeps each answer in the package's text store (linkgen.textcache: per user, one
store per fingerprint of the package's modules), keyed on the exact data (the rationals the
bases, the ternary's offsets and the legs' squared lengths are snapped to) and the length scale,
as JSON (a float's repr reads back to the same double).  A solve that raises (not reducible, not
certified) is not kept: it raises again in every build.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from fractions import Fraction

from ..textcache import kept

Exact = tuple[Fraction, Fraction]
Point = tuple[float, float]


@dataclass(frozen=True)
class Root:
    """One real root: the ternary's turn from the sketch and its three pairs' positions."""

    theta: float  # radians, in (-pi, pi]
    multiplicity: int  # >1: two or more assemblies meet (a singular position)
    positions: tuple[Point, Point, Point]
    error: float  # the worst leg length error after polishing, over the length scale


@dataclass(frozen=True)
class Solution:
    """A triad at one position of its bases: its polynomial and every assembly it has there."""

    degree: int  # of the characteristic polynomial in t, the factors (1 + t^2) divided out
    real_roots: int  # its distinct real roots (Sturm's count)
    at_pi: bool  # theta = pi is a root too
    roots: tuple[Root, ...]  # in the order of theta
    coefficients: tuple[float, ...]  # the polynomial's, highest first, scaled to a largest of 1 (to read)


def solve(bases: list[Exact], local: list[Exact], lengths2: list[Fraction], scale: float) -> Solution:
    """``polynomial.solve(bases, local, lengths2, scale)``, made once per user and package."""

    def make() -> str:
        from .polynomial import solve as exact_solve  # python-flint and mpmath: imported only when not kept

        return _text(exact_solve(bases, local, lengths2, scale))

    return _read(kept("triad solution", (bases, local, lengths2, scale), make))


def _text(sol: Solution) -> str:
    return json.dumps([sol.degree, sol.real_roots, sol.at_pi,
                       [[r.theta, r.multiplicity, [list(p) for p in r.positions], r.error] for r in sol.roots],
                       list(sol.coefficients)])


def _read(text: str) -> Solution:
    degree, real_roots, at_pi, roots, coefficients = json.loads(text)
    return Solution(degree, real_roots, at_pi, tuple(
        Root(theta, multiplicity, (tuple(p[0]), tuple(p[1]), tuple(p[2])), error)
        for theta, multiplicity, p, error in roots), tuple(coefficients))
