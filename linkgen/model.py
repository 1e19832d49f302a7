"""Stage 2 types: the validated mechanism, in radians and length units.

Every entity keeps its declaration index and its place in the file (line and
key) so later stages order by the file and report errors where the user wrote.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from functools import cached_property

from .options import Options


@dataclass(frozen=True)
class Where:
    line: int
    key: str


@dataclass(frozen=True)
class Joint:
    name: str
    index: int
    kind: str  # "revolute" | "prismatic"
    x: float
    y: float
    axis: float  # radians; the slide direction of a prismatic pair, 0 for a revolute pair
    where: Where

    @property
    def revolute(self) -> bool:
        return self.kind == "revolute"


@dataclass(frozen=True)
class Point:
    name: str
    index: int  # order among all points, in links order
    link: str
    x: float
    y: float
    where: Where


@dataclass(frozen=True)
class Link:
    name: str
    index: int
    joints: tuple[str, ...]
    fixed: bool
    points: tuple[Point, ...]
    where: Where


@dataclass(frozen=True)
class Input:
    index: int
    kind: str  # "revolute" | "prismatic" | "distance"
    joint: str  # the driven pair ("" for a distance input)
    link: str  # revolute: the driven link; prismatic: the slider
    relative_to: str  # revolute: the reference link; prismatic: the guide
    between: tuple[str, ...]  # distance input: the two pairs
    start: float  # radians or length units
    stop: float
    speed: float  # per second, radians or length units
    where: Where

    @property
    def column(self) -> str:
        if self.kind == "revolute":
            return f"theta_{self.joint}"
        if self.kind == "prismatic":
            return f"s_{self.joint}"
        return f"d_{self.between[0]}_{self.between[1]}"


@dataclass(frozen=True)
class Prismatic:
    """The two links of a prismatic pair: the guide carries the line."""

    joint: str
    guide: str
    slider: str


@dataclass(frozen=True)
class Mechanism:
    name: str
    title: str
    source: str  # the file's base name, for banners
    path: str  # the file as given, for error messages
    length_unit: str
    angle_unit: str  # "deg" | "rad": how the file wrote angles
    joints: tuple[Joint, ...]
    links: tuple[Link, ...]
    inputs: tuple[Input, ...]
    prismatic: tuple[Prismatic, ...]
    outputs: tuple[str, ...]  # names; empty means the default set
    outputs_where: Where | None
    order: int
    samples: int
    where: Where  # the top of the file
    inputs_where: Where  # the inputs: key
    options: Options = Options()  # options: what the programs compute in and how
    options_where: Mapping[str, Where] = field(default_factory=dict)  # where the file gives each option
    sweep: str = "together"  # how the inputs move over the sweep: "together" or "grid" (every combination)

    @cached_property
    def _joints(self) -> dict[str, Joint]:
        return {j.name: j for j in self.joints}

    @cached_property
    def _links(self) -> dict[str, Link]:
        return {lk.name: lk for lk in self.links}

    @cached_property
    def _carriers(self) -> dict[str, tuple[Link, ...]]:
        carriers: dict[str, list[Link]] = {j.name: [] for j in self.joints}
        for lk in self.links:
            for name in dict.fromkeys(lk.joints):
                if name in carriers:
                    carriers[name].append(lk)
        return {name: tuple(links) for name, links in carriers.items()}

    @cached_property
    def _prismatic(self) -> dict[str, Prismatic]:
        return {p.joint: p for p in self.prismatic}

    def joint(self, name: str) -> Joint:
        return self._joints[name]

    def link(self, name: str) -> Link:
        return self._links[name]

    def links_of(self, joint: str) -> tuple[Link, ...]:
        """The links that carry the pair, in links order."""
        return self._carriers[joint]

    def prismatic_of(self, joint: str) -> Prismatic:
        return self._prismatic[joint]

    @cached_property
    def points(self) -> tuple[Point, ...]:
        return tuple(p for lk in self.links for p in lk.points)

    @cached_property
    def positions(self) -> dict[str, tuple[float, float]]:
        """Sketch position of every pair and point."""
        return {**{j.name: (j.x, j.y) for j in self.joints}, **{p.name: (p.x, p.y) for p in self.points}}

    @property
    def fixed(self) -> Link:
        return next(lk for lk in self.links if lk.fixed)
