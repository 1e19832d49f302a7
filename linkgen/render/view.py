"""What every template needs, derived from the step log alone (no language here).

The view groups the procedure into the blocks a program is made of: the
constants taken from the sketch, the records the procedure computes, the run
(steps in the manual's order, each resolver as one block), the resolver groups
with the records they read from outside, and the public outputs.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from .. import status
from ..steplog import Column, ResolverGroup, Step, StepLog, Variable
from ..units import angular_inputs, factor

if TYPE_CHECKING:  # the closure strategy's: imported where a group has one
    from ..closurelog import Closure
    from .closure import Plan

CENTRE_LINKS = 20  # links of a mechanism whose instant centres the manual lists (n(n-1)/2 of them: 190)


@dataclass(frozen=True)
class Output:
    """One named output of the public state: a pair or point, a link, or a prismatic
    pair (its position and its slide displacement together)."""

    name: str
    kind: str  # point | angle | prismatic | direction | centre
    columns: tuple[Column, ...]
    kinds: tuple[str, ...]  # record kind (POINT, ANGLE, VARIABLE) of each column's variable

    @property
    def fields(self) -> tuple[tuple[str, Column, str], ...]:
        """(public field, column, record kind): x, vx, ... phi, omega, ... s, ds, ..."""
        return tuple((c.name.split(".", 1)[1], c, k) for c, k in zip(self.columns, self.kinds))


@dataclass(frozen=True)
class Cell:
    """One output column of the CSV: its owner's public field."""

    owner: str
    field: str  # public field: x, vx, phi, s, ...
    column: Column
    kind: str  # record kind of the column's variable


@dataclass(frozen=True)
class Group:
    """One resolver block: a group's chosen Add-link candidate (variant 0) or a fallback."""

    group: ResolverGroup  # the block's own record
    steps: tuple[Step, ...]
    reads: tuple[Variable, ...]  # computed before the group: copied, rates zeroed on Jacobian passes
    resolve: Step  # the group's resolve step
    index: int  # among all blocks
    slot: int  # its group's index among the groups the program computes
    first: int  # index of its group's first block
    count: int  # blocks of its group
    ends: tuple[tuple[str, str], ...]  # position variables of each Add-link's pairs
    bent: tuple[tuple[str, str], ...]  # (name, kind) of the records it sets, Add-links first: their accelerations
    # are the rates pass's plus the Add-links' accelerations times their sensitivities (linear in them)

    @property
    def size(self) -> int:
        """Add-links of the block: its state holds their lengths, then its chains' branches."""
        return len(self.group.add_links)

    @property
    def loop(self) -> bool:
        """Whether the block is a loop block (strategy loop, extraction.loops): its state is an assumed
        angle as the arc length of the leg its first step places, read off the pairs as one."""
        return bool(self.steps) and self.steps[0].function == "loop_point"

    @property
    def arm(self) -> str:
        """A loop block's leg length record (the arc length's radius; "" for an Add-link block)."""
        return self.steps[0].args[1].var if self.loop else ""

    @property
    def suffix(self) -> str:
        """Names the block's function: 1 for group 1, 1_v2 for its second fallback."""
        k = self.group.variant
        return f"{self.group.number}" + (f"_v{k}" if k else "")


@dataclass(frozen=True)
class View:
    log: StepLog
    constants: tuple[Variable, ...]
    records: tuple[Variable, ...]  # computed records, inputs first
    run: tuple[Step, ...]  # the steps executed in order; a resolve step stands for its group
    groups: tuple[Group, ...]  # the chosen block of each resolver group
    blocks: tuple[Group, ...]  # every block, fallbacks after their group's chosen one
    outputs: tuple[Output, ...]
    cells: tuple[Cell, ...]  # output columns in CSV order
    inputs: tuple[Variable, ...]
    sigma_steps: tuple[int, ...]  # steps that report a conditioning
    nmax: int  # the largest block state (Add-link lengths, measured branches, orientation), with the closure
    # strategy at least its largest group's Newton unknowns (its Jacobian is solved as the Add-links' is)
    record_order: int  # derivative order of the records: a resolver needs velocities for its Jacobian

    @property
    def degree_inputs(self) -> tuple[int, ...]:
        """The inputs the programs take in degrees (options.units file, linkgen.units): solve()
        divides them by DEGREE before it computes."""
        return angular_inputs(self.log)

    @property
    def angle_words(self) -> str:
        """The unit the programs take and give angles in: degrees with units: file (linkgen.units), else radians."""
        return "degrees" if factor(self.log) else "radians"

    @property
    def checks(self) -> bool:
        """Whether the program reports singular and near-singular steps and every step's
        conditioning (options.checks; off: positions and rates, status 0 or a failure)."""
        return self.log.options.checks

    @property
    def measures(self) -> bool:
        """Whether the chains measure their conditioning: with the checks, or where a resolver
        picks its block by it."""
        return self.checks or bool(self.groups)

    def resolver_of_group(self, number: int) -> Group:
        return next(g for g in self.groups if g.group.number == number)

    def resolver(self, step: int) -> Group:
        """The group whose resolver is this step."""
        return next(g for g in self.groups if g.resolve.number == step)

    @property
    def measured(self) -> frozenset[int]:
        """Steps whose branch a block reads off the last solution (a work field each)."""
        return frozenset(b.step for g in self.blocks for b in g.group.branches)

    @property
    def closure(self) -> bool:
        """Whether the resolvers solve their groups' loop-closure equations (strategy closure)."""
        return bool(self.groups) and self.groups[0].group.closure is not None

    def closure_plan(self, group: Group) -> Plan:
        """How the programs compute a group's loop-closure equations (render.closure)."""
        assert group.group.closure is not None
        return _closure_plan(group.group.closure)

    def blocks_of(self, group: Group) -> tuple[Group, ...]:
        return self.blocks[group.first:group.first + group.count]

    @property
    def failures(self) -> tuple[int, ...]:
        """The reasons of a status whose row has no outputs, of those the programs report."""
        return status.failures(self.log.options.strategy if self.groups else None)

    @property
    def last_step(self) -> int:
        """The largest step number (the size of the per-step arrays)."""
        return max(s.number for s in self.log.steps)

    @property
    def main_steps(self) -> tuple[Step, ...]:
        """The procedure's steps, without the fallback blocks."""
        return tuple(s for s in self.log.steps if not s.variant)


def _outputs(log: StepLog) -> tuple[Output, ...]:
    """Outputs in column order, each with its columns (an output appears once)."""
    grouped: dict[str, list[Column]] = {}
    for c in log.columns[len(log.inputs):]:
        grouped.setdefault(c.name.split(".")[0], []).append(c)
    out = []
    for name, cols in grouped.items():
        kinds = tuple(log.variable(c.variable).kind for c in cols)
        kind = "angle" if kinds[0] == "ANGLE" else "prismatic" if "VARIABLE" in kinds else "point"
        kind = "direction" if log.variable(cols[0].variable).role == "direction" else kind
        kind = "centre" if kinds[0] == "CENTRE" else kind
        out.append(Output(name, kind, tuple(cols), kinds))
    return tuple(out)


def build_view(log: StepLog) -> View:
    inside = {n for g in log.groups for n in g.steps}
    run = tuple(s for s in log.steps if s.number not in inside and not s.variant)
    pos = {v.entity: v.name for v in log.variables if v.role == "pair"}
    blocks: list[Group] = []
    for slot, g in enumerate(log.groups):
        first = len(blocks)
        records = (g, *g.variants)
        for b in records:
            blocks.append(Group(b, tuple(log.step(n) for n in b.steps), tuple(log.variable(v) for v in b.reads),
                                log.step(g.step), len(blocks), slot, first, len(records),
                                tuple((pos[k], pos[u]) for k, u in b.pairs),
                                tuple((n, log.variable(n).kind) for n in b.sets)))
    inputs = tuple(v for v in log.variables if v.role == "input")
    used = {a.var for s in log.steps for a in s.args if a.kind == "var"}
    used |= {name for b in blocks for pair in b.ends for name in pair}  # (constant outputs are published as drawn)
    live = used | {c.variable for c in log.columns} | {o for s in log.steps for o in s.outputs}
    computed = tuple(v for v in log.variables if not v.constant and v.role != "input" and v.name in live)
    return View(
        log,
        tuple(v for v in log.variables if v.constant and v.name in used),
        inputs + computed,
        run,
        tuple(b for b in blocks if not b.group.variant),
        tuple(blocks),
        _outputs(log),
        tuple(Cell(c.name.split(".")[0], c.name.split(".", 1)[1], c, log.variable(c.variable).kind)
              for c in log.columns[len(log.inputs):]),
        inputs,
        tuple(s.number for s in log.steps if s.fails),
        max([len(b.group.add_links) + len(b.group.branches) + 1 for b in blocks]
            + [2 * len(_closure_plan(g.closure).unknowns) for g in log.groups if g.closure], default=1),
        max(log.order, 1) if log.groups else log.order,
    )


def _closure_plan(closure: Closure) -> Plan:
    """render.closure's plan of a group's loop-closure equations (imported where a group has them)."""
    from .closure import plan

    return plan(closure)
