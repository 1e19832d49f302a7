"""How each language spells the procedure: names, numbers, references and calls.

Templates lay the files out; these classes say how one call, one record or one
constant is written in C, Python or MATLAB/Octave.  Nothing here decides what is
computed: that is the step log's job.
"""

from __future__ import annotations

from .. import status
from ..names import c_field, m_field
from ..primitives import PRIMITIVES
from ..primitives.dsl import record_fields
from ..primitives.printers import literal
from ..steplog import Arg, BranchSign, Column, Step, StepLog, Variable, held
from .view import Group


class Spelling:
    """Shared rules; subclasses spell records, references and calls."""

    name = ""
    comment = ""

    def __init__(self, order: int, log: StepLog, measured: frozenset[int] = frozenset()):
        self.order = order
        self.log = log
        self.variables = {v.name: v for v in log.variables}
        self.measured = measured  # steps whose branch is read off the last solution

    def ident(self, name: str) -> str:
        """A pair, point or link name as a field of the program's outputs (linkgen.names)."""
        return name

    @staticmethod
    def lit(value: float | int) -> str:
        return literal(value)

    def zero_record(self) -> str:
        """The fields of a zero VARIABLE record at the program's order."""
        return ", ".join(["0.0"] * (self.order + 1))

    def arg(self, a: Arg, scope: Group | None, step: Step | None = None) -> str:
        if a.kind == "var":
            return self.ref(a.var, scope)
        if a.kind == "int":
            if step is not None and step.change_points and a.label == "minv":
                return self.branch(step, int(a.value))
            if step is not None and step.number in self.measured and a.label == "minv":
                return self.work(f"br{step.number}")
            return str(int(a.value))
        return self.lit(float(a.value))

    def work(self, field: str) -> str:
        """A field of the work record."""
        return f"w.{field}"

    def sign_measure(self, b: BranchSign) -> str:
        """The expression whose sign is a chain's branch in a solved configuration."""
        p = [self.xy(v) for v in b.points]
        if b.kind == "side":
            return (f"({p[1][0]} - {p[0][0]}) * ({p[2][1]} - {p[0][1]}) - "
                    f"({p[1][1]} - {p[0][1]}) * ({p[2][0]} - {p[0][0]})")
        t = self.angle(b.angle)
        return f"({p[1][0]} - {p[0][0]}) * cos({t}) + ({p[1][1]} - {p[0][1]}) * sin({t})"

    def xy(self, var: str) -> tuple[str, str]:
        """A position record's x and y."""
        raise NotImplementedError

    def get(self, var: str, field: str) -> str:
        """One field of a record (x, dy, the, ddv, ...)."""
        raise NotImplementedError

    def published(self, c: Column) -> str:
        """What a program writes into an output column: a constant record's field as drawn,
        a computed point's x and y with the origin added back, any other field as computed."""
        drawn = self.log.drawn(c)
        if drawn is not None:
            return self.lit(drawn)
        text, offset = self.get(c.variable, c.field), self.log.offset(c)
        if not offset:
            return text
        return f"{text} + {self.lit(offset)}" if offset > 0 else f"{text} - {self.lit(-offset)}"

    def angle(self, var: str) -> str:
        """An angle record's value."""
        raise NotImplementedError

    def branch(self, step: Step, b0: int) -> str:
        """The branch of a chain that flips at change points, computed from the first input."""
        raise NotImplementedError

    def first_input(self) -> tuple[Variable, float, bool]:
        """The first input's record, its sketch value and whether it is an angle."""
        v = next(v for v in self.variables.values() if v.role == "input")
        return v, v.sketch[0], v.kind == "ANGLE"

    def ref(self, var: str, scope: Group | None) -> str:
        raise NotImplementedError

    @staticmethod
    def external(var: str, scope: Group | None) -> bool:
        return scope is not None and any(v.name == var for v in scope.reads)

    @staticmethod
    def constant(var: str, scope_vars: dict[str, Variable]) -> bool:
        return scope_vars[var].constant

    @staticmethod
    def status_code(step: Step, reason: int) -> int:
        return status.code(step.number, reason)

    @staticmethod
    def note_codes(step: Step) -> str:
        """note()'s codes of a step: where it is singular, where it is near singular."""
        return f"{status.code(step.number, status.SINGULAR)}, {status.code(step.number, status.NEAR_SINGULAR)}"

    def sigma_status(self, sigma: str) -> tuple[str, str]:
        """The conditions on a conditioning ``sigma`` for a singular and a near-singular position."""
        p = self.log.policy
        return f"{sigma} < {self.lit(p.singular)}", f"{sigma} < {self.lit(p.near_singular)}"

    def fields(self, kind: str) -> tuple[str, ...]:
        return record_fields(kind, self.order)

    def input_record(self, var: Variable, k: int) -> str:
        """The statement that builds an input record from the k-th input, rate and acceleration."""
        raise NotImplementedError

    nan = "NAN"  # a bound of the reach with no gap on its side

    def reach_call(self, value: str) -> str:
        """reach_at(...) of the step log's reach for the input value expression ``value``."""
        r = self.log.reach
        low, high = (self.nan if x is None else self.lit(x) for x in (r.low, r.high))
        return f"reach_at({value}, {low}, {high}, {int(r.periodic)})"

    def reach_check(self) -> list[str]:
        """The lines that fail a row the mechanism does not reach from the sketch (none without a reach)."""
        raise NotImplementedError

    def reach_low(self) -> str:
        """The reach's lower end, from which the continuation counts an angle's turns (nan without one)."""
        r = self.log.reach
        return self.nan if r is None or r.low is None else self.lit(r.low)


class C(Spelling):
    name = "c"
    comment = "/*"
    _field = {"x": "P.x", "y": "P.y", "dx": "DP.x", "dy": "DP.y", "ddx": "DDP.x", "ddy": "DDP.y"}

    def ident(self, name: str) -> str:
        return c_field(name)

    def ref(self, var: str, scope: Group | None) -> str:
        if self.variables[var].constant or self.external(var, scope):
            return var
        return f"w->{var}"

    def field(self, kind: str, f: str) -> str:
        return self._field[f] if kind == "POINT" else f

    def work(self, field: str) -> str:
        return f"w->{field}"

    def xy(self, var: str) -> tuple[str, str]:
        r = self.ref(var, None)
        return f"{r}.P.x", f"{r}.P.y"

    def get(self, var: str, field: str) -> str:
        return f"{self.ref(var, None)}.{self.field(self.variables[var].kind, field)}"

    def angle(self, var: str) -> str:
        return f"{self.ref(var, None)}.the"

    def branch(self, step: Step, b0: int) -> str:
        """branch_at(...) on the array change_N that call() declares before the step (an array, not a
        compound literal: C++ has none)."""
        v, theta0, periodic = self.first_input()
        value = f"w->{v.name}.{'the' if periodic else 'v'}"
        return (f"branch_at({value}, {b0}, {self.lit(theta0)}, change_{step.number}, "
                f"{len(step.change_points)}, {int(periodic)})")

    def input_record(self, var: Variable, k: int) -> str:
        sources = ("in", "din", "ddin")
        return " ".join(f"w->{var.name}.{f} = {src}[{k}];" for f, src in zip(self.fields(var.kind), sources))

    def reach_check(self) -> list[str]:
        if self.log.reach is None:
            return []
        low, high = self.log.reach.codes()
        return [f"st = {self.reach_call('in[0]')};", f"if (st != 0) return st < 0 ? {low} : {high};"]

    def initializer(self, v: Variable) -> str:
        """Braced initializer of a constant record (derivatives zero)."""
        value = held(v, self.log.origin)
        if v.kind == "POINT":
            levels = [f"{{{self.lit(value[0])}, {self.lit(value[1])}}}"] + ["{0.0, 0.0}"] * self.order
            return "{" + ", ".join(levels) + "}"
        return "{" + ", ".join([self.lit(value[0])] + ["0.0"] * self.order) + "}"

    def note_sigma(self, step: Step) -> str:
        """note() of a resolver's step, whose status its conditioning gives."""
        sig = f"w->sigma[{step.number}]"
        singular, near = self.sigma_status(sig)
        return (f"note(w, {singular} ? {status.SINGULAR} : {near} ? {status.NEAR_SINGULAR} : 0, "
                f"{self.note_codes(step)});")

    def call(self, step: Step, scope: Group | None) -> list[str]:
        prim = PRIMITIVES[step.function]
        args = [self.arg(a, scope, step) for a in step.args]
        args += [f"&{self.ref(o, scope)}" for o in step.outputs]
        if prim.sigma is not None:
            args.append(f"&w->sigma[{step.number}]")
        text = f"{step.function}({', '.join(args)});"
        points = ", ".join(self.lit(p) for p in step.change_points)
        head = [f"static const double change_{step.number}[] = {{{points}}};"] if step.change_points else []
        if prim.status is None:
            return [*head, text]
        if scope is None:
            return [*head, f"st = {text}", f"if (st == 1) return {self.status_code(step, 1)};",
                    f"note(w, st, {self.note_codes(step)});"]
        lines = [*head, f"st = {text}", "if (st == 1) return 1;", f"if (live) note(w, st, {self.note_codes(step)});"]
        if prim.sigma is not None:
            lines.append(f"w->chains = fmin(w->chains, w->sigma[{step.number}]);")
        return lines


class Python(Spelling):
    name = "py"
    comment = "#"

    def ref(self, var: str, scope: Group | None) -> str:
        if self.variables[var].constant or self.external(var, scope):
            return var
        return f"w.{var}"

    def xy(self, var: str) -> tuple[str, str]:
        r = self.ref(var, None)
        return f"{r}[0]", f"{r}[1]"

    def get(self, var: str, field: str) -> str:
        return f"{self.ref(var, None)}[{self.fields(self.variables[var].kind).index(field)}]"

    def angle(self, var: str) -> str:
        return f"{self.ref(var, None)}[0]"

    def branch(self, step: Step, b0: int) -> str:
        v, theta0, periodic = self.first_input()
        points = ", ".join(self.lit(p) for p in step.change_points) + ","
        return f"branch_at(w.{v.name}[0], {b0}, {self.lit(theta0)}, ({points}), {periodic})"

    def reach_check(self) -> list[str]:
        if self.log.reach is None:
            return []
        low, high = self.log.reach.codes()
        return [f"st = {self.reach_call('inputs[0]')}", "if st:", f"    return {low} if st < 0 else {high}"]

    def input_record(self, var: Variable, k: int) -> str:
        sources = ("inputs", "d_inputs", "dd_inputs")[: self.order + 1]
        fields = ", ".join(f"{src}[{k}]" for src in sources) + ("," if self.order == 0 else "")
        return f"w.{var.name} = ({fields})"

    def initializer(self, v: Variable) -> str:
        value = held(v, self.log.origin)
        zeros = [0.0] * (len(record_fields(v.kind, self.order)) - len(value))
        return "(" + ", ".join(self.lit(x) for x in (*value, *zeros)) + ("," if v.kind != "POINT" and
                                                                          self.order == 0 else "") + ")"

    def note_sigma(self, step: Step) -> str:
        """note() of a resolver's step, whose status its conditioning gives."""
        singular, near = self.sigma_status(f"w.sigma[{step.number}]")
        return (f"w.note({status.SINGULAR} if {singular} else {status.NEAR_SINGULAR} if {near} else 0, "
                f"{self.note_codes(step)})")

    def call(self, step: Step, scope: Group | None) -> list[str]:
        prim = PRIMITIVES[step.function]
        args = ", ".join(self.arg(a, scope, step) for a in step.args)
        targets = [self.ref(o, scope) for o in step.outputs]
        if prim.status is None:
            return [f"{', '.join(targets)} = {step.function}({args})"]
        head = ["st"] + ([f"w.sigma[{step.number}]"] if prim.sigma is not None else [])
        lines = [f"{', '.join(head + targets)} = {step.function}({args})"]
        if scope is None:
            return lines + ["if st == 1:", f"    return {self.status_code(step, 1)}",
                            f"w.note(st, {self.note_codes(step)})"]
        lines += ["if st == 1:", "    return 1, None", "if live:", f"    w.note(st, {self.note_codes(step)})"]
        if prim.sigma is not None:
            lines.append(f"w.chains = min(w.chains, w.sigma[{step.number}])")
        return lines


class Octave(Spelling):
    name = "m"
    comment = "%"

    def ident(self, name: str) -> str:
        return m_field(name)

    def ref(self, var: str, scope: Group | None) -> str:
        """Constants live in the work struct too (MATLAB has no file-level constants)."""
        return var if self.external(var, scope) else f"w.{var}"

    def xy(self, var: str) -> tuple[str, str]:
        r = self.ref(var, None)
        return f"{r}.x", f"{r}.y"

    def get(self, var: str, field: str) -> str:
        return f"{self.ref(var, None)}.{field}"

    def angle(self, var: str) -> str:
        return f"{self.ref(var, None)}.the"

    def branch(self, step: Step, b0: int) -> str:
        v, theta0, periodic = self.first_input()
        points = ", ".join(self.lit(p) for p in step.change_points)
        value = f"w.{v.name}.{'the' if periodic else 'v'}"
        return f"branch_at({value}, {b0}, {self.lit(theta0)}, [{points}], {int(periodic)})"

    nan = "NaN"

    def reach_check(self) -> list[str]:
        if self.log.reach is None:
            return []
        low, high = self.log.reach.codes()
        return [f"st = {self.reach_call('in(1)')};", "if st ~= 0", f"    status = {high};", "    if st < 0",
                f"        status = {low};", "    end", "    return;", "end"]

    def input_record(self, var: Variable, k: int) -> str:
        sources = ("in", "din", "ddin")
        pairs = ", ".join(f"'{f}', {src}({k + 1})" for f, src in zip(self.fields(var.kind), sources))
        return f"w.{var.name} = struct({pairs});"

    def zero_struct(self) -> str:
        """A zero VARIABLE record at the program's order."""
        return "struct(" + ", ".join(f"'{f}', 0" for f in record_fields("VARIABLE", self.order)) + ")"

    def rates(self, kind: str) -> tuple[str, ...]:
        """The derivative fields of a record kind."""
        return record_fields(kind, self.order)[2 if kind == "POINT" else 1:]

    def initializer(self, v: Variable) -> str:
        names = record_fields(v.kind, self.order)
        value = held(v, self.log.origin)
        values = [*value, *([0.0] * (len(names) - len(value)))]
        return "struct(" + ", ".join(f"'{n}', {self.lit(x)}" for n, x in zip(names, values)) + ")"

    def note_sigma(self, step: Step) -> list[str]:
        """note() of a resolver's step, whose status its conditioning gives."""
        singular, near = self.sigma_status(f"w.sigma({step.number})")
        return [f"if {singular}", f"    w = note(w, {status.SINGULAR}, {self.note_codes(step)});", f"elseif {near}",
                f"    w = note(w, {status.NEAR_SINGULAR}, {self.note_codes(step)});", "end"]

    def call(self, step: Step, scope: Group | None) -> list[str]:
        prim = PRIMITIVES[step.function]
        args = ", ".join(self.arg(a, scope, step) for a in step.args)
        targets = [self.ref(o, scope) for o in step.outputs]
        if prim.status is not None:
            targets.append("st")
        if prim.sigma is not None:
            targets.append(f"w.sigma({step.number})")
        lhs = f"[{', '.join(targets)}]" if len(targets) > 1 else targets[0]
        lines = [f"{lhs} = {step.function}({args});"]
        if prim.status is None:
            return lines
        if scope is None:
            return lines + ["if st == 1", f"    status = {self.status_code(step, 1)};", "    return;", "end",
                            f"w = note(w, st, {self.note_codes(step)});"]
        lines += ["if st == 1", "    st = 1;", "    res = [];", "    return;", "end", "if live",
                  f"    w = note(w, st, {self.note_codes(step)});", "end"]
        if prim.sigma is not None:
            lines.append(f"w.chains = min(w.chains, w.sigma({step.number}));")
        return lines


class Manual(Spelling):
    """The manual's listing: calls written with the names a reader sees in the figure."""

    name = "md"

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
            return number(float(a.value))
        return self.ref(a.var)

    def call(self, step: Step, scope: Group | None = None) -> str:
        outs = [self.ref(o) for o in step.outputs]
        lhs = outs[0] if len(outs) == 1 else f"[{', '.join(outs)}]"
        return f"{lhs} = {step.function}({', '.join(self.arg(a, None, step) for a in step.args)})"


def number(x: float) -> str:
    """A number for the manual: 10 significant digits, enough for a calculator."""
    text = "%.10g" % x
    return "0" if text == "-0" else text
