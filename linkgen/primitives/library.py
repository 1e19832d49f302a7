"""The runtime library: mech.cpp's functions, each written once in the DSL.

Formulas (derived in docs/primitives.md, proved against sympy in the tests):
displacements are trig-free where the lecture used acos (the two-circle 3R chain
with Kahan's area formula, the slider chain with D = (l - p)(l + p)); velocities
and accelerations come from the differentiated constraints, solved in the local
frame of the chain so that the determinant carries no cancellation.  Every
tolerance is relative; no length constant appears anywhere.

This module holds the functions that place one thing from known ones (an input, a
point of a placed link, a link's angle, a residual); ``dyads`` the two-link chains.
"""

from __future__ import annotations

from .. import status
from .centres import instant_centre
from .directions import angle_direction, link_direction
from .dsl import NAN, PI, Primitive, atan2, cos, fabs, select, sin, sqrt
from .dyads import PPR_links, PRP_links, PRR_links, RPR_links, RRR_links
from .loops import loop_point, loop_residual, loop_turn
from .vectors import Motion, PlaneBuilder, primitive


@primitive
def crank_input(b: PlaneBuilder) -> Primitive:
    """Pair j2 at distance l from j1 in the direction theta + phi (input angle plus root link angle)."""
    j1 = b.point("j1")
    ln = b.scalar("l")
    theta, phi = b.record("theta", "ANGLE"), b.record("phi", "ANGLE")
    t = b.let("t", theta.the + phi.the)
    r = b.vec("r", b.direction("t", t).scaled(ln))
    om = b.let("om", theta.dthe + phi.dthe)
    al = b.let("al", theta.ddthe + phi.ddthe)
    b.output_point("j2", j1 + b.rotating("r", r, om, al))
    return b.build()


@primitive
def coupler_point(b: PlaneBuilder) -> Primitive:
    """Point jc of a link at local coordinates (gsi, eta) from its point j0, x axis at the link angle phi."""
    j0 = b.point("j0")
    phi = b.record("phi", "ANGLE")
    gsi, eta = b.scalars("gsi", "eta")
    r = b.local("r", b.direction("p", phi.the), gsi, eta)
    b.output_point("jc", j0 + b.rotating("r", r, phi.dthe, phi.ddthe))
    return b.build()


@primitive
def link_point(b: PlaneBuilder) -> Primitive:
    """Point jc of a link at local coordinates (gsi, eta) in the frame of two of its points: origin j1, x axis the
    unit vector e along j2 - j1 (no angle, no trigonometry; e's rates are those of the link's angle).  Fails where
    the two points coincide (or their distance's square underflows).
    """
    j1, j2 = b.points("j1", "j2")
    gsi, eta = b.scalars("gsi", "eta")
    d = b.difference(j1, j2)
    r2 = b.let("r2", d.p.dot(d.p))
    ir = b.let("ir", select(r2.eq(0), NAN, 1 / sqrt(r2)))
    r = b.local("r", b.vec("e", d.p.scaled(ir)), gsi, eta)
    ir2 = b.let("ir2", ir * ir)  # 1 / |d|^2 without a second division
    om = b.let("om", d.p.cross(d.v) * ir2)
    al = b.let("al", (d.p.cross(d.a) - 2 * om * d.p.dot(d.v)) * ir2)
    b.output_point("jc", j1 + b.rotating("r", r, om, al))
    return b.build(status=select(r2.eq(0), status.CANNOT_CLOSE, 0), fail=r2.eq(0))


@primitive
def pair_point(b: PlaneBuilder) -> Primitive:
    """Point jc of a link linear in two of its points: jc = j1 + along d + across n(d) with d = j2 - j1 and n(d) =
    (-dy, dx), (along, across) the point's coordinates in the sketch's frame (d, n(d)); its rates the same map of d'
    and d'' (no root, no division, no angle).  Fails where the two points coincide (or their distance's square
    underflows).
    """
    j1, j2 = b.points("j1", "j2")
    along, across = b.scalars("along", "across")
    d = b.difference(j1, j2)
    r2 = b.let("r2", d.p.dot(d.p))
    arm = Motion(b.local("r", d.p, along, across), b.local("rv", d.v, along, across),
                 b.local("ra", d.a, along, across))
    b.output_point("jc", j1 + arm)
    return b.build(status=select(r2.eq(0), status.CANNOT_CLOSE, 0), fail=r2.eq(0))


@primitive
def slider_input(b: PlaneBuilder) -> Primitive:
    """Slider point jp at displacement s along the guide line (pg, psig) and its pair jc at (gsi, eta)."""
    pg = b.point("pg")
    psig = b.record("psig", "ANGLE")
    s = b.record("s", "VARIABLE")
    gsi, eta = b.scalars("gsi", "eta")
    u = b.direction("g", psig.the)
    om, al = psig.dthe, psig.ddthe
    jp = b.vec("jp", pg.p + u.scaled(s.v))
    r = b.local("r", u, gsi, eta)
    jpv = b.sliding_velocity("jpv", pg.v, s.dv, s.v * om, u)
    jpa = b.sliding_acceleration("jpa", pg.a, s.ddv, 2 * s.dv * om + s.v * al, s.v * om * om, u)
    slider = Motion(jp, jpv, jpa)
    b.output_point("jp", slider)
    b.output_point("jc", slider + b.rotating("r", r, om, al))
    return b.build()


@primitive
def link_angle(b: PlaneBuilder) -> Primitive:
    """Angle of a link from two of its points j1, j2, plus the sketch offset off, wrapped to (-pi, pi]."""
    j1, j2 = b.points("j1", "j2")
    off = b.scalar("off")
    d = b.difference(j1, j2)
    r2 = b.let("r2", d.p.dot(d.p))
    th = b.wrapped("th", atan2(d.p.y, d.p.x) + off)
    om, al = b.angle_rates(d, r2)
    b.output("angle", "ANGLE", the=th, dthe=om, ddthe=al)
    return b.build(status=select(r2.eq(0), status.CANNOT_CLOSE, 0), fail=r2.eq(0))


@primitive
def crank_angle(b: PlaneBuilder) -> Primitive:
    """Angle of a link an input angle turns (crank_input): the input angle theta plus the root link angle phi
    plus the sketch offset off, wrapped to (-pi, pi], with their rates; no atan2 of the placed points (their
    rounding does not reach it).  Beyond one and a half turns either way (an input of many turns) wrapped by
    atan2 of its sine and cosine."""
    theta, phi = b.record("theta", "ANGLE"), b.record("phi", "ANGLE")
    off = b.scalar("off")
    raw = b.let("th0", theta.the + phi.the + off)
    near = select(raw > PI, raw - 2 * PI, select(raw <= -PI, raw + 2 * PI, raw))
    th = b.let("th", select(fabs(raw) >= 3 * PI, atan2(sin(raw), cos(raw)), near))
    b.output("angle", "ANGLE", the=th, dthe=theta.dthe + phi.dthe, ddthe=theta.ddthe + phi.ddthe)
    return b.build()


@primitive
def offset_angle(b: PlaneBuilder) -> Primitive:
    """Angle of a link that keeps a constant angle off to a known angle phi."""
    phi = b.record("phi", "ANGLE")
    off = b.scalar("off")
    th = b.wrapped("th", phi.the + off)
    b.output("angle", "ANGLE", the=th, dthe=phi.dthe, ddthe=phi.ddthe)
    return b.build()


@primitive
def link_residual(b: PlaneBuilder) -> Primitive:
    """Over-constraint residual f = |j2 - j1| - l of a link the Solver did not use, with its rates (where the pairs
    coincide, the distance's rates as they part).
    """
    j1, j2 = b.points("j1", "j2")
    ln = b.record("l", "VARIABLE")
    m = b.difference(j1, j2)
    d, dv, da = m.p, m.v, m.a
    r = b.let("r", d.norm())
    ir = b.let("ir", select(r.eq(0), NAN, 1 / r))
    # coincident pairs: |d(t)| = t |dv| + t^2 dv.da / (2 |dv|) + ... (t^2 |da| / 2 where dv = 0)
    s = b.let("s", dv.norm())
    iv = b.let("iv", select(s.eq(0), NAN, 1 / s))
    rd = b.let("rd", select(r.eq(0), dv.norm(), d.dot(dv) * ir))  # s where read: a rate alone needs no sqrt of it
    parting = b.let("rp", select(s.eq(0), da.norm(), dv.dot(da) * iv))
    rdd = b.let("rdd", select(r.eq(0), parting, (dv.dot(dv) + d.dot(da) - rd * rd) * ir))
    b.output("f", "VARIABLE", v=r - ln.v, dv=rd - ln.dv, ddv=rdd - ln.ddv)
    return b.build()


PRIMITIVES: dict[str, Primitive] = {
    p.name: p
    for p in (
        crank_input,
        slider_input,
        link_angle,
        crank_angle,
        offset_angle,
        coupler_point,
        link_point,
        pair_point,
        RRR_links,
        PRR_links,
        PRP_links,
        RPR_links,
        PPR_links,
        link_residual,
        loop_point,
        loop_residual,
        loop_turn,
        link_direction,
        angle_direction,
        instant_centre,
    )
}
