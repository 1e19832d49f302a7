"""How the C program spells the procedure: records are structs the work record points to."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ...steplog import Step, Variable, held
from ..spelling import Spelling, Syntax
from .printer import field
from .tangent import tape
from .words import WORDS

if TYPE_CHECKING:
    from ...render.view import Group


class C(Spelling):
    # branch_at reads the array change_N that call() declares before the step (C++ has no compound literal)
    syntax = Syntax(work="w->", note="note(w, {st}, {codes});", conditional="{cond} ? {a} : {b}",
                    change_list="change_{number}, {count}")
    words = WORDS

    def member(self, kind: str, field_name: str) -> str:
        return "." + field(kind, field_name)

    def input_record(self, var: Variable, k: int) -> str:
        """The statement that builds an input record from the k-th input, rate and acceleration."""
        sources = ("in", "din", "ddin")
        return " ".join(f"w->{var.name}.{f} = {src}[{k}];" for f, src in zip(self.fields(var.kind), sources))

    def exit(self, code: str, step: int = 0) -> str:
        """The statement that ends a row with a failure's code at step ``step``: through failed() where run()
        publishes its rows (the conditioning of the steps after it reset there), else back to the resolvers'
        row driver."""
        return f"return {code};" if self.log.groups else f"return failed(out, {code}, {step});"

    def sigma(self, step: Step) -> str:
        """Where a step's conditioning goes: straight into the public state where run() publishes its rows
        (no per-row copy), else the work record the resolvers' row driver reads."""
        return super().sigma(step) if self.log.groups else f"out->sigma[{step.number}]"

    def reach_fail(self, low: int, high: int) -> list[str]:
        return [f"st = {self.reach_call('in[0]')};", f"if (st != 0) {self.exit(f'st < 0 ? {low} : {high}')}"]

    def initializer(self, v: Variable) -> str:
        """Braced initializer of a constant record (derivatives zero)."""
        value = held(v, self.log.origin)
        if v.kind == "POINT":
            levels = [f"{{{self.lit(value[0])}, {self.lit(value[1])}}}"] + ["{0.0, 0.0}"] * self.order
            return "{" + ", ".join(levels) + "}"
        return "{" + ", ".join([self.lit(value[0])] + ["0.0"] * self.order) + "}"

    def pair_call(self, step: Step, scope: Group) -> list[str]:
        """A step's two-channel copy (NAME_2) in a block's pass that measures a Jacobian column and the
        residuals' rates at zero Add-link rate at once: the second channel's records are the block's t_
        locals, what it reads from outside live (w->), the constants themselves.  No note: the pass
        measures (the rates pass after it notes); it keeps its position values in the work's tape."""
        prim = self.callees[step.number]
        pairs = list(zip(step.args, prim.params))
        args = [("&" if a.kind == "var" else "") + self.arg(a, scope, step) for a, _ in pairs]
        args += [f"&{self.second(a.var, scope)}" for a, p in pairs if p.is_record]
        args += [f"&{self.ref(o, scope)}" for o in step.outputs] + [f"&t_{o}" for o in step.outputs]
        args.append(f"w->tape + {self.tape_at(step, scope)}")
        if prim.sigma is not None:
            args.append(f"&{self.sigma(step)}")
        return self._block_call(step, f"{step.function}_2({', '.join(args)});", noted=False)

    def tape_at(self, step: Step, scope: Group) -> int:
        """Where a step's values start in the work's tape: after those of the block's steps before it."""
        before = scope.steps[: scope.steps.index(step)]
        return sum(len(tape(self.callees[s.number])) for s in before if s.function)

    def tape_call(self, step: Step, scope: Group) -> list[str]:
        """A step's rates copy (NAME_r) in a block's pass at the solved Add-link rates: the positions' values
        as the last Newton pass (pair_call) kept them in the work's tape; it notes the kept status."""
        prim = self.callees[step.number]
        at = self.tape_at(step, scope)
        args = [("&" if a.kind == "var" else "") + self.arg(a, scope, step) for a in step.args]
        args += [f"w->tape[{at + k}]" for k in range(len(tape(prim)))]
        args += [f"&{self.ref(o, scope)}" for o in step.outputs]
        return self._block_call(step, f"{step.function}_r({', '.join(args)});", noted=True)

    def _block_call(self, step: Step, text: str, noted: bool) -> list[str]:
        """A block's call of a primitive copy: the step's change points, the call, a chain that cannot close
        ending the pass, the status noted where the pass notes, the block's worst chain conditioning."""
        prim = self.callees[step.number]
        points = ", ".join(self.lit(p) for p in step.change_points)
        head = [f"static const double change_{step.number}[] = {{{points}}};"] if step.change_points else []
        if prim.status is None:
            return [*head, text]
        lines = [*head, f"st = {text}", "if (st == 1) return 1;", *(self.notes("st", step) if noted else ())]
        if prim.sigma is not None:
            lines.append(f"if ({self.sigma(step)} < w->chains) w->chains = {self.sigma(step)};")
        return lines

    def second(self, var: str, scope: Group) -> str:
        """A record as a two-channel call's second channel reads it (pair_call)."""
        if self.external(var, scope):
            return self.work(var)
        if self.variables[var].constant:
            return var
        return f"t_{var}"

    def call(self, step: Step, scope: Group | None, velocities: bool = False) -> list[str]:
        """A step's call; a failing chain ends the row (inside a resolver block: the block's pass;
        ``velocities``: its order-1 copy, for a pass whose accelerations are not read)."""
        prim = self.callees[step.number]
        args = [("&" if a.kind == "var" else "") + self.arg(a, scope, step) for a in step.args]
        args += [f"&{self.ref(o, scope)}" for o in step.outputs]
        if prim.sigma is not None:
            args.append(f"&{self.sigma(step)}")
        text = f"{prim.name}{'_1' if velocities else ''}({', '.join(args)});"
        points = ", ".join(self.lit(p) for p in step.change_points)
        head = [f"static const double change_{step.number}[] = {{{points}}};"] if step.change_points else []
        if prim.status is None:
            return [*head, text]
        if scope is None:
            return [*head, f"st = {text}", f"if (st == 1) {self.exit(str(self.status_code(step, 1)), step.number)}",
                    *self.notes("st", step)]
        lines = [*head, f"st = {text}", "if (st == 1) return 1;", *(f"if (live) {n}" for n in self.notes("st", step))]
        if prim.sigma is not None:
            lines.append(f"if ({self.sigma(step)} < w->chains) w->chains = {self.sigma(step)};")
        return lines
