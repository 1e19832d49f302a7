"""How the manual spells the procedure: calls written with the names a reader sees in the figure."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ...steplog import Arg, Step
from ..spelling import Spelling

if TYPE_CHECKING:
    from ...render.view import Group, View


def number(x: float | int) -> str:
    """A number for the manual: 10 significant digits, enough for a calculator."""
    text = "%.10g" % x
    return "0" if text == "-0" else text


class Manual(Spelling):
    """The manual's listing (the paper's): pairs, points and inputs by their names, flags signed."""

    @staticmethod
    def lit(value: float | int) -> str:
        return number(value)

    @staticmethod
    def order_of(view: View) -> int:
        """The manual speaks of the derivatives the outputs have."""
        return view.log.order

    def ref(self, var: str, scope: Group | None = None) -> str:
        v = self.variables[var]
        return v.entity if v.role in ("pair", "point", "input") else var

    def arg(self, a: Arg, scope: Group | None = None, step: Step | None = None) -> str:
        if a.kind == "int":
            if step is not None and step.change_points and a.label == "minv":
                return f"{int(a.value):+d} flipped at change points"
            if step is not None and step.number in self.measured and a.label == "minv":
                return f"{int(a.value):+d} then as solved"
            return "%+d" % int(a.value)
        if a.kind == "real":
            return self.lit(float(a.value))
        return self.ref(a.var)

    def call(self, step: Step, scope: Group | None = None) -> str:
        outs = [self.ref(o) for o in step.outputs]
        lhs = outs[0] if len(outs) == 1 else f"[{', '.join(outs)}]"
        return f"{lhs} = {step.function}({', '.join(self.arg(a, None, step) for a in step.args)})"
