"""Stage 4: extract the systematic-analysis procedure.

The Solver (the paper's Algorithm 1) scans the unknown pairs in declaration
order and computes each one as soon as it can: as a point of a link that is
already placed (``coupler_point``), through an input (``crank_input``,
``slider_input``), or as the middle pair of a two-link chain whose ends are
known (``RRR_links``, ``PRR_links``, ``PRP_links``, ``RPR_links``,
``PPR_links``: every planar dyad).  When no chain is computable the Add-link
process installs a temporary binary link (candidates by section 3.3.1, chosen
by the smallest norm of f at a probe input, section 6); each link the Solver
then leaves unused gives a residual, and the over-constraint resolver iterates
the Add-link lengths until every residual vanishes.

Every choice breaks ties by declaration order, so a file always gives the same
procedure.
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass, field, replace
from typing import NamedTuple

from . import exact
from .errors import ProcedureError
from .model import Input, Link
from .steplog import AddLink, Arg, BranchSign, Candidate, LJColumn, LJMatrix, Residual, ResolverGroup, Step, Variable
from .topology import Topology, input_direction, reference_angle, wrap_angle

RESOLVER_TOLERANCE = 1e-10  # relative to the length scale; one Newton step is taken past it
RESOLVER_MAX_ITERATIONS = 8
CONTINUATION_HALVINGS = 20
RESOLVER_MAX_MOVE = 0.1  # relative to the length scale: farther from the start lengths is another assembly
RESOLVER_MIN_CHAIN_SIGMA = 0.05  # below it, a block's Add-links are a poor coordinate of the assembly
MAX_VARIANTS = 8  # fallback Add-link candidates per resolver group
GOOD_LEVER = 0.25  # a block that magnifies its frame angle's error more than fourfold ranks after the others
PROBE_ANGLE = math.radians(5.0)  # the paper's +5 degrees for ranking Add-link candidates
PROBE_LENGTH = 0.05  # times the length scale, for prismatic and distance inputs


class Unsupported(Exception):
    """The Solver reached a state this procedure form cannot express."""


@dataclass
class Carrier:
    """A link in the Solver's sense: a user link, a linear actuator or an Add-link."""

    name: str
    kind: str  # link | actuator | addlink
    pairs: tuple[str, ...]
    length: str = ""  # VARIABLE of an actuator or Add-link


@dataclass
class _AddLinkDraft:
    name: str
    var: str
    pairs: tuple[str, str]
    length: float
    group: int
    candidates: tuple[Candidate, ...] = ()
    probe: tuple[float, ...] = ()


@dataclass
class _VariantDraft:
    """Another usable Add-link candidate of a group: its steps are a fallback the resolver
    switches to where the chosen candidate's own chain degenerates."""

    group: int
    pairs: tuple[str, str]
    length: float
    steps: list[Step]
    variables: dict[str, Variable]


@dataclass
class _GroupDraft:
    number: int
    add_links: list[str] = field(default_factory=list)
    residuals: list[str] = field(default_factory=list)


@dataclass
class Procedure:
    variables: tuple[Variable, ...]
    steps: tuple[Step, ...]
    lj: LJMatrix
    add_links: tuple[AddLink, ...]
    residuals: tuple[Residual, ...]
    groups: tuple[ResolverGroup, ...]
    positions: dict[str, str]  # pair/point -> POINT variable
    angles: dict[str, str]  # link -> ANGLE variable of its angle
    slides: dict[str, str]  # prismatic pair -> VARIABLE of its displacement


def _rot(angle: float, x: float, y: float) -> tuple[float, float]:
    """Coordinates of (x, y) in a frame turned by ``angle``."""
    c, s = exact.cos(angle), exact.sin(angle)
    return c * x + s * y, -s * x + c * y


def _side(o: tuple[float, float], d: tuple[float, float], p: tuple[float, float]) -> float:
    return (d[0] - o[0]) * (p[1] - o[1]) - (d[1] - o[1]) * (p[0] - o[0])


def _sign(value: float) -> int:
    return 1 if value >= 0 else -1


class Extractor:
    """Mutable Solver state; copied to try Add-link candidates."""

    def __init__(self, topo: Topology):
        self.topo = topo
        self.m = topo.mechanism
        self.variables: dict[str, Variable] = {}
        self.steps: list[Step] = []
        self.pos: dict[str, str] = {}
        self.orient: dict[str, str] = {}
        self.coupled: dict[str, str] = {}  # link -> placed link it slides on (same rotation)
        self.tied: dict[str, list[str]] = {lk.name: [] for lk in self.m.links}
        self.placed: set[str] = set()
        self.lines: dict[str, tuple[str, str]] = {}
        self.slides: dict[str, str] = {}
        self.angles: dict[str, str] = {}
        self.applied: set[int] = set()
        self.used: set[str] = set()
        self.carriers: list[Carrier] = [Carrier(lk.name, "link", lk.joints) for lk in self.m.links]
        self.inputs: list[str] = []
        self.known: list[str] = []
        self.columns: list[LJColumn] = self._initial_columns()
        self.add_links: list[_AddLinkDraft] = []
        self.residuals: list[Residual] = []
        self.groups: list[_GroupDraft] = []
        self.variants: list[_VariantDraft] = []
        self.group = 0
        self.residual_links: set[str] = set()
        self.joint_names = {j.name for j in self.m.joints}

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

    # -- what a link carries -----------------------------------------------------
    def link(self, name: str) -> Link:
        return self.m.link(name)

    def copy(self, pair: str, link: str) -> str:
        """The name of the link's copy of a pair: a prismatic pair's position is its
        slider's copy; the guide's copy of the reference point is ``S@guide``."""
        if self.m.joint(pair).revolute or self.m.prismatic_of(pair).slider == link:
            return pair
        return f"{pair}@{link}"

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
        return next(c for c in self.carriers if c.name == name)

    # -- LJ-matrix ---------------------------------------------------------------
    def _initial_columns(self) -> list[LJColumn]:
        cols = [LJColumn(mb.label if len(self.link(mb.link).joints) > 2 else mb.link, "member",
                         tuple(p for p in (mb.a, mb.b) if p), mb.link) for mb in self.topo.members]
        for inp in self.m.inputs:
            if inp.kind == "revolute":
                a = input_direction(self.m, self.link(inp.link), inp.joint).target
                r = input_direction(self.m, self.link(inp.relative_to), inp.joint).target
                pairs = tuple(p for p in (a, r) if p in {j.name for j in self.m.joints})
                cols.append(LJColumn(inp.column, "input", pairs, inp.link))
            elif inp.kind == "prismatic":
                cols.append(LJColumn(inp.column, "input", (inp.joint,), inp.link))
            else:
                cols.append(LJColumn(inp.column, "actuator", inp.between, ""))
        return cols

    def is_known(self, pair: str) -> bool:
        if self.m.joint(pair).revolute:
            return pair in self.pos
        return self.m.prismatic_of(pair).guide in self.placed

    # -- emitting steps ---------------------------------------------------------------
    def emit(self, action: str, function: str, args: list[Arg], outputs: list[str], target: str, *,
             chain: str = "", pairs: tuple[str, ...] = (), links: tuple[str, ...] = (), branch: int = 0,
             reason: str = "", branch_reason: str = "", fails: bool = False) -> None:
        step = Step(len(self.steps) + 1, action, function, tuple(args), tuple(outputs), target, chain, pairs,
                    links, branch, reason, branch_reason, (), self.group, fails)
        index = len(self.steps)
        self.steps.append(step)
        self.refresh()
        now = [j.name for j in self.m.joints if self.is_known(j.name) and j.name not in self.known]
        self.known += now
        self.steps[index] = replace(step, determines=tuple(now))
        self.close_group()

    def refresh(self) -> None:
        """Propagate orientation through prismatic pairs, place links, find unused links."""
        changed = True
        while changed:
            changed = False
            for p in self.m.prismatic:
                for a, b in ((p.guide, p.slider), (p.slider, p.guide)):
                    if a in self.placed and not self.oriented(b):
                        self.coupled[b] = a
                        changed = True
            for lk in self.m.links:
                if lk.name in self.placed:
                    continue
                tied = self.tied[lk.name]
                for n in self.own(lk.name):
                    if n in self.pos and n not in tied:
                        if not tied:
                            tied.append(n)
                        elif self.oriented(lk.name) or self.distinct(tied):
                            raise Unsupported(f"link {lk.name} is over-determined at {n}")
                        else:
                            self.add_residual(lk.name, tied[0], n, self.member_length(lk.name, tied[0], n))
                            tied.append(n)
                if tied and (self.oriented(lk.name) or self.distinct(tied)):
                    self.placed.add(lk.name)
                    changed = True
        for c in self.carriers:
            unused = c.kind != "link" and c.name not in self.used and c.name not in self.residual_links
            if unused and all(p in self.pos for p in c.pairs):
                self.add_residual(c.name, c.pairs[0], c.pairs[1], c.length)

    def member_length(self, link: str, a: str, b: str) -> str:
        (xa, ya), (xb, yb) = self.xy(a), self.xy(b)
        return self.const_length(link, a, b, math.hypot(xb - xa, yb - ya))

    def const_length(self, link: str, a: str, b: str, value: float) -> str:
        name = f"l_{link}" if len(self.link(link).joints) == 2 else f"l_{link}_{a}_{b}"
        for v in self.variables.values():
            if v.role == "length" and v.entity == f"{link}:{a}-{b}":
                return v.name
        return self.new_var(name, "VARIABLE", "length", f"{link}:{a}-{b}", (value,))

    def add_residual(self, link: str, a: str, b: str, length: str) -> None:
        if not self.group:
            return  # a redundant constraint the sketch already satisfies (e.g. an exact parallelogram)
        self.residual_links.add(link)
        n = len(self.residuals) + 1
        f = self.new_var(f"f{n}", "VARIABLE", "residual", link)
        self.residuals.append(Residual(f, link, (a, b), length, 0))
        self.groups[-1].residuals.append(f)
        self.steps.append(Step(
            len(self.steps) + 1, "residual", "link_residual",
            (Arg("var", self.pos[a]), Arg("var", self.pos[b]), Arg("var", length)), (f,), link, "", (a, b),
            (link,), 0, f"{a} and {b} are both known, but link {link} was not used to find them: its length "
            "must come out right, which the resolver ensures", "", (), self.group, True))

    def close_group(self) -> None:
        if not self.group:
            return
        g = self.groups[-1]
        if len(g.residuals) > len(g.add_links):
            raise Unsupported("more unused links than Add-links")
        if len(g.residuals) == len(g.add_links):
            self.hoist(g)
            self.steps.append(Step(
                len(self.steps) + 1, "resolve", "", (), tuple(g.add_links), f"group{g.number}", "", (), (), 0,
                f"Newton-Raphson on {', '.join(g.add_links)} until "
                + " and ".join(f"{r.link}" for r in self.residuals if r.name in g.residuals)
                + (" regains its length" if len(g.residuals) == 1 else " regain their lengths"),
                "", (), g.number, True))
            self.group = 0

    def hoist(self, g: _GroupDraft) -> None:
        """Move the steps of the group that do not depend on its Add-links before it."""
        start = next(i for i, s in enumerate(self.steps) if s.group == g.number)
        dep = set(g.add_links)
        before, inside = [], []
        for s in self.steps[start:]:
            reads = {a.var for a in s.args if a.kind == "var"}
            if s.action == "add_link" or reads & dep:
                inside.append(s)
                dep |= set(s.outputs)
            else:
                before.append(replace(s, group=0))
        for r in g.residuals:
            if r not in dep:
                raise Unsupported("a residual does not depend on the Add-links")
        self.steps[start:] = before + inside

    # -- reusable pieces --------------------------------------------------------------
    def oriented(self, link: str) -> bool:
        return link in self.orient or link in self.placed or link in self.coupled

    def frame(self, link: str) -> str:
        """An ANGLE variable turning with the link (emitting link_angle if needed)."""
        if link in self.orient:
            return self.orient[link]
        if link in self.coupled:
            self.orient[link] = self.frame(self.coupled[link])
            return self.orient[link]
        tied = self.tied[link]
        d = self.topo.direction(link)
        origin, target = self.named(d.origin, link), self.named(d.target, link) if d.target else ""
        if target and origin in tied and target in tied:
            a, b = origin, target
        else:
            a = tied[0]
            b = next(n for n in tied[1:] if self.xy(n) != self.xy(a))
        (xa, ya), (xb, yb) = self.xy(a), self.xy(b)
        off = wrap_angle(d.angle - exact.atan2(yb - ya, xb - xa))
        var = self.new_var(f"phi_{link}", "ANGLE", "link", link, sketch=(wrap_angle(d.angle),))
        self.emit("angle", "link_angle",
                  [Arg("var", self.pos[a]), Arg("var", self.pos[b]), Arg("real", value=off, label="off")], [var], link,
                  pairs=(a, b), links=(link,), fails=True,
                  reason=f"{a} and {b} of link {link} are known, so its angle is")
        self.orient[link] = var
        self.angles[link] = var
        return var

    def line(self, pair: str) -> tuple[str, str]:
        """(guide point, line angle) of a prismatic pair whose guide is placed."""
        if pair in self.lines:
            return self.lines[pair]
        j = self.m.joint(pair)
        guide = self.m.prismatic_of(pair).guide
        if self.link(guide).fixed:
            g = self.new_var(f"g_{pair}", "POINT", "guide", pair, (j.x, j.y))
            psi = self.new_var(f"psi_{pair}", "ANGLE", "line", pair, (wrap_angle(j.axis),))
        else:
            base = self.frame(guide)
            off = wrap_angle(j.axis - self.angle0(base))
            if off == 0.0:
                psi = base
            else:
                psi = self.new_var(f"psi_{pair}", "ANGLE", "line", pair, sketch=(wrap_angle(j.axis),))
                self.emit("line", "offset_angle", [Arg("var", base), Arg("real", value=off, label="off")], [psi], pair,
                          pairs=(), links=(guide,), reason=f"the slide axis of {pair} turns with its guide {guide}")
            g = self.pos.get(f"{pair}@{guide}")
            if g is None:
                g = self.new_var(f"g_{pair}", "POINT", "guide", pair, sketch=(j.x, j.y))
                self.pos[f"{pair}@{guide}"] = g
                self.tied[guide].append(f"{pair}@{guide}")
                self.point_on(guide, pair, g, psi,
                              f"the guide {guide} of {pair} is placed, so its copy of the reference point is known")
        self.lines[pair] = (g, psi)
        return self.lines[pair]

    def point_on(self, link: str, name: str, out: str, frame: str, reason: str) -> None:
        """coupler_point: ``name`` at its sketch offset from a tied point of a placed link."""
        base = self.tied[link][0]
        gsi, eta = _rot(self.angle0(frame), *(a - b for a, b in zip(self.xy(name), self.xy(base))))
        self.emit("point", "coupler_point",
                  [Arg("var", self.pos[base]), Arg("var", frame), Arg("real", value=gsi, label="gsi"),
                   Arg("real", value=eta, label="eta")], [out], name, pairs=(base,), links=(link,), reason=reason)

    def length_of(self, carrier: str, a: str, b: str) -> str:
        c = self.carrier(carrier)
        return c.length if c.kind != "link" else self.member_length(carrier, a, b)

    # -- Solver rules ----------------------------------------------------------------
    def start(self) -> None:
        fixed = self.m.fixed
        for n in [*fixed.joints, *(p.name for p in fixed.points)]:
            if n in {j.name for j in self.m.joints} and not self.m.joint(n).revolute:
                continue
            self.pos[n] = self.new_var(f"p_{n}", "POINT", "pair" if n in fixed.joints else "point", n, self.xy(n))
        self.tied[fixed.name] = [n for n in self.own(fixed.name)]
        angle = wrap_angle(self.topo.direction(fixed.name).angle)
        frame = self.new_var(f"phi_{fixed.name}", "ANGLE", "link", fixed.name, (angle,))
        self.orient[fixed.name] = self.angles[fixed.name] = frame
        self.placed.add(fixed.name)
        for inp, value in zip(self.m.inputs, self.topo.sketch_inputs):
            kind = "ANGLE" if inp.kind == "revolute" else "VARIABLE"
            self.inputs.append(self.new_var(f"in{inp.index + 1}", kind, "input", inp.column, sketch=(value,)))
            if inp.kind == "distance":
                self.carriers.append(Carrier(inp.column, "actuator", inp.between, self.inputs[-1]))
        self.emit("fixed", "", [], [], fixed.name, links=(fixed.name,),
                  reason=f"link {fixed.name} is the frame: its pairs are fixed")

    def try_inputs(self) -> bool:
        for inp in self.m.inputs:
            if inp.index not in self.applied and self.apply_input(inp):
                self.applied.add(inp.index)
                return True
        return False

    def apply_input(self, inp: Input) -> bool:
        var = self.inputs[inp.index]
        if inp.kind == "revolute":
            if inp.link in self.placed or inp.joint not in self.pos or inp.relative_to not in self.placed:
                return False
            drive = input_direction(self.m, self.link(inp.link), inp.joint)
            ref = self.reference(inp, reference_angle(self.m, inp))
            target = drive.target
            if target in {j.name for j in self.m.joints}:
                target = self.copy(target, inp.link)
            out = self.point_var(target, self.role(target)) if "@" not in target else \
                self.new_var(f"g_{drive.target}", "POINT", "guide", drive.target, sketch=self.xy(target))
            (xj, yj), (xa, ya) = self.xy(inp.joint), self.xy(target)
            self.pos[target] = out
            self.tied[inp.link] = [inp.joint, target]
            self.emit("input", "crank_input",
                      [Arg("var", self.pos[inp.joint]), Arg("real", value=math.hypot(xa - xj, ya - yj), label="l"),
                       Arg("var", var), Arg("var", ref)], [out], drive.target, pairs=(inp.joint,),
                      links=(inp.link, inp.relative_to),
                      reason=f"{inp.joint} is known and link {inp.relative_to} is placed, so the input angle "
                             f"{inp.column} turns link {inp.link} to {drive.target}")
            return True
        if inp.kind == "prismatic":
            if inp.relative_to not in self.placed or inp.link in self.placed:
                return False
            g, psi = self.line(inp.joint)
            j = self.m.joint(inp.joint)
            other = next((n for n in self.own(inp.link) if n != inp.joint), inp.joint)
            gsi, eta = _rot(j.axis, *(a - b for a, b in zip(self.xy(other), self.xy(inp.joint))))
            jp = self.point_var(inp.joint)
            self.pos[inp.joint] = jp
            outs = [jp]
            if other != inp.joint:
                self.pos[other] = self.point_var(other, self.role(other))
                outs.append(self.pos[other])
            else:
                outs.append(self.new_var(f"p_{inp.joint}_copy", "POINT", "pair", inp.joint, sketch=self.xy(other)))
            self.slides[inp.joint] = var
            self.tied[inp.link] = [inp.joint] + ([other] if other != inp.joint else [])
            self.emit("input", "slider_input",
                      [Arg("var", g), Arg("var", psi), Arg("var", var), Arg("real", value=gsi, label="gsi"),
                       Arg("real", value=eta, label="eta")], outs, inp.joint, pairs=(inp.joint,),
                      links=(inp.link, inp.relative_to),
                      reason=f"the guide {inp.relative_to} of {inp.joint} is placed, so the input displacement "
                             f"{inp.column} moves the slider {inp.link}")
            return True
        return False  # a distance input acts as a link of variable length in the chains

    def reference(self, inp: Input, root_angle: float) -> str:
        """The ANGLE of the reference link seen from the input pair."""
        name = f"ref_{inp.joint}"
        if self.link(inp.relative_to).fixed:
            return self.new_var(name, "ANGLE", "reference", inp.joint, (wrap_angle(root_angle),))
        base = self.frame(inp.relative_to)
        off = wrap_angle(root_angle - self.angle0(base))
        if off == 0.0:
            return base
        var = self.new_var(name, "ANGLE", "reference", inp.joint, sketch=(wrap_angle(root_angle),))
        self.emit("angle", "offset_angle", [Arg("var", base), Arg("real", value=off, label="off")], [var], inp.joint,
                  links=(inp.relative_to,), reason=f"the input at {inp.joint} is measured from this direction of "
                                                   f"link {inp.relative_to}")
        return var

    def role(self, name: str) -> str:
        return "pair" if name in {j.name for j in self.m.joints} else "point"

    def try_point(self, pair: str) -> bool:
        """An unknown revolute pair on a placed link: coupler_point."""
        if not self.m.joint(pair).revolute:
            return False
        for lk in self.m.links_of(pair):
            if lk.name in self.placed:
                frame = self.frame(lk.name)
                self.pos[pair] = self.point_var(pair)
                self.tied[lk.name].append(pair)
                self.point_on(lk.name, pair, self.pos[pair], frame,
                              f"link {lk.name} is placed (its pairs {', '.join(self.tied[lk.name][:2])} are known), "
                              f"so {pair} follows as a point of it")
                return True
        return False

    def ends(self, carrier: Carrier, middle: str) -> list[tuple[str, str]]:
        """Known ends of a carrier for a chain through ``middle``: (pair, 'R' | 'P')."""
        if carrier.kind == "link" and carrier.name in self.placed:
            return []
        out = []
        for p in carrier.pairs:
            if p == middle:
                continue
            if self.m.joint(p).revolute:
                if p in self.pos:
                    out.append((p, "R"))
            elif carrier.kind == "link":
                pr = self.m.prismatic_of(p)
                if pr.slider == carrier.name and pr.guide in self.placed:
                    out.append((p, "P"))
        return out

    def carriers_of(self, pair: str) -> list[Carrier]:
        return [c for c in self.carriers if pair in c.pairs and (c.kind == "link" or c.name not in self.used)]

    def try_chain(self, pair: str, only: str = "") -> bool:
        """The pair as the middle of a two-link chain whose two ends are known."""
        carriers = [c for c in self.carriers_of(pair) if not (c.kind == "link" and c.name in self.placed)]
        joint = self.m.joint(pair)
        if not joint.revolute:
            pr = self.m.prismatic_of(pair)
            carriers = [c for c in carriers if c.name in (pr.guide, pr.slider)]
        for i, a in enumerate(carriers):
            for b in carriers[i + 1:]:
                if only and only not in (a.name, b.name):
                    continue
                for e1, t1 in self.ends(a, pair):
                    for e2, t2 in self.ends(b, pair):
                        if e1 == e2:
                            continue
                        kind = t1 + ("R" if joint.revolute else "P") + t2
                        if kind == "PPP":
                            continue
                        if self.chain(kind, pair, a, e1, b, e2):
                            return True
        return False

    def chain(self, kind: str, x: str, a: Carrier, e1: str, b: Carrier, e2: str) -> bool:
        if kind == "RRR":
            return self.rrr(x, a, e1, b, e2)
        if kind in ("RRP", "PRR"):
            return self.prr(x, *((a, e1, b, e2) if kind == "RRP" else (b, e2, a, e1)))
        if kind == "PRP":
            return self.prp(x, a, e1, b, e2)
        if kind == "RPR":
            return self.rpr(x, a, e1, b, e2)
        if kind in ("PPR", "RPP"):
            return self.ppr(x, *((a, e1, b, e2) if kind == "PPR" else (b, e2, a, e1)))
        return False

    def mark(self, x: str, *carriers: Carrier) -> None:
        for c in carriers:
            if c.kind == "link":
                if x not in self.tied[c.name]:
                    self.tied[c.name].append(x)
            else:
                self.used.add(c.name)

    def branch_note(self, sign: int, sketch: float, what: str) -> str:
        if sketch == 0.0:
            return f"the sketch draws this chain at a toggle ({what} is zero); branch {sign:+d} is taken"
        return f"the sketch has {what} {'positive' if sign > 0 else 'negative'}, so branch {sign:+d}"

    def rrr(self, x: str, a: Carrier, e1: str, b: Carrier, e2: str) -> bool:
        p1, p2, px = self.xy(e1), self.xy(e2), self.xy(x)
        side = _side(p1, p2, px)
        sign = _sign(side)
        l1, l2 = self.length_of(a.name, e1, x), self.length_of(b.name, x, e2)
        self.pos[x] = self.point_var(x)
        self.mark(x, a, b)
        self.emit("chain", "RRR_links",
                  [Arg("var", self.pos[e1]), Arg("var", self.pos[e2]), Arg("var", l1), Arg("var", l2),
                   Arg("int", value=sign, label="minv")], [self.pos[x]], x, chain="RRR", pairs=(e1, e2),
                  links=(a.name, b.name), branch=sign, fails=True,
                  reason=f"{x} is joined to the known {e1} by {a.name} and to the known {e2} by {b.name}: "
                         "a 3R two-link chain with both ends known",
                  branch_reason=self.branch_note(sign, side, f"{x} on the left of {e1}->{e2}"))
        return True

    def prr(self, x: str, a: Carrier, er: str, b: Carrier, ep: str) -> bool:
        """a turns about the known revolute er; b slides on the known line of ep."""
        j = self.m.joint(ep)
        g, psi = self.line(ep)
        pr, px, pp = self.xy(er), self.xy(x), self.xy(ep)
        along = (px[0] - pr[0]) * exact.cos(j.axis) + (px[1] - pr[1]) * exact.sin(j.axis)
        sign = _sign(along)
        gsi, eta = _rot(j.axis, px[0] - pp[0], px[1] - pp[1])
        length = self.length_of(a.name, er, x)
        self.pos[x] = self.point_var(x)
        self.pos[ep] = self.point_var(ep)
        s = self.new_var(f"s_{ep}", "VARIABLE", "slide", ep, sketch=(0.0,))
        self.slides[ep] = s
        self.mark(x, a, b)
        self.mark(ep, b)
        self.emit("chain", "PRR_links",
                  [Arg("var", self.pos[er]), Arg("var", length), Arg("var", g), Arg("var", psi),
                   Arg("real", value=gsi, label="gsi"), Arg("real", value=eta, label="eta"),
                   Arg("int", value=sign, label="minv")], [s, self.pos[ep], self.pos[x]], x, chain="RRP",
                  pairs=(er, ep), links=(a.name, b.name), branch=sign, fails=True,
                  reason=f"{x} is joined to the known {er} by {a.name} and rides on the slider {b.name} of the "
                         f"known line {ep}: a 2R1P two-link chain with both ends known",
                  branch_reason=self.branch_note(sign, along, f"{x} ahead of {er} along the axis of {ep}"))
        return True

    def prp(self, x: str, a: Carrier, e1: str, b: Carrier, e2: str) -> bool:
        args: list[Arg] = []
        outs: list[str] = []
        for e in (e1, e2):
            j = self.m.joint(e)
            g, psi = self.line(e)
            gsi, eta = _rot(j.axis, *(p - q for p, q in zip(self.xy(x), self.xy(e))))
            args += [Arg("var", g), Arg("var", psi), Arg("real", value=gsi, label="gsi"),
                     Arg("real", value=eta, label="eta")]
            self.slides[e] = self.new_var(f"s_{e}", "VARIABLE", "slide", e, sketch=(0.0,))
            self.pos[e] = self.point_var(e)
            outs += [self.slides[e], self.pos[e]]
        self.pos[x] = self.point_var(x)
        outs.append(self.pos[x])
        self.mark(x, a, b)
        self.mark(e1, a)
        self.mark(e2, b)
        self.emit("chain", "PRP_links", args, outs, x, chain="PRP", pairs=(e1, e2), links=(a.name, b.name),
                  fails=True, reason=f"{x} joins the slider {a.name} on the known line {e1} and the slider {b.name} "
                                     f"on the known line {e2}: a 1R2P two-link chain (one solution)")
        return True

    def rpr(self, x: str, a: Carrier, e1: str, b: Carrier, e2: str) -> bool:
        pr = self.m.prismatic_of(x)
        if {a.name, b.name} != {pr.guide, pr.slider}:
            return False
        (eg, es) = (e1, e2) if a.name == pr.guide else (e2, e1)
        j = self.m.joint(x)
        ag, bg = _rot(j.axis, *(p - q for p, q in zip(self.xy(x), self.xy(eg))))
        as_, bs = _rot(j.axis, *(p - q for p, q in zip(self.xy(x), self.xy(es))))
        d = (self.xy(es)[0] - self.xy(eg)[0], self.xy(es)[1] - self.xy(eg)[1])
        along = d[0] * exact.cos(j.axis) + d[1] * exact.sin(j.axis)
        sign = _sign(along)
        psi = self.new_var(f"psi_{x}", "ANGLE", "line", x, sketch=(wrap_angle(j.axis),))
        s = self.new_var(f"s_{x}", "VARIABLE", "slide", x, sketch=(0.0,))
        self.pos[x] = self.point_var(x)
        self.slides[x] = s
        self.orient[pr.guide] = self.orient[pr.slider] = psi
        self.mark(x, self.carrier(pr.slider))
        self.emit("chain", "RPR_links",
                  [Arg("var", self.pos[eg]), Arg("var", self.pos[es]), Arg("real", value=ag, label="ag"),
                   Arg("real", value=bg, label="bg"), Arg("real", value=as_, label="as"),
                   Arg("real", value=bs, label="bs"),
                   Arg("int", value=sign, label="minv")], [psi, s, self.pos[x]], x, chain="RPR", pairs=(eg, es),
                  links=(pr.guide, pr.slider), branch=sign, fails=True,
                  reason=f"the guide {pr.guide} turns about the known {eg} and the slider {pr.slider} about the "
                         f"known {es}, sliding along one line at {x}: an RPR two-link chain with both ends known",
                  branch_reason=self.branch_note(sign, along, f"{es} ahead of {eg} along the axis of {x}"))
        return True

    def ppr(self, x: str, b: Carrier, ep: str, a: Carrier, er: str) -> bool:
        """b slides on the known line of ep; a turns about the known er; x joins them."""
        px = self.m.prismatic_of(x)
        if {a.name, b.name} != {px.guide, px.slider}:
            return False
        je, jx = self.m.joint(ep), self.m.joint(x)
        if exact.sin(jx.axis - je.axis) == 0.0:
            return False  # parallel slides: the chain cannot fix the position
        g, psi = self.line(ep)
        xa, ya = _rot(je.axis, *(p - q for p, q in zip(self.xy(x), self.xy(er))))
        xb, yb = _rot(je.axis, *(p - q for p, q in zip(self.xy(x), self.xy(ep))))
        sgn = 1 if px.slider == a.name else -1
        s1 = self.new_var(f"s_{ep}", "VARIABLE", "slide", ep, sketch=(0.0,))
        sx = self.new_var(f"s_{x}", "VARIABLE", "slide", x, sketch=(0.0,))
        self.pos[ep] = self.point_var(ep)
        self.pos[x] = self.point_var(x)
        self.slides[ep], self.slides[x] = s1, sx
        self.orient[a.name] = psi
        self.mark(ep, b)
        self.mark(x, self.carrier(px.slider))
        self.emit("chain", "PPR_links",
                  [Arg("var", self.pos[er]), Arg("var", g), Arg("var", psi), Arg("real", value=xa, label="xa"),
                   Arg("real", value=ya, label="ya"), Arg("real", value=xb, label="xb"),
                   Arg("real", value=yb, label="yb"),
                   Arg("real", value=wrap_angle(jx.axis - je.axis), label="cx"), Arg("int", value=sgn, label="sgn")],
                  [s1, self.pos[ep], sx, self.pos[x]], x, chain="PPR", pairs=(ep, er), links=(b.name, a.name),
                  fails=True, reason=f"the slider {b.name} rides on the known line {ep} and carries the slide {x} of "
                                     f"{a.name}, which turns about the known {er}: a PPR two-link chain (one solution)")
        return True

    # -- the Solver loop -----------------------------------------------------------
    def progress(self) -> bool:
        """One Solver action; False when nothing is computable."""
        if self.try_inputs():
            return True
        for j in self.m.joints:
            if not self.is_known(j.name) and (self.try_point(j.name) or self.try_chain(j.name)):
                return True
        return False

    def solve(self, stop_at_close: bool = False) -> bool:
        """Run the Solver until every pair is known (True) or nothing is computable (False)."""
        while True:
            open_group = self.group
            if not self.progress():
                return all(self.is_known(j.name) for j in self.m.joints)
            if stop_at_close and open_group and not self.group:
                return True

    def finish(self) -> None:
        for p in self.m.prismatic:
            if p.joint not in self.slides:
                raise Unsupported(f"the prismatic pair {p.joint} is not used by any chain")
        for lk in self.m.links:
            for pt in lk.points:
                if pt.name not in self.pos:
                    frame = self.frame(lk.name)
                    self.pos[pt.name] = self.point_var(pt.name, "point")
                    self.point_on(lk.name, pt.name, self.pos[pt.name], frame, f"point {pt.name} of link {lk.name}")
        for lk in self.m.links:
            self.link_angle(lk.name)

    def link_angle(self, link: str) -> None:
        """The link's own angle (its direction from the sketch), for the outputs."""
        if link in self.angles:
            return
        d = self.topo.direction(link)
        if link in self.orient or link in self.coupled:
            base = self.frame(link)
            off = wrap_angle(d.angle - self.angle0(base))
            if off == 0.0:
                self.angles[link] = base
                return
            var = self.new_var(f"phi_{link}", "ANGLE", "link", link, sketch=(wrap_angle(d.angle),))
            self.emit("angle", "offset_angle", [Arg("var", base), Arg("real", value=off, label="off")], [var], link,
                      links=(link,), reason=f"link {link} keeps a constant angle to its slide")
            self.angles[link] = var
            return
        self.angles[link] = self.frame(link)


def _probe(topo: Topology) -> tuple[float, ...]:
    return tuple(
        v + (PROBE_ANGLE if i.kind == "revolute" else PROBE_LENGTH * topo.length_scale)
        for i, v in zip(topo.mechanism.inputs, topo.sketch_inputs)
    )


def _rounded(norm: float | None) -> float | None:
    """Norms to 33 significant bits (10 digits): the runtime's trigonometry differs in the
    last digits between machines, and candidates with equal norms must tie everywhere.
    Binary digits, so that a sketch scaled by 2^k ranks its candidates the same (decimal
    digits broke a four-way tie differently at two scales: triad_1953)."""
    if norm is None:
        return None
    mantissa, exponent = math.frexp(norm)
    return math.ldexp(round(mantissa * 2.0**33) / 2.0**33, exponent)


def candidates(ex: Extractor) -> list[tuple[str, str]]:
    """Add-link candidates by section 3.3.1: a known pair K and an unknown pair U already
    joined to another known pair by a link, K and U on no common link; K first."""
    joints = ex.m.joints
    known = [j.name for j in joints if j.revolute and j.name in ex.pos]
    out = []
    for k in known:
        for u in (j.name for j in joints if j.revolute and j.name not in ex.pos):
            carriers = ex.carriers_of(u)
            if any(k in c.pairs for c in carriers):
                continue
            if any(e != k for c in carriers for e, _ in ex.ends(c, u)):
                out.append((k, u))
    return out


def install(ex: Extractor, k: str, u: str) -> None:
    """Install the Add-link k-u and compute u through it."""
    if not ex.group:
        ex.groups.append(_GroupDraft(len(ex.groups) + 1))
        ex.group = ex.groups[-1].number
    n = len(ex.add_links) + 1
    (xk, yk), (xu, yu) = ex.xy(k), ex.xy(u)
    length = math.hypot(xu - xk, yu - yk)
    name = f"add{n}"
    var = ex.new_var(name, "VARIABLE", "addlink", name, sketch=(length,))
    ex.carriers.append(Carrier(name, "addlink", (k, u), var))
    ex.columns.append(LJColumn(name, "addlink", (k, u), ""))
    ex.add_links.append(_AddLinkDraft(name, var, (k, u), length, ex.group))
    ex.groups[-1].add_links.append(var)
    ex.emit("add_link", "", [], [var], name, pairs=(k, u), links=(name,),
            reason=f"no two-link chain is computable, so the Add-link {name} joins the known {k} to the unknown {u}")
    if not ex.try_chain(u, only=name):
        raise Unsupported(f"the Add-link {k}-{u} does not complete a chain")


class _Trial(NamedTuple):
    """One Add-link candidate tried: its rank key first (usable, a norm, a good lever, the norm, order)."""

    unusable: bool
    no_norm: bool
    poor_lever: bool
    norm_key: float
    index: int
    pairs: tuple[str, str]
    norm: float | None
    usable: bool
    lever: float | None
    extractor: Extractor | None


def rank(ex: Extractor, evaluate_norm) -> tuple[Extractor, _AddLinkDraft]:
    """Try every candidate; keep the one with the smallest norm of f at the probe among
    those whose lever is at least GOOD_LEVER (else among all)."""
    probe = _probe(ex.topo)
    tried = []
    for index, (k, u) in enumerate(candidates(ex)):
        trial: Extractor | None = copy.deepcopy(ex)
        usable, norm, lever = False, None, None
        try:
            install(trial, k, u)
            trial.solve(stop_at_close=True)
            usable = not trial.group
            if usable:
                norm = _rounded(evaluate_norm(trial, probe))
                lever = _placement_lever(trial.steps[len(ex.steps):], trial.steps, trial.variables)
        except Unsupported:
            trial = None
        tried.append(_Trial(not usable, norm is None, lever is None or lever < GOOD_LEVER,
                            norm if norm is not None else 0.0, index, (k, u), norm, usable, lever, trial))
    if not tried:
        raise Unsupported("no Add-link candidate exists")
    tried.sort(key=lambda t: t[:5])
    best = tried[0]
    if best.extractor is None:
        raise Unsupported("no Add-link candidate completes a chain")
    chosen: Extractor = best.extractor
    draft = next(d for d in chosen.add_links if d.pairs == best.pairs and not d.candidates)
    draft.candidates = tuple(Candidate(t.pairs, t.norm, t.usable, t.lever) for t in tried)
    draft.probe = probe
    start = len(ex.steps)
    others = [t for t in tried[1:] if t.usable and t.extractor is not None
              and len(t.extractor.add_links) == len(chosen.add_links)]
    for t in others[:MAX_VARIANTS]:
        trial = t.extractor
        new = {name: v for name, v in trial.variables.items() if name not in ex.variables}
        chosen.variants.append(_VariantDraft(chosen.groups[-1].number, t.pairs, trial.add_links[-1].length,
                                             trial.steps[start:], new))
    return chosen, draft


def extract(topo: Topology, evaluate_norm) -> Procedure:
    """Run the Solver, installing Add-links where it stops, and finish with angles and points.

    ``evaluate_norm(extractor, inputs)`` returns the norm of the open group's
    residuals with every Add-link at its sketch length (see ``evaluate``).
    """
    ex = Extractor(topo)
    try:
        ex.start()
        while not ex.solve():
            ex, _ = rank(ex, evaluate_norm)
        if ex.group:
            raise Unsupported("an Add-link group is left open")
        ex.finish()
    except Unsupported as exc:
        m = topo.mechanism
        raise ProcedureError(f"linkgen cannot extract a procedure for this mechanism: {exc}",
                             m.path, m.where.line, "links") from None
    return _freeze(ex)


def _freeze(ex: Extractor) -> Procedure:
    """Number the steps and turn the drafts into step-log records."""
    steps = [replace(s, number=i + 1) for i, s in enumerate(ex.steps)]
    residuals = tuple(replace(r, step=next(s.number for s in steps if r.name in s.outputs)) for r in ex.residuals)
    add_links = tuple(
        AddLink(d.name, d.pairs, d.length,
                next(s.number for s in steps if s.action == "add_link" and s.target == d.name), d.candidates, d.probe)
        for d in ex.add_links
    )
    variables = dict(ex.variables)
    groups = []
    for g in ex.groups:
        block = [s for s in steps if s.group == g.number and s.action not in ("add_link", "resolve")]
        resolve = next(s for s in steps if s.group == g.number and s.action == "resolve")
        later = {a.var for s in steps if s.number > resolve.number for a in s.args if a.kind == "var"}
        needed = {o for s in block for o in s.outputs} & (later | set(ex.pos.values()) | set(ex.angles.values())
                                                          | set(ex.slides.values()))
        variants = []
        for draft in (d for d in ex.variants if d.group == g.number):
            variant = _variant(draft, len(variants) + 1, len(steps), variables, needed)
            if variant is not None:
                vsteps, vgroup = variant
                steps += vsteps
                variants.append(vgroup)
        adds = [a for a in add_links if a.name in g.add_links]
        main = replace(_block_group(g.number, 0, block, tuple(g.add_links), tuple(g.residuals), variables),
                       step=resolve.number, pairs=tuple(a.pairs for a in adds), lengths=tuple(a.length for a in adds))
        by_number = {s.number: s for s in steps}
        main, *variants = (replace(b, lever=_lever(b, by_number, variables)) for b in (main, *variants))
        groups.append(_with_branch_signs(main, variants, by_number, variables))
    lj = LJMatrix(tuple(j.name for j in ex.m.joints), tuple(not j.revolute for j in ex.m.joints),
                  tuple(ex.columns), ())
    return Procedure(tuple(variables.values()), tuple(steps), lj, add_links, residuals, tuple(groups),
                     dict(ex.pos), dict(ex.angles), dict(ex.slides))


def _with_branch_signs(main: ResolverGroup, variants: list[ResolverGroup], steps: dict[int, Step],
                       variables: dict[str, Variable]) -> ResolverGroup:
    """The group with its fallbacks, every block knowing how to read its chains' branches
    off a solved configuration (so that any block can take over where the assembly has
    moved: its chains' branches are those of the configuration, not of the sketch)."""
    blocks = (main, *variants)
    every = set.intersection(*(set(b.writes) for b in blocks))

    def known(name: str, block: ResolverGroup) -> bool:
        return name in every or name in block.reads or variables[name].constant

    def signs(block: ResolverGroup) -> ResolverGroup:
        out = []
        for s in (steps[n] for n in block.steps):
            sign = _branch_sign(s)
            if sign is not None and all(known(v, block) for v in (*sign.points, sign.angle) if v):
                out.append(sign)
        return replace(block, branches=tuple(out))

    return replace(signs(main), variants=tuple(signs(v) for v in variants))


def _lever(block: ResolverGroup, steps: dict[int, Step], variables: dict[str, Variable]) -> float:
    """The block's lever: _placement_lever of its steps."""
    return _placement_lever([steps[n] for n in block.steps], list(steps.values()), variables)


def _placement_lever(block: list[Step], steps: list[Step], variables: dict[str, Variable]) -> float:
    """The worst ratio, over the block's point placements, of the base its frame angle is
    measured on to the arm of the placed point (at most 1).  A placement magnifies the
    angle's error by the inverse: a block that must turn a needle to place a far pair is
    a poor coordinate of the assembly, whatever its chains' conditioning."""
    producer = {o: s for s in steps for o in s.outputs}
    producer.update({o: s for s in block for o in s.outputs})  # fallback blocks write the same variables

    def base(frame: str) -> float | None:
        s = producer.get(frame)
        if s is None:
            return None
        if s.function == "offset_angle":
            return base(s.args[0].var)
        if s.function == "link_angle":
            (xa, ya), (xb, yb) = (variables[a.var].sketch[:2] for a in s.args[:2])
            return math.hypot(xb - xa, yb - ya)
        return None

    worst = 1.0
    for s in block:
        if s.function != "coupler_point":
            continue
        b = base(s.args[1].var)
        arm = math.hypot(s.args[2].value, s.args[3].value)
        if b is not None and arm > b:
            worst = min(worst, b / arm)
    return worst


def _branch_sign(s: Step) -> BranchSign | None:
    """How to read step s's branch off a configuration (None: it has no branch)."""
    if not s.branch:
        return None
    var = [a.var for a in s.args if a.kind == "var"]
    if s.function == "RRR_links":  # jb left of j1 -> j2
        return BranchSign(s.number, "side", (var[0], var[1], s.outputs[0]), "", s.branch)
    if s.function == "PRR_links":  # (jb - jr).u of the guide
        return BranchSign(s.number, "along", (var[0], s.outputs[2]), var[3], s.branch)
    if s.function == "RPR_links":  # (js - jg).u of the line
        return BranchSign(s.number, "along", (var[0], var[1]), s.outputs[0], s.branch)
    raise ValueError(f"no branch sign for {s.function}")


def _block_group(number: int, variant: int, block: list[Step], adds: tuple[str, ...], residuals: tuple[str, ...],
                 variables: dict[str, Variable]) -> ResolverGroup:
    """The resolver record of one block of steps (a group or one of its variants)."""
    writes = [o for s in block for o in s.outputs]
    reads: list[str] = []
    for s in block:
        for a in s.args:
            if (a.kind == "var" and a.var not in writes and a.var not in adds and a.var not in reads
                    and not variables[a.var].constant):
                reads.append(a.var)
    return ResolverGroup(number, 0, "newton-addlink", adds, residuals, tuple(s.number for s in block), tuple(reads),
                         tuple(writes), RESOLVER_TOLERANCE, RESOLVER_MAX_ITERATIONS, CONTINUATION_HALVINGS,
                         RESOLVER_MAX_MOVE, RESOLVER_MIN_CHAIN_SIGMA, variant=variant)


def _variant(draft: _VariantDraft, k: int, first: int, variables: dict[str, Variable],
             needed: set[str]) -> tuple[list[Step], ResolverGroup] | None:
    """A candidate's block as fallback k of its group: its own Add-link and residual records
    (renamed), the same records for everything the rest of the procedure reads."""
    rename = {}
    for name, v in draft.variables.items():
        same = name in variables and (variables[name].kind, variables[name].value) == (v.kind, v.value)
        if v.role in ("addlink", "residual") or (name in variables and not same):
            rename[name] = f"{name}_v{k}"
    block = [s for s in draft.steps if s.action not in ("add_link", "resolve")]
    writes = {rename.get(o, o) for s in block for o in s.outputs}
    if not needed <= writes:
        return None
    for name, v in draft.variables.items():
        variables.setdefault(rename.get(name, name), replace(v, name=rename.get(name, name)))
    out = []
    for s in block:
        args = tuple(replace(a, var=rename.get(a.var, a.var)) if a.kind == "var" else a for a in s.args)
        outputs = tuple(rename.get(o, o) for o in s.outputs)
        out.append(replace(s, number=first + len(out) + 1, args=args, outputs=outputs, group=draft.steps[0].group,
                           variant=k))
    adds = tuple(rename[v.name] for v in draft.variables.values() if v.role == "addlink")
    residuals = tuple(rename[v.name] for v in draft.variables.values() if v.role == "residual")
    group = replace(_block_group(draft.group, k, out, adds, residuals, variables), pairs=(draft.pairs,),
                    lengths=(draft.length,))
    return out, group
