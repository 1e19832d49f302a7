"""The instant centre of two links, from one point and the angle record of each.

Link 1 moves with angular velocity w1, its point a with velocity a'; link 2 with w2, its point b
with b'.  The velocity of link 2 at a is b' + w2 k x (a - b), so the velocity of link 1 relative
to link 2 at a is g = a' - b' - w2 k x (a - b), and at any point c it is g + (w1 - w2) k x (c - a).
It vanishes at c = a + k x g / (w1 - w2): the centre.  Its conditioning is
sigma = |w1 - w2| / (|w1| + |w2| + |g| / |a - b|) (the last term 0 where a = b; sigma 0 where the
sum is 0): the rounding of w1 - w2 is of the order of eps times the angular rates at hand, the
links' and the relative velocity over the points' distance, so the centre's relative error is
of the order of eps / sigma; and sigma <= |a - b| / |c - a|.  Below the singular threshold the centre is
at infinity (status 1) and x, y are nan; where g is zero there too, the links move alike and
every point is a centre (status 2): x, y are a's (the pair of a first centre).  u = k x g / |g|
(its sign chosen so that ux > 0, or uy > 0 where ux = 0) is the direction in which the centre
lies from a: for a centre at infinity, the direction of that point at infinity.
"""

from __future__ import annotations

from ..policy import SINGULAR
from .dsl import NAN, Primitive, fabs, select, sqrt
from .vectors import PlaneBuilder, Vec, primitive


@primitive
def instant_centre(b: PlaneBuilder) -> Primitive:
    """Instant centre c of link 1 (point a, angle p) and link 2 (point b, angle q): the point where they move alike."""
    a = b.point("a")
    w1 = b.record("p", "ANGLE").dthe
    o = b.point("b")
    w2 = b.record("q", "ANGLE").dthe
    e = b.vec("e", a.p - o.p)
    dv = b.vec("dv", a.v - o.v)
    g = b.vec("g", Vec(dv.x + w2 * e.y, dv.y - w2 * e.x))
    dw = b.let("dw", w1 - w2)
    gn = b.let("gn", sqrt(g.dot(g)))
    el = b.let("el", sqrt(e.dot(e)))
    ge = b.let("ge", select(el.eq(0), 0.0, gn / el))
    m = b.let("m", fabs(w1) + fabs(w2) + ge)
    sg = b.let("sg", select(m.eq(0), 0.0, fabs(dw) / m))
    flag = b.let("st", select(sg >= SINGULAR, 0.0, select(gn.eq(0), 2.0, 1.0)))
    idw = b.let("idw", select(sg >= SINGULAR, 1 / dw, select(gn.eq(0), 0.0, NAN)))
    dn = b.let("dn", select(gn.eq(0), NAN, gn))
    # the direction's sign: ux = -gy k > 0, else uy = gx k > 0 where gy = 0; divided by |g| (a unit
    # vector along an axis is exact) and + 0 (no -0)
    k = b.let("k", select(g.y < 0, 1.0, select(g.y > 0, -1.0, select(g.x > 0, 1.0, -1.0))))
    b.output("c", "CENTRE", x=a.p.x - g.y * idw, y=a.p.y + g.x * idw, ux=k * (0.0 - g.y) / dn + 0.0,
             uy=k * g.x / dn + 0.0, status=flag, sigma=sg)
    return b.build()
