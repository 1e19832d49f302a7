"""Two-link chains: a pair joined to two known ends, one chain function per planar dyad.

RRR_links (3R), PRR_links (2R1P), PRP_links (1R2P), RPR_links (the inverted slider-crank)
and PPR_links (the Scotch yoke).  Each chain's branch is read off the sketch.
"""

from __future__ import annotations

from .. import exact
from ..steplog import Arg
from ..topology import wrap_angle
from .emit import emit
from .placement import line, rot
from .state import Carrier, Workspace


def carriers_of(ws: Workspace, pair: str) -> list[Carrier]:
    """Links, actuators and unused Add-links that carry the pair."""
    return [c for c in ws.carriers_with(pair) if c.kind == "link" or c.name not in ws.used]


def ends(ws: Workspace, carrier: Carrier, middle: str) -> list[tuple[str, str]]:
    """Known ends of a carrier for a chain through ``middle``: (pair, 'R' | 'P')."""
    if carrier.kind == "link" and carrier.name in ws.placed:
        return []
    out = []
    for p in carrier.pairs:
        if p == middle:
            continue
        if ws.m.joint(p).revolute:
            if p in ws.pos:
                out.append((p, "R"))
        elif carrier.kind == "link":
            pr = ws.m.prismatic_of(p)
            if pr.slider == carrier.name and pr.guide in ws.placed:
                out.append((p, "P"))
    return out


def try_chain(ws: Workspace, pair: str, only: str = "", slides: bool = False) -> bool:
    """The pair as the middle of a two-link chain whose two ends are known (through the
    carrier ``only`` when given; with ``slides``, only a chain with a prismatic pair)."""
    carriers = [c for c in carriers_of(ws, pair) if not (c.kind == "link" and c.name in ws.placed)]
    joint = ws.m.joint(pair)
    if not joint.revolute:
        pr = ws.m.prismatic_of(pair)
        carriers = [c for c in carriers if c.name in (pr.guide, pr.slider)]
    for i, a in enumerate(carriers):
        for b in carriers[i + 1:]:
            if only and only not in (a.name, b.name):
                continue
            for e1, t1 in ends(ws, a, pair):
                for e2, t2 in ends(ws, b, pair):
                    if e1 == e2:
                        continue
                    kind = t1 + ("R" if joint.revolute else "P") + t2
                    if kind != "PPP" and (not slides or "P" in kind) and _chain(ws, kind, pair, a, e1, b, e2):
                        return True
    return False


def _chain(ws: Workspace, kind: str, x: str, a: Carrier, e1: str, b: Carrier, e2: str) -> bool:
    if kind == "RRR":
        return _rrr(ws, x, a, e1, b, e2)
    if kind in ("RRP", "PRR"):
        return _prr(ws, x, *((a, e1, b, e2) if kind == "RRP" else (b, e2, a, e1)))
    if kind == "PRP":
        return _prp(ws, x, a, e1, b, e2)
    if kind == "RPR":
        return _rpr(ws, x, a, e1, b, e2)
    return _ppr(ws, x, *((a, e1, b, e2) if kind == "PPR" else (b, e2, a, e1)))


def mark(ws: Workspace, x: str, *carriers: Carrier) -> None:
    """x is now known on these carriers (tied to a link; an actuator or Add-link used)."""
    for c in carriers:
        if c.kind == "link":
            if x not in ws.tied[c.name]:
                ws.tied[c.name].append(x)
        else:
            ws.used.add(c.name)


def _sign(value: float) -> int:
    return 1 if value >= 0 else -1


def _branch_note(sign: int, sketch: float, what: str) -> str:
    if sketch == 0.0:
        return f"the sketch draws this chain at a toggle ({what} is zero); branch {sign:+d} is taken"
    return f"the sketch has {what} {'positive' if sign > 0 else 'negative'}, so branch {sign:+d}"


def _along(p: tuple[float, float], q: tuple[float, float], axis: float) -> float:
    """(q - p) along the direction ``axis``."""
    return (q[0] - p[0]) * exact.cos(axis) + (q[1] - p[1]) * exact.sin(axis)


def _local(ws: Workspace, axis: float, name: str, base: str) -> tuple[float, float]:
    """name - base in the frame of ``axis``."""
    return rot(axis, *(p - q for p, q in zip(ws.xy(name), ws.xy(base))))


def _rrr(ws: Workspace, x: str, a: Carrier, e1: str, b: Carrier, e2: str) -> bool:
    p1, p2, px = ws.xy(e1), ws.xy(e2), ws.xy(x)
    side = (p2[0] - p1[0]) * (px[1] - p1[1]) - (p2[1] - p1[1]) * (px[0] - p1[0])
    sign = _sign(side)
    l1, l2 = ws.length_of(a.name, e1, x), ws.length_of(b.name, x, e2)
    ws.pos[x] = ws.point_var(x)
    mark(ws, x, a, b)
    emit(ws, "chain", "RRR_links",
         [Arg("var", ws.pos[e1]), Arg("var", ws.pos[e2]), Arg("var", l1), Arg("var", l2),
          Arg("int", value=sign, label="minv")], [ws.pos[x]], x, chain="RRR", pairs=(e1, e2),
         links=(a.name, b.name), branch=sign, fails=True,
         reason=f"{x} is joined to the known {e1} by {a.name} and to the known {e2} by {b.name}: "
                "a 3R two-link chain with both ends known",
         branch_reason=_branch_note(sign, side, f"{x} on the left of {e1}->{e2}"))
    return True


def _prr(ws: Workspace, x: str, a: Carrier, er: str, b: Carrier, ep: str) -> bool:
    """a turns about the known revolute er; b slides on the known line of ep."""
    j = ws.m.joint(ep)
    g, psi = line(ws, ep)
    along = _along(ws.xy(er), ws.xy(x), j.axis)
    sign = _sign(along)
    gsi, eta = _local(ws, j.axis, x, ep)
    length = ws.length_of(a.name, er, x)
    ws.pos[x] = ws.point_var(x)
    ws.pos[ep] = ws.point_var(ep)
    s = ws.new_var(f"s_{ep}", "VARIABLE", "slide", ep, sketch=(0.0,))
    ws.slides[ep] = s
    mark(ws, x, a, b)
    mark(ws, ep, b)
    emit(ws, "chain", "PRR_links",
         [Arg("var", ws.pos[er]), Arg("var", length), Arg("var", g), Arg("var", psi),
          Arg("real", value=gsi, label="gsi"), Arg("real", value=eta, label="eta"),
          Arg("int", value=sign, label="minv")], [s, ws.pos[ep], ws.pos[x]], x, chain="RRP",
         pairs=(er, ep), links=(a.name, b.name), branch=sign, fails=True,
         reason=f"{x} is joined to the known {er} by {a.name} and rides on the slider {b.name} of the "
                f"known line {ep}: a 2R1P two-link chain with both ends known",
         branch_reason=_branch_note(sign, along, f"{x} ahead of {er} along the axis of {ep}"))
    return True


def _prp(ws: Workspace, x: str, a: Carrier, e1: str, b: Carrier, e2: str) -> bool:
    args: list[Arg] = []
    outs: list[str] = []
    for e in (e1, e2):
        g, psi = line(ws, e)
        gsi, eta = _local(ws, ws.m.joint(e).axis, x, e)
        args += [Arg("var", g), Arg("var", psi), Arg("real", value=gsi, label="gsi"),
                 Arg("real", value=eta, label="eta")]
        ws.slides[e] = ws.new_var(f"s_{e}", "VARIABLE", "slide", e, sketch=(0.0,))
        ws.pos[e] = ws.point_var(e)
        outs += [ws.slides[e], ws.pos[e]]
    ws.pos[x] = ws.point_var(x)
    outs.append(ws.pos[x])
    mark(ws, x, a, b)
    mark(ws, e1, a)
    mark(ws, e2, b)
    emit(ws, "chain", "PRP_links", args, outs, x, chain="PRP", pairs=(e1, e2), links=(a.name, b.name),
         fails=True, reason=f"{x} joins the slider {a.name} on the known line {e1} and the slider {b.name} "
                            f"on the known line {e2}: a 1R2P two-link chain (one solution)")
    return True


def _rpr(ws: Workspace, x: str, a: Carrier, e1: str, b: Carrier, e2: str) -> bool:
    pr = ws.m.prismatic_of(x)
    if {a.name, b.name} != {pr.guide, pr.slider}:
        return False
    eg, es = (e1, e2) if a.name == pr.guide else (e2, e1)
    axis = ws.m.joint(x).axis
    ag, bg = _local(ws, axis, x, eg)
    as_, bs = _local(ws, axis, x, es)
    along = _along(ws.xy(eg), ws.xy(es), axis)
    sign = _sign(along)
    psi = ws.new_var(f"psi_{x}", "ANGLE", "line", x, sketch=(wrap_angle(axis),))
    s = ws.new_var(f"s_{x}", "VARIABLE", "slide", x, sketch=(0.0,))
    ws.pos[x] = ws.point_var(x)
    ws.slides[x] = s
    ws.orient[pr.guide] = ws.orient[pr.slider] = psi
    mark(ws, x, ws.carrier(pr.slider))
    emit(ws, "chain", "RPR_links",
         [Arg("var", ws.pos[eg]), Arg("var", ws.pos[es]), Arg("real", value=ag, label="ag"),
          Arg("real", value=bg, label="bg"), Arg("real", value=as_, label="as"),
          Arg("real", value=bs, label="bs"),
          Arg("int", value=sign, label="minv")], [psi, s, ws.pos[x]], x, chain="RPR", pairs=(eg, es),
         links=(pr.guide, pr.slider), branch=sign, fails=True,
         reason=f"the guide {pr.guide} turns about the known {eg} and the slider {pr.slider} about the "
                f"known {es}, sliding along one line at {x}: an RPR two-link chain with both ends known",
         branch_reason=_branch_note(sign, along, f"{es} ahead of {eg} along the axis of {x}"))
    return True


def _ppr(ws: Workspace, x: str, b: Carrier, ep: str, a: Carrier, er: str) -> bool:
    """b slides on the known line of ep; a turns about the known er; x joins them."""
    px = ws.m.prismatic_of(x)
    if {a.name, b.name} != {px.guide, px.slider}:
        return False
    je, jx = ws.m.joint(ep), ws.m.joint(x)
    if exact.sin(jx.axis - je.axis) == 0.0:
        return False  # parallel slides: the chain cannot fix the position
    g, psi = line(ws, ep)
    xa, ya = _local(ws, je.axis, x, er)
    xb, yb = _local(ws, je.axis, x, ep)
    sgn = 1 if px.slider == a.name else -1
    s1 = ws.new_var(f"s_{ep}", "VARIABLE", "slide", ep, sketch=(0.0,))
    sx = ws.new_var(f"s_{x}", "VARIABLE", "slide", x, sketch=(0.0,))
    ws.pos[ep] = ws.point_var(ep)
    ws.pos[x] = ws.point_var(x)
    ws.slides[ep], ws.slides[x] = s1, sx
    ws.orient[a.name] = psi
    mark(ws, ep, b)
    mark(ws, x, ws.carrier(px.slider))
    emit(ws, "chain", "PPR_links",
         [Arg("var", ws.pos[er]), Arg("var", g), Arg("var", psi), Arg("real", value=xa, label="xa"),
          Arg("real", value=ya, label="ya"), Arg("real", value=xb, label="xb"),
          Arg("real", value=yb, label="yb"),
          Arg("real", value=wrap_angle(jx.axis - je.axis), label="cx"), Arg("int", value=sgn, label="sgn")],
         [s1, ws.pos[ep], sx, ws.pos[x]], x, chain="PPR", pairs=(ep, er), links=(b.name, a.name),
         fails=True, reason=f"the slider {b.name} rides on the known line {ep} and carries the slide {x} of "
                            f"{a.name}, which turns about the known {er}: a PPR two-link chain (one solution)")
    return True
