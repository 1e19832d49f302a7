"""The MATLAB/Octave printer of a DSL primitive: a subfunction on structs."""

from __future__ import annotations

from ...primitives.dsl import Expr, Param, Primitive, Select, record_fields
from ...primitives.printers import RecordExprs, masks, statements


class OctaveExprs(RecordExprs):
    consts = {"eps": "eps", "nan": "NaN", "pi": "pi"}

    def select(self, cond: str, a: str, b: str) -> str:
        raise ValueError("MATLAB has no conditional expression; selections are statements")

    def assign(self, target: str, e: Expr, indent: str = "    ") -> list[str]:
        """``target = e`` where e may be a chain of selections: if / elseif / else."""
        if not isinstance(e, Select):
            return [f"{indent}{target} = {self.expr(e)};"]
        out = []
        keyword = "if"
        while isinstance(e, Select):
            out.append(f"{indent}{keyword} {self.expr(e.cond)}")
            out.append(f"{indent}    {target} = {self.expr(e.a)};")
            keyword = "elseif"
            e = e.b
        out += [f"{indent}else", f"{indent}    {target} = {self.expr(e)};", f"{indent}end"]
        return out


def octave_function(prim: Primitive, order: int) -> str:
    """A MATLAB/Octave subfunction: records are structs, outputs then status and sigma."""
    exprs = OctaveExprs(prim)
    outs = [p.name for p in prim.outputs]
    if prim.status is not None:
        outs.append("st")
    if prim.sigma is not None:
        outs.append("sigma")
    ret = f"[{', '.join(outs)}]" if len(outs) > 1 else outs[0]
    lines = [f"function {ret} = {prim.name}({', '.join(p.name for p in prim.params)})", f"    % {prim.doc}"]

    def store(p: Param, f: str, e: Expr) -> list[str]:
        return exprs.assign(f"{p.name}.{f}", e)

    lines += [f"    {p.name} = struct();" for p in prim.outputs if not record_fields(p.kind, order)]  # none yet
    lines += statements(prim, order, exprs, lambda name, e, _: exprs.assign(name, e), store)
    if prim.status is not None:
        for cond, fields in masks(prim, order, exprs.or_op):
            lines.append(f"    if {cond}")
            lines += [f"        {p.name}.{f} = NaN;" for p, f in fields]
            lines.append("    end")
    lines.append("end")
    return "\n".join(lines) + "\n"
