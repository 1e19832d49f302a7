"""The instant centres of a mechanism classified from its topology alone (Nie et al. 2021).

- first: a revolute pair joins the two links; the centre is the pair.
- secondary: not first, and the Aronhold-Kennedy theorem places it from first centres alone:
  two other links k give two lines, each through the first centres (i, k) and (k, j).
- third A: the theorem places it with the help of other centres (first, secondary, centres of
  prismatic pairs and centres it placed before), or it lies on at least one line of two such
  centres (the paper's "on a known line"; its place then needs the velocities).  A prismatic
  pair's centre is at infinity, perpendicular to the slide: the theorem uses it as known, and
  the paper counts it as a third centre of type A (its Table 4), and so does linkgen.
- third B: on no such line.

The paper's tables: five-bar five first and five third A; single-loop six-bar six first, six third
A and three third B; the Stephenson six-bar seven first, two secondary and six third A.
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import combinations

from ..model import Mechanism

FIRST, SECONDARY, THIRD_A, THIRD_B = "first", "secondary", "third A", "third B"
CLASSES = (FIRST, SECONDARY, THIRD_A, THIRD_B)


@dataclass(frozen=True)
class Centre:
    """One centre: its links (in the file's order), class, the pair that joins the links (if
    any), whether the theorem places it, and the Kennedy lines it lies on: each the third link
    k of a line through the centres (i, k) and (k, j), the two that place it first."""

    links: tuple[str, str]
    kind: str
    pair: str
    placed: bool
    lines: tuple[str, ...]

    @property
    def name(self) -> str:
        return f"ic:{self.links[0]}:{self.links[1]}"


def _joins(m: Mechanism) -> tuple[dict[frozenset[str], str], dict[frozenset[str], str]]:
    """The revolute and the prismatic pair that joins each two links."""
    revolute: dict[frozenset[str], str] = {}
    prismatic: dict[frozenset[str], str] = {}
    for j in m.joints:
        if j.revolute:
            for a, b in combinations([lk.name for lk in m.links_of(j.name)], 2):
                revolute.setdefault(frozenset((a, b)), j.name)
        else:
            p = m.prismatic_of(j.name)
            prismatic.setdefault(frozenset((p.guide, p.slider)), j.name)
    return revolute, prismatic


def _lines(links: list[str], a: str, b: str, known: set[frozenset[str]]) -> list[str]:
    """The third links k whose centres (a, k) and (k, b) are both known."""
    return [k for k in links if k not in (a, b) and frozenset((a, k)) in known and frozenset((k, b)) in known]


def classify(m: Mechanism) -> tuple[Centre, ...]:
    """Every centre of the mechanism, in the order of its links' pairs (links in the file's order)."""
    links = [lk.name for lk in m.links]
    pairs = list(combinations(links, 2))
    revolute, prismatic = _joins(m)
    first = set(revolute)
    secondary = {frozenset(p) for p in pairs if frozenset(p) not in first and len(_lines(links, *p, first)) >= 2}
    known = first | set(prismatic) | secondary
    placed: dict[frozenset[str], tuple[str, ...]] = {}
    grown = True
    while grown:  # the theorem with every centre placed so far, until it places no more
        grown = False
        for a, b in pairs:
            key = frozenset((a, b))
            if key not in known and len(found := _lines(links, a, b, known)) >= 2:
                known.add(key)
                placed[key] = tuple(found[:2])
                grown = True
    out = []
    for a, b in pairs:
        key = frozenset((a, b))
        lines = placed.get(key) or tuple(_lines(links, a, b, known))
        if key in first:
            out.append(Centre((a, b), FIRST, revolute[key], True, ()))
        elif key in prismatic:
            out.append(Centre((a, b), THIRD_A, prismatic[key], True, ()))
        elif key in secondary:
            out.append(Centre((a, b), SECONDARY, "", True, tuple(_lines(links, a, b, first)[:2])))
        else:
            out.append(Centre((a, b), THIRD_A if lines else THIRD_B, "", key in placed, lines))
    return tuple(out)
