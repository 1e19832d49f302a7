"""What every template needs, derived from the step log alone (no language here).

The view groups the procedure into the blocks a program is made of: the
constants taken from the sketch, the records the procedure computes, the run
(steps in the manual's order, each resolver as one block), the resolver groups
with the records they read from outside, and the public outputs.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..steplog import Column, ResolverGroup, Step, StepLog, Variable

KIND_OF_OUTPUT = {"POINT": "point", "ANGLE": "angle", "VARIABLE": "slide"}


@dataclass(frozen=True)
class Output:
    """One named output of the public state: a pair, point, link or slider."""

    name: str
    kind: str  # point | angle | slide
    variable: Variable
    columns: tuple[Column, ...]

    @property
    def fields(self) -> tuple[tuple[str, Column], ...]:
        """(public field, column): x, vx, ... phi, omega, ... s, ds, ..."""
        return tuple((c.name.split(".", 1)[1], c) for c in self.columns)


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
    out: list[Output] = []
    seen: dict[str, int] = {}
    for c in log.columns[len(log.inputs):]:
        owner = c.name.split(".")[0]
        v = log.variable(c.variable)
        key = f"{owner}/{KIND_OF_OUTPUT[v.kind]}"
        if key not in seen:
            seen[key] = len(out)
            out.append(Output(owner, KIND_OF_OUTPUT[v.kind], v, ()))
        o = out[seen[key]]
        out[seen[key]] = Output(o.name, o.kind, o.variable, o.columns + (c,))
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
    return View(
        log,
        tuple(v for v in log.variables if v.constant),
        inputs + computed,
        run,
        tuple(groups),
        _outputs(log),
        inputs,
        tuple(s.number for s in log.steps if s.fails),
        max((len(g.add_links) for g in log.groups), default=1),
        max(log.order, 1) if log.groups else log.order,
    )
