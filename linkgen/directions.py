"""``angles: unit``: the output angles as unit vectors, computed without trigonometry.

Every link angle an output column reads becomes a direction record (a POINT record of role
``direction``: (cos, sin) of the angle and their rates).  Where the angle comes from two
points of the link (``link_angle``, ``crank_angle`` of a crank's two pairs, or ``offset_angle`` of such an
angle), ``link_direction``
takes the direction straight from the two points, turned by the sketch offset; an angle that
a chain computes (the line of an RPR chain) is turned into its direction by
``angle_direction`` (cos and sin); a constant angle gives a constant direction.

The step that computed an angle only the outputs read is replaced by its direction step,
under the same number, so every status code means what it means in the angle build.  Where
other steps read the angle, or a resolver iterates it, the direction is a step of its own
after the procedure's last step (the fallback blocks' numbers move up by as many).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import TypeVar

from . import exact
from .columns import direction_columns
from .errors import and_list
from .steplog import Arg, Column, Procedure, ResolverGroup, Step, Variable
from .topology import wrap_angle

P = TypeVar("P", bound=Procedure)


@dataclass(frozen=True)
class Source:
    """Where a direction comes from: two points and the offset from their segment to the
    link's direction (``link_direction``), a computed angle (``angle_direction``), or an
    angle that never moves (``constant``: ``off`` is the angle)."""

    kind: str  # link_direction | angle_direction | constant
    points: tuple[str, ...] = ()  # the two position records (link_direction)
    angle: str = ""  # the angle record (angle_direction)
    off: float = 0.0
    step: Step | None = None  # the link_angle step the points come from


def source(proc: Procedure, producer: dict[str, Step], name: str) -> Source:
    """Where the direction of the angle record ``name`` comes from (following offset angles to their base)."""
    v = proc.variable(name)
    if v.constant:
        return Source("constant", off=v.value[0])
    s = producer.get(name)  # none for an input's record
    if s is None:
        return Source("angle_direction", angle=name)
    if s.function == "link_angle":
        return Source("link_direction", (s.args[0].var, s.args[1].var), off=s.args[2].value, step=s)
    if s.function == "crank_angle":  # from the crank's two pairs, as its link_angle would be
        crank = next(c for c in producer.values() if c.function == "crank_input" and
                     (c.args[2].var, c.args[3].var) == (s.args[0].var, s.args[1].var))
        return Source("link_direction", (crank.args[0].var, crank.outputs[0]), off=s.args[2].value, step=s)
    if s.function == "offset_angle":
        base = source(proc, producer, s.args[0].var)
        if base.kind != "angle_direction":
            return replace(base, off=base.off + s.args[1].value)
    return Source("angle_direction", angle=name)


def _variable(proc: Procedure, name: str, u: str, src: Source) -> Variable:
    """The direction record of angle record ``name``: constant where the angle is."""
    v = proc.variable(name)
    sketch = (exact.cos(v.sketch[0]), exact.sin(v.sketch[0]))
    if src.kind == "constant":
        return Variable(u, "POINT", "direction", v.entity, (exact.cos(src.off), exact.sin(src.off)), sketch)
    return Variable(u, "POINT", "direction", v.entity, (), sketch)


def _step(proc: Procedure, number: int, u: str, src: Source, owners: list[str]) -> Step:
    """The step that computes direction ``u`` of the links ``owners``."""
    links = tuple(owners)
    whose = f"link{'s' if len(owners) > 1 else ''} {and_list(owners)}"
    if src.kind == "angle_direction":
        return Step(number, "direction", "angle_direction", (Arg("var", src.angle),), (u,), ", ".join(owners), "",
                    (), links, 0, f"the angle {src.angle} is known, so the direction of {whose} is", "", (), 0, False)
    pairs = tuple(proc.variable(p).entity for p in src.points)
    off = wrap_angle(src.off)
    args = (*(Arg("var", p) for p in src.points), Arg("real", value=exact.cos(off), label="c"),
            Arg("real", value=exact.sin(off), label="s"))
    return Step(number, "direction", "link_direction", args, (u,), ", ".join(owners), "", pairs, links, 0,
                f"{pairs[0]} and {pairs[1]} are known, so the direction of {whose} is", "", (), 0, True)


def _name(taken: set[str], entity: str) -> str:
    """A record name for the direction of ``entity`` that no record has yet."""
    name = f"u_{entity}"
    while name in taken:
        name += "_"
    return name


def unit_directions(proc: P, columns: tuple[Column, ...], inputs: int) -> tuple[P, tuple[Column, ...]]:
    """The procedure with a direction record for every angle the output columns read, and
    the columns with the directions' in place of the angles' (the inputs' first ``inputs``
    columns stay angles: they are what the caller passes)."""
    producer = {o: s for s in proc.steps if not s.variant for o in s.outputs}
    readers = {a.var for s in proc.steps for a in s.args if a.kind == "var"}
    owners: dict[str, list[str]] = {}  # angle record -> the links whose columns read it
    for c in columns[inputs:]:
        if c.quantity == "angle":
            owners.setdefault(c.variable, []).append(c.name.split(".", 1)[0])
    last = max((s.number for s in proc.steps if not s.variant), default=0)
    replaced: dict[int, Step] = {}
    added: list[Step] = []
    variables: list[Variable] = []
    made: dict[str, str] = {}
    taken = {v.name for v in proc.variables}
    for name, links in owners.items():
        src = source(proc, producer, name)
        u = _name(taken, proc.variable(name).entity)
        taken.add(u)
        variables.append(_variable(proc, name, u, src))
        made[name] = u
        if src.kind == "constant":
            continue
        s = producer.get(name)
        if s and name not in readers and not s.group and s.outputs == (name,) and src.kind == "link_direction":
            replaced[s.number] = _step(proc, s.number, u, src, links)
        else:
            added.append(_step(proc, last + len(added) + 1, u, src, links))
    steps = [replaced.get(s.number, s) for s in proc.steps if not s.variant] + added
    moved = renumbered(replace(proc, variables=proc.variables + tuple(variables)), last, len(added))
    steps += [s for s in moved.steps if s.variant]
    return replace(moved, steps=tuple(steps)), direction_columns(columns, made, inputs)


def renumbered(proc: P, last: int, shift: int) -> P:
    """The procedure with every step numbered after ``last`` (the fallback blocks') moved up by ``shift``."""
    if not shift:
        return proc

    def n(number: int) -> int:
        return number + shift if number > last else number

    def group(g: ResolverGroup) -> ResolverGroup:
        return replace(g, step=n(g.step), steps=tuple(n(k) for k in g.steps),
                       branches=tuple(replace(b, step=n(b.step)) for b in g.branches),
                       variants=tuple(group(v) for v in g.variants))

    return replace(proc, steps=tuple(replace(s, number=n(s.number)) for s in proc.steps),
                   add_links=tuple(replace(a, step=n(a.step)) for a in proc.add_links),
                   residuals=tuple(replace(r, step=n(r.step)) for r in proc.residuals),
                   groups=tuple(group(g) for g in proc.groups))

