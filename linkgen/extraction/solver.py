"""The Solver (the paper's Algorithm 1): compute each unknown pair as soon as it can.

It scans the unknown pairs in declaration order and computes the first it can: as a
point of a placed link (``link_point``, ``pair_point`` for a point no chain reads, or
``coupler_point`` where one point of it is known), through an input (``crank_input``,
``slider_input``), or as the middle pair of a two-link chain whose ends are known (in extract's
second pass, a chain on a slide first inside an Add-link group: ``slides_first``).
Every choice breaks ties by declaration order, so a file always gives the same procedure.
"""

from __future__ import annotations

import math

from ..model import Input
from ..steplog import Arg, LJColumn
from ..topology import Topology, input_direction, reference_angle, wrap_angle
from .chains import try_chain
from .emit import emit
from .index import Index
from .placement import line, link_angle, point_on, reference, rot
from .state import Carrier, Unsupported, Workspace


def start(topo: Topology) -> Workspace:
    """The frame's pairs and points known, the inputs' records made (step 1)."""
    ws = Workspace(topo, Index.of(topo))
    m = ws.m
    ws.tied = {lk.name: [] for lk in m.links}
    ws.carriers = [Carrier(lk.name, "link", lk.joints) for lk in m.links]
    ws.columns = _initial_columns(ws)
    fixed = m.fixed
    for n in [*fixed.joints, *(p.name for p in fixed.points)]:
        if n in ws.joint_names and not m.joint(n).revolute:
            continue
        ws.pos[n] = ws.new_var(f"p_{n}", "POINT", "pair" if n in fixed.joints else "point", n, ws.xy(n))
    ws.tied[fixed.name] = list(ws.own(fixed.name))
    angle = wrap_angle(topo.direction(fixed.name).angle)
    base = ws.new_var(f"phi_{fixed.name}", "ANGLE", "link", fixed.name, (angle,))
    ws.orient[fixed.name] = ws.angles[fixed.name] = base
    ws.place(fixed.name)
    for inp, value in zip(m.inputs, topo.sketch_inputs):
        kind = "ANGLE" if inp.kind == "revolute" else "VARIABLE"
        ws.inputs.append(ws.new_var(f"in{inp.index + 1}", kind, "input", inp.column, sketch=(value,)))
        if inp.kind == "distance":
            ws.carriers.append(Carrier(inp.column, "actuator", inp.between, ws.inputs[-1]))
    emit(ws, "fixed", "", [], [], fixed.name, links=(fixed.name,),
         reason=f"link {fixed.name} is the frame: its pairs are fixed")
    return ws


def _initial_columns(ws: Workspace) -> list[LJColumn]:
    """The LJ-matrix's columns after rules (i) and (ii): truss members, inputs, actuators."""
    m = ws.m
    cols = [LJColumn(mb.label if len(m.link(mb.link).joints) > 2 else mb.link, "member",
                     tuple(p for p in (mb.a, mb.b) if p), mb.link) for mb in ws.topo.members]
    for inp in m.inputs:
        if inp.kind == "revolute":
            a = input_direction(m, m.link(inp.link), inp.joint).target
            r = input_direction(m, m.link(inp.relative_to), inp.joint).target
            cols.append(LJColumn(inp.column, "input", tuple(p for p in (a, r) if p in ws.joint_names), inp.link))
        elif inp.kind == "prismatic":
            cols.append(LJColumn(inp.column, "input", (inp.joint,), inp.link))
        else:
            cols.append(LJColumn(inp.column, "actuator", inp.between, ""))
    return cols


def solve(ws: Workspace, stop_at_close: bool = False) -> bool:
    """Run the Solver until every pair is known (True) or nothing is computable (False);
    with ``stop_at_close``, also stop (True) when the open resolver group closes."""
    while True:
        open_group = ws.group
        if not _progress(ws):
            return all(ws.is_known(j.name) for j in ws.m.joints)
        if stop_at_close and open_group and not ws.group:
            return True


def _progress(ws: Workspace) -> bool:
    """One Solver action; False when nothing is computable.  The first pair in declaration
    order that can be computed is: the frontier holds every pair whose chains changed since
    it was last tried (emit's refresh pushes them), and a pair that failed stays failed until
    then."""
    for inp in ws.m.inputs:
        if inp.index not in ws.applied and _apply_input(ws, inp):
            ws.applied.add(inp.index)
            return True
    if ws.slides_first and ws.group and _slide_first(ws):
        return True
    while (pair := ws.frontier.pop()) is not None:
        if not ws.is_known(pair) and (_try_point(ws, pair) or try_chain(ws, pair)):
            return True
    return False


def _slide_first(ws: Workspace) -> bool:
    """In an open group, a point of a placed link, else a chain on a slide, before any other
    chain: a slide line has no residual, so a group whose slide the Solver leaves unused never
    closes (extract's second pass; the first pair in declaration order, as everywhere)."""
    unknown = [j.name for j in ws.m.joints if not ws.is_known(j.name)]
    return any(_try_point(ws, p) for p in unknown) or any(try_chain(ws, p, slides=True) for p in unknown)


def _apply_input(ws: Workspace, inp: Input) -> bool:
    if inp.kind == "revolute":
        return _crank(ws, inp)
    if inp.kind == "prismatic":
        return _slider(ws, inp)
    return False  # a distance input acts as a link of variable length in the chains


def _crank(ws: Workspace, inp: Input) -> bool:
    if inp.link in ws.placed or inp.joint not in ws.pos or inp.relative_to not in ws.placed:
        return False
    drive = input_direction(ws.m, ws.link(inp.link), inp.joint)
    ref = reference(ws, inp, reference_angle(ws.m, inp))
    target = drive.target
    if target in ws.joint_names:
        target = ws.copy(target, inp.link)
    out = ws.point_var(target, ws.role(target)) if "@" not in target else \
        ws.new_var(f"g_{drive.target}", "POINT", "guide", drive.target, sketch=ws.xy(target))
    (xj, yj), (xa, ya) = ws.xy(inp.joint), ws.xy(target)
    ws.pos[target] = out
    ws.tied[inp.link] = [inp.joint, target]
    emit(ws, "input", "crank_input",
         [Arg("var", ws.pos[inp.joint]), Arg("real", value=math.hypot(xa - xj, ya - yj), label="l"),
          Arg("var", ws.inputs[inp.index]), Arg("var", ref)], [out], drive.target, pairs=(inp.joint,),
         links=(inp.link, inp.relative_to),
         reason=f"{inp.joint} is known and link {inp.relative_to} is placed, so the input angle "
                f"{inp.column} turns link {inp.link} to {drive.target}")
    return True


def _slider(ws: Workspace, inp: Input) -> bool:
    if inp.relative_to not in ws.placed or inp.link in ws.placed:
        return False
    g, psi = line(ws, inp.joint)
    j = ws.m.joint(inp.joint)
    other = next((n for n in ws.own(inp.link) if n != inp.joint), inp.joint)
    gsi, eta = rot(j.axis, *(a - b for a, b in zip(ws.xy(other), ws.xy(inp.joint))))
    jp = ws.point_var(inp.joint)
    ws.pos[inp.joint] = jp
    outs = [jp]
    if other != inp.joint:  # a pair the slider guides is its copy on the slider (as _crank names it)
        pair = other.split("@")[0]
        ws.pos[other] = ws.point_var(other, ws.role(other)) if "@" not in other else \
            ws.new_var(f"g_{pair}", "POINT", "guide", pair, sketch=ws.xy(other))
        outs.append(ws.pos[other])
    else:
        outs.append(ws.new_var(f"p_{inp.joint}_copy", "POINT", "pair", inp.joint, sketch=ws.xy(other)))
    ws.slides[inp.joint] = ws.inputs[inp.index]
    ws.tied[inp.link] = [inp.joint] + ([other] if other != inp.joint else [])
    emit(ws, "input", "slider_input",
         [Arg("var", g), Arg("var", psi), Arg("var", ws.inputs[inp.index]), Arg("real", value=gsi, label="gsi"),
          Arg("real", value=eta, label="eta")], outs, inp.joint, pairs=(inp.joint,),
         links=(inp.link, inp.relative_to),
         reason=f"the guide {inp.relative_to} of {inp.joint} is placed, so the input displacement "
                f"{inp.column} moves the slider {inp.link}")
    return True


def _try_point(ws: Workspace, pair: str) -> bool:
    """An unknown revolute pair on a placed link: link_point (placement.point_on)."""
    if not ws.m.joint(pair).revolute:
        return False
    for lk in ws.m.links_of(pair):
        if lk.name in ws.placed:
            ws.pos[pair] = ws.point_var(pair)
            ws.tied[lk.name].append(pair)
            point_on(ws, lk.name, pair, ws.pos[pair],
                     f"link {lk.name} is placed (its pairs {', '.join(ws.tied[lk.name][:2])} are known), "
                     f"so {pair} follows as a point of it")
            return True
    return False


def finish(ws: Workspace) -> None:
    """Every point of a placed link (linear in two of its pairs where no group computes them: no chain reads
    a point), then every link's angle for the outputs."""
    for p in ws.m.prismatic:
        if p.joint not in ws.slides:
            raise Unsupported(f"the prismatic pair {p.joint} is not used by any chain")
    for lk in ws.m.links:
        for pt in lk.points:
            if pt.name not in ws.pos:
                ws.pos[pt.name] = ws.point_var(pt.name, "point")
                point_on(ws, lk.name, pt.name, ws.pos[pt.name], f"point {pt.name} of link {lk.name}", linear=True)
    for lk in ws.m.links:
        link_angle(ws, lk.name)
