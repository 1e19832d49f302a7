"""The Solver's state: what is known, and the procedure emitted so far.

``SolverState`` is frozen: the Solver, the Add-link process and the resolver plan
pass it between them, and a candidate probe starts from it without copying the
world.  A ``Workspace`` is one stage's private working copy (``thaw``); the stage
returns it ``frozen`` when it is done.  Steps and variables are frozen records,
shared between every copy.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass, field, fields, replace
from itertools import islice
from types import MappingProxyType
from typing import Any

from ..model import Link
from ..steplog import Arg, Candidate, LJColumn, Residual, Step, Variable
from ..topology import Topology
from .index import Frontier, Index, copy


class Unsupported(Exception):
    """The Solver reached a state this procedure form cannot express."""


@dataclass(frozen=True)
class Carrier:
    """A link in the Solver's sense: a user link, a linear actuator or an Add-link."""

    name: str
    kind: str  # link | actuator | addlink
    pairs: tuple[str, ...]
    length: str = ""  # VARIABLE of an actuator or Add-link


@dataclass(frozen=True)
class AddLinkDraft:
    """An installed Add-link before the steps are numbered: its VARIABLE ``var``, its sketch
    length, its resolver group, and (once ranked) the candidates and the probe inputs."""

    name: str
    var: str
    pairs: tuple[str, str]
    length: float
    group: int
    candidates: tuple[Candidate, ...] = ()
    probe: tuple[float, ...] = ()


@dataclass(frozen=True)
class VariantDraft:
    """Another usable Add-link candidate of a group: its steps are a fallback the resolver
    switches to where the chosen candidate's own chain degenerates."""

    group: int
    pairs: tuple[tuple[str, str], ...]  # its Add-links' pairs (several where the group needs them at once)
    lengths: tuple[float, ...]
    steps: tuple[Step, ...]
    variables: tuple[Variable, ...]


@dataclass(frozen=True)
class GroupDraft:
    """A resolver group while the Solver runs: its Add-link and residual variables so far."""

    number: int
    add_links: tuple[str, ...] = ()
    residuals: tuple[str, ...] = ()


def _frozen(value: object) -> object:
    if isinstance(value, dict):
        return MappingProxyType({k: _frozen(v) for k, v in value.items()})
    if isinstance(value, (list, tuple)):
        return tuple(value)
    if isinstance(value, set):
        return frozenset(value)
    return value


def _thawed(value: object) -> object:
    if isinstance(value, MappingProxyType):
        return dict(value)
    if isinstance(value, tuple):
        return list(value)
    if isinstance(value, frozenset):
        return set(value)
    return value


@dataclass(frozen=True)
class SolverState:
    """Everything the Solver knows and has emitted (see Workspace for the fields)."""

    topo: Topology
    index: Index
    variables: MappingProxyType[str, Variable]
    steps: tuple[Step, ...]
    pos: MappingProxyType[str, str]
    orient: MappingProxyType[str, str]
    coupled: MappingProxyType[str, str]
    tied: MappingProxyType[str, tuple[str, ...]]
    placed: frozenset[str]
    lines: MappingProxyType[str, tuple[str, str]]
    slides: MappingProxyType[str, str]
    angles: MappingProxyType[str, str]
    applied: frozenset[int]
    used: frozenset[str]
    carriers: tuple[Carrier, ...]
    inputs: tuple[str, ...]
    known: tuple[str, ...]
    columns: tuple[LJColumn, ...]
    add_links: tuple[AddLinkDraft, ...]
    residuals: tuple[Residual, ...]
    groups: tuple[GroupDraft, ...]
    variants: tuple[VariantDraft, ...]
    group: int
    residual_links: frozenset[str]
    slides_first: bool = False


@dataclass
class Workspace:
    """A mutable working copy of a SolverState, private to one stage.

    ``pos`` maps a pair or point (or a guide's copy ``S@guide`` of a prismatic pair's
    reference point) to its POINT variable; ``orient`` a link to an ANGLE turning with
    it; ``coupled`` a link to the placed link it slides on; ``tied`` a link to the known
    names on it, in the order found; ``group`` is the open resolver group (0: none).

    Besides the state, a working copy keeps what ``emit`` needs to look only at what a step
    changed: how much of ``pos``, ``orient``, ``carriers`` and ``used`` it has seen, the
    links placed in order, and the Solver's frontier (every pair, in a fresh copy).
    """

    topo: Topology
    index: Index
    variables: dict[str, Variable] = field(default_factory=dict)
    steps: list[Step] = field(default_factory=list)
    pos: dict[str, str] = field(default_factory=dict)
    orient: dict[str, str] = field(default_factory=dict)
    coupled: dict[str, str] = field(default_factory=dict)
    tied: dict[str, list[str]] = field(default_factory=dict)
    placed: set[str] = field(default_factory=set)
    lines: dict[str, tuple[str, str]] = field(default_factory=dict)
    slides: dict[str, str] = field(default_factory=dict)
    angles: dict[str, str] = field(default_factory=dict)
    applied: set[int] = field(default_factory=set)
    used: set[str] = field(default_factory=set)
    carriers: list[Carrier] = field(default_factory=list)
    inputs: list[str] = field(default_factory=list)
    known: list[str] = field(default_factory=list)
    columns: list[LJColumn] = field(default_factory=list)
    add_links: list[AddLinkDraft] = field(default_factory=list)
    residuals: list[Residual] = field(default_factory=list)
    groups: list[GroupDraft] = field(default_factory=list)
    variants: list[VariantDraft] = field(default_factory=list)
    group: int = 0
    residual_links: set[str] = field(default_factory=set)
    slides_first: bool = False  # in an open group, chains on a slide before the others (see solver._progress)

    def __post_init__(self) -> None:
        self.m = self.topo.mechanism
        self.joint_names = self.index.joint_names
        self.frontier = Frontier(self.index.order, self.index.order)
        self.known_set = set(self.known)
        self.lengths = {v.entity: v.name for v in reversed(self.variables.values()) if v.role == "length"}
        self.seen = {"pos": len(self.pos), "orient": len(self.orient), "carriers": len(self.carriers),
                     "used": len(self.used), "placed": 0}
        self.placed_order: list[str] = []

    @classmethod
    def thaw(cls, state: SolverState) -> Workspace:
        values: dict[str, Any] = {f.name: _thawed(getattr(state, f.name)) for f in fields(SolverState)}
        ws = cls(**values)
        ws.tied = {link: list(names) for link, names in ws.tied.items()}
        return ws

    def frozen(self) -> SolverState:
        values: dict[str, Any] = {f.name: _frozen(getattr(self, f.name)) for f in fields(SolverState)}
        return SolverState(**values)

    # -- names and variables ---------------------------------------------------
    def new_var(self, name: str, kind: str, role: str, entity: str, value: tuple[float, ...] = (),
                sketch: tuple[float, ...] = ()) -> str:
        base, k = name, 2
        while name in self.variables:
            name, k = f"{base}_{k}", k + 1
        self.variables[name] = Variable(name, kind, role, entity, value, sketch or value)
        return name

    def xy(self, name: str) -> tuple[float, float]:
        return self.topo.position(name.split("@")[0])

    def angle0(self, var: str) -> float:
        return self.variables[var].sketch[0]

    def point_var(self, entity: str, role: str = "pair") -> str:
        return self.new_var(f"p_{entity}", "POINT", role, entity, sketch=self.xy(entity))

    def role(self, name: str) -> str:
        return "pair" if name in self.joint_names else "point"

    def const_length(self, link: str, a: str, b: str, value: float) -> str:
        entity = f"{link}:{a}-{b}"
        if entity not in self.lengths:
            name = f"l_{link}" if len(self.link(link).joints) == 2 else f"l_{link}_{a}_{b}"
            self.lengths[entity] = self.new_var(name, "VARIABLE", "length", entity, (value,))
        return self.lengths[entity]

    def member_length(self, link: str, a: str, b: str) -> str:
        (xa, ya), (xb, yb) = self.xy(a), self.xy(b)
        return self.const_length(link, a, b, math.hypot(xb - xa, yb - ya))

    def length_of(self, carrier: str, a: str, b: str) -> str:
        c = self.carrier(carrier)
        return c.length if c.kind != "link" else self.member_length(carrier, a, b)

    # -- what a link carries -----------------------------------------------------
    def link(self, name: str) -> Link:
        return self.m.link(name)

    def copy(self, pair: str, link: str) -> str:
        """The name of the link's copy of a pair (see ``index.copy``)."""
        return copy(self.index.slider_of, pair, link)

    def named(self, name: str, link: str) -> str:
        """A pair's or point's name as seen on a link (see ``copy``)."""
        return self.copy(name, link) if name in self.joint_names else name

    def own(self, link: str) -> list[str]:
        """Names of the points of this link whose positions the Solver may know."""
        lk = self.link(link)
        return [self.copy(j, link) for j in lk.joints] + [p.name for p in lk.points]

    def distinct(self, names: list[str]) -> bool:
        return len({self.xy(n) for n in names}) >= 2

    def carrier(self, name: str) -> Carrier:
        if name in self.index.link_order:
            return self.carriers[self.index.link_order[name]]
        return next(c for c in self.extra_carriers() if c.name == name)

    def extra_carriers(self) -> list[Carrier]:
        """The actuators and Add-links (the carriers after the links, which come first in links order)."""
        return self.carriers[len(self.index.link_order):]

    def carriers_with(self, pair: str) -> list[Carrier]:
        """Every carrier of the pair, in carriers order."""
        links = [self.carriers[self.index.link_order[lk.name]] for lk in self.m.links_of(pair)]
        return links + [c for c in self.extra_carriers() if pair in c.pairs]

    def is_known(self, pair: str) -> bool:
        if self.m.joint(pair).revolute:
            return pair in self.pos
        return self.m.prismatic_of(pair).guide in self.placed

    def oriented(self, link: str) -> bool:
        return link in self.orient or link in self.placed or link in self.coupled

    # -- the procedure -------------------------------------------------------------
    def append(self, action: str, function: str, args: list[Arg], outputs: list[str], target: str, *,
               chain: str = "", pairs: tuple[str, ...] = (), links: tuple[str, ...] = (), branch: int = 0,
               reason: str = "", branch_reason: str = "", fails: bool = False) -> int:
        """Append a step in the open group (its number for now: its place); returns its index."""
        self.steps.append(Step(len(self.steps) + 1, action, function, tuple(args), tuple(outputs), target, chain,
                               pairs, links, branch, reason, branch_reason, (), self.group, fails))
        return len(self.steps) - 1

    def place(self, link: str) -> None:
        self.placed.add(link)
        self.placed_order.append(link)

    def unseen(self, what: str) -> list[str]:
        """The names added to ``pos`` or ``orient`` (``what``) since the last call, in the order added."""
        table = self.pos if what == "pos" else self.orient
        new = len(table) - self.seen[what]
        self.seen[what] = len(table)
        return list(islice(reversed(table), new))[::-1]

    def newly_placed(self) -> list[str]:
        """The links placed since the last call, in the order placed."""
        out = self.placed_order[self.seen["placed"]:]
        self.seen["placed"] = len(self.placed_order)
        return out

    def newly_known(self, names: Iterable[str], placed: Iterable[str]) -> tuple[str, ...]:
        """The pairs that became known with the ``names`` now in pos and the links ``placed``
        (a prismatic pair is known with its guide), in joints order."""
        now = {n for n in names if n in self.joint_names and self.is_known(n)}
        now.update(p for lk in placed for p in self.index.guided.get(lk, ()))
        out = sorted(now - self.known_set, key=self.index.order.__getitem__)
        self.known += out
        self.known_set.update(out)
        return tuple(out)

    def set_determines(self, index: int, pairs: tuple[str, ...]) -> None:
        self.steps[index] = replace(self.steps[index], determines=pairs)
