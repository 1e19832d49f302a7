"""What every template needs, derived from the step log alone (no language here).

The view groups the procedure into the blocks a program is made of: the
constants taken from the sketch, the records the procedure computes, the run
(steps in the manual's order, each resolver as one block), the resolver groups
with the records they read from outside, and the public outputs.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..steplog import Column, ResolverGroup, Step, StepLog, Variable


@dataclass(frozen=True)
class Output:
    """One named output of the public state: a pair or point, a link, or a prismatic
    pair (its position and its slide displacement together)."""

    name: str
    kind: str  # point | angle | prismatic
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
    group: ResolverGroup
    steps: tuple[Step, ...]
    reads: tuple[Variable, ...]  # computed before the group: copied, rates zeroed on Jacobian passes
    resolve: Step
    first_add: int  # index of its first Add-link among all Add-links


@dataclass(frozen=True)
class View:
    log: StepLog
    constants: tuple[Variable, ...]
    records: tuple[Variable, ...]  # computed records, inputs first
    run: tuple[Step, ...]  # the steps executed in order; a resolve step stands for its group
    groups: tuple[Group, ...]
    outputs: tuple[Output, ...]
    cells: tuple[Cell, ...]  # output columns in CSV order
    inputs: tuple[Variable, ...]
    sigma_steps: tuple[int, ...]  # steps that report a conditioning
    nmax: int  # the largest resolver group
    record_order: int  # derivative order of the records: a resolver needs velocities for its Jacobian

    def resolver_of_group(self, number: int) -> Group:
        return next(g for g in self.groups if g.group.number == number)

    def resolver(self, step: int) -> Group:
        """The group whose resolver is this step."""
        return next(g for g in self.groups if g.resolve.number == step)


def _outputs(log: StepLog) -> tuple[Output, ...]:
    """Outputs in column order, each with its columns (an output appears once)."""
    grouped: dict[str, list[Column]] = {}
    for c in log.columns[len(log.inputs):]:
        grouped.setdefault(c.name.split(".")[0], []).append(c)
    out = []
    for name, cols in grouped.items():
        kinds = tuple(log.variable(c.variable).kind for c in cols)
        kind = "angle" if kinds[0] == "ANGLE" else "prismatic" if "VARIABLE" in kinds else "point"
        out.append(Output(name, kind, tuple(cols), kinds))
    return tuple(out)


def build_view(log: StepLog) -> View:
    inside = {n for g in log.groups for n in g.steps}
    run = tuple(s for s in log.steps if s.number not in inside)
    groups = []
    first = 0
    for g in log.groups:
        groups.append(Group(g, tuple(log.step(n) for n in g.steps), tuple(log.variable(v) for v in g.reads),
                            log.step(g.step), first))
        first += len(g.add_links)
    inputs = tuple(v for v in log.variables if v.role == "input")
    computed = tuple(v for v in log.variables if not v.constant and v.role != "input")
    used = {a.var for s in log.steps for a in s.args if a.kind == "var"} | {c.variable for c in log.columns}
    return View(
        log,
        tuple(v for v in log.variables if v.constant and v.name in used),
        inputs + computed,
        run,
        tuple(groups),
        _outputs(log),
        tuple(Cell(c.name.split(".")[0], c.name.split(".", 1)[1], c, log.variable(c.variable).kind)
              for c in log.columns[len(log.inputs):]),
        inputs,
        tuple(s.number for s in log.steps if s.fails),
        max((len(g.add_links) for g in log.groups), default=1),
        max(log.order, 1) if log.groups else log.order,
    )
