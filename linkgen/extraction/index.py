"""What the Solver looks up by name, and which pairs it has yet to try.

``Index`` is built once per mechanism and shared by every copy of the Solver's state: the
names a link knows its pairs and points by, the links that know each name, the prismatic
pairs each link guides.  ``Frontier`` holds the pairs whose chance of being computed changed
since the Solver last tried them, smallest declaration index first, so that the Solver
still computes the first computable pair in declaration order without scanning them all.
"""

from __future__ import annotations

import heapq
from collections.abc import Iterable, Mapping
from dataclasses import dataclass

from ..topology import Topology


@dataclass(frozen=True)
class Index:
    """Look-ups by name that do not change while the Solver runs."""

    joint_names: frozenset[str]
    order: Mapping[str, int]  # pair -> its declaration index
    link_order: Mapping[str, int]  # link -> its declaration index
    slider_of: Mapping[str, str]  # prismatic pair -> its slider
    guided: Mapping[str, tuple[str, ...]]  # link -> the prismatic pairs it guides, in declaration order
    slides: Mapping[str, tuple[str, ...]]  # link -> the prismatic pairs it guides or slides in
    owners: Mapping[str, tuple[str, ...]]  # a name as links know it (see copy) -> those links, in links order

    @classmethod
    def of(cls, topo: Topology) -> Index:
        m = topo.mechanism
        slider_of = {p.joint: p.slider for p in m.prismatic}
        guided: dict[str, list[str]] = {}
        slides: dict[str, list[str]] = {}
        for p in m.prismatic:
            guided.setdefault(p.guide, []).append(p.joint)
            for side in (p.guide, p.slider):
                slides.setdefault(side, []).append(p.joint)
        owners: dict[str, list[str]] = {}
        for lk in m.links:
            for name in [copy(slider_of, j, lk.name) for j in lk.joints] + [p.name for p in lk.points]:
                owners.setdefault(name, []).append(lk.name)
        return cls(frozenset(j.name for j in m.joints), {j.name: j.index for j in m.joints},
                   {lk.name: lk.index for lk in m.links}, slider_of, _tuples(guided), _tuples(slides), _tuples(owners))


def _tuples(table: dict[str, list[str]]) -> dict[str, tuple[str, ...]]:
    return {k: tuple(v) for k, v in table.items()}


def copy(slider_of: Mapping[str, str], pair: str, link: str) -> str:
    """The name of the link's copy of a pair: a prismatic pair's position is its slider's
    copy; the guide's copy of the reference point is ``S@guide``."""
    return pair if slider_of.get(pair, link) == link else f"{pair}@{link}"


class Frontier:
    """The pairs to try, smallest declaration index first, each at most once until pushed again."""

    def __init__(self, order: Mapping[str, int], names: Iterable[str]):
        self.order = order
        self.heap = [(order[n], n) for n in names]
        heapq.heapify(self.heap)
        self.queued = {n for _, n in self.heap}

    def push(self, names: Iterable[str]) -> None:
        for n in names:
            if n not in self.queued:
                self.queued.add(n)
                heapq.heappush(self.heap, (self.order[n], n))

    def pop(self) -> str | None:
        if not self.heap:
            return None
        _, name = heapq.heappop(self.heap)
        self.queued.discard(name)
        return name
