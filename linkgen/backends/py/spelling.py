"""How the Python program spells the procedure: records are tuples in a work object."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ...steplog import Step, Variable
from ..spelling import Spelling, Syntax
from .printer import inline_lines

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

    def literals(self, var: str) -> list[str]:
        """A constant record's fields as literals (a call inlined reads them in place)."""
        return [self.lit(x) for x in self.padded(self.variables[var])]

    def unpacked(self, var: str) -> str:
        """The statement that unpacks a computed record into one local per field (_p_A_x, ...)."""
        names = [f"_{var}_{f}" for f in self.fields(self.variables[var].kind)]
        return f"{', '.join(names)}{',' if len(names) == 1 else ''} = {self.ref(var, None)}"

    def initializer(self, v: Variable) -> str:
        """The tuple of a constant record (derivatives zero)."""
        one = v.kind != "POINT" and self.order == 0
        return "(" + ", ".join(self.lit(x) for x in self.padded(v)) + ("," if one else "") + ")"

    def call(self, step: Step, scope: Group | None) -> list[str]:
        """A step's call; a failing chain ends the row (inside a resolver block: the block's pass)."""
        prim = self.primitives[step.function]
        args = [self.arg(a, scope, step) for a in step.args]
        fields: list[str | list[str]] = [self.literals(a.var) if a.kind == "var" and self.variables[a.var].constant
                                         else text for a, text in zip(step.args, args)]
        targets = [self.ref(o, scope) for o in step.outputs]
        failed = [f"return {self.status_code(step, 1)}" if scope is None else "return 1, None"]
        lines = [f"# {step.function}({', '.join(args)}), inline"]
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
