"""The loop strategy's two functions (options: strategy loop): the point a loop assumes, and the
angle that comes back round the loop.

A loop block assumes the angle of one leg K-X of a group, carried as the arc length s = l theta
of the leg (a length, like an Add-link's: the resolver's tolerance, reach and path checks read it
as one); the group's two-link chains then run round the loop from X and place X again, and the
residual is the angle that comes back less the one assumed, as an arc of the same leg.
"""

from __future__ import annotations

from .. import status
from .dsl import EPS, NAN, Primitive, atan2, either, fabs, select
from .vectors import Motion, PlaneBuilder, primitive


@primitive
def loop_point(b: PlaneBuilder) -> Primitive:
    """Pair j2 of a leg of length l at the arc length s from its known pair j1: at the angle s / l (the angle a
    loop assumes), with the rates of s (the leg's length is a link's, constant).  Fails where the angle is no
    number (a leg of length 0, or s / l beyond 1 / eps rad, where an angle has no digits left)."""
    j1 = b.point("j1")
    ln, s = b.record("l", "VARIABLE"), b.record("s", "VARIABLE")
    zero = ln.v.eq(0)
    t = b.let("t", select(zero, NAN, s.v / ln.v))
    bad = either(zero, fabs(t) * EPS > 1)
    r = b.vec("r", b.direction("a", b.let("ta", select(bad, NAN, t))).scaled(ln.v))
    om, al = b.let("om", select(zero, NAN, s.dv / ln.v)), b.let("al", select(zero, NAN, s.ddv / ln.v))
    b.output_point("j2", j1 + b.rotating("r", r, om, al))
    return b.build(status=select(bad, status.CANNOT_CLOSE, 0), fail=bad)


@primitive
def loop_residual(b: PlaneBuilder) -> Primitive:
    """The loop's residual f = l wrap(theta' - s / l): the angle theta' of j2 - j1 that comes back round the loop
    less the angle assumed (the arc length s of the leg of length l), as an arc of the leg, in (-pi l, pi l]
    however many turns s / l is from theta' (the angle from the assumed direction u to j2 - j1:
    atan2(u x d, u . d)), with its rates.  Fails where the two points coincide or the assumed angle is no
    number (as loop_point)."""
    j1, j2 = b.points("j1", "j2")
    ln, s = b.record("l", "VARIABLE"), b.record("s", "VARIABLE")
    d = b.difference(j1, j2)
    r2 = b.let("r2", d.p.dot(d.p))
    zero = ln.v.eq(0)
    t = b.let("t", select(zero, NAN, s.v / ln.v))
    bad = either(either(zero, fabs(t) * EPS > 1), r2.eq(0))
    u = b.direction("a", b.let("ta", select(bad, NAN, t)))
    th = b.let("th", atan2(u.cross(d.p), u.dot(d.p)))
    om, al = b.angle_rates(d, r2)
    b.output("f", "VARIABLE", v=ln.v * th, dv=ln.v * om - s.dv, ddv=ln.v * al - s.ddv)
    return b.build(status=select(bad, status.CANNOT_CLOSE, 0), fail=bad)


@primitive
def loop_turn(b: PlaneBuilder) -> Primitive:
    """The turn c = (j2 - j1) x (j3 - j1) of the body a loop places, with its rates; fails (code 1) where its sign is
    not the drawn one, turn (+1 or -1): a body turned over, its mirror image, keeps every length round the loop
    but is no assembly."""
    j1, j2, j3 = b.points("j1", "j2", "j3")
    turn = b.scalar("turn", "INT")
    u = Motion(b.vec("u", j2.p - j1.p), b.vec("uv", j2.v - j1.v), b.vec("ua", j2.a - j1.a))
    w = Motion(b.vec("w", j3.p - j1.p), b.vec("wv", j3.v - j1.v), b.vec("wa", j3.a - j1.a))
    c = b.let("k", u.p.cross(w.p))
    dc = u.v.cross(w.p) + u.p.cross(w.v)
    ddc = u.a.cross(w.p) + 2 * u.v.cross(w.v) + u.p.cross(w.a)
    b.output("c", "VARIABLE", v=c, dv=dc, ddv=ddc)
    return b.build(status=select(c * turn > 0, 0, status.CANNOT_CLOSE), fail=(c * turn <= 0))
