"""Placing things on placed links: a link's angle, a slide's line, a point at its offset."""

from __future__ import annotations

import math

from .. import exact
from ..model import Input
from ..policy import GOOD_LEVER
from ..steplog import Arg, Step
from ..topology import wrap_angle
from .emit import emit
from .state import Workspace


def rot(angle: float, x: float, y: float) -> tuple[float, float]:
    """Coordinates of (x, y) in a frame turned by ``angle``."""
    c, s = exact.cos(angle), exact.sin(angle)
    return c * x + s * y, -s * x + c * y


def frame(ws: Workspace, link: str) -> str:
    """An ANGLE variable turning with the link (emitting link_angle if needed)."""
    if link in ws.orient:
        return ws.orient[link]
    if link in ws.coupled:
        ws.orient[link] = frame(ws, ws.coupled[link])
        return ws.orient[link]
    crank = _crank_step(ws, link)
    if crank is not None:
        return _crank_angle(ws, link, crank)
    tied = ws.tied[link]
    d = ws.topo.direction(link)
    origin, target = ws.named(d.origin, link), ws.named(d.target, link) if d.target else ""
    if target and origin in tied and target in tied:
        a, b = origin, target
    else:
        a = tied[0]
        b = next(n for n in tied[1:] if ws.xy(n) != ws.xy(a))
    (xa, ya), (xb, yb) = ws.xy(a), ws.xy(b)
    off = wrap_angle(d.angle - exact.atan2(yb - ya, xb - xa))
    var = ws.new_var(f"phi_{link}", "ANGLE", "link", link, sketch=(wrap_angle(d.angle),))
    emit(ws, "angle", "link_angle", [Arg("var", ws.pos[a]), Arg("var", ws.pos[b]), Arg("real", value=off, label="off")],
         [var], link, pairs=(a, b), links=(link,), fails=True,
         reason=f"{a} and {b} of link {link} are known, so its angle is known")
    ws.orient[link] = var
    ws.angles[link] = var
    return var


def _crank_step(ws: Workspace, link: str) -> Step | None:
    """The crank_input step that turns ``link`` by an input, outside a resolver group (None elsewhere)."""
    if ws.group:
        return None
    return next((s for s in ws.steps if s.function == "crank_input" and s.links[0] == link), None)


def _crank_angle(ws: Workspace, link: str, crank: Step) -> str:
    """The angle of a link an input turns: the input angle plus its reference plus the offset from the
    crank's direction (its pair to the pair it places) to the link's (crank_angle: no atan2)."""
    joint, placed = crank.args[0].var, crank.outputs[0]
    (xa, ya), (xb, yb) = (ws.variables[n].sketch[:2] for n in (joint, placed))
    d = ws.topo.direction(link)
    off = wrap_angle(d.angle - exact.atan2(yb - ya, xb - xa))
    theta, phi = crank.args[2].var, crank.args[3].var
    var = ws.new_var(f"phi_{link}", "ANGLE", "link", link, sketch=(wrap_angle(d.angle),))
    emit(ws, "angle", "crank_angle", [Arg("var", theta), Arg("var", phi), Arg("real", value=off, label="off")],
         [var], link, pairs=(ws.variables[joint].entity, ws.variables[placed].entity), links=(link,),
         reason=f"the input {ws.variables[theta].entity} turns link {link}, so its angle is the input's")
    ws.orient[link] = var
    ws.angles[link] = var
    return var


def offset(ws: Workspace, base: str, off: float, name: str, role: str, entity: str, sketch: float, target: str,
           links: tuple[str, ...], reason: str) -> str:
    """An angle a constant ``off`` from the angle ``base`` (base itself when off is 0)."""
    if off == 0.0:
        return base
    var = ws.new_var(name, "ANGLE", role, entity, sketch=(wrap_angle(sketch),))
    emit(ws, "angle" if role != "line" else "line", "offset_angle",
         [Arg("var", base), Arg("real", value=off, label="off")], [var], target, links=links, reason=reason)
    return var


def line(ws: Workspace, pair: str) -> tuple[str, str]:
    """(guide point, line angle) of a prismatic pair whose guide is placed."""
    if pair in ws.lines:
        return ws.lines[pair]
    j = ws.m.joint(pair)
    guide = ws.m.prismatic_of(pair).guide
    if ws.link(guide).fixed:
        g = ws.new_var(f"g_{pair}", "POINT", "guide", pair, (j.x, j.y))
        psi = ws.new_var(f"psi_{pair}", "ANGLE", "line", pair, (wrap_angle(j.axis),))
    else:
        base = frame(ws, guide)
        psi = offset(ws, base, wrap_angle(j.axis - ws.angle0(base)), f"psi_{pair}", "line", pair, j.axis, pair,
                     (guide,), f"the slide axis of {pair} turns with its guide {guide}")
        copy = ws.pos.get(f"{pair}@{guide}")
        if copy is not None:
            g = copy
        else:
            g = ws.new_var(f"g_{pair}", "POINT", "guide", pair, sketch=(j.x, j.y))
            ws.pos[f"{pair}@{guide}"] = g
            ws.tied[guide].append(f"{pair}@{guide}")
            point_on(ws, guide, pair, g,
                     f"the guide {guide} of {pair} is placed, so its copy of the reference point is known")
    ws.lines[pair] = (g, psi)
    return ws.lines[pair]


def point_on(ws: Workspace, link: str, name: str, out: str, reason: str, linear: bool = False) -> None:
    """``name`` (the record ``out``) at its sketch place on a placed link: from two known points of the link
    where it has them, on the pair whose base is longest against the point's distance from its first point
    (the base's direction error turns the point by that lever): in the frame of their unit vector
    (link_point: a rounding or a resolver's tolerance that stretches the base does not reach the point), or,
    with ``linear`` (a point no chain reads) where neither pair comes out of a resolver group (whose tolerance
    can stretch their distance), linear in them (pair_point: no root, no division); else at its
    offset from the nearest known point along the link's angle (coupler_point, with link_angle where the angle
    is not known yet); also where that lever is below GOOD_LEVER and the link's angle is known otherwise (a
    slider link turning with its line: an RPR chain's angle does not depend on the short base)."""
    tied = [n for n in ws.tied[link] if ws.pos[n] != out]
    here = ws.xy(name)
    pairs = [(a, b) for a in tied for b in tied if ws.xy(a) != ws.xy(b)]
    best = min(pairs, key=lambda p: math.dist(here, ws.xy(p[0])) / math.dist(ws.xy(p[1]), ws.xy(p[0])), default=None)
    oriented = link in ws.orient or link in ws.coupled  # its angle known without these points (a slide's line)
    if best is not None and oriented and math.dist(*map(ws.xy, best)) < GOOD_LEVER * math.dist(here, ws.xy(best[0])):
        best = None  # a short base against a long arm: the line's angle places the point better
    if best is not None:
        base, far = best
        r = tuple(a - b for a, b in zip(here, ws.xy(base)))
        d = tuple(a - b for a, b in zip(ws.xy(far), ws.xy(base)))
        grouped = {o for s in ws.steps if s.group for o in s.outputs}
        if linear and not {ws.pos[base], ws.pos[far]} & grouped:
            function, labels, coords = "pair_point", ("along", "across"), exact.along_across(r[0], r[1], d[0], d[1])
        else:
            function, labels, coords = "link_point", ("gsi", "eta"), exact.local(r[0], r[1], d[0], d[1])
        emit(ws, "point", function,
             [Arg("var", ws.pos[base]), Arg("var", ws.pos[far])]
             + [Arg("real", value=v, label=k) for k, v in zip(labels, coords)], [out], name, pairs=(base, far),
             links=(link,), fails=True, reason=reason)
        return
    base = min(tied, key=lambda n: math.dist(here, ws.xy(n)))
    r = tuple(a - b for a, b in zip(here, ws.xy(base)))
    angle = frame(ws, link)
    gsi, eta = rot(ws.angle0(angle), *r)
    emit(ws, "point", "coupler_point",
         [Arg("var", ws.pos[base]), Arg("var", angle), Arg("real", value=gsi, label="gsi"),
          Arg("real", value=eta, label="eta")], [out], name, pairs=(base,), links=(link,), reason=reason)


def reference(ws: Workspace, inp: Input, root_angle: float) -> str:
    """The ANGLE of the reference link seen from the input pair."""
    name = f"ref_{inp.joint}"
    if ws.link(inp.relative_to).fixed:
        return ws.new_var(name, "ANGLE", "reference", inp.joint, (wrap_angle(root_angle),))
    base = frame(ws, inp.relative_to)
    return offset(ws, base, wrap_angle(root_angle - ws.angle0(base)), name, "reference", inp.joint, root_angle,
                  inp.joint, (inp.relative_to,),
                  f"the input at {inp.joint} is measured from this direction of link {inp.relative_to}")


def link_angle(ws: Workspace, link: str) -> None:
    """The link's own angle (its direction from the sketch), for the outputs."""
    if link in ws.angles:
        return
    d = ws.topo.direction(link)
    if link in ws.orient or link in ws.coupled:
        base = frame(ws, link)
        ws.angles[link] = offset(ws, base, wrap_angle(d.angle - ws.angle0(base)), f"phi_{link}", "link", link,
                                 d.angle, link, (link,), f"link {link} keeps a constant angle to its slide")
        return
    ws.angles[link] = frame(ws, link)
