"""Stage 5 types: the step log, a plain serialisable record of every decision.

Templates and the evaluator read nothing else.  Only builtins cross this boundary
(str, int, float, bool, tuples of them); ``to_json`` writes it deterministically.
"""

from __future__ import annotations

import functools
import json
from dataclasses import dataclass, field, fields
from typing import NewType

from .census import Assemblies
from .closurelog import Closure
from .codes import StatusCode as StatusCode
from .codes import status_codes
from .instant.record import CentreAt as CentreAt
from .motion import Conditioning as Conditioning
from .motion import Gap as Gap
from .motion import Reach as Reach
from .motion import Singular as Singular
from .options import Options
from .policy import Policy
from .primitives.dsl import record_fields
from .summary.records import Summary


@dataclass(frozen=True)
class Variable:
    """A record in the generated code: a pair's motion, a link angle, a slider displacement.

    ``value`` holds the displacement fields of a constant record (its derivatives
    are zero); computed records have ``value == ()``.  ``sketch`` holds the
    displacement fields at the sketch, which every local coordinate refers to.
    Both give points as drawn; the programs hold them relative to the step log's
    ``origin`` (``held``).
    """

    name: str
    kind: str  # POINT | ANGLE | VARIABLE
    role: str  # pair | point | link | line | guide | slide | input | reference | length | addlink | residual
    # | direction (a link's unit vector: angles: unit)
    entity: str  # the pair, point, link or input it belongs to
    value: tuple[float, ...]
    sketch: tuple[float, ...]

    @property
    def constant(self) -> bool:
        return bool(self.value)


def held(v: Variable, origin: tuple[float, float]) -> tuple[float, ...]:
    """A constant record's displacement fields as the programs hold them: points relative
    to the step log's origin (a direction is no point)."""
    if v.kind != "POINT" or v.role == "direction":
        return v.value
    return v.value[0] - origin[0], v.value[1] - origin[1]


@dataclass(frozen=True)
class Arg:
    """One argument of a runtime call: a variable, a real constant or an integer flag."""

    kind: str  # var | real | int
    var: str = ""
    value: float = 0.0
    label: str = ""  # what a constant means, for comments: "gsi", "l1", ...


@dataclass(frozen=True)
class Step:
    number: int
    action: str  # fixed | input | chain | point | angle | line | add_link | residual | resolve | direction
    function: str  # runtime function called ("" for fixed, add_link, resolve)
    args: tuple[Arg, ...]
    outputs: tuple[str, ...]  # variables written, in the function's output order
    target: str  # what the step determines (pair, point, link, line or Add-link)
    chain: str  # RRR | RRP | PRP | RPR | PPR for two-link chains
    pairs: tuple[str, ...]  # known pairs (or lines) read
    links: tuple[str, ...]  # links (truss members) used
    branch: int  # +1 / -1 for chains with two assemblies, 0 otherwise
    reason: str  # one sentence: why this is computable now
    branch_reason: str
    determines: tuple[str, ...]  # pairs that become known (their LJ entries turn negative)
    group: int  # resolver group the step is iterated in (0: none)
    fails: bool  # the function reports a status
    change_points: tuple[float, ...] = ()  # input values where the branch flips (a change point)
    variant: int = 0  # >0: the step belongs to fallback variant k of its resolver group


@dataclass(frozen=True)
class Candidate:
    pairs: tuple[str, str]  # (known pair, unknown pair)
    norm: float | None  # |f| at the probe input, None when a chain cannot close there
    usable: bool  # the Solver completes its group with it
    lever: float | None = None  # the block's lever (None where the candidate does not complete its group)
    also: tuple[tuple[str, str], ...] = ()  # the Add-links installed with it (a group needing several at once)


@dataclass(frozen=True)
class AddLink:
    name: str  # LJ column and variable: add1, add2, ...
    pairs: tuple[str, str]
    length: float  # in the sketch: the resolver's first start value
    step: int
    candidates: tuple[Candidate, ...]  # ranked: usable first, then by norm, then as enumerated
    probe: tuple[float, ...]  # the input values at which the norms were computed


@dataclass(frozen=True)
class Residual:
    name: str  # variable f1, f2, ...
    link: str  # the link (or actuator) the Solver did not use
    pairs: tuple[str, str]
    length: str  # VARIABLE record it must equal
    step: int


@dataclass(frozen=True)
class BranchSign:
    """How a resolver block reads one chain's branch off a solved configuration.

    ``side``: the sign of (b - a) x (c - a) for points (a, b, c), the 3R chain's c left
    of a->b.  ``along``: the sign of (c - a).u for points (a, c) and u the direction
    of ``angle``.  A zero keeps the branch the block had.
    """

    step: int
    kind: str  # side | along
    points: tuple[str, ...]  # position variables
    angle: str  # the line's angle variable (along only)
    sketch: int  # the branch in the sketch


@dataclass(frozen=True)
class ResolverGroup:
    """Newton-Raphson on Add-link lengths until every unused link regains its length."""

    number: int
    step: int  # the resolve step
    add_links: tuple[str, ...]
    residuals: tuple[str, ...]
    steps: tuple[int, ...]  # steps iterated, in order
    reads: tuple[str, ...]  # variables computed before the group that it reads
    writes: tuple[str, ...]  # variables the group computes
    lever: float = 1.0  # worst frame base over arm of the block's point placements (<= 1): conditioning starts there
    variant: int = 0  # 0: the chosen candidate; k: its k-th fallback
    pairs: tuple[tuple[str, str], ...] = ()  # the Add-links' pairs (known, unknown)
    lengths: tuple[float, ...] = ()  # the Add-links' sketch lengths
    variants: tuple[ResolverGroup, ...] = ()  # fallbacks: other candidates, tried in this order
    branches: tuple[BranchSign, ...] = ()  # chains whose branch follows the last solution
    closure: Closure | None = None  # strategy closure: the group's loop-closure equations (chosen block only)

    @property
    def sets(self) -> tuple[str, ...]:
        """The records the block sets: its Add-links, then what its steps write (each once); the resolver
        bends their accelerations by the Add-links' (linear in them)."""
        return tuple(dict.fromkeys((*self.add_links, *self.writes)))

    def start(self) -> list[float]:
        """The block's state in the sketch: Add-link lengths, its chains' branches, then its
        orientation (0: not known until a block solves; see the runtime's on_path)."""
        return [*self.lengths, *(float(b.sketch) for b in self.branches), 0.0]


@dataclass(frozen=True)
class LJColumn:
    name: str
    kind: str  # member | input | actuator | addlink
    pairs: tuple[str, ...]
    link: str


@dataclass(frozen=True)
class LJMatrix:
    """Rows pairs, columns links (after rule i/ii); states after each step are
    derived from each step's ``determines`` and the Add-link steps' new columns."""

    rows: tuple[str, ...]
    prismatic: tuple[bool, ...]
    columns: tuple[LJColumn, ...]
    known: tuple[str, ...]  # pairs known before step 1


@dataclass(frozen=True)
class Column:
    """One CSV column: ``variable``'s ``field`` (x, y, dx, the, v, ...)."""

    name: str
    variable: str
    field: str
    quantity: str  # position | velocity | acceleration | angle | angular_velocity | angular_acceleration


@dataclass(frozen=True)
class PairInfo:
    name: str
    kind: str
    x: float
    y: float
    axis: float
    links: tuple[str, ...]
    guide: str
    slider: str


@dataclass(frozen=True)
class LinkInfo:
    name: str
    fixed: bool
    pairs: tuple[str, ...]
    points: tuple[str, ...]
    lengths: tuple[tuple[str, str, float], ...]  # truss members
    direction: tuple[str, str]  # (origin, target); target "" when it is a prismatic axis
    angle: float


@dataclass(frozen=True)
class InputInfo:
    index: int
    kind: str
    column: str
    joint: str
    link: str
    relative_to: str
    between: tuple[str, ...]
    start: float
    stop: float
    speed: float
    sketch: float
    variable: str


@dataclass(frozen=True)
class Omitted:
    """A step of the whole procedure that the chosen outputs do not need."""

    number: int
    target: str


@dataclass(frozen=True)
class Header:
    """The mechanism as the programs and the manual see it: its names, units, the sketch's
    scale and origin, its mobility, the sweep, its pairs, links and inputs."""

    linkgen_version: str
    name: str
    title: str
    source: str
    length_unit: str
    angle_unit: str
    length_scale: float
    origin: tuple[float, float]  # the programs compute points relative to it (topology.sketch_origin)
    grubler: int
    mobility: int
    redundant: int
    order: int
    samples: int
    sweep: str  # "together" (row k: every input at k/(samples-1) of its range) or "grid" (every combination)
    pairs: tuple[PairInfo, ...]
    links: tuple[LinkInfo, ...]
    inputs: tuple[InputInfo, ...]


@dataclass(frozen=True)
class Procedure:
    """The systematic-analysis procedure that extraction finds: the records, the numbered
    steps, the LJ-matrix, the Add-links, the residuals and the resolver groups."""

    variables: tuple[Variable, ...]
    steps: tuple[Step, ...]
    lj: LJMatrix
    add_links: tuple[AddLink, ...]
    residuals: tuple[Residual, ...]
    groups: tuple[ResolverGroup, ...]

    def variable(self, name: str) -> Variable:
        return self._variables[name]

    def step(self, number: int) -> Step:
        return self._steps[number]

    @functools.cached_property
    def _variables(self) -> dict[str, Variable]:
        return {v.name: v for v in self.variables}

    @functools.cached_property
    def _steps(self) -> dict[int, Step]:
        return {s.number: s for s in self.steps}


@dataclass(frozen=True)
class StepLog(Procedure, Header):
    """The step log: the mechanism, its procedure, the columns of the outputs, the policy and
    the motion facts, its fields in that order (a dataclass takes its bases' fields first, the
    last base's first).  Status codes and runtime functions are made from the rest."""

    columns: tuple[Column, ...]
    status_codes: tuple[StatusCode, ...] = field(init=False)  # status_codes(): what each status means
    runtime: tuple[str, ...] = field(init=False)  # runtime(): the runtime functions the programs need
    policy: Policy
    conditioning: tuple[Conditioning, ...] = ()
    outputs: tuple[str, ...] = ()  # the outputs asked for (empty: the default set)
    omitted: tuple[Omitted, ...] = ()  # steps left out: the outputs do not need them
    reach: Reach | None = None  # one input: the input values reached from the sketch
    gaps: tuple[Gap, ...] = ()  # one input: where each chain cannot close
    options: Options = Options()  # what the programs compute in and how (the file's options and the flags)
    summary: Summary | None = None  # the engineering summary over the sweep (linkgen.summary; built with the sweep)
    centres: tuple[CentreAt, ...] = ()  # every instant centre at the sketch (with the sweep: for the manual)
    assemblies: Assemblies | None = None  # every assembly at the sketch's inputs (None: not looked for)

    def __post_init__(self) -> None:
        object.__setattr__(self, "status_codes", status_codes(self))
        object.__setattr__(self, "runtime", runtime(self))

    def step_limits(self) -> tuple[float, ...]:
        """The continuation's largest step of each input: an angle's in radians, a length's
        in length units."""
        p = self.policy
        return tuple(p.step_angle if i.kind == "revolute" else p.step_length * self.length_scale for i in self.inputs)

    def drawn(self, c: Column) -> float | None:
        """An output column of a constant record: its value as drawn (0 for a rate); None
        for a computed record."""
        v = self.variable(c.variable)
        if not v.constant:
            return None
        fields = record_fields(v.kind, 0)
        return v.value[fields.index(c.field)] if c.field in fields else 0.0

    def offset(self, c: Column) -> float:
        """What a program adds to publish a field: the origin's x or y to a point's or a centre's, else 0."""
        v = self.variable(c.variable)
        point = v.kind == "POINT" and v.role != "direction" or v.kind == "CENTRE"
        if not point or c.field not in ("x", "y"):
            return 0.0
        return self.origin[c.field == "y"]

    @property
    def shifted(self) -> bool:
        """Whether the programs hold points relative to an origin other than (0, 0)."""
        return self.origin != (0.0, 0.0)

    def to_json(self) -> str:
        return json.dumps(_plain(self), indent=2, allow_nan=False, ensure_ascii=False) + "\n"


Draft = NewType("Draft", StepLog)
"""A step log without its motion facts (change points, gaps, reach, conditioning): what
``linkgen.analysis`` reads to find them.  Never rendered; the log is made from it and them."""


def runtime(log: StepLog) -> tuple[str, ...]:
    """The runtime functions the log's programs call: its steps', the resolver's with resolver
    groups (and the closure strategy's where it is chosen), branch_at with change points and
    reach_at with a reach."""
    names = {s.function for s in log.steps if s.function}
    if log.groups:
        names |= {"resolver", "link_residual"} | ({"closure"} if log.groups[0].closure else set())
    if any(s.change_points for s in log.steps):
        names.add("branch_at")
    if log.reach is not None:
        names.add("reach_at")
    return tuple(sorted(names))


_PLAIN = frozenset((str, int, float, bool, type(None)))  # the types a step log holds as they are
_FIELDS: dict[type, tuple[str, ...]] = {}  # a dataclass's field names in order (dataclasses.fields, once a class)


def _plain(obj: object) -> object:
    if type(obj) in _PLAIN:
        return obj
    if hasattr(obj, "__dataclass_fields__"):
        names = _FIELDS.get(type(obj))
        if names is None:
            names = _FIELDS[type(obj)] = tuple(f.name for f in fields(obj))  # type: ignore[arg-type]
        return {name: _plain(getattr(obj, name)) for name in names}
    if isinstance(obj, tuple):
        return [x if type(x) in _PLAIN else _plain(x) for x in obj]
    if obj is None or isinstance(obj, (str, int, float, bool)):
        return obj
    raise TypeError(f"{type(obj).__name__} is not allowed in the step log")

