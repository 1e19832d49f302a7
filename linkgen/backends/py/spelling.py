"""How the Python program spells the procedure: records are tuples in a work object."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ...steplog import Step, Variable
from ..spelling import Spelling, Syntax
from .printer import inline_lines

if TYPE_CHECKING:
    from ...render.view import Group, View


class Python(Spelling):
    syntax = Syntax(note="w.note({st}, {codes})", conditional="{a} if {cond} else {b}", change_list="({points},)",
                    booleans=("False", "True"))

    def __init__(self, view: View):
        super().__init__(view)
        # records _run holds in locals too (_p_A_x, ...) once a step of its own has computed them: all but
        # those a resolver's blocks compute, which its passes rewrite in the work
        self.held: set[str] = set()
        self.rewritten = {o for b in view.blocks for s in b.steps for o in s.outputs}

    def member(self, kind: str, field: str) -> str:
        return f"[{self.fields(kind).index(field)}]"

    def reach_fail(self, low: int, high: int) -> list[str]:
        return [f"st = {self.reach_call('inputs[0]')}", "if st:", f"    return {low} if st < 0 else {high}"]

    def input_record(self, var: Variable, k: int) -> str:
        """The statement that builds an input record from the k-th input, rate and acceleration (in _run,
        held in locals too)."""
        sources = ("inputs", "d_inputs", "dd_inputs")[: self.order + 1]
        fields = ", ".join(f"{src}[{k}]" for src in sources) + ("," if self.order == 0 else "")
        return f"{self.hold(var.name, None)} = ({fields})"

    def local_names(self, var: str) -> list[str]:
        """The locals a record's fields are held in (_p_A_x, ...)."""
        return [f"_{var}_{f}" for f in self.fields(self.variables[var].kind)]

    def hold(self, var: str, scope: Group | None) -> str:
        """The target of a record a step computes: in _run (scope None) its locals and the work's record
        (``_p_A_x, ... = w.p_A``), from then on read from the locals; elsewhere the work's record."""
        target = self.ref(var, scope)
        if scope is not None or var in self.rewritten:
            return target
        self.held.add(var)
        names = self.local_names(var)
        return f"{', '.join(names)}{',' if len(names) == 1 else ''} = {target}"

    def fields_of(self, var: str, scope: Group | None) -> list[str]:
        """What a call inlined reads in place of a record's fields: a constant's literals, the locals _run
        holds a record in; none (the record is unpacked) for the others."""
        if self.variables[var].constant:
            return [self.lit(x) for x in self.padded(self.variables[var])]
        return self.local_names(var) if scope is None and var in self.held else []

    def unpacked(self, var: str) -> str:
        """The statement that unpacks a computed record into one local per field (_p_A_x, ...)."""
        names = self.local_names(var)
        return f"{', '.join(names)}{',' if len(names) == 1 else ''} = {self.ref(var, None)}"

    def initializer(self, v: Variable) -> str:
        """The tuple of a constant record (derivatives zero)."""
        one = v.kind != "POINT" and self.order == 0
        return "(" + ", ".join(self.lit(x) for x in self.padded(v)) + ("," if one else "") + ")"

    def call(self, step: Step, scope: Group | None) -> list[str]:
        """A step's call; a failing chain ends the row (inside a resolver block: the block's pass)."""
        prim = self.callees[step.number]
        args = [self.arg(a, scope, step) for a in step.args]
        fields = [self.fields_of(a.var, scope) or text if a.kind == "var" else text for a, text in zip(step.args, args)]
        targets = [self.hold(o, scope) for o in step.outputs]
        failed = [f"return {self.status_code(step, 1)}" if scope is None else "return 1, None"]
        lines = [f"# {prim.name}({', '.join(args)}), inline"]
        lines += inline_lines(prim, self.order, fields, targets, self.sigma(step), failed)
        if prim.status is None:
            return lines
        if scope is None:
            notes = [line for n in self.notes("st", step) for line in ("if st:", f"    {n}")]  # a call saved a row
            return lines + notes
        lines += [line for n in self.notes("st", step) for line in ("if live:", f"    {n}")]
        if prim.sigma is not None:
            lines.append(f"w.chains = min(w.chains, {self.sigma(step)})")
        return lines


class Unpacked(Python):
    """The Python spelling where the computed records are read from their unpacked fields (_publish)."""

    def get(self, var: str, field: str) -> str:
        return f"_{var}_{field}" if self.ref(var, None) != var else super().get(var, field)
