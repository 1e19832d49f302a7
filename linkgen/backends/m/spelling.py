"""How the MATLAB/Octave program spells the procedure: records are structs in a work struct."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ... import status
from ...primitives.dsl import record_fields
from ...steplog import Step, Variable
from ..spelling import Spelling, Syntax
from .words import WORDS

if TYPE_CHECKING:
    from ...render.view import Group


class Octave(Spelling):
    # constants live in the work struct too: MATLAB has no file-level constants
    syntax = Syntax(file_constants=False, nan="NaN", subscript="({})", note="w = note(w, {st}, {codes});",
                    change_list="[{points}]")
    words = WORDS

    def member(self, kind: str, field: str) -> str:
        return f".{field}"

    def reach_fail(self, low: int, high: int) -> list[str]:
        return [f"st = {self.reach_call('in(1)')};", "if st ~= 0", f"    status = {high};", "    if st < 0",
                f"        status = {low};", "    end", "    return;", "end"]

    def input_record(self, var: Variable, k: int) -> str:
        """The statement that builds an input record from the k-th input, rate and acceleration."""
        sources = ("in", "din", "ddin")
        pairs = ", ".join(f"'{f}', {src}({k + 1})" for f, src in zip(self.fields(var.kind), sources))
        return f"w.{var.name} = struct({pairs});"

    def zero_struct(self) -> str:
        """A zero VARIABLE record at the program's order."""
        return "struct(" + ", ".join(f"'{f}', 0" for f in record_fields("VARIABLE", self.order)) + ")"

    def rates(self, kind: str) -> tuple[str, ...]:
        """The derivative fields of a record kind."""
        return self.fields(kind)[2 if kind == "POINT" else 1:]

    def initializer(self, v: Variable) -> str:
        """The struct of a constant record (derivatives zero)."""
        pairs = zip(self.fields(v.kind), self.padded(v))
        return "struct(" + ", ".join(f"'{n}', {self.lit(x)}" for n, x in pairs) + ")"

    def note_sigma(self, step: Step) -> list[str]:
        """note() of a resolver's step, whose status its conditioning gives (MATLAB has no
        conditional expression: if, elseif)."""
        singular, near = self.sigma_status(step)
        return [f"if {singular}", f"    {self.note(str(status.SINGULAR), step)}", f"elseif {near}",
                f"    {self.note(str(status.NEAR_SINGULAR), step)}", "end"]

    def call(self, step: Step, scope: Group | None) -> list[str]:
        """A step's call; a failing chain ends the row (inside a resolver block: the block's pass)."""
        prim = self.callees[step.number]
        args = ", ".join(self.arg(a, scope, step) for a in step.args)
        targets = [self.ref(o, scope) for o in step.outputs]
        if prim.status is not None:
            targets.append("st")
        if prim.sigma is not None:
            targets.append(self.sigma(step))
        lhs = f"[{', '.join(targets)}]" if len(targets) > 1 else targets[0]
        lines = [f"{lhs} = {prim.name}({args});"]
        if prim.status is None:
            return lines
        if scope is None:
            return lines + ["if st == 1", f"    status = {self.status_code(step, 1)};", "    return;", "end",
                            *self.notes("st", step)]
        lines += ["if st == 1", "    st = 1;", "    res = [];", "    return;", "end"]
        lines += [line for n in self.notes("st", step) for line in ("if live", f"    {n}", "end")]
        if prim.sigma is not None:
            lines.append(f"w.chains = min(w.chains, {self.sigma(step)});")
        return lines
