"""The loop strategy's blocks (options: strategy loop): the literature's method for a class-III group.

A group whose unknown pairs X1, X2, X3 are the three pairs of one ternary link, each held by a
binary leg K_i-X_i to a pair K_i known before the group (Fig. 14's six-bar), is decomposed into
two-link chains: assume the angle of leg 1 (X1 = K1 + l1 (cos, sin)), place X3 by the chain on
the body's side X1X3 and leg 3, X2 by the side X3X2 and leg 2, and X1 again by the side X2X1 and
leg 1; the angle of K1-X1 that comes back, less the one assumed, is the residual.  The reverse
loop runs the chains the other way round (X2 by the side X1X2 and leg 2, X3, then X1); at a
fixed point its slope is the reciprocal of the forward loop's, so one of them contracts unless
|g'| = 1.  Each block carries the angle as the leg's arc length s = l1 theta (a length, as an
Add-link's is), so the resolver's tolerance, reach and path checks and Newton's machinery read it
unchanged.  The blocks join their group's fallbacks, after the Add-link blocks; the runtime tries
them first under strategy loop.  A group of another shape (prismatic legs, more Add-links, a
point placed inside the group the loop does not write) gets none: its Add-link blocks are iterated
by Newton, which the manual states (``unlooped``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from ..model import Mechanism
from ..steplog import Arg, BranchSign, ResolverGroup, Step, Variable

LOOP_ITERATIONS = 60  # strategy loop's iteration cap unless one is set: |g'| = 0.6 gains 1e-13 in 60 steps
LOOP_ROLE = "loop"  # the role of a loop block's arc length and of the pair it places again


@dataclass(frozen=True)
class Triad:
    """A class-III group's shape: its ternary link, the unknown pairs X1..X3 in the order the forward loop
    assumes them, their legs and the legs' known pairs K1..K3."""

    body: str
    xs: tuple[str, str, str]
    legs: tuple[str, str, str]
    ks: tuple[str, str, str]


def triad(m: Mechanism, group: ResolverGroup, variables: dict[str, Variable]) -> Triad | None:
    """The group's class-III shape, or None where it has another (the loop strategy falls back to Newton)."""
    pairs = {v.entity: v.name for v in variables.values() if v.role == "pair"}
    unknown = sorted(v.entity for v in variables.values() if v.role == "pair" and v.name in group.writes)
    known = {j for j, name in pairs.items() if variables[name].constant or name in group.reads}
    revolute = {j.name for j in m.joints if j.revolute}
    bodies = [lk for lk in m.links if not lk.fixed and sorted(lk.joints) == unknown]
    if len(unknown) != 3 or len(bodies) != 1 or not set(unknown) <= revolute:
        return None
    legs, ks = [], []
    for x in unknown:
        held = [lk for lk in m.links if not lk.fixed and len(lk.joints) == 2 and x in lk.joints
                and (set(lk.joints) - {x}) <= known & revolute]
        if len(held) != 1:
            return None
        legs.append(held[0].name)
        ks.append(next(j for j in held[0].joints if j != x))
    return Triad(bodies[0].name, tuple(unknown), tuple(legs), tuple(ks))  # type: ignore[arg-type]


def _length(variables: dict[str, Variable], link: str, a: str, b: str, sketch: dict[str, tuple[float, float]]) -> str:
    """The length record of link between pairs a and b (added where the procedure has none)."""
    for v in variables.values():
        if v.role == "length" and v.entity in (f"{link}:{a}-{b}", f"{link}:{b}-{a}"):
            return v.name
    d = math.dist(sketch[a], sketch[b])
    name = f"l_{link}_{a}_{b}"
    variables[name] = Variable(name, "VARIABLE", "length", f"{link}:{a}-{b}", (d,), (d,))
    return name


def side(a: tuple[float, float], b: tuple[float, float], c: tuple[float, float]) -> int:
    """+1 where c lies left of a -> b (or on it), else -1: the branch of the chain on a -> b placing c, and
    the turn of a body a, b, c."""
    return 1 if (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]) >= 0 else -1


def loop_block(t: Triad, group: ResolverGroup, reverse: bool, variant: int, first: int,
               variables: dict[str, Variable],
               sketch: dict[str, tuple[float, float]]) -> tuple[list[Step], ResolverGroup]:
    """The steps and record of one loop block (fallback ``variant`` of its group, steps numbered after ``first``)."""
    pos = {v.entity: v.name for v in variables.values() if v.role == "pair"}
    order = (0, 1, 2) if reverse else (0, 2, 1)  # the pairs the chains place in turn, X1 again last
    x1, k1, leg1 = t.xs[0], t.ks[0], t.legs[0]
    arm = _length(variables, leg1, k1, x1, sketch)
    tag = f"{group.number}_v{variant}"
    s, f, again = f"s{tag}", f"f{tag}", f"p_{x1}_loop{tag}"
    dx, dy = sketch[x1][0] - sketch[k1][0], sketch[x1][1] - sketch[k1][1]
    s0 = variables[arm].value[0] * math.atan2(dy, dx)
    variables[s] = Variable(s, "VARIABLE", LOOP_ROLE, f"{leg1} (loop {tag})", (), (s0,))
    variables[again] = Variable(again, "POINT", LOOP_ROLE, f"{x1} (loop {tag})", (), sketch[x1])
    variables[f] = Variable(f, "VARIABLE", "residual", leg1, (), ())
    way = "reverse" if reverse else "forward"
    steps = [Step(first + 1, "point", "loop_point", (Arg("var", pos[k1]), Arg("var", arm), Arg("var", s)),
                  (pos[x1],), x1, "", (k1,), (leg1,), 0,
                  f"the {way} loop of group {group.number} assumes the angle of {leg1} ({k1}-{x1}), carried as its "
                  f"arc length {s}", "", (x1,), group.number, False, variant=variant)]
    chains = [(order[i], order[i + 1] if i < 2 else 0) for i in range(3)]
    for i, (a, b) in enumerate(chains):
        xa, xb, kb, leg = t.xs[a], t.xs[b], t.ks[b], t.legs[b]
        out = again if i == 2 else pos[xb]
        body_side = _length(variables, t.body, xa, xb, sketch)
        length = _length(variables, leg, kb, xb, sketch)
        branch = side(sketch[xa], sketch[kb], sketch[xb])
        steps.append(Step(first + 2 + i, "chain", "RRR_links",
                          (Arg("var", pos[xa]), Arg("var", pos[kb]), Arg("var", body_side), Arg("var", length),
                           Arg("int", value=branch, label="minv")),
                          (out,), xb, "RRR", (xa, kb), (t.body, leg), branch,
                          f"round the loop: {xb} from {xa} by the side {xa}{xb} of {t.body} and {leg} from {kb}",
                          f"the sketch has {xb} {'left' if branch > 0 else 'right'} of {xa}->{kb}", (xb,),
                          group.number, True, variant=variant))
    turn, side_of = f"c{tag}", side(sketch[x1], sketch[t.xs[1]], sketch[t.xs[2]])
    variables[turn] = Variable(turn, "VARIABLE", LOOP_ROLE, f"{t.body} (loop {tag})", (), ())
    steps.append(Step(first + 5, "check", "loop_turn", (*(Arg("var", pos[x]) for x in t.xs),
                                                        Arg("int", value=side_of, label="turn")), (turn,), t.body,
                      "", t.xs, (t.body,), 0,
                      f"the body {t.body} as drawn, not turned over (its mirror image keeps every length round the "
                      "loop but is no assembly)", "", (), group.number, True, variant=variant))
    steps.append(Step(first + 6, "residual", "loop_residual",
                      (Arg("var", pos[k1]), Arg("var", again), Arg("var", arm), Arg("var", s)), (f,), leg1, "",
                      (k1, x1), (leg1,), 0,
                      f"the angle of {leg1} that comes back round the loop must be the one assumed", "", (),
                      group.number, True, variant=variant))
    writes = tuple(o for st in steps for o in st.outputs)
    reads = tuple(dict.fromkeys(a.var for st in steps for a in st.args if a.kind == "var" and a.var not in writes
                                and a.var != s and not variables[a.var].constant))
    signs = tuple(BranchSign(st.number, "side", (st.args[0].var, st.args[1].var, pos[st.target]), "", st.branch)
                  for st in steps if st.function == "RRR_links")
    block = ResolverGroup(group.number, 0, (s,), (f,), tuple(st.number for st in steps), reads, writes,
                          variant=variant, pairs=((k1, x1),), lengths=(s0,), branches=signs)
    return steps, block


def with_loops(m: Mechanism, steps: tuple[Step, ...], variables: tuple[Variable, ...],
               groups: tuple[ResolverGroup, ...]) -> tuple[tuple[Step, ...], tuple[Variable, ...],
                                                       tuple[ResolverGroup, ...], tuple[int, ...]]:
    """The procedure with the forward and reverse loop blocks of every class-III group appended to its
    fallbacks; and the groups that have none (their resolver stays Newton on the Add-links)."""
    by_name = {v.name: v for v in variables}
    pos = {v.entity: v.name for v in variables if v.role == "pair"}
    sketch = {v.entity: (v.sketch[0], v.sketch[1]) for v in variables if v.role == "pair"}
    out, done, unlooped = list(steps), [], []
    for g in groups:
        t = triad(m, g, by_name)
        written = {o for n in g.steps for o in next(s for s in steps if s.number == n).outputs} - set(g.residuals)
        if t is None or len(g.add_links) != 1 or not written <= {pos[x] for x in t.xs}:
            unlooped.append(g.number)
            done.append(g)
            continue
        blocks: list[ResolverGroup] = []
        for reverse in (False, True):
            vsteps, block = loop_block(t, g, reverse, len(g.variants) + len(blocks) + 1, len(out), by_name, sketch)
            out += vsteps
            blocks.append(block)
        done.append(replace(g, variants=g.variants + tuple(blocks)))
        out = [replace(s, reason=s.reason + "; strategy loop: first the forward, then the reverse loop that "
                       f"assumes the angle of {t.legs[0]} ({t.ks[0]}-{t.xs[0]}), the Add-link blocks by Newton where "
                       "neither contracts") if s.number == g.step else s for s in out]
    out = [replace(s, reason=s.reason + "; strategy loop: this group is no ternary link held by three revolute legs, "
                   "so Newton on its Add-links") if s.action == "resolve" and s.group in unlooped else s for s in out]
    return tuple(out), tuple(by_name.values()), tuple(done), tuple(unlooped)
