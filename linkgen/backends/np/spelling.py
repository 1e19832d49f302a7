"""How the numpy kernel spells the procedure: records are tuples of arrays (or numbers) in a
work object, and every number taken from the sketch is a design parameter ``c[name]``."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ... import status
from ...primitives import PRIMITIVES
from ...primitives.dsl import record_fields
from ...steplog import Arg, BranchSign, Column, Step, Variable
from ..py.spelling import Python
from ..spelling import Syntax

if TYPE_CHECKING:
    from ...render.view import Group, View


class Numpy(Python):
    syntax = Syntax(work="w.", file_constants=False, conditional="{a} if {cond} else {b}", change_list="({points},)",
                    booleans=("False", "True"))

    def __init__(self, view: View):
        super().__init__(view)
        self._measures: dict[int, list[tuple[str, str]]] = {}  # group_measures of each group's first block

    def param_names(self, v: Variable) -> list[str]:
        """The design parameters of a constant record's displacement fields: a pair's or a
        point's x and y by its name (O2.x), any other record by its own (l_coupler)."""
        name = v.entity if v.role in ("pair", "point") else v.name
        return [f"{name}.{f}" for f in record_fields(v.kind, 0)] if v.kind == "POINT" else [name]

    @staticmethod
    def step_param(step: Step, k: int) -> str:
        """The design parameter of a step's k-th argument, a number: the step and the runtime
        function's name of the parameter (step5.gsi; step4.gsi2 for PRP_links' second slider)."""
        return f"step{step.number}.{PRIMITIVES[step.function].params[k].name.rstrip('_')}"

    def params(self) -> list[tuple[str, float, str]]:
        """(name, sketch value, what it is) of every design parameter, constants first, then the
        steps' numbers."""
        out = []
        for v in (v for v in self.log.variables if v.constant):
            what = f"{v.role} {v.entity}" + (" (as drawn)" if v.kind == "POINT" else "")
            out += [(name, x, what) for name, x in zip(self.param_names(v), v.value)]
        for s in self.log.steps:
            for k, a in enumerate(s.args):
                if a.kind == "real":
                    out.append((self.step_param(s, k), float(a.value), f"step {s.number}: {s.function} of {s.target}"))
        names = [name for name, _, _ in out]
        if len(set(names)) != len(names):
            raise ValueError(f"{self.log.name}: two design parameters share a name")
        return out

    def arg(self, a: Arg, scope: Group | None, step: Step | None = None) -> str:
        if a.kind == "real" and step is not None:
            return f'c["{self.step_param(step, step.args.index(a))}"]'
        return super().arg(a, scope, step)

    def initializer(self, v: Variable) -> str:
        """A constant record from the design parameters: a point relative to the origin, rates 0."""
        shift = self.log.origin if v.kind == "POINT" else (0.0,)
        value = [f'c["{name}"] - {self.lit(o)}' if v.kind == "POINT" else f'c["{name}"]'
                 for name, o in zip(self.param_names(v), shift)]
        rates = ["0.0"] * (len(record_fields(v.kind, self.order)) - len(value))
        return "(" + ", ".join(value + rates) + ("," if len(value + rates) == 1 else "") + ")"

    def input_record(self, var: Variable, k: int) -> str:
        """The statement that builds an input record from the k-th input column, rate and acceleration."""
        fields = ", ".join(f"{src}[{k}]" for src in ("x", "dx", "ddx")[: self.order + 1])
        return f"w.{var.name} = ({fields}{',' if self.order == 0 else ''})"

    def published(self, c: Column) -> str:
        """A constant record's field as given (a design parameter; its rates 0), a computed
        point's x and y with the origin added back, any other field as computed."""
        v = self.log.variable(c.variable)
        if not v.constant:
            return super().published(c)
        fields = record_fields(v.kind, 0)
        return self.in_units(c, f'c["{self.param_names(v)[fields.index(c.field)]}"]' if c.field in fields else "0.0")

    def sigma(self, step: Step) -> str:
        """A step's conditioning on the block, in the list the block's steps fill."""
        return f"sigma[{step.number}]"

    def codes(self, step: Step) -> str:
        """A step's (status, row code) pairs in the order they prevail: a chain that cannot close,
        a singular position, a near-singular one (those its function returns; a resolve step's, all
        three with the checks, else the first)."""
        every = (status.CANNOT_CLOSE, status.SINGULAR, status.NEAR_SINGULAR)
        returned = self.callees[step.number].codes() if step.function else every if self.checks else every[:1]
        pairs = [(r, status.code(step.number, r)) for r in (status.CANNOT_CLOSE, status.SINGULAR, status.NEAR_SINGULAR)
                 if r in returned]
        return "(" + ", ".join(f"({r}, {c})" for r, c in pairs) + ("," if len(pairs) == 1 else "") + ")"

    def sign_measure(self, b: BranchSign) -> str:
        """The expression whose sign is a chain's branch in a solved configuration (on arrays)."""
        return super().sign_measure(b).replace("cos(", "np.cos(").replace("sin(", "np.sin(")

    def sign_rate(self, b: BranchSign) -> str:
        """The rate of sign_measure (on arrays)."""
        return super().sign_rate(b).replace("cos(", "np.cos(").replace("sin(", "np.sin(")

    def group_measures(self, g: Group, view: View) -> list[tuple[str, str]]:
        """The distinct sign measures of the chains of every block of a resolver group, with their
        rates, in order (blocks share chains: each is computed once); spelt once per group (every
        block's block_measures reads them: 30 ms of a build of double_triad spelt them anew)."""
        if g.index not in self._measures:  # a spelling spells one view
            pairs = [(self.sign_measure(bs), self.sign_rate(bs)) for b in view.blocks_of(g) for bs in b.group.branches]
            self._measures[g.index] = list(dict.fromkeys(pairs))
        return self._measures[g.index]

    def block_measures(self, g: Group, view: View, block: Group) -> list[int]:
        """The numbers (from 1, in group_measures' order) of a block's chains' sign measures."""
        texts = {m: k for k, (m, _) in reversed(list(enumerate(self.group_measures(g, view))))}
        return [texts[self.sign_measure(bs)] + 1 for bs in block.group.branches]

    @staticmethod
    def position_fields(v: Variable) -> int:
        """The fields of a record that hold its position (the rest are its rates)."""
        return len(record_fields(v.kind, 0))

    def block_writes(self, b: Group) -> list[tuple[str, int, int]]:
        """The records a resolver block computes, its Add-links first, with their fields' count
        and their position's."""
        return [(name, len(self.fields(self.variables[name].kind)), self.position_fields(self.variables[name]))
                for name in b.group.add_links + b.group.writes]

    def branch_targets(self, b: Group) -> str:
        """The work fields of a block's measured branches, as targets of one assignment."""
        return "".join(f"{self.work(f'br{bs.step}')}, " for bs in b.group.branches).rstrip()

    def on_lanes(self) -> bool:
        """Whether the kernel solves a resolver's rows on lanes: with the resolver settings its
        lanes have (Newton on the Add-link lengths, the first- or second-order predictor, the polishing step);
        with others NAME.py solves every row."""
        o = self.log.options
        return o.strategy == "newton" and o.predictor in (1, 2) and o.polish

    @staticmethod
    def reads_parameters(b: Group) -> bool:
        """Whether a block's steps read a number of the sketch (a design parameter)."""
        return any(a.kind == "real" for s in b.steps for a in s.args)

    def block_call(self, step: Step, scope: Group, suffix: str = "") -> list[str]:
        """A step's call in a resolver block (to the primitive named with the suffix), which keeps
        its chains' worst conditioning."""
        lines = self.call(step, scope, suffix)
        if PRIMITIVES[step.function].sigma is not None:
            lines.append(f"chains = np.minimum(chains, {self.sigma(step)})")
        return lines

    def call(self, step: Step, scope: Group | None, suffix: str = "") -> list[str]:
        """A step's call on a block of rows (to the primitive named with the suffix, outside a
        resolver block to its variant with the sketch's records held still where it has one); one
        that can fail reports its status and codes."""
        prim = self.callees[step.number]
        name = step.function + suffix if suffix else prim.name
        args = ", ".join(self.arg(a, scope, step) for a in step.args)
        targets = ", ".join(self.ref(o, scope) for o in step.outputs)
        if prim.status is None:
            return [f"_, _, {targets} = {name}({args})"]
        sigma = self.sigma(step) if prim.sigma is not None else "_"
        return [f"st, {sigma}, {targets} = {name}({args})", f"report.append((st, {self.codes(step)}))"]
