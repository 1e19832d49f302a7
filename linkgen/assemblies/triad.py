"""A resolver group's shape: the class-III triad whose closure reduces to one polynomial.

A triad is a ternary link T whose three pairs P1, P2, P3 are held by three legs, each a
binary link or a linear actuator from Pi to a pair Bi known before the group, or a block on
a slide fixed to the frame (Pi then stays on a line: ``slides``); the ternary's own pairs are
revolute.  It is read off the step log: the pairs the group's block writes, the links that
carry them, the pairs known before the group.  Any other group (one with another prismatic
pair, one that needs several Add-links at once) is ``NotReducible``.
All the triad's numbers are exact fractions: the sketch's coordinates rounded to the grid of
``grid`` (2^-64 of the length scale, far below a double's own spacing there, 2^-52 of it;
a coordinate of 1e-300 in a sketch of size 100 would otherwise carry a denominator of
a thousand digits into every coefficient of the polynomial).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

from ..errors import and_list
from ..steplog import ResolverGroup, StepLog

Exact = tuple[Fraction, Fraction]


class NotReducible(Exception):
    """A resolver group that linkgen does not reduce to one polynomial (its count would be a guess)."""


@dataclass(frozen=True)
class Leg:
    """A binary link (or the actuator ``column``) from the ternary's pair ``pair`` to the known pair ``base``."""

    carrier: str
    pair: str
    base: str
    length2: Fraction | None  # the squared sketch length; None for an actuator (its input's value)
    input: int = -1  # the actuator's input index
    line: tuple[Exact, Fraction] | None = None  # a block on a fixed slide (``base`` its prismatic pair):
    # ``pair`` stays on the line n . P = d, as (n, d) in the programs' coordinates


@dataclass(frozen=True)
class Triad:
    """Resolver group ``group``: the ternary ``ternary`` (its pairs ``pairs``, their sketch offsets
    ``local`` from the first, exact) held by ``legs`` (in the order of ``pairs``)."""

    group: int
    ternary: str
    pairs: tuple[str, str, str]
    local: tuple[Exact, Exact, Exact]
    legs: tuple[Leg, Leg, Leg]

    def describe(self) -> str:
        held = ", ".join(f"{leg.carrier} on the slide {leg.base}" if leg.line else f"{leg.carrier} at {leg.base}"
                         for leg in self.legs)
        return f"the ternary link {self.ternary} held by {held}"


GRID_BITS = 64  # the grid is 2^-GRID_BITS of the length scale (rounded up to a power of 2)


def grid(scale: float) -> Fraction:
    """The spacing the triad's data are rounded to: a power of 2 at most 2^-GRID_BITS of the length scale."""
    return Fraction(2) ** (math.frexp(scale)[1] - GRID_BITS)


def snap(x: float, unit: Fraction) -> Fraction:
    """x rounded to the nearest multiple of ``unit`` (exactly)."""
    return round(Fraction(x) / unit) * unit


def group_pairs(log: StepLog, g: ResolverGroup) -> list[str]:
    """The pairs whose positions the group's block writes, in the order written."""
    kinds = {v.name: v for v in log.variables}
    return [kinds[w].entity for w in g.writes if kinds[w].role == "pair"]


def known_before(log: StepLog, g: ResolverGroup) -> set[str]:
    """The pairs known before the group's block: fixed, or written by an earlier step of the procedure."""
    first = min(g.steps)
    made = {o for s in log.steps if s.number < first and not s.variant for o in s.outputs}
    return {v.entity for v in log.variables if v.role == "pair" and (v.constant or v.name in made)}


def triad_of(log: StepLog, g: ResolverGroup) -> Triad:
    """The group as a triad, or NotReducible with the reason in words."""
    if len(g.add_links) != 1:
        raise NotReducible(f"resolver group {g.number} needs {len(g.add_links)} Add-links at once (a group of "
                           "class IV or higher); linkgen reduces only class-III triads to one polynomial")
    pairs = {p.name: p for p in log.pairs}
    inside = group_pairs(log, g)
    known = known_before(log, g)
    carriers = _carriers(log)
    slides = {p: _slide(log, p, g.number) for p in inside if pairs[p].kind == "prismatic"}
    blocks = {block: pair for pair, (block, _) in slides.items()}
    inside = [p for p in inside if p not in slides]
    ternaries = [lk for lk in log.links if lk.name not in blocks and sum(p in inside for p in lk.pairs) >= 2]
    if len(ternaries) != 1:
        raise NotReducible(f"resolver group {g.number} is not a class-III triad (one ternary link held by three "
                           f"binary links): {and_list(lk.name for lk in ternaries)} each join two or more of its "
                           "pairs (a group of class IV or higher); linkgen reduces only triads to one polynomial")
    t = ternaries[0]
    legs = [leg for p in t.pairs if p in inside
            for leg in _legs(log, p, t.name, known, set(inside), carriers, {b: (s, slides[s][1]) for b, s in
                                                                             blocks.items()})]
    placed = {leg.pair for leg in legs}
    if len(legs) != 3 or len(placed) != 3 or any(p not in t.pairs for p in inside):
        raise NotReducible(f"resolver group {g.number} is not a class-III triad (one ternary link held by three "
                           f"binary links): {len(legs)} links hold {t.name} from pairs known before the group")
    held = tuple(leg.pair for leg in legs)
    unit = grid(log.length_scale)
    x0, y0 = snap(pairs[held[0]].x, unit), snap(pairs[held[0]].y, unit)
    local = tuple((snap(pairs[p].x, unit) - x0, snap(pairs[p].y, unit) - y0) for p in held)
    return Triad(g.number, t.name, (held[0], held[1], held[2]), (local[0], local[1], local[2]),
                 (legs[0], legs[1], legs[2]))


def _slide(log: StepLog, pair: str, group: int) -> tuple[str, float]:
    """(the block, the slide's axis) of a prismatic pair of the group that holds a block on a fixed slide, else
    NotReducible."""
    p = next(q for q in log.pairs if q.name == pair)
    links = {lk.name: lk for lk in log.links}
    block = p.slider if links[p.guide].fixed else p.guide if links[p.slider].fixed else ""
    if not block or len(links[block].pairs) != 2:
        raise NotReducible(f"resolver group {group} has the prismatic pair {pair}, not a block on a slide fixed to "
                           "the frame; linkgen reduces only triads whose legs are binary links or such blocks to one "
                           "polynomial")
    return block, p.axis


def _carriers(log: StepLog) -> dict[str, list[tuple[str, tuple[str, ...]]]]:
    """Every pair's links and actuators, each with the other pairs it carries."""
    out: dict[str, list[tuple[str, tuple[str, ...]]]] = {}
    for lk in log.links:
        for p in lk.pairs:
            out.setdefault(p, []).append((lk.name, tuple(q for q in lk.pairs if q != p)))
    for i in log.inputs:
        if i.kind == "distance":
            a, b = i.between
            out.setdefault(a, []).append((i.column, (b,)))
            out.setdefault(b, []).append((i.column, (a,)))
    return out


def _legs(log: StepLog, pair: str, ternary: str, known: set[str], inside: set[str],
          carriers: dict[str, list[tuple[str, tuple[str, ...]]]], blocks: dict[str, tuple[str, float]]) -> list[Leg]:
    """The legs that hold the ternary's pair: carriers with exactly one known pair and no other of the group's,
    and blocks on a fixed slide (the pair moves on the line along the slide's axis through its sketch position)."""
    pairs = {p.name: p for p in log.pairs}
    actuators = {i.column: i.index for i in log.inputs if i.kind == "distance"}
    unit = grid(log.length_scale)
    out = []
    for name, others in carriers.get(pair, ()):
        if name == ternary:
            continue
        if name in blocks:
            slide, axis = blocks[name]
            n = (Fraction(-math.sin(axis)), Fraction(math.cos(axis)))
            at = (snap(pairs[pair].x - log.origin[0], unit), snap(pairs[pair].y - log.origin[1], unit))
            out.append(Leg(name, pair, slide, None, line=(n, n[0] * at[0] + n[1] * at[1])))
            continue
        bases = [q for q in others if q in known]
        if any(q in inside for q in others) or len(bases) > 1:
            raise NotReducible(f"{name} joins {pair} to more than one pair of the group or known before it: "
                               "not a class-III triad")
        if not bases:
            continue  # a link found after the group
        b = bases[0]
        if pairs[b].kind == "prismatic":
            raise NotReducible(f"{name} holds {pair} from the prismatic pair {b}; linkgen reduces only groups of "
                               "revolute pairs to one polynomial")
        if name in actuators:
            out.append(Leg(name, pair, b, None, actuators[name]))
            continue
        dx = snap(pairs[b].x, unit) - snap(pairs[pair].x, unit)
        dy = snap(pairs[b].y, unit) - snap(pairs[pair].y, unit)
        out.append(Leg(name, pair, b, dx * dx + dy * dy))
    return out
