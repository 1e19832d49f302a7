"""A class-IV resolver group read as two links on their own pivots, tied by two links or slots.

The group is two rigid links (bodies), each turning about one revolute pair known before the group
(its pivot), and two ties between them: a binary link from a pair of one body to a pair of the
other (a distance), or a block with a revolute pair X on one body and a prismatic pair with the
other body (X then stays on the line through its sketch position along the slide's axis, fixed in
that body: a slot).  tests/regressions/class4_slot.yaml is one: the ternaries left (on O1) and
right (on the crank tip O2), tied by upper and by a block on C in a slot of right; no two-link
chain and no single Add-link makes it computable alone.  Any other shape is ``NotReducible``.  As
for the triad (``triad``), every number is an exact fraction on the grid of ``triad.grid``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

from ..errors import and_list
from ..steplog import ResolverGroup, StepLog
from .triad import Exact, NotReducible, grid, group_pairs, known_before, snap

ZERO: Exact = (Fraction(0), Fraction(0))


@dataclass(frozen=True)
class Tie:
    """A tie between the bodies: the pair at ``a`` of body ``body`` (offset from its pivot) and the point
    ``b`` of the other body (offset from that one's pivot) are ``length2`` apart (a link), or the first
    keeps to the line through the second with the sketch normal ``normal`` fixed in the other body (a slot)."""

    link: str
    body: int
    a: Exact
    b: Exact
    length2: Fraction
    normal: Exact | None = None  # a slot: the slide's sketch normal (-sin axis, cos axis), as fractions


@dataclass(frozen=True)
class Spot:
    """Where a pair of the group is: ``pivot[body] + R(theta_body) a + R(theta_turn) b``."""

    pair: str
    body: int
    a: Exact
    turn: int
    b: Exact


@dataclass(frozen=True)
class Pivoted:
    """Resolver group ``group`` as two bodies on their own pivots tied by two ties."""

    group: int
    links: tuple[str, str]
    pivots: tuple[str, str]
    ties: tuple[Tie, Tie]
    spots: tuple[Spot, ...]
    slots: tuple[tuple[str, int, float], ...]  # each slot's prismatic pair, the body it turns with, its sketch axis

    def axes(self, angles: tuple[float, ...]) -> dict[str, float]:
        """Each slot's axis (radians, the programs' angle of its slide) at the bodies' turns ``angles``."""
        return {pair: axis + angles[k] for pair, k, axis in self.slots}

    @property
    def pairs(self) -> tuple[str, ...]:
        return tuple(s.pair for s in self.spots)

    def describe(self) -> str:
        ties = " and ".join(f"the slot of {t.link}" if t.normal else t.link for t in self.ties)
        return (f"the links {self.links[0]} (on {self.pivots[0]}) and {self.links[1]} (on {self.pivots[1]}) "
                f"tied by {ties}")


def pivoted_of(log: StepLog, g: ResolverGroup) -> Pivoted:
    """The group as two bodies on their own pivots tied by two ties, or NotReducible with the reason."""
    pairs = {p.name: p for p in log.pairs}
    links = {lk.name: lk for lk in log.links}
    inside = set(group_pairs(log, g))
    known = known_before(log, g)
    shape = f"resolver group {g.number} is not two links on their own pivots tied by two links or slots"
    bodies = [lk for lk in log.links if not lk.fixed and len(lk.pairs) >= 3 and set(lk.pairs) <= inside | known
              and len(set(lk.pairs) & known) == 1 and len(set(lk.pairs) & inside) >= 2]
    if len(bodies) != 2 or any(i.kind == "distance" and set(i.between) & inside for i in log.inputs):
        raise NotReducible(f"{shape}: its links on one known pair are {and_list(b.name for b in bodies) or 'none'}")
    owner = {p: k for k, b in enumerate(bodies) for p in b.pairs if p in inside}
    pivots = [next(p for p in b.pairs if p in known) for b in bodies]
    if any(pairs[p].kind != "revolute" for p in pivots):
        raise NotReducible(f"{shape}: a body turns about a prismatic pair")
    unit = grid(log.length_scale)

    def at(name: str) -> Exact:
        return snap(pairs[name].x, unit), snap(pairs[name].y, unit)

    def minus(a: Exact, b: Exact) -> Exact:
        return a[0] - b[0], a[1] - b[1]

    def local(name: str, k: int) -> Exact:
        return minus(at(name), at(pivots[k]))

    ties: list[Tie] = []
    slots: list[tuple[str, int, float]] = []
    spots = [Spot(p, k, local(p, k), k, ZERO) for k, b in enumerate(bodies) for p in b.pairs if p in inside
             and not (pairs[p].kind == "prismatic" and len(links[pairs[p].slider].pairs) == 2)]
    used = set(owner)
    for lk in log.links:
        if lk in bodies or not set(lk.pairs) & inside:
            continue
        if len(lk.pairs) != 2 or not set(lk.pairs) <= inside:
            raise NotReducible(f"{shape}: {lk.name} joins {and_list(lk.pairs)}")
        x, y = lk.pairs
        kinds = (pairs[x].kind, pairs[y].kind)
        if kinds == ("revolute", "revolute") and x in owner and y in owner and owner[x] != owner[y]:
            d = minus(at(x), at(y))
            x, y = (x, y) if owner[x] == 0 else (y, x)
            ties.append(Tie(lk.name, 0, local(x, 0), local(y, 1), d[0] ** 2 + d[1] ** 2))
            continue
        if "prismatic" not in kinds or "revolute" not in kinds:
            raise NotReducible(f"{shape}: {lk.name} joins {x} and {y}")
        x, s = (x, y) if kinds[0] == "revolute" else (y, x)
        other = pairs[s].guide if pairs[s].slider == lk.name else pairs[s].slider
        k = next((j for j, b in enumerate(bodies) if b.name == other), -1)
        if x not in owner or k < 0 or k == owner[x]:
            raise NotReducible(f"{shape}: the block {lk.name} does not slide in the other body's slot")
        j = owner[x]
        axis = pairs[s].axis
        ties.append(Tie(lk.name, j, local(x, j), local(x, k), Fraction(0),
                        (Fraction(-math.sin(axis)), Fraction(math.cos(axis)))))
        if pairs[s].slider == lk.name:  # the block carries the prismatic pair: its offset from X turns with k
            spots.append(Spot(s, j, local(x, j), k, minus(at(s), at(x))))
        slots.append((s, k, axis))
        used.add(s)
    if len(ties) != 2 or inside - used:
        raise NotReducible(f"{shape}: {len(ties)} ties, pairs left {and_list(sorted(inside - used)) or 'none'}")
    return Pivoted(g.number, (bodies[0].name, bodies[1].name), (pivots[0], pivots[1]), (ties[0], ties[1]),
                   tuple(spots), tuple(slots))
