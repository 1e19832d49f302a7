"""A group's loop-closure equations (steplog.Closure) as the programs compute them (no language here).

Newton's unknowns are the positions the group places by its chains (x and y of each: unknown k is
coordinate k % 2 of ``Plan.unknowns[k // 2]``).  A point fixed in a link's frame is no unknown: it
follows from the others, c = o + w (b - a) with w complex (``Plan.derived``, nested frames
substituted), and its two frame rows go with it, so the system is smaller by two a point and
square still.  What is left are the distance rows, each in length units so that the resolver's
tolerance applies as it does to an Add-link's residual: g = (dx^2 + dy^2 - l^2) / (2 l), about
|b - a| - l near a solution (l a literal, or the record of a length that changes with the
inputs), with dg/dq = (fx dx + fy dy) / l for each unknown coordinate q the ends depend on.
``values`` and ``in_process`` compute them for the in-process evaluator, in the programs' order of
operations.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from types import SimpleNamespace
from typing import Any

from ..closurelog import Closure, Frame


@dataclass(frozen=True)
class End:
    """A position a row or a derived point reads: an unknown, a derived point or a known record."""

    var: str  # the POINT variable
    unknown: int = -1  # its index among the plan's unknowns (x is unknown 2i)
    derived: int = -1  # its index among the plan's derived points


@dataclass(frozen=True)
class Term:
    """w times a position (w complex: x gets re X - im Y, y gets im X + re Y)."""

    end: End
    w: tuple[float, float]


@dataclass(frozen=True)
class Derived:
    """A point fixed in its link's frame, the sum of its terms (unknowns and known positions)."""

    index: int
    var: str
    terms: tuple[Term, ...]


@dataclass(frozen=True)
class Entry:
    """One nonzero Jacobian entry of a distance row: (fx dx + fy dy) / l."""

    column: int
    fx: float
    fy: float


@dataclass(frozen=True)
class Row:
    """|b - a| = l: g = (dx^2 + dy^2 - l^2) / (2 l) with (dx, dy) = b - a."""

    index: int
    step: int  # the step whose constraint it is
    link: str
    ends: tuple[End, End]  # a, b
    length: float  # l in the sketch
    variable: str  # the VARIABLE record l is read from where it changes with the inputs, else ""
    entries: tuple[Entry, ...]


@dataclass(frozen=True)
class Plan:
    unknowns: tuple[str, ...]
    derived: tuple[Derived, ...]
    rows: tuple[Row, ...]


def plan(c: Closure) -> Plan:
    """The closure's Newton unknowns, its derived points and its rows."""
    framed = {f.point: f for f in c.frames}
    unknowns = tuple(u for u in c.unknowns if u not in framed)
    index = {u: i for i, u in enumerate(unknowns)}
    derived = {f.point: k for k, f in enumerate(f for f in c.frames)}

    def end(var: str) -> End:
        return End(var, index.get(var, -1), derived.get(var, -1))

    points = tuple(Derived(derived[f.point], f.point, tuple(Term(end(v), w) for v, w in _expand(f, framed).items()))
                   for f in c.frames)
    rows = []
    for i, d in enumerate(c.distances):
        a, b = end(d.points[0]), end(d.points[1])
        rows.append(Row(i, d.step, d.link, (a, b), d.length, d.variable, _entries(a, b, points)))
    return Plan(unknowns, points, tuple(rows))


def _expand(f: Frame, framed: dict[str, Frame]) -> dict[str, tuple[float, float]]:
    """A frame point as w-weighted positions none of which is a frame point: c = o + w b - w a."""
    out: dict[str, complex] = {}
    w = complex(*f.w)
    for var, weight in ((f.origin, 1.0 + 0j), (f.base[1], w), (f.base[0], -w)):
        inner = {var: (1.0, 0.0)} if var not in framed else _expand(framed[var], framed)
        for v, x in inner.items():
            out[v] = out.get(v, 0j) + weight * complex(*x)
    return {v: (x.real, x.imag) for v, x in out.items() if x != 0}


def _entries(a: End, b: End, points: tuple[Derived, ...]) -> tuple[Entry, ...]:
    """The Jacobian of |b - a|'s row: d(dx + i dy) / dq for each unknown coordinate q."""
    columns: dict[int, tuple[float, float]] = {}

    def add(column: int, fx: float, fy: float) -> None:
        x, y = columns.get(column, (0.0, 0.0))
        columns[column] = (x + fx, y + fy)

    for e, sign in ((b, 1.0), (a, -1.0)):
        terms = points[e.derived].terms if e.derived >= 0 else (Term(e, (1.0, 0.0)),)
        for t in terms:
            if t.end.unknown >= 0:
                re, im = t.w
                add(2 * t.end.unknown, sign * re, sign * im)
                add(2 * t.end.unknown + 1, -sign * im, sign * re)
    return tuple(Entry(k, fx, fy) for k, (fx, fy) in sorted(columns.items()) if (fx, fy) != (0.0, 0.0))


def values(p: Plan, x: list[float], known: Callable[[str, int], float]) -> tuple[list[float], list[list[float]]]:
    """The residuals and Jacobian of a plan at the unknowns x (``known(record, i)``: field i of a
    record the group reads: a position's x or y, a length's value), in the programs' order of operations."""
    n = len(x)
    g, jac = [0.0] * n, [[0.0] * n for _ in range(n)]
    at = derived(p, x, known)

    def xy(e: End) -> tuple[float, float]:
        if e.unknown >= 0:
            return x[2 * e.unknown], x[2 * e.unknown + 1]
        return at[e.derived] if e.derived >= 0 else (known(e.var, 0), known(e.var, 1))

    for r in p.rows:
        (ax, ay), (bx, by) = xy(r.ends[0]), xy(r.ends[1])
        dx, dy = bx - ax, by - ay
        ell = known(r.variable, 0) if r.variable else r.length
        g[r.index] = (dx * dx + dy * dy - ell * ell) / (2 * ell)
        for e in r.entries:
            jac[r.index][e.column] = entry(e, dx, dy) / ell
    return g, jac


def entry(e: Entry, dx: float, dy: float) -> float:
    """fx dx + fy dy as the programs write it: a unit factor as a sign, a zero one left out."""
    if e.fy == 0.0 and abs(e.fx) == 1.0:
        return dx if e.fx > 0 else -dx
    if e.fx == 0.0 and abs(e.fy) == 1.0:
        return dy if e.fy > 0 else -dy
    return e.fx * dx + e.fy * dy


def derived(p: Plan, x: list[float], known: Callable[[str, int], float]) -> list[tuple[float, float]]:
    """Every derived point's x and y at the unknowns x, its terms summed in order."""
    out = []
    for d in p.derived:
        px = py = 0.0
        for k, t in enumerate(d.terms):
            u = t.end.unknown
            tx, ty = (x[2 * u], x[2 * u + 1]) if u >= 0 else (known(t.end.var, 0), known(t.end.var, 1))
            re, im = t.w
            px, py = (re * tx - im * ty, im * tx + re * ty) if k == 0 else (px + (re * tx - im * ty),
                                                                             py + (im * tx + re * ty))
        out.append((px, py))
    return out


def in_process(c: Closure, records: dict[Any, Any], adopt: Callable[[list[list[float]]], None]) -> SimpleNamespace:
    """A group's closure as the Python runtime's resolve_closure takes it, on the evaluator's
    records (each position a tuple: x, y, then its rates); ``adopt(states)`` reads every block's
    state off the records once the solution is in them."""
    p = plan(c)

    def known(name: str, i: int) -> float:
        return float(records[name][i])

    def place() -> list[float]:
        return [records[u][i] for u in p.unknowns for i in (0, 1)]

    def equations(x: list[float]) -> tuple[list[float], list[list[float]]]:
        return values(p, x, known)

    def adopt_solution(x: list[float], states: list[list[float]]) -> None:
        points = [(d.var, xy) for d, xy in zip(p.derived, derived(p, x, known))]
        for var, xy in [(u, (x[2 * i], x[2 * i + 1])) for i, u in enumerate(p.unknowns)] + points:
            records[var] = (*xy, *records[var][2:])
        adopt(states)

    return SimpleNamespace(place=place, equations=equations, adopt=adopt_solution)
