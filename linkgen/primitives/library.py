"""The runtime library: mech.cpp's functions, each written once in the DSL.

Formulas (derived in docs/primitives.md, proved against sympy in the tests):
displacements are trig-free where the lecture used acos (the two-circle 3R chain
with Kahan's area formula, the slider chain with D = (l - p)(l + p)); velocities
and accelerations come from the differentiated constraints, solved in the local
frame of the chain so that the determinant carries no cancellation.  Every
tolerance is relative; no length constant appears anywhere.

Vectors are pairs of expressions; ``u`` is a unit direction, ``n`` its left normal.
"""

from __future__ import annotations

from ..policy import NEAR_SINGULAR, SINGULAR, TOGGLE_SLACK
from .dsl import (
    EPS,
    NAN,
    PI,
    Builder,
    Expr,
    Primitive,
    atan2,
    cos,
    either,
    fabs,
    fmax,
    fmin,
    select,
    sin,
    sqrt,
)

Vec = tuple[Expr, Expr]


def _status(fail: Expr, sigma: Expr) -> Expr:
    return select(fail, 1, select(sigma < SINGULAR, 3, select(sigma < NEAR_SINGULAR, 4, 0)))


def _wrap(b: Builder, name: str, angle: Expr) -> Expr:
    """Angle wrapped to (-pi, pi]."""
    return b.let(name, select(angle > PI, angle - 2 * PI, select(angle <= -PI, angle + 2 * PI, angle)))


def _local(b: Builder, name: str, u: Vec, gsi: Expr, eta: Expr) -> Vec:
    """The vector gsi*u + eta*n in global coordinates."""
    return (
        b.let(f"{name}x", gsi * u[0] - eta * u[1]),
        b.let(f"{name}y", gsi * u[1] + eta * u[0]),
    )


def _dir(b: Builder, name: str, angle: Expr) -> Vec:
    return b.let(f"c{name}", cos(angle)), b.let(f"s{name}", sin(angle))


def _norm(d: Vec) -> Expr:
    """|d| as sqrt(dx^2 + dy^2): correctly rounded sqrt makes it the same bits in every
    language (hypot implementations differ in the last bit between libraries)."""
    return sqrt(d[0] * d[0] + d[1] * d[1])


def _dot(a: Vec, c: Vec) -> Expr:
    return a[0] * c[0] + a[1] * c[1]


def _cross(a: Vec, c: Vec) -> Expr:
    return a[0] * c[1] - a[1] * c[0]


def _point(j) -> tuple[Vec, Vec, Vec]:
    return (j.x, j.y), (j.dx, j.dy), (j.ddx, j.ddy)


def _point_result(p: Vec, v: Vec, a: Vec) -> dict[str, Expr]:
    return {"x": p[0], "y": p[1], "dx": v[0], "dy": v[1], "ddx": a[0], "ddy": a[1]}


def _rotating(b: Builder, name: str, r: Vec, om: Expr, al: Expr) -> tuple[Vec, Vec]:
    """Velocity and acceleration of a vector r fixed in a body turning at om, al."""
    vel = (b.let(f"{name}vx", -om * r[1]), b.let(f"{name}vy", om * r[0]))
    om2 = om * om
    acc = (b.let(f"{name}ax", -al * r[1] - om2 * r[0]), b.let(f"{name}ay", al * r[0] - om2 * r[1]))
    return vel, acc


def crank_input() -> Primitive:
    b = Builder(
        "crank_input",
        "Pair j2 at distance l from j1 in the direction theta + phi (input angle plus root link angle).",
    )
    j1 = b.record("j1", "POINT")
    ln = b.scalar("l")
    theta = b.record("theta", "ANGLE")
    phi = b.record("phi", "ANGLE")
    t = b.let("t", theta.the + phi.the)
    u = _dir(b, "t", t)
    r = (b.let("rx", ln * u[0]), b.let("ry", ln * u[1]))
    om = b.let("om", theta.dthe + phi.dthe)
    al = b.let("al", theta.ddthe + phi.ddthe)
    vel, acc = _rotating(b, "r", r, om, al)
    p, v, a = _point(j1)
    b.output(
        "j2", "POINT",
        **_point_result(
            (p[0] + r[0], p[1] + r[1]), (v[0] + vel[0], v[1] + vel[1]), (a[0] + acc[0], a[1] + acc[1])
        ),
    )
    return b.build()


def coupler_point() -> Primitive:
    b = Builder(
        "coupler_point",
        "Point jc of a link at local coordinates (gsi, eta) from its point j0, x axis at the link angle phi.",
    )
    j0 = b.record("j0", "POINT")
    phi = b.record("phi", "ANGLE")
    gsi = b.scalar("gsi")
    eta = b.scalar("eta")
    u = _dir(b, "p", phi.the)
    r = _local(b, "r", u, gsi, eta)
    vel, acc = _rotating(b, "r", r, phi.dthe, phi.ddthe)
    p, v, a = _point(j0)
    b.output(
        "jc", "POINT",
        **_point_result(
            (p[0] + r[0], p[1] + r[1]), (v[0] + vel[0], v[1] + vel[1]), (a[0] + acc[0], a[1] + acc[1])
        ),
    )
    return b.build()


def slider_input() -> Primitive:
    b = Builder(
        "slider_input",
        "Slider point jp at displacement s along the guide line (pg, psig) and its pair jc at (gsi, eta).",
    )
    pg = b.record("pg", "POINT")
    psig = b.record("psig", "ANGLE")
    s = b.record("s", "VARIABLE")
    gsi = b.scalar("gsi")
    eta = b.scalar("eta")
    u = _dir(b, "g", psig.the)
    om, al = psig.dthe, psig.ddthe
    p, v, a = _point(pg)
    jp = (b.let("jpx", p[0] + s.v * u[0]), b.let("jpy", p[1] + s.v * u[1]))
    r = _local(b, "r", u, gsi, eta)
    jpv = (
        b.let("jpvx", v[0] + s.dv * u[0] - s.v * om * u[1]),
        b.let("jpvy", v[1] + s.dv * u[1] + s.v * om * u[0]),
    )
    jpa = (
        b.let("jpax", a[0] + s.ddv * u[0] - (2 * s.dv * om + s.v * al) * u[1] - s.v * om * om * u[0]),
        b.let("jpay", a[1] + s.ddv * u[1] + (2 * s.dv * om + s.v * al) * u[0] - s.v * om * om * u[1]),
    )
    vel, acc = _rotating(b, "r", r, om, al)
    b.output("jp", "POINT", **_point_result(jp, jpv, jpa))
    b.output(
        "jc", "POINT",
        **_point_result(
            (jp[0] + r[0], jp[1] + r[1]),
            (jpv[0] + vel[0], jpv[1] + vel[1]),
            (jpa[0] + acc[0], jpa[1] + acc[1]),
        ),
    )
    return b.build()


def _angle_rates(b: Builder, d: Vec, dv: Vec, da: Vec, r2: Expr) -> tuple[Expr, Expr]:
    """omega and alpha of the direction of a segment d with rates dv, da."""
    ir2 = b.let("ir2", select(r2.eq(0), NAN, 1 / r2))
    om = b.let("om", _cross(d, dv) * ir2)
    al = b.let("al", (_cross(d, da) - 2 * om * _dot(d, dv)) * ir2)
    return om, al


def _difference(b: Builder, j1, j2) -> tuple[Vec, Vec, Vec]:
    p1, v1, a1 = _point(j1)
    p2, v2, a2 = _point(j2)
    d = (b.let("dx", p2[0] - p1[0]), b.let("dy", p2[1] - p1[1]))
    dv = (b.let("dvx", v2[0] - v1[0]), b.let("dvy", v2[1] - v1[1]))
    da = (b.let("dax", a2[0] - a1[0]), b.let("day", a2[1] - a1[1]))
    return d, dv, da


def link_angle() -> Primitive:
    b = Builder(
        "link_angle",
        "Angle of a link from two of its points j1, j2, plus the sketch offset off, wrapped to (-pi, pi].",
    )
    j1 = b.record("j1", "POINT")
    j2 = b.record("j2", "POINT")
    off = b.scalar("off")
    d, dv, da = _difference(b, j1, j2)
    r2 = b.let("r2", _dot(d, d))
    th = _wrap(b, "th", atan2(d[1], d[0]) + off)
    om, al = _angle_rates(b, d, dv, da, r2)
    b.output("angle", "ANGLE", the=th, dthe=om, ddthe=al)
    return b.build(status=select(r2.eq(0), 1, 0))


def offset_angle() -> Primitive:
    b = Builder("offset_angle", "Angle of a link that keeps a constant angle off to a known angle phi.")
    phi = b.record("phi", "ANGLE")
    off = b.scalar("off")
    th = _wrap(b, "th", phi.the + off)
    b.output("angle", "ANGLE", the=th, dthe=phi.dthe, ddthe=phi.ddthe)
    return b.build()


def link_residual() -> Primitive:
    b = Builder(
        "link_residual",
        "Over-constraint residual f = |j2 - j1| - l of a link the Solver did not use, with its rates "
        "(where the pairs coincide, the distance's rates as they part).",
    )
    j1 = b.record("j1", "POINT")
    j2 = b.record("j2", "POINT")
    ln = b.record("l", "VARIABLE")
    d, dv, da = _difference(b, j1, j2)
    r = b.let("r", _norm(d))
    ir = b.let("ir", select(r.eq(0), NAN, 1 / r))
    # coincident pairs: |d(t)| = t |dv| + t^2 dv.da / (2 |dv|) + ... (t^2 |da| / 2 where dv = 0)
    s = b.let("s", _norm(dv))
    iv = b.let("iv", select(s.eq(0), NAN, 1 / s))
    rd = b.let("rd", select(r.eq(0), s, _dot(d, dv) * ir))
    parting = b.let("rp", select(s.eq(0), _norm(da), _dot(dv, da) * iv))
    rdd = b.let("rdd", select(r.eq(0), parting, (_dot(dv, dv) + _dot(d, da) - rd * rd) * ir))
    b.output("f", "VARIABLE", v=r - ln.v, dv=rd - ln.dv, ddv=rdd - ln.ddv)
    return b.build()


def rrr_links() -> Primitive:
    b = Builder(
        "RRR_links",
        "3R chain: pair jb at distance l1 from j1 and l2 from j2, on the side minv (+1 left of j1->j2).",
    )
    j1 = b.record("j1", "POINT")
    j2 = b.record("j2", "POINT")
    l1 = b.record("l1", "VARIABLE")
    l2 = b.record("l2", "VARIABLE")
    minv = b.scalar("minv", "INT")
    p1, v1, a1 = _point(j1)
    p2, v2, a2 = _point(j2)
    d = (b.let("dx", p2[0] - p1[0]), b.let("dy", p2[1] - p1[1]))
    q = b.let("q", _norm(d))
    iq = b.let("iq", select(q.eq(0), NAN, 1 / q))
    u = (b.let("ux", d[0] * iq), b.let("uy", d[1] * iq))
    # Kahan's area formula on the sorted sides x >= y >= z
    hi = b.let("hi", fmax(l1.v, l2.v))
    lo = b.let("lo", fmin(l1.v, l2.v))
    x = b.let("x", fmax(hi, q))
    z = b.let("z", fmin(lo, q))
    y = b.let("y", select(q >= hi, hi, select(q <= lo, lo, q)))
    k = b.let("k", z - (x - y))
    fail = b.let("fail", either(either(k < -TOGGLE_SLACK * EPS * x, q.eq(0)), lo <= 0))
    kk = b.let("kk", fmax(k, 0))
    area4 = b.let("area4", sqrt((x + (y + z)) * kk * (z + (x - y)) * (x + (y - z))))  # 4 x the triangle's area
    h = b.let("h", area4 * iq / 2)
    a = b.let("a", (q + (l1.v - l2.v) * ((l1.v + l2.v) * iq)) / 2)
    a2_ = b.let("a2", (q + (l2.v - l1.v) * ((l1.v + l2.v) * iq)) / 2)
    # At a toggle (k <= 0: the circles touch, or miss by rounding) jb lies on the line: halfway
    # between the circles' nearest points, as a is at an exact toggle.  a's division by q would
    # magnify the miss there by l/q (a folded chain with a needle: 4 eps L off its circles).
    flat = b.let("flat", select(q >= hi, (l1.v + (q - l2.v)) / 2,
                                select(l1.v >= l2.v, (l1.v + (q + l2.v)) / 2, (q - (l1.v + l2.v)) / 2)))
    at = b.let("at", select(k > 0, a, flat))
    hn = b.let("hn", minv * h)
    e1 = (b.let("e1x", at * u[0] - hn * u[1]), b.let("e1y", at * u[1] + hn * u[0]))
    sigma = b.let("sigma", select(fail, 0, fmin(area4 / (2 * l1.v * l2.v), 1)))
    # derivatives: (jb - ji).(jb' - ji') = li li', solved in the (u, n) frame:
    #   a bu + hn bn = r1,  -a2 bu + hn bn = r2   (determinant hn q)
    e2 = (b.let("e2x", -a2_ * u[0] - hn * u[1]), b.let("e2y", -a2_ * u[1] + hn * u[0]))
    ihq = b.let("ihq", select(hn.eq(0), NAN, 1 / (hn * q)))

    def solve(tag: str, rhs1: Expr, rhs2: Expr) -> Vec:
        r1 = b.let(f"r1{tag}", rhs1)
        r2 = b.let(f"r2{tag}", rhs2)
        bu = b.let(f"bu{tag}", (r1 - r2) * iq)
        bn = b.let(f"bn{tag}", (a2_ * r1 + a * r2) * ihq)
        return b.let(f"b{tag}x", bu * u[0] - bn * u[1]), b.let(f"b{tag}y", bu * u[1] + bn * u[0])

    vel = solve("v", l1.v * l1.dv + _dot(e1, v1), l2.v * l2.dv + _dot(e2, v2))
    w1 = (vel[0] - v1[0], vel[1] - v1[1])
    w2 = (vel[0] - v2[0], vel[1] - v2[1])
    acc = solve(
        "a",
        l1.v * l1.ddv + l1.dv * l1.dv - _dot(w1, w1) + _dot(e1, a1),
        l2.v * l2.ddv + l2.dv * l2.dv - _dot(w2, w2) + _dot(e2, a2),
    )
    b.output("jb", "POINT", **_point_result((p1[0] + e1[0], p1[1] + e1[1]), vel, acc))
    return b.build(status=_status(fail, sigma), sigma=sigma)


def prr_links() -> Primitive:
    b = Builder(
        "PRR_links",
        "2R1P chain: pair jb at distance l from jr, carried at (gsi, eta) by a slider on the guide "
        "line (pg, psig); s is the slider displacement from pg, jp the slider point, minv the side.",
    )
    jr = b.record("jr", "POINT")
    ln = b.record("l", "VARIABLE")
    pg = b.record("pg", "POINT")
    psig = b.record("psig", "ANGLE")
    gsi = b.scalar("gsi")
    eta = b.scalar("eta")
    minv = b.scalar("minv", "INT")
    pr, vr, ar = _point(jr)
    p, v, a = _point(pg)
    u = _dir(b, "g", psig.the)
    om, al = psig.dthe, psig.ddthe
    r = _local(b, "r", u, gsi, eta)
    w = (b.let("wx", p[0] + r[0] - pr[0]), b.let("wy", p[1] + r[1] - pr[1]))
    wu = b.let("wu", _dot(w, u))
    pn = b.let("pn", _cross(w, u))  # signed distance of jr from the line of jb
    ap = b.let("ap", fabs(pn))
    k = b.let("k", ln.v - ap)
    fail = b.let("fail", either(k < -TOGGLE_SLACK * EPS * fmax(ln.v, ap), ln.v <= 0))
    rd = b.let("rd", sqrt(fmax(k, 0) * (ln.v + ap)))
    eu = b.let("eu", minv * rd)  # (jb - jr).u
    en = -pn  # (jb - jr).n
    e = (b.let("ex", eu * u[0] - en * u[1]), b.let("ey", eu * u[1] + en * u[0]))
    s = b.let("sv", eu - wu)
    jb = (b.let("jbx", pr[0] + e[0]), b.let("jby", pr[1] + e[1]))
    jp = (b.let("jpx", jb[0] - r[0]), b.let("jpy", jb[1] - r[1]))
    sigma = b.let("sigma", select(fail, 0, fmin(rd / ln.v, 1)))
    ieu = b.let("ieu", select(eu.eq(0), NAN, 1 / eu))
    sg = b.let("sgsi", s + gsi)
    rel = (b.let("relvx", v[0] - vr[0]), b.let("relvy", v[1] - vr[1]))
    ds = b.let("ds", (ln.v * ln.dv - _dot(e, rel) - om * (sg * en - eta * eu)) * ieu)
    jpv = (
        b.let("jpvx", v[0] + ds * u[0] - s * om * u[1]),
        b.let("jpvy", v[1] + ds * u[1] + s * om * u[0]),
    )
    rv, ra = _rotating(b, "r", r, om, al)
    jbv = (b.let("jbvx", jpv[0] + rv[0]), b.let("jbvy", jpv[1] + rv[1]))
    wv = (jbv[0] - vr[0], jbv[1] - vr[1])
    rela = (b.let("relax", a[0] - ar[0]), b.let("relay", a[1] - ar[1]))
    om2 = b.let("om2", om * om)
    dds = b.let(
        "dds",
        (
            ln.v * ln.ddv + ln.dv * ln.dv - _dot(wv, wv) - _dot(e, rela)
            - 2 * ds * om * en - sg * (al * en - om2 * eu) + eta * (al * eu + om2 * en)
        ) * ieu,
    )
    tn = b.let("tn", 2 * ds * om + s * al)
    jpa = (
        b.let("jpax", a[0] + dds * u[0] - tn * u[1] - s * om2 * u[0]),
        b.let("jpay", a[1] + dds * u[1] + tn * u[0] - s * om2 * u[1]),
    )
    b.output("s", "VARIABLE", v=s, dv=ds, ddv=dds)
    b.output("jp", "POINT", **_point_result(jp, jpv, jpa))
    b.output("jb", "POINT", **_point_result(jb, jbv, (jpa[0] + ra[0], jpa[1] + ra[1])))
    return b.build(status=_status(fail, sigma), sigma=sigma)


def prp_links() -> Primitive:
    b = Builder(
        "PRP_links",
        "1R2P chain: pair jb joins two sliders on the guide lines (pg1, psig1) and (pg2, psig2), "
        "at (gsi1, eta1) and (gsi2, eta2) from their slider points jp1, jp2 (displacements s1, s2).",
    )
    pg1 = b.record("pg1", "POINT")
    psig1 = b.record("psig1", "ANGLE")
    gsi1 = b.scalar("gsi1")
    eta1 = b.scalar("eta1")
    pg2 = b.record("pg2", "POINT")
    psig2 = b.record("psig2", "ANGLE")
    gsi2 = b.scalar("gsi2")
    eta2 = b.scalar("eta2")
    guides = []
    for i, (pg, psig, gsi, eta) in enumerate(((pg1, psig1, gsi1, eta1), (pg2, psig2, gsi2, eta2)), 1):
        u = _dir(b, f"g{i}", psig.the)
        r = _local(b, f"r{i}", u, gsi, eta)
        guides.append((pg, psig, u, r))
    (pa, psa, u1, r1), (pb, psb, u2, r2) = guides
    cr = b.let("cr", _cross(u1, u2))
    icr = b.let("icr", select(cr.eq(0), NAN, 1 / cr))
    g = (b.let("gx", pb.x + r2[0] - pa.x - r1[0]), b.let("gy", pb.y + r2[1] - pa.y - r1[1]))
    # jb from guide 1, then jp2 = jb - r2 and s2 from it: every constraint then holds to
    # rounding (computing s2 from g as well would put jp2 and jb apart by the conditioned error)
    s1 = b.let("sv1", _cross(g, u2) * icr)
    jp1 = (b.let("jp1x", pa.x + s1 * u1[0]), b.let("jp1y", pa.y + s1 * u1[1]))
    jbp = (b.let("jbx", jp1[0] + r1[0]), b.let("jby", jp1[1] + r1[1]))
    jp2 = (b.let("jp2x", jbp[0] - r2[0]), b.let("jp2y", jbp[1] - r2[1]))
    s2 = b.let("sv2", (jp2[0] - pb.x) * u2[0] + (jp2[1] - pb.y) * u2[1])
    sigma = b.let("sigma", fmin(fabs(cr), 1))
    rv1, ra1 = _rotating(b, "r1", r1, psa.dthe, psa.ddthe)
    rv2, ra2 = _rotating(b, "r2", r2, psb.dthe, psb.ddthe)
    # s1 u1 - s2 u2 = g  differentiated: s1' u1 - s2' u2 = gv
    om1, om2 = psa.dthe, psb.dthe
    gv = (
        b.let("gvx", pb.dx + rv2[0] - s2 * om2 * u2[1] - pa.dx - rv1[0] + s1 * om1 * u1[1]),
        b.let("gvy", pb.dy + rv2[1] + s2 * om2 * u2[0] - pa.dy - rv1[1] - s1 * om1 * u1[0]),
    )
    ds1 = b.let("ds1", _cross(gv, u2) * icr)
    ds2 = b.let("ds2", _cross(gv, u1) * icr)
    jp1v = (b.let("jp1vx", pa.dx + ds1 * u1[0] - s1 * om1 * u1[1]),
            b.let("jp1vy", pa.dy + ds1 * u1[1] + s1 * om1 * u1[0]))
    jp2v = (b.let("jp2vx", pb.dx + ds2 * u2[0] - s2 * om2 * u2[1]),
            b.let("jp2vy", pb.dy + ds2 * u2[1] + s2 * om2 * u2[0]))
    al1, al2 = psa.ddthe, psb.ddthe
    t1n = b.let("t1n", 2 * ds1 * om1 + s1 * al1)
    t2n = b.let("t2n", 2 * ds2 * om2 + s2 * al2)
    t1u = b.let("t1u", s1 * om1 * om1)
    t2u = b.let("t2u", s2 * om2 * om2)
    # sliding-point accelerations without the s'' terms
    k1 = (b.let("k1x", pa.ddx - t1n * u1[1] - t1u * u1[0]), b.let("k1y", pa.ddy + t1n * u1[0] - t1u * u1[1]))
    k2 = (b.let("k2x", pb.ddx - t2n * u2[1] - t2u * u2[0]), b.let("k2y", pb.ddy + t2n * u2[0] - t2u * u2[1]))
    ga = (b.let("gax", k2[0] + ra2[0] - k1[0] - ra1[0]), b.let("gay", k2[1] + ra2[1] - k1[1] - ra1[1]))
    dds1 = b.let("dds1", _cross(ga, u2) * icr)
    dds2 = b.let("dds2", _cross(ga, u1) * icr)
    jp1a = (b.let("jp1ax", k1[0] + dds1 * u1[0]), b.let("jp1ay", k1[1] + dds1 * u1[1]))
    jp2a = (b.let("jp2ax", k2[0] + dds2 * u2[0]), b.let("jp2ay", k2[1] + dds2 * u2[1]))
    b.output("s1", "VARIABLE", v=s1, dv=ds1, ddv=dds1)
    b.output("jp1", "POINT", **_point_result(jp1, jp1v, jp1a))
    b.output("s2", "VARIABLE", v=s2, dv=ds2, ddv=dds2)
    b.output("jp2", "POINT", **_point_result(jp2, jp2v, jp2a))
    b.output(
        "jb", "POINT",
        **_point_result(
            jbp,
            (jp1v[0] + rv1[0], jp1v[1] + rv1[1]),
            (jp1a[0] + ra1[0], jp1a[1] + ra1[1]),
        ),
    )
    return b.build(status=_status(cr.eq(0), sigma), sigma=sigma)


def rpr_links() -> Primitive:
    b = Builder(
        "RPR_links",
        "RPR chain: a guide link turning about jg and a slider link turning about js slide along one "
        "line; (ag, bg) and (as, bs) are the pair's reference point seen from jg and js in the line's "
        "frame.  Gives the line angle psi, the displacement s and the pair's slider point jp.",
    )
    jg = b.record("jg", "POINT")
    js = b.record("js", "POINT")
    ag = b.scalar("ag")
    bg = b.scalar("bg")
    as_ = b.scalar("as_")
    bs = b.scalar("bs")
    minv = b.scalar("minv", "INT")
    d, dv, da = _difference(b, jg, js)
    hh = b.let("hh", bg - bs)  # distance of js from the line through jg, along n
    q = b.let("q", _norm(d))
    ah = b.let("ah", fabs(hh))
    k = b.let("k", q - ah)
    fail = b.let("fail", either(k < -TOGGLE_SLACK * EPS * fmax(q, ah), q.eq(0)))
    t = b.let("t", sqrt(fmax(k, 0) * (q + ah)))
    iq = b.let("iq", select(q.eq(0), NAN, 1 / q))
    mt = b.let("mt", minv * t)  # d.u
    u = (b.let("ux", (mt * d[0] + hh * d[1]) * iq * iq), b.let("uy", (mt * d[1] - hh * d[0]) * iq * iq))
    psi = b.let("th", atan2(u[1], u[0]))
    s = b.let("sv", mt + (as_ - ag))
    r = _local(b, "r", u, as_, bs)
    # t = |d.u| over the chain's largest length: the line's angle is the direction of d, so it is
    # ill-conditioned at the toggle (d square to the line) and where the pivots nearly meet
    arm = b.let("arm", fmax(fmax(fabs(ag), fabs(as_)), fmax(fabs(bg), fabs(bs))))
    sigma = b.let("sigma", select(fail, 0, fmin(t / fmax(q, arm), 1)))
    imt = b.let("imt", select(mt.eq(0), NAN, 1 / mt))
    dvn = b.let("dvn", _cross(u, dv))  # d'.n
    dvu = b.let("dvu", _dot(dv, u))
    om = b.let("om", dvn * imt)
    ds = b.let("ds", dvu + om * hh)
    al = b.let("al", (_cross(u, da) - 2 * om * dvu - om * om * hh) * imt)
    dds = b.let("dds", _dot(da, u) + om * dvn + al * hh)
    rv, ra = _rotating(b, "r", r, om, al)
    b.output("psi", "ANGLE", the=psi, dthe=om, ddthe=al)
    b.output("s", "VARIABLE", v=s, dv=ds, ddv=dds)
    b.output(
        "jp", "POINT",
        **_point_result(
            (js.x + r[0], js.y + r[1]), (js.dx + rv[0], js.dy + rv[1]), (js.ddx + ra[0], js.ddy + ra[1])
        ),
    )
    return b.build(status=_status(fail, sigma), sigma=sigma)


def ppr_links() -> Primitive:
    b = Builder(
        "PPR_links",
        "PPR chain: link b slides on the guide line (pg, psig) and shares a second prismatic pair, "
        "of axis psig + cx, with link a turning about jr.  (xa, ya): the pair's reference point on a "
        "from jr; (xb, yb): on b from b's slider point; both in the guide's frame.  sgn is +1 when a "
        "is the slider of the second pair.  Gives s1, jp1 on the guide and sx, jpx of the second pair.",
    )
    jr = b.record("jr", "POINT")
    pg = b.record("pg", "POINT")
    psig = b.record("psig", "ANGLE")
    xa = b.scalar("xa")
    ya = b.scalar("ya")
    xb = b.scalar("xb")
    yb = b.scalar("yb")
    cx = b.scalar("cx")
    sgn = b.scalar("sgn", "INT")
    om, al = psig.dthe, psig.ddthe
    u1 = _dir(b, "g", psig.the)
    ux = _dir(b, "ax", psig.the + cx)
    ra = _local(b, "ra", u1, xa, ya)
    rb = _local(b, "rb", u1, xb, yb)
    ax_ = (b.let("pax", jr.x + ra[0]), b.let("pay", jr.y + ra[1]))
    w = (b.let("wx", ax_[0] - pg.x - rb[0]), b.let("wy", ax_[1] - pg.y - rb[1]))
    cr = b.let("cr", _cross(u1, ux))
    icr = b.let("icr", select(cr.eq(0), NAN, 1 / cr))
    s1 = b.let("sv1", _cross(w, ux) * icr)
    m = (b.let("mx", w[0] - s1 * u1[0]), b.let("my", w[1] - s1 * u1[1]))  # a's copy - b's copy
    mu = b.let("mu", _dot(m, ux))
    jp1 = (b.let("jp1x", pg.x + s1 * u1[0]), b.let("jp1y", pg.y + s1 * u1[1]))
    bx_ = (b.let("pbx", jp1[0] + rb[0]), b.let("pby", jp1[1] + rb[1]))
    sigma = b.let("sigma", fmin(fabs(cr), 1))
    rav, raa = _rotating(b, "ra", ra, om, al)
    rbv, rba = _rotating(b, "rb", rb, om, al)
    # m x ux = 0 differentiated: m' x ux + om (m.ux) = 0, m' = k1 - s1' u1
    k1 = (
        b.let("k1x", jr.dx + rav[0] - pg.dx - rbv[0] + s1 * om * u1[1]),
        b.let("k1y", jr.dy + rav[1] - pg.dy - rbv[1] - s1 * om * u1[0]),
    )
    ds1 = b.let("ds1", (_cross(k1, ux) + om * mu) * icr)
    mv = (b.let("mvx", k1[0] - ds1 * u1[0]), b.let("mvy", k1[1] - ds1 * u1[1]))
    mvu = b.let("mvu", _dot(mv, ux))
    jp1v = (
        b.let("jp1vx", pg.dx + ds1 * u1[0] - s1 * om * u1[1]),
        b.let("jp1vy", pg.dy + ds1 * u1[1] + s1 * om * u1[0]),
    )
    tn = b.let("tn", 2 * ds1 * om + s1 * al)
    tu = b.let("tu", s1 * om * om)
    k2 = (
        b.let("k2x", jr.ddx + raa[0] - pg.ddx - rba[0] + tn * u1[1] + tu * u1[0]),
        b.let("k2y", jr.ddy + raa[1] - pg.ddy - rba[1] - tn * u1[0] + tu * u1[1]),
    )
    dds1 = b.let("dds1", (_cross(k2, ux) + 2 * om * mvu + al * mu) * icr)
    ma = (k2[0] - dds1 * u1[0], k2[1] - dds1 * u1[1])
    jp1a = (
        b.let("jp1ax", pg.ddx + dds1 * u1[0] - tn * u1[1] - tu * u1[0]),
        b.let("jp1ay", pg.ddy + dds1 * u1[1] + tn * u1[0] - tu * u1[1]),
    )
    slider_a = sgn > 0
    jbv = (jp1v[0] + rbv[0], jp1v[1] + rbv[1])
    jba = (jp1a[0] + rba[0], jp1a[1] + rba[1])
    jav = (jr.dx + rav[0], jr.dy + rav[1])
    jaa = (jr.ddx + raa[0], jr.ddy + raa[1])
    jx = {
        f: b.let(f"jx{f}", select(slider_a, fa, fb))
        for f, fa, fb in (("x", ax_[0], bx_[0]), ("y", ax_[1], bx_[1]))
    }
    for f, fa, fb in (("dx", jav[0], jbv[0]), ("dy", jav[1], jbv[1]), ("ddx", jaa[0], jba[0]), ("ddy", jaa[1], jba[1])):
        jx[f] = b.let(f"jx{f}", select(slider_a, fa, fb))
    b.output("s1", "VARIABLE", v=s1, dv=ds1, ddv=dds1)
    b.output("jp1", "POINT", **_point_result(jp1, jp1v, jp1a))
    b.output("sx", "VARIABLE", v=sgn * mu, dv=sgn * mvu, ddv=sgn * (_dot(ma, ux) + om * _cross(ux, mv)))
    b.output("jpx", "POINT", **jx)
    return b.build(status=_status(cr.eq(0), sigma), sigma=sigma)


PRIMITIVES: dict[str, Primitive] = {
    p.name: p
    for p in (
        crank_input(),
        slider_input(),
        link_angle(),
        offset_angle(),
        coupler_point(),
        rrr_links(),
        prr_links(),
        prp_links(),
        rpr_links(),
        ppr_links(),
        link_residual(),
    )
}
