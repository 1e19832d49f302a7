"""The two-link chains of the runtime library (mech.cpp's *_links), each written once in the DSL.

Each finds the middle pair of a dyad whose two ends are known (formulas in
docs/primitives.md): the displacement trig-free where a toggle can occur, the rates
from the differentiated constraints solved in the chain's own frame.  Each reports a
status and its conditioning sigma (``vectors.chain_status``).
"""

from __future__ import annotations

from ..policy import TOGGLE_SLACK
from .dsl import EPS, NAN, Expr, Logic, Primitive, atan2, either, fabs, fmax, fmin, select, sqrt
from .vectors import Motion, PlaneBuilder, Vec, chain_status, primitive


@primitive
def RRR_links(b: PlaneBuilder) -> Primitive:
    """3R chain: pair jb at distance l1 from j1 and l2 from j2, on the side minv (+1 left of j1->j2)."""
    j1, j2 = b.points("j1", "j2")
    l1, l2 = b.record("l1", "VARIABLE"), b.record("l2", "VARIABLE")
    minv = b.scalar("minv", "INT")
    d = b.vec("d", j2.p - j1.p)
    dd = b.let("dd", d.dot(d))
    q = b.let("q", sqrt(dd))
    # Kahan's area formula on the sorted sides x >= y >= z
    hi = b.let("hi", fmax(l1.v, l2.v))
    lo = b.let("lo", fmin(l1.v, l2.v))
    x = b.let("x", fmax(hi, q))
    z = b.let("z", fmin(lo, q))
    y = b.let("y", select(q >= hi, hi, select(q <= lo, lo, q)))
    k = b.let("k", z - (x - y))
    # 4 x the triangle's area.  Open (each of (l1 + l2)^2 - q^2 and q^2 - (l1 - l2)^2 over a third of its
    # first term, so neither cancels more than 1.6 bits): sqrt of their product, from q^2 alone; else, near a
    # toggle, Kahan's formula on the sorted sides, which needs q.
    s2 = b.let("s2", (l1.v + l2.v) * (l1.v + l2.v))
    t2 = b.let("t2", (l1.v - l2.v) * (l1.v - l2.v))
    o1 = b.let("o1", s2 - dd)
    o2 = b.let("o2", dd - t2)
    is_open = Logic("and", 3 * o1 > s2, 3 * o2 > dd)  # written out where read: the sympy oracle differentiates lets
    # an open triangle never fails (o1 > 0 and o2 > 0 give t2 < dd < s2, so lo > 0, q > 0, and k > 0 with a
    # margin of 0.18 q over its rounding): 0 there, the same value, so that the C computes k, x, y and z only
    # near a toggle (printer.py's branch on the open test)
    fail = b.let("fail", select(is_open, 0, either(either(k < -TOGGLE_SLACK * EPS * x, q.eq(0)), lo <= 0)))
    kk = b.let("kk", fmax(k, 0))
    kahan = sqrt((x + (y + z)) * kk * (z + (x - y)) * (x + (y - z)))
    area4 = b.let("area4", select(is_open, sqrt(o1 * o2), kahan))
    # jb - j1 = e1 = A d + area4 M n(d), with A = a / q (a: jb's distance along d) and M = minv / (2 q^2):
    # on the open triangle A = (q^2 + l1^2 - l2^2) / (2 q^2) from q^2 alone, so that neither square root
    # waits for the other and no division waits for a square root (docs/primitives.md); else from q.
    idd2 = b.let("idd2", select(dd.eq(0), NAN, 0.5 / dd))
    c = b.let("c", (l1.v - l2.v) * (l1.v + l2.v))
    # near a toggle, from q
    iq = b.let("iq", select(q.eq(0), NAN, 1 / q))
    a = b.let("a", (q + (l1.v - l2.v) * ((l1.v + l2.v) * iq)) / 2)
    a2 = b.let("a2", (q + (l2.v - l1.v) * ((l1.v + l2.v) * iq)) / 2)
    # At a toggle (k <= 0: the circles touch, or miss by rounding) jb lies on the line: halfway
    # between the circles' nearest points, as a is at an exact toggle.  a's division by q would
    # magnify the miss there by l/q (a folded chain with a needle: 4 eps L off its circles).
    flat = b.let("flat", select(q >= hi, (l1.v + (q - l2.v)) / 2,
                                select(l1.v >= l2.v, (l1.v + (q + l2.v)) / 2, (q - (l1.v + l2.v)) / 2)))
    at = b.let("at", select(k > 0, a, flat))
    ao = b.let("ao", (dd + c) * idd2)
    mi = b.let("mi", minv * idd2)
    m = b.vec("m", Vec(-mi * d.y, mi * d.x))
    # else in the chain's frame (u, n), u = d / q: e1 = at u + hn n, exact at an exact toggle
    u = b.vec("u", Vec(d.x * iq, d.y * iq))
    hn = b.let("hn", minv * (area4 * iq / 2))
    e1 = b.vec("e1", Vec(select(is_open, ao * d.x + area4 * m.x, at * u.x - hn * u.y),
                         select(is_open, ao * d.y + area4 * m.y, at * u.y + hn * u.x)))
    # times a reciprocal of the lengths alone: a C compiler folds it where they are the sketch's constants
    ratio = b.let("ratio", select(fail, 0, area4 * (0.5 / (l1.v * l2.v))))
    sigma = b.let("sigma", fmin(ratio, 1))
    # derivatives: (jb - ji).(jb' - ji') = li li', solved in the (u, n) frame of u = d / q:
    #   a bu + hn bn = r1,  -a2 bu + hn bn = r2   (determinant hn q = minv area4 / 2)
    # jb' = bu u + bn n = (r1 - r2) d / q^2 + (A2 r1 + A r2) n(d) / (hn q), A = a / q and A2 = a2 / q
    ar = b.let("ar", select(is_open, ao, a * iq))
    a2r = b.let("a2r", select(is_open, (dd - c) * idd2, a2 * iq))
    e2 = b.vec("e2", Vec(-a2r * d.x + area4 * m.x, -a2r * d.y + area4 * m.y))
    sd = b.vec("sd", d.scaled(2 * idd2))
    ihq = b.let("ihq", select(area4.eq(0), NAN, 2 * minv / area4))
    tn = b.vec("tn", Vec(-ihq * d.y, ihq * d.x))

    def solve(tag: str, rhs1: Expr, rhs2: Expr) -> Vec:
        r1 = b.let(f"r1{tag}", rhs1)
        r2 = b.let(f"r2{tag}", rhs2)
        bu = b.let(f"bu{tag}", r1 - r2)
        bn = b.let(f"bn{tag}", a2r * r1 + ar * r2)
        return b.vec(f"b{tag}", Vec(bu * sd.x + bn * tn.x, bu * sd.y + bn * tn.y))

    vel = solve("v", l1.v * l1.dv + e1.dot(j1.v), l2.v * l2.dv + e2.dot(j2.v))
    w1 = vel - j1.v
    w2 = vel - j2.v
    # |wi|^2 subtracted last: it waits for jb's velocity, the rest for positions and the ends' rates
    acc = solve(
        "a",
        l1.v * l1.ddv + l1.dv * l1.dv + e1.dot(j1.a) - w1.dot(w1),
        l2.v * l2.ddv + l2.dv * l2.dv + e2.dot(j2.a) - w2.dot(w2),
    )
    b.output_point("jb", Motion(j1.p + e1, vel, acc))
    return b.build(status=chain_status(fail, sigma), sigma=sigma, fail=fail)


@primitive
def PRR_links(b: PlaneBuilder) -> Primitive:
    """2R1P chain: pair jb at distance l from jr, carried at (gsi, eta) by a slider on the guide line (pg, psig); s
    is the slider displacement from pg, jp the slider point, minv the side.
    """
    jr = b.point("jr")
    ln = b.record("l", "VARIABLE")
    pg = b.point("pg")
    psig = b.record("psig", "ANGLE")
    gsi, eta = b.scalars("gsi", "eta")
    minv = b.scalar("minv", "INT")
    u = b.direction("g", psig.the)
    om, al = psig.dthe, psig.ddthe
    r = b.local("r", u, gsi, eta)
    w = b.vec("w", pg.p + r - jr.p)
    wu = b.let("wu", w.dot(u))
    pn = b.let("pn", w.cross(u))  # signed distance of jr from the line of jb
    ap = b.let("ap", fabs(pn))
    k = b.let("k", ln.v - ap)
    big = b.let("big", fmax(ln.v, ap))
    fail = b.let("fail", either(k < -TOGGLE_SLACK * EPS * big, ln.v <= 0))
    rd = b.let("rd", sqrt(fmax(k, 0) * (ln.v + ap)))
    eu = b.let("eu", minv * rd)  # (jb - jr).u
    en = -pn  # (jb - jr).n
    e = b.local("e", u, eu, en)
    s = b.let("sv", eu - wu)
    jb = b.vec("jb", jr.p + e)
    jp = b.vec("jp", jb - r)
    # 1 / l folded where l is the sketch's; rd is 0 where the chain fails (k < 0 or l <= 0) and where l * l
    # underflows, as for a subnormal l whose 1 / l is inf: sigma 0 there, not 0 * inf
    ratio = b.let("ratio", select(rd.eq(0), 0, rd * (1 / ln.v)))
    sigma = b.let("sigma", fmin(ratio, 1))
    ieu = b.let("ieu", select(eu.eq(0), NAN, 1 / eu))
    sg = b.let("sgsi", s + gsi)
    rel = b.vec("relv", pg.v - jr.v)
    ds = b.let("ds", (ln.v * ln.dv - e.dot(rel) - om * (sg * en - eta * eu)) * ieu)
    jpv = b.sliding_velocity("jpv", pg.v, ds, s * om, u)
    rm = b.rotating("r", r, om, al)
    jbv = b.vec("jbv", jpv + rm.v)
    wv = jbv - jr.v
    rela = b.vec("rela", pg.a - jr.a)
    om2 = b.let("om2", om * om)
    dds = b.let(
        "dds",
        (
            ln.v * ln.ddv + ln.dv * ln.dv - wv.dot(wv) - e.dot(rela)
            - 2 * ds * om * en - sg * (al * en - om2 * eu) + eta * (al * eu + om2 * en)
        ) * ieu,
    )
    tn = b.let("tn", 2 * ds * om + s * al)
    jpa = b.sliding_acceleration("jpa", pg.a, dds, tn, s * om2, u)
    b.output("s", "VARIABLE", v=s, dv=ds, ddv=dds)
    b.output_point("jp", Motion(jp, jpv, jpa))
    b.output_point("jb", Motion(jb, jbv, jpa + rm.a))
    return b.build(status=chain_status(fail, sigma), sigma=sigma, fail=fail)


@primitive
def PRP_links(b: PlaneBuilder) -> Primitive:
    """1R2P chain: pair jb joins two sliders on the guide lines (pg1, psig1) and (pg2, psig2), at (gsi1, eta1) and
    (gsi2, eta2) from their slider points jp1, jp2 (displacements s1, s2).
    """
    pg1 = b.point("pg1")
    psig1 = b.record("psig1", "ANGLE")
    gsi1, eta1 = b.scalars("gsi1", "eta1")
    pg2 = b.point("pg2")
    psig2 = b.record("psig2", "ANGLE")
    gsi2, eta2 = b.scalars("gsi2", "eta2")
    u1 = b.direction("g1", psig1.the)
    r1 = b.local("r1", u1, gsi1, eta1)
    u2 = b.direction("g2", psig2.the)
    r2 = b.local("r2", u2, gsi2, eta2)
    cr = b.let("cr", u1.cross(u2))
    icr = b.let("icr", select(cr.eq(0), NAN, 1 / cr))
    g = b.vec("g", pg2.p + r2 - pg1.p - r1)
    # jb from guide 1, then jp2 = jb - r2 and s2 from it: every constraint then holds to
    # rounding (computing s2 from g as well would put jp2 and jb apart by the conditioned error)
    s1 = b.let("sv1", g.cross(u2) * icr)
    jp1 = b.vec("jp1", pg1.p + u1.scaled(s1))
    jb = b.vec("jb", jp1 + r1)
    jp2 = b.vec("jp2", jb - r2)
    s2 = b.let("sv2", (jp2 - pg2.p).dot(u2))
    acr = b.let("acr", fabs(cr))
    sigma = b.let("sigma", fmin(acr, 1))
    om1, al1, om2, al2 = psig1.dthe, psig1.ddthe, psig2.dthe, psig2.ddthe
    rm1 = b.rotating("r1", r1, om1, al1)
    rm2 = b.rotating("r2", r2, om2, al2)
    # s1 u1 - s2 u2 = g  differentiated: s1' u1 - s2' u2 = gv
    gv = b.vec("gv", Vec(
        pg2.v.x + rm2.v.x - s2 * om2 * u2.y - pg1.v.x - rm1.v.x + s1 * om1 * u1.y,
        pg2.v.y + rm2.v.y + s2 * om2 * u2.x - pg1.v.y - rm1.v.y - s1 * om1 * u1.x,
    ))
    ds1 = b.let("ds1", gv.cross(u2) * icr)
    ds2 = b.let("ds2", gv.cross(u1) * icr)
    jp1v = b.sliding_velocity("jp1v", pg1.v, ds1, s1 * om1, u1)
    jp2v = b.sliding_velocity("jp2v", pg2.v, ds2, s2 * om2, u2)
    t1n = b.let("t1n", 2 * ds1 * om1 + s1 * al1)
    t2n = b.let("t2n", 2 * ds2 * om2 + s2 * al2)
    t1u = b.let("t1u", s1 * om1 * om1)
    t2u = b.let("t2u", s2 * om2 * om2)
    # sliding-point accelerations without the s'' terms
    k1 = b.vec("k1", Vec(pg1.a.x - t1n * u1.y - t1u * u1.x, pg1.a.y + t1n * u1.x - t1u * u1.y))
    k2 = b.vec("k2", Vec(pg2.a.x - t2n * u2.y - t2u * u2.x, pg2.a.y + t2n * u2.x - t2u * u2.y))
    ga = b.vec("ga", k2 + rm2.a - k1 - rm1.a)
    dds1 = b.let("dds1", ga.cross(u2) * icr)
    dds2 = b.let("dds2", ga.cross(u1) * icr)
    jp1a = b.vec("jp1a", k1 + u1.scaled(dds1))
    jp2a = b.vec("jp2a", k2 + u2.scaled(dds2))
    b.output("s1", "VARIABLE", v=s1, dv=ds1, ddv=dds1)
    b.output_point("jp1", Motion(jp1, jp1v, jp1a))
    b.output("s2", "VARIABLE", v=s2, dv=ds2, ddv=dds2)
    b.output_point("jp2", Motion(jp2, jp2v, jp2a))
    b.output_point("jb", Motion(jb, jp1v + rm1.v, jp1a + rm1.a))
    return b.build(status=chain_status(cr.eq(0), sigma), sigma=sigma, fail=cr.eq(0))


@primitive
def RPR_links(b: PlaneBuilder) -> Primitive:
    """RPR chain: a guide link turning about jg and a slider link turning about js slide along one line; (ag, bg)
    and (as, bs) are the pair's reference point seen from jg and js in the line's frame.  Gives the line angle psi,
    the displacement s and the pair's slider point jp.
    """
    jg, js = b.points("jg", "js")
    ag, bg, as_, bs = b.scalars("ag", "bg", "as_", "bs")
    minv = b.scalar("minv", "INT")
    dm = b.difference(jg, js)
    d, dv, da = dm.p, dm.v, dm.a
    hh = b.let("hh", bg - bs)  # distance of js from the line through jg, along n
    q = b.let("q", d.norm())
    ah = b.let("ah", fabs(hh))
    k = b.let("k", q - ah)
    big = b.let("big", fmax(q, ah))
    fail = b.let("fail", either(k < -TOGGLE_SLACK * EPS * big, q.eq(0)))
    t = b.let("t", sqrt(fmax(k, 0) * (q + ah)))
    iq = b.let("iq", select(q.eq(0), NAN, 1 / q))
    mt = b.let("mt", minv * t)  # d.u
    u = b.vec("u", Vec((mt * d.x + hh * d.y) * iq * iq, (mt * d.y - hh * d.x) * iq * iq))
    psi = b.let("th", atan2(u.y, u.x))
    s = b.let("sv", mt + (as_ - ag))
    r = b.local("r", u, as_, bs)
    # t = |d.u| over the chain's largest length: the line's angle is the direction of d, so it is
    # ill-conditioned at the toggle (d square to the line) and where the pivots nearly meet
    arms = [b.let(f"a{k}", fabs(x)) for k, x in enumerate((ag, as_, bg, bs))]
    arm = b.let("arm", fmax(b.let("arm1", fmax(arms[0], arms[1])), b.let("arm2", fmax(arms[2], arms[3]))))
    reach = b.let("reach", fmax(q, arm))
    ratio = b.let("ratio", select(fail, 0, t / reach))
    sigma = b.let("sigma", fmin(ratio, 1))
    imt = b.let("imt", select(mt.eq(0), NAN, 1 / mt))
    dvn = b.let("dvn", u.cross(dv))  # d'.n
    dvu = b.let("dvu", dv.dot(u))
    om = b.let("om", dvn * imt)
    ds = b.let("ds", dvu + om * hh)
    al = b.let("al", (u.cross(da) - 2 * om * dvu - om * om * hh) * imt)
    dds = b.let("dds", da.dot(u) + om * dvn + al * hh)
    b.output("psi", "ANGLE", the=psi, dthe=om, ddthe=al)
    b.output("s", "VARIABLE", v=s, dv=ds, ddv=dds)
    b.output_point("jp", js + b.rotating("r", r, om, al))
    return b.build(status=chain_status(fail, sigma), sigma=sigma, fail=fail)


@primitive
def PPR_links(b: PlaneBuilder) -> Primitive:
    """PPR chain: link b slides on the guide line (pg, psig) and shares a second prismatic pair, of axis psig + cx,
    with link a turning about jr.  (xa, ya): the pair's reference point on a from jr; (xb, yb): on b from b's slider
    point; both in the guide's frame.  sgn is +1 when a is the slider of the second pair.  Gives s1, jp1 on the
    guide and sx, jpx of the second pair.
    """
    jr, pg = b.points("jr", "pg")
    psig = b.record("psig", "ANGLE")
    xa, ya, xb, yb, cx = b.scalars("xa", "ya", "xb", "yb", "cx")
    sgn = b.scalar("sgn", "INT")
    om, al = psig.dthe, psig.ddthe
    u1 = b.direction("g", psig.the)
    ux = b.direction("ax", psig.the + cx)
    ra = b.local("ra", u1, xa, ya)
    rb = b.local("rb", u1, xb, yb)
    on_a = b.vec("pa", jr.p + ra)
    w = b.vec("w", on_a - pg.p - rb)
    cr = b.let("cr", u1.cross(ux))
    icr = b.let("icr", select(cr.eq(0), NAN, 1 / cr))
    s1 = b.let("sv1", w.cross(ux) * icr)
    m = b.vec("m", w - u1.scaled(s1))  # a's copy - b's copy
    mu = b.let("mu", m.dot(ux))
    jp1 = b.vec("jp1", pg.p + u1.scaled(s1))
    on_b = b.vec("pb", jp1 + rb)
    acr = b.let("acr", fabs(cr))
    sigma = b.let("sigma", fmin(acr, 1))
    rma = b.rotating("ra", ra, om, al)
    rmb = b.rotating("rb", rb, om, al)
    # m x ux = 0 differentiated: m' x ux + om (m.ux) = 0, m' = k1 - s1' u1
    k1 = b.vec("k1", Vec(
        jr.v.x + rma.v.x - pg.v.x - rmb.v.x + s1 * om * u1.y,
        jr.v.y + rma.v.y - pg.v.y - rmb.v.y - s1 * om * u1.x,
    ))
    ds1 = b.let("ds1", (k1.cross(ux) + om * mu) * icr)
    mv = b.vec("mv", k1 - u1.scaled(ds1))
    mvu = b.let("mvu", mv.dot(ux))
    jp1v = b.sliding_velocity("jp1v", pg.v, ds1, s1 * om, u1)
    tn = b.let("tn", 2 * ds1 * om + s1 * al)
    tu = b.let("tu", s1 * om * om)
    k2 = b.vec("k2", Vec(
        jr.a.x + rma.a.x - pg.a.x - rmb.a.x + tn * u1.y + tu * u1.x,
        jr.a.y + rma.a.y - pg.a.y - rmb.a.y - tn * u1.x + tu * u1.y,
    ))
    dds1 = b.let("dds1", (k2.cross(ux) + 2 * om * mvu + al * mu) * icr)
    ma = k2 - u1.scaled(dds1)
    jp1a = b.sliding_acceleration("jp1a", pg.a, dds1, tn, tu, u1)
    slider_a = sgn > 0
    a_side = Motion(on_a, jr.v + rma.v, jr.a + rma.a).fields()
    b_side = Motion(on_b, jp1v + rmb.v, jp1a + rmb.a).fields()
    jx = {f: b.let(f"jx{f}", select(slider_a, a_side[f], b_side[f])) for f in a_side}
    b.output("s1", "VARIABLE", v=s1, dv=ds1, ddv=dds1)
    b.output_point("jp1", Motion(jp1, jp1v, jp1a))
    b.output("sx", "VARIABLE", v=sgn * mu, dv=sgn * mvu, ddv=sgn * (ma.dot(ux) + om * ux.cross(mv)))
    b.output("jpx", "POINT", **jx)
    return b.build(status=chain_status(cr.eq(0), sigma), sigma=sigma, fail=cr.eq(0))
