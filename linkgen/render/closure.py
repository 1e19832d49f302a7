"""A group's loop-closure equations (steplog.Closure) as the programs compute them: one row at a
time, each with its residual's terms and its Jacobian's nonzero entries (no language here).

Unknown k is coordinate k % 2 (x, y) of position k // 2 of ``Closure.unknowns``.  Every row
is in length units, so the resolver's tolerance applies to it as it does to an Add-link's
residual: a distance row is g = (dx^2 + dy^2 - l^2) / (2 l), about |b - a| - l near a
solution, with dg/db = (dx, dy) / l (l a literal, or the record of a length that changes with
the inputs); a frame row (x or y of point = origin + w (b - a)) is
g = c - o - (p (bx - ax) + q (by - ay)), linear, its Jacobian constant.  ``values`` and
``in_process`` compute them for the in-process evaluator.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from types import SimpleNamespace
from typing import Any

from ..steplog import Closure, Distance, Frame


@dataclass(frozen=True)
class Coord:
    """One coordinate a row reads: an unknown's (unknown >= 0) or a known position's."""

    var: str  # the POINT variable
    axis: str  # x | y
    unknown: int  # its index among the unknowns, -1 where the position is known before the group


@dataclass(frozen=True)
class Entry:
    """One nonzero Jacobian entry of a row: a frame row's factor; a distance row's dx or dy over
    l, with the factor's sign (+1 or -1)."""

    column: int
    factor: float
    term: str  # "" (frame) | dx | dy (distance)


@dataclass(frozen=True)
class Row:
    index: int
    kind: str  # distance | frame
    step: int  # the step whose constraint it is
    link: str
    coords: tuple[Coord, ...]  # distance: a.x, a.y, b.x, b.y; frame: c, o (the row's axis), a.x, a.y, b.x, b.y
    constants: tuple[float, ...]  # distance: l (in the sketch); frame: p, q
    entries: tuple[Entry, ...]
    variable: str = ""  # distance: the VARIABLE record l is read from, where it changes with the inputs


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
    entries = [Entry(c.unknown, sign, term)
               for cs, sign in ((b, 1.0), (a, -1.0)) for c, term in zip(cs, ("dx", "dy")) if c.unknown >= 0]
    return Row(i, "distance", d.step, d.link, (*a, *b), (d.length,), tuple(sorted(entries, key=lambda e: e.column)),
               d.variable)


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


def values(rows_: tuple[Row, ...], x: list[float], known: Callable[[str, int], float]) -> tuple[list[float],
                                                                                            list[list[float]]]:
    """The residuals and Jacobian of a group's rows at the unknowns x (``known(record, i)``: field i of
    a record the group reads: a position's x or y, a length's value), in the programs' order of operations."""
    n = len(x)
    g, jac = [0.0] * n, [[0.0] * n for _ in range(n)]
    for r in rows_:
        k = [x[c.unknown] if c.unknown >= 0 else known(c.var, c.axis == "y") for c in r.coords]
        if r.kind == "distance":
            ell = known(r.variable, 0) if r.variable else r.constants[0]
            d = {"dx": k[2] - k[0], "dy": k[3] - k[1]}
            g[r.index] = (d["dx"] * d["dx"] + d["dy"] * d["dy"] - ell * ell) / (2 * ell)
            for e in r.entries:
                jac[r.index][e.column] = (d[e.term] if e.factor > 0 else -d[e.term]) / ell
        else:
            g[r.index] = k[0] - k[1] - r.constants[0] * (k[4] - k[2]) - r.constants[1] * (k[5] - k[3])
            for e in r.entries:
                jac[r.index][e.column] = e.factor
    return g, jac


def in_process(c: Closure, records: dict[Any, Any], adopt: Callable[[list[list[float]]], None]) -> SimpleNamespace:
    """A group's closure as the Python runtime's resolve_closure takes it, on the evaluator's
    records (each position a tuple: x, y, then its rates); ``adopt(states)`` reads every block's
    state off the records once the solution is in them."""
    rows_ = rows(c)

    def place() -> list[float]:
        return [records[u][i] for u in c.unknowns for i in (0, 1)]

    def equations(x: list[float]) -> tuple[list[float], list[list[float]]]:
        return values(rows_, x, lambda name, i: float(records[name][i]))

    def adopt_solution(x: list[float], states: list[list[float]]) -> None:
        for i, u in enumerate(c.unknowns):
            records[u] = (x[2 * i], x[2 * i + 1], *records[u][2:])
        adopt(states)

    return SimpleNamespace(place=place, equations=equations, adopt=adopt_solution)
