"""How a generated program spells the procedure: the rules every language shares.

Templates lay the files out; a backend's Spelling (the templates' ``L``) says how one call,
one record or one constant is written in its language.  Nothing here decides what is
computed: that is the step log's job.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from .. import status
from ..instant.names import field_name, is_centre
from ..primitives.dsl import record_fields
from ..primitives.printers import literal
from ..steplog import Arg, BranchSign, Column, Step, StepLog, Variable, held
from ..units import DEGREE, converted
from . import Words
from .program import step_primitives

if TYPE_CHECKING:
    from ..render.view import Group, View


@dataclass(frozen=True)
class Syntax:
    """How a language writes the pieces the shared rules put together."""

    work: str = "w."  # how the work record's fields are reached
    file_constants: bool = True  # constant records are the file's own names (else fields of the work record)
    nan: str = "NAN"  # a bound of the reach with no gap on its side
    subscript: str = "[{}]"  # an element of an array (of the per-step sigma)
    note: str = ""  # note(): remember status {st} of a step with note codes {codes}
    conditional: str = ""  # {a} where {cond} holds, else {b}
    change_list: str = ""  # branch_at's change points of step {number}: the literals {points}, {count} of them
    booleans: tuple[str, str] = ("0", "1")  # false and true


class Spelling:
    """A program's spelling: references to records and their fields, literals, the branch and
    reach calls; subclasses spell the statements (calls, input records, initializers)."""

    syntax = Syntax()
    words = Words()  # what the language makes of the user's names

    def __init__(self, view: View):
        self.log: StepLog = view.log
        self.order = self.order_of(view)
        self.variables = {v.name: v for v in self.log.variables}
        self.measured = view.measured  # steps whose branch is read off the last solution
        self.checks = view.checks  # singular and near-singular steps noted, the conditioning reported
        self.callees = step_primitives(view)  # by step number (held still outside resolver blocks: still.py)
        self._reads: dict[int, set[str]] = {}  # block index -> the names of the records it reads (external)

    @staticmethod
    def order_of(view: View) -> int:
        """The derivative order of the records the program holds."""
        return view.record_order

    def ident(self, name: str) -> str:
        """A pair, point or link name as a field of the program's outputs (linkgen.names)."""
        return self.words.field(field_name(name) if is_centre(name) else name)

    @staticmethod
    def lit(value: float | int) -> str:
        """A number as the language writes it: the shortest spelling that reads back the same."""
        return literal(value)

    def flag(self, value: bool) -> str:
        return self.syntax.booleans[value]

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
        return f"{self.syntax.work}{field}"

    def ref(self, var: str, scope: Group | None) -> str:
        """A record as a step reads or writes it: a constant or a record read from outside a resolver
        block by its name, a computed one in the work record."""
        if self.external(var, scope) or (self.syntax.file_constants and self.variables[var].constant):
            return var
        return self.work(var)

    def external(self, var: str, scope: Group | None) -> bool:
        """Whether a block reads the record from before its group (each block's names gathered once)."""
        if scope is not None and scope.index not in self._reads:
            self._reads[scope.index] = {v.name for v in scope.reads}
        return scope is not None and var in self._reads[scope.index]

    def member(self, kind: str, field: str) -> str:
        """How a record of a kind is followed to one of its fields (``.P.x``, ``[0]``, ``.x``)."""
        raise NotImplementedError

    def get(self, var: str, field: str) -> str:
        """One field of a record (x, dy, the, ddv, ...)."""
        return self.ref(var, None) + self.member(self.variables[var].kind, field)

    def xy(self, var: str) -> tuple[str, str]:
        """A position record's x and y."""
        return self.get(var, "x"), self.get(var, "y")

    def angle(self, var: str) -> str:
        """An angle record's value."""
        return self.get(var, "the")

    def sign_measure(self, b: BranchSign) -> str:
        """The expression whose sign is a chain's branch in a solved configuration."""
        p = [self.xy(v) for v in b.points]
        if b.kind == "side":
            return (f"({p[1][0]} - {p[0][0]}) * ({p[2][1]} - {p[0][1]}) - "
                    f"({p[1][1]} - {p[0][1]}) * ({p[2][0]} - {p[0][0]})")
        t = self.angle(b.angle)
        return f"({p[1][0]} - {p[0][0]}) * cos({t}) + ({p[1][1]} - {p[0][1]}) * sin({t})"

    def sign_rate(self, b: BranchSign) -> str:
        """The rate of sign_measure: a block's state holds the measure and this rate, so the
        predictor moves it along and the chain's branch flips where it passes zero (a chain
        passing its fold, where its two links are in line, goes on on its other branch)."""
        p = [self.xy(v) for v in b.points]
        d = [(self.get(v, "dx"), self.get(v, "dy")) for v in b.points]
        if b.kind == "side":
            return (f"({d[1][0]} - {d[0][0]}) * ({p[2][1]} - {p[0][1]}) + ({p[1][0]} - {p[0][0]}) * "
                    f"({d[2][1]} - {d[0][1]}) - ({d[1][1]} - {d[0][1]}) * ({p[2][0]} - {p[0][0]}) - "
                    f"({p[1][1]} - {p[0][1]}) * ({d[2][0]} - {d[0][0]})")
        t, dt = self.angle(b.angle), self.get(b.angle, "dthe")
        return (f"({d[1][0]} - {d[0][0]}) * cos({t}) + ({d[1][1]} - {d[0][1]}) * sin({t}) + "
                f"(({p[1][1]} - {p[0][1]}) * cos({t}) - ({p[1][0]} - {p[0][0]}) * sin({t})) * {dt}")

    def published(self, c: Column) -> str:
        """What a program writes into an output column: a constant record's field as drawn,
        a computed point's x and y with the origin added back, any other field as computed."""
        drawn = self.log.drawn(c)
        if drawn is not None:
            return self.in_units(c, self.lit(drawn))
        text, offset = self.get(c.variable, c.field), self.log.offset(c)
        if not offset:
            return self.in_units(c, text)
        return f"{text} + {self.lit(offset)}" if offset > 0 else f"{text} - {self.lit(-offset)}"

    def all_drawn(self, outputs: Any) -> bool:
        """Whether every field of the outputs is a constant record's as drawn (a program's
        publish() then reads nothing the row computed)."""
        return all(self.log.drawn(c) is not None for o in outputs for _, c, _ in o.fields)

    def in_units(self, c: Column, text: str) -> str:
        """An output column's value in the programs' units: an angle or its rate times DEGREE where
        they work in degrees (linkgen.units), else as computed."""
        return f"{text} * {self.lit(DEGREE)}" if converted(self.log, c) else text

    def change_points(self, step: Step) -> str:
        """The change points of a step's chain as branch_at takes them."""
        points = ", ".join(self.lit(p) for p in step.change_points)
        return self.syntax.change_list.format(points=points, number=step.number, count=len(step.change_points))

    def branch(self, step: Step, b0: int) -> str:
        """The branch of a chain that flips at change points, computed from the first input."""
        v = next(v for v in self.variables.values() if v.role == "input")
        periodic = v.kind == "ANGLE"
        value = self.get(v.name, "the" if periodic else "v")
        return (f"branch_at({value}, {b0}, {self.lit(v.sketch[0])}, {self.change_points(step)}, "
                f"{self.flag(periodic)})")

    @staticmethod
    def status_code(step: Step, reason: int) -> int:
        return int(status.code(step.number, reason))

    @staticmethod
    def note_codes(step: Step) -> str:
        """note()'s codes of a step: where it is singular, where it is near singular."""
        return f"{status.code(step.number, status.SINGULAR)}, {status.code(step.number, status.NEAR_SINGULAR)}"

    def sigma(self, step: Step) -> str:
        """The conditioning a step reports, in the work record."""
        return self.work("sigma" + self.syntax.subscript.format(step.number))

    def sigma_status(self, step: Step) -> tuple[str, str]:
        """The conditions on a step's conditioning for a singular and a near-singular position."""
        p = self.log.policy
        return f"{self.sigma(step)} < {self.lit(p.singular)}", f"{self.sigma(step)} < {self.lit(p.near_singular)}"

    def note(self, st: str, step: Step) -> str:
        """The statement that notes status ``st`` of a step (note() keeps the first singular and the
        first near-singular step's code)."""
        return self.syntax.note.format(st=st, codes=self.note_codes(step))

    def notes(self, st: str, step: Step) -> list[str]:
        """note()'s statement where the program has its checks, else none."""
        return [self.note(st, step)] if self.checks else []

    def note_sigma(self, step: Step) -> str | list[str]:
        """note() of a resolver's step, whose status its conditioning gives."""
        singular, near = self.sigma_status(step)
        near_or_not = self.syntax.conditional.format(cond=near, a=status.NEAR_SINGULAR, b=0)
        return self.note(self.syntax.conditional.format(cond=singular, a=status.SINGULAR, b=near_or_not), step)

    def fields(self, kind: str) -> tuple[str, ...]:
        return record_fields(kind, self.order)

    def reach_call(self, value: str) -> str:
        """reach_at(...) of the step log's reach for the input value expression ``value``."""
        r = self.log.reach
        if r is None:
            raise ValueError(f"{self.log.name} has no reach to check")
        low, high = (self.syntax.nan if x is None else self.lit(x) for x in (r.low, r.high))
        return f"reach_at({value}, {low}, {high}, {int(r.periodic)})"

    def reach_low(self) -> str:
        """The reach's lower end, from which the continuation counts an angle's turns (nan without one)."""
        r = self.log.reach
        return self.syntax.nan if r is None or r.low is None else self.lit(r.low)

    def reach_check(self) -> list[str]:
        """The lines that fail a row the mechanism does not reach from the sketch (none without a reach)."""
        return [] if self.log.reach is None else self.reach_fail(*self.log.reach.codes())

    def reach_fail(self, low: int, high: int) -> list[str]:
        """The lines that check the first input against the reach and end the row with status ``low``
        below it, ``high`` above."""
        raise NotImplementedError

    def padded(self, v: Variable) -> tuple[float, ...]:
        """A constant record's fields as the program holds them: its displacement, zero derivatives."""
        value = held(v, self.log.origin)
        return (*value, *([0.0] * (len(record_fields(v.kind, self.order)) - len(value))))
