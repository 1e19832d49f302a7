"""A group's loop-closure equations (steplog.Closure) as the programs compute them: one row at a
time, each with its residual's terms and its Jacobian's nonzero entries (no language here).

Unknown k is coordinate k % 2 (x, y) of position k // 2 of ``Closure.unknowns``.  Every row
is in length units, so the resolver's tolerance applies to it as it does to an Add-link's
residual: a distance row is g = (dx^2 + dy^2 - l^2) / (2 l), about |b - a| - l near a
solution, with dg/db = (dx, dy) / l; a frame row (x or y of point = origin + w (b - a)) is
g = c - o - (p (bx - ax) + q (by - ay)), linear, its Jacobian constant.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..steplog import Closure, Distance, Frame


@dataclass(frozen=True)
class Coord:
    """One coordinate a row reads: an unknown's (unknown >= 0) or a known position's."""

    var: str  # the POINT variable
    axis: str  # x | y
    unknown: int  # its index among the unknowns, -1 where the position is known before the group


@dataclass(frozen=True)
class Entry:
    """One nonzero Jacobian entry of a row: factor, times the row's dx or dy where term says so."""

    column: int
    factor: float
    term: str  # "" | dx | dy


@dataclass(frozen=True)
class Row:
    index: int
    kind: str  # distance | frame
    step: int  # the step whose constraint it is
    link: str
    coords: tuple[Coord, ...]  # distance: a.x, a.y, b.x, b.y; frame: c, o (the row's axis), a.x, a.y, b.x, b.y
    constants: tuple[float, ...]  # distance: l^2, 1 / (2 l); frame: p, q
    entries: tuple[Entry, ...]


def rows(c: Closure) -> tuple[Row, ...]:
    """The rows of a group's closure equations: its distances, then x and y of each frame."""
    index = {name: i for i, name in enumerate(c.unknowns)}
    out = [_distance(k, d, index) for k, d in enumerate(c.distances)]
    for f in c.frames:
        for axis in ("x", "y"):
            out.append(_frame(len(out), f, axis, index))
    return tuple(out)


def _coords(var: str, index: dict[str, int]) -> tuple[Coord, Coord]:
    k = index.get(var, -1)
    return Coord(var, "x", 2 * k if k >= 0 else -1), Coord(var, "y", 2 * k + 1 if k >= 0 else -1)


def _distance(i: int, d: Distance, index: dict[str, int]) -> Row:
    a, b = (_coords(p, index) for p in d.points)
    inverse = 1.0 / d.length
    entries = [Entry(c.unknown, sign * inverse, term)
               for cs, sign in ((b, 1.0), (a, -1.0)) for c, term in zip(cs, ("dx", "dy")) if c.unknown >= 0]
    return Row(i, "distance", d.step, d.link, (*a, *b), (d.length * d.length, 0.5 * inverse),
               tuple(sorted(entries, key=lambda e: e.column)))


def _frame(i: int, f: Frame, axis: str, index: dict[str, int]) -> Row:
    re, im = f.w
    p, q = (re, -im) if axis == "x" else (im, re)
    c, o = (_coords(n, index)[axis == "y"] for n in (f.point, f.origin))
    a, b = (_coords(n, index) for n in f.base)
    factors: dict[int, float] = {}
    for coord, factor in ((c, 1.0), (o, -1.0), (a[0], p), (a[1], q), (b[0], -p), (b[1], -q)):
        if coord.unknown >= 0:
            factors[coord.unknown] = factors.get(coord.unknown, 0.0) + factor
    entries = tuple(Entry(k, x, "") for k, x in sorted(factors.items()) if x != 0.0)
    return Row(i, "frame", f.step, f.link, (c, o, *a, *b), (p, q), entries)
