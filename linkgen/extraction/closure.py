"""The closure strategy's equations (options: strategy closure).

Newton on all loop-closure equations of a resolver group at once: the unknowns are the
positions the group's chosen block places (x and y of each), the equations the rigid-link
constraints its steps hold, read off them: a 3R chain's two distances (an Add-link's is no
constraint and is left out), a point fixed in its link's frame (two rows: coupler_point's, on
the link's angle, or link_point's, on two of its points) and the length of
each link the Solver did not use (the residual's).  Each placement gives two rows and each
Add-link's row is traded for a residual's, so the system is square.  A length that changes with
the inputs (an actuator's) is read from its record as the row is computed.  A group with a step
these do not cover (a prismatic pair's chain) is refused, with the step that stops it.
"""

from __future__ import annotations

from dataclasses import replace

from .. import exact
from ..closurelog import Closure, Distance, Frame
from ..errors import and_list
from ..steplog import ResolverGroup, Step, Variable


class ClosureRefused(Exception):
    """A resolver group the closure strategy writes no equations for (the message says why)."""


def with_closures(steps: tuple[Step, ...], variables: tuple[Variable, ...],
                  groups: tuple[ResolverGroup, ...]) -> tuple[tuple[Step, ...], tuple[ResolverGroup, ...]]:
    """The steps and groups with every group's closure equations, its resolve step saying so."""
    by_name = {v.name: v for v in variables}
    producer = {o: s for s in steps if not s.variant for o in s.outputs}
    closed = tuple(replace(g, closure=closure(g, [s for s in steps if s.number in g.steps], by_name, producer))
                   for g in groups)
    reasons = {g.step: _reason(g, by_name) for g in closed}
    return tuple(replace(s, reason=reasons[s.number]) if s.number in reasons else s for s in steps), closed


def closure(group: ResolverGroup, block: list[Step], variables: dict[str, Variable],
            producer: dict[str, Step]) -> Closure:
    """The loop-closure equations of a group's chosen block (its steps in order)."""
    adds = set(group.add_links)
    unknowns: list[str] = []
    distances: list[Distance] = []
    frames: list[Frame] = []
    for s in block:
        var = [a.var for a in s.args if a.kind == "var"]
        if s.function == "RRR_links":
            for end, length in ((var[0], var[2]), (var[1], var[3])):
                if length not in adds:
                    distances.append(_distance((end, s.outputs[0]), length, s.number, _link(length, variables),
                                               variables))
        elif s.function == "link_residual":
            distances.append(_distance((var[0], var[1]), var[2], s.number, s.target, variables))
        elif s.function == "coupler_point":
            a, b = _base(var[1], producer, s)
            frames.append(Frame(s.outputs[0], var[0], (a, b), _ratio(variables, s.outputs[0], var[0], a, b),
                                s.number, s.links[0]))
        elif s.function == "link_point":
            (ax, ay), (bx, by), (px, py) = (variables[n].sketch[:2] for n in (var[0], var[1], s.outputs[0]))
            ratio = exact.along_across(px - ax, py - ay, bx - ax, by - ay)
            frames.append(Frame(s.outputs[0], var[0], (var[0], var[1]), ratio, s.number, s.links[0]))
        elif s.function not in ("link_angle", "offset_angle"):
            raise ClosureRefused(f"it handles resolver groups of revolute pairs only, and step {s.number} of "
                                 f"group {group.number} places {s.target} by {s.function}")
        unknowns += [o for o in s.outputs if variables[o].kind == "POINT"]
    if len(distances) + 2 * len(frames) != 2 * len(unknowns):
        raise ClosureRefused(f"group {group.number} has {len(distances) + 2 * len(frames)} constraints on "
                             f"{2 * len(unknowns)} coordinates")
    return Closure(tuple(unknowns), tuple(distances), tuple(frames))


def _distance(points: tuple[str, str], length: str, step: int, link: str, variables: dict[str, Variable]) -> Distance:
    """|points[1] - points[0]| = the record ``length`` (its value, or the record where it changes with the inputs)."""
    v = variables[length]
    return Distance(points, v.value[0], step, link) if v.constant else Distance(points, v.sketch[0], step, link, length)


def _link(length: str, variables: dict[str, Variable]) -> str:
    """The link a length record belongs to (its entity is link:pair-pair; an actuator's is its input's)."""
    v = variables[length]
    return v.entity.split(":")[0] if v.role == "length" else v.entity


def _base(angle: str, producer: dict[str, Step], s: Step) -> tuple[str, str]:
    """The two points of a link whose direction a frame angle is measured on (through offsets)."""
    p = producer.get(angle)
    while p is not None and p.function == "offset_angle":
        p = producer.get(next(a.var for a in p.args if a.kind == "var"))
    if p is None or p.function != "link_angle":
        raise ClosureRefused(f"step {s.number} places {s.target} in a frame that is not a link's direction")
    a, b = (a.var for a in p.args if a.kind == "var")
    return a, b


def _ratio(variables: dict[str, Variable], c: str, o: str, a: str, b: str) -> tuple[float, float]:
    """w = (c - o) / (b - a) as complex numbers of the sketch positions: c - o = w (b - a) for
    any position of the rigid link that carries the four points."""
    cc, oo, aa, bb = (complex(*variables[n].sketch[:2]) for n in (c, o, a, b))
    w = (cc - oo) / (bb - aa)
    return w.real, w.imag


def _reason(g: ResolverGroup, variables: dict[str, Variable]) -> str:
    """The resolve step's sentence under the closure strategy."""
    assert g.closure is not None
    c = g.closure
    links = list(dict.fromkeys([d.link for d in c.distances] + [f.link for f in c.frames]))
    pairs = [variables[u].entity for u in c.unknowns]
    return (f"Newton on the loop-closure equations of {and_list(pairs)} until {and_list(links)} keep their shapes; "
            f"then {and_list(list(g.add_links))} read off the solution")
