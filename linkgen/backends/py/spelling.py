"""How the Python program spells the procedure: records are tuples in a work object."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ...steplog import Step, Variable
from ..spelling import Spelling, Syntax

if TYPE_CHECKING:
    from ...render.view import Group


class Python(Spelling):
    syntax = Syntax(note="w.note({st}, {codes})", conditional="{a} if {cond} else {b}", change_list="({points},)",
                    booleans=("False", "True"))

    def member(self, kind: str, field: str) -> str:
        return f"[{self.fields(kind).index(field)}]"

    def reach_fail(self, low: int, high: int) -> list[str]:
        return [f"st = {self.reach_call('inputs[0]')}", "if st:", f"    return {low} if st < 0 else {high}"]

    def input_record(self, var: Variable, k: int) -> str:
        """The statement that builds an input record from the k-th input, rate and acceleration."""
        sources = ("inputs", "d_inputs", "dd_inputs")[: self.order + 1]
        fields = ", ".join(f"{src}[{k}]" for src in sources) + ("," if self.order == 0 else "")
        return f"w.{var.name} = ({fields})"

    def initializer(self, v: Variable) -> str:
        """The tuple of a constant record (derivatives zero)."""
        one = v.kind != "POINT" and self.order == 0
        return "(" + ", ".join(self.lit(x) for x in self.padded(v)) + ("," if one else "") + ")"

    def call(self, step: Step, scope: Group | None) -> list[str]:
        """A step's call; a failing chain ends the row (inside a resolver block: the block's pass)."""
        prim = self.primitives[step.function]
        args = ", ".join(self.arg(a, scope, step) for a in step.args)
        targets = [self.ref(o, scope) for o in step.outputs]
        if prim.status is None:
            return [f"{', '.join(targets)} = {step.function}({args})"]
        head = ["st"] + ([self.sigma(step)] if prim.sigma is not None else [])
        lines = [f"{', '.join(head + targets)} = {step.function}({args})"]
        if scope is None:
            notes = [line for n in self.notes("st", step) for line in ("if st:", f"    {n}")]  # a call saved a row
            return lines + ["if st == 1:", f"    return {self.status_code(step, 1)}", *notes]
        lines += ["if st == 1:", "    return 1, None"]
        lines += [line for n in self.notes("st", step) for line in ("if live:", f"    {n}")]
        if prim.sigma is not None:
            lines.append(f"w.chains = min(w.chains, {self.sigma(step)})")
        return lines
