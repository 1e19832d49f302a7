"""A class-IV resolver group read as two bodies on four-bars, tied by two couplers.

The group is two rigid links L and R (each with three or more pairs, all of the group), every
other link of it binary: a leg joins a body's pair to a pair known before the group, a coupler
joins a pair of L to a pair of R.  Each body has two legs (it rides on a four-bar of the known
pairs) and two couplers tie the bodies: the six distance equations of quaternary_fold's group,
which needs two Add-links at once.  A body's second leg may instead be a block on a slide fixed to
the frame (quaternary_slide): its pair then stays on the line along the slide's axis through the
pair's sketch position.  Any other class-IV shape is ``NotReducible``.  As for the
triad (``triad``), every number is an exact fraction on the grid of ``triad.grid``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

from ..errors import and_list
from ..steplog import ResolverGroup, StepLog
from .triad import Exact, NotReducible, _slide, grid, group_pairs, known_before, snap


@dataclass(frozen=True)
class Body:
    """A rigid link of the group: its first leg (``base`` to ``pair``) turns by phi, the link by theta
    (both from the sketch); its second leg holds ``held`` at ``length2`` from ``other_base``."""

    link: str
    base: str
    pair: str
    leg: Exact  # the first leg's sketch vector, base to pair
    other_base: str
    held: Exact  # the second leg's pair, offset from ``pair`` in the sketch
    length2: Fraction  # the second leg's squared length
    legs: tuple[str, str]  # the two legs' link names
    pairs: tuple[str, ...]  # the body's pairs
    local: tuple[Exact, ...]  # their sketch offsets from ``pair``
    line: tuple[Exact, Exact] | None = None  # a second leg that is a block on a fixed slide (``other_base`` its
    # prismatic pair): (n, a), ``held``'s pair stays on n . P = n . a (programs' coordinates; ``length2`` 0)


@dataclass(frozen=True)
class Coupler:
    """A binary link from ``left`` (a pair of body 0) to ``right`` (of body 1)."""

    link: str
    left: Exact  # offsets from each body's first-leg pair
    right: Exact
    length2: Fraction


@dataclass(frozen=True)
class TwoBodies:
    """Resolver group ``group`` as two bodies on four-bars tied by two couplers."""

    group: int
    bodies: tuple[Body, Body]
    couplers: tuple[Coupler, Coupler]

    @property
    def pairs(self) -> tuple[str, ...]:
        return self.bodies[0].pairs + self.bodies[1].pairs

    def describe(self) -> str:
        left, right = self.bodies
        return (f"the links {left.link} (on {left.legs[0]}, {left.legs[1]}) and {right.link} (on {right.legs[0]}, "
                f"{right.legs[1]}) tied by {self.couplers[0].link} and {self.couplers[1].link}")


def two_bodies_of(log: StepLog, g: ResolverGroup) -> TwoBodies:
    """The group as two bodies on four-bars tied by two couplers, or NotReducible with the reason."""
    pairs = {p.name: p for p in log.pairs}
    inside = set(group_pairs(log, g))
    known = known_before(log, g)
    slides = {p: _slide(log, p, g.number) for p in inside if pairs[p].kind == "prismatic"}
    blocks = {block: (pair, axis) for pair, (block, axis) in slides.items()}
    inside -= set(slides)
    bodies = [lk for lk in log.links if len(lk.pairs) >= 3 and set(lk.pairs) <= inside]
    binary = [lk for lk in log.links if len(lk.pairs) == 2 and set(lk.pairs) & inside and lk.name not in blocks]
    shape = (f"resolver group {g.number} is not two links on four-bars tied by two couplers (the class-IV shape "
             "linkgen counts)")
    actuated = any(i.kind == "distance" and set(i.between) & inside for i in log.inputs)
    if len(bodies) != 2 or actuated or any(p not in {q for b in bodies for q in b.pairs} for p in inside):
        raise NotReducible(f"{shape}: its links with three or more pairs are {and_list(b.name for b in bodies)}")
    owner = {p: k for k, b in enumerate(bodies) for p in b.pairs}
    legs: list[list[tuple[str, str, str]]] = [[], []]
    for name, (slide, _) in blocks.items():
        (p,) = (q for q in next(lk for lk in log.links if lk.name == name).pairs if q != slide)
        legs[owner[p]].append((name, p, slide))
    couplers: list[tuple[str, str, str]] = []
    for lk in binary:
        a, b = lk.pairs
        if a in inside and b in inside and owner[a] != owner[b]:
            couplers.append((lk.name, a, b) if owner[a] == 0 else (lk.name, b, a))
        elif (a in inside) != (b in inside) and (a in known or b in known):
            p, base = (a, b) if a in inside else (b, a)
            if pairs[base].kind == "prismatic":
                raise NotReducible(f"{lk.name} holds {p} from the prismatic pair {base}; linkgen counts class-IV "
                                   "groups of revolute pairs only")
            legs[owner[p]].append((lk.name, p, base))
        else:
            raise NotReducible(f"{shape}: {lk.name} joins {a} and {b}")
    if [len(x) for x in legs] != [2, 2] or len(couplers) != 2:
        raise NotReducible(f"{shape}: {len(legs[0])} and {len(legs[1])} legs, {len(couplers)} couplers")
    unit = grid(log.length_scale)

    def at(name: str) -> Exact:
        return snap(pairs[name].x, unit), snap(pairs[name].y, unit)

    def minus(a: Exact, b: Exact) -> Exact:
        return a[0] - b[0], a[1] - b[1]

    made = []
    for k, lk in enumerate(bodies):
        (leg0, p0, b0), (leg1, p1, b1) = sorted(legs[k], key=lambda leg: leg[0] in blocks)  # a block second
        if leg0 in blocks:
            raise NotReducible(f"{shape}: both legs of {lk.name} are blocks on slides")
        first = at(p0)
        held = minus(at(p1), first)
        line = None
        if leg1 in blocks:
            axis = blocks[leg1][1]
            line = ((Fraction(-math.sin(axis)), Fraction(math.cos(axis))),
                    (snap(pairs[p1].x - log.origin[0], unit), snap(pairs[p1].y - log.origin[1], unit)))
        d = minus(at(p1), at(b1)) if line is None else (Fraction(0), Fraction(0))
        made.append(Body(lk.name, b0, p0, minus(first, at(b0)), b1, held, d[0] ** 2 + d[1] ** 2, (leg0, leg1),
                         tuple(lk.pairs), tuple(minus(at(p), first) for p in lk.pairs), line))
    ties = []
    for name, a, b in couplers:
        d = minus(at(a), at(b))
        ties.append(Coupler(name, minus(at(a), at(made[0].pair)), minus(at(b), at(made[1].pair)),
                            d[0] ** 2 + d[1] ** 2))
    return TwoBodies(g.number, (made[0], made[1]), (ties[0], ties[1]))
