"""The loop strategy's two functions (options: strategy loop): the point a loop assumes, and the
angle that comes back round the loop.

A loop block assumes the angle of one leg K-X of a group, carried as the arc length s = l theta
of the leg (a length, like an Add-link's: the resolver's tolerance, reach and path checks read it
as one); the group's two-link chains then run round the loop from X and place X again, and the
residual is the angle that comes back less the one assumed, as an arc of the same leg.
"""

from __future__ import annotations

from .. import status
from .dsl import Primitive, atan2, select
from .vectors import Motion, PlaneBuilder, primitive


@primitive
def loop_point(b: PlaneBuilder) -> Primitive:
    """Pair j2 of a leg of length l at the arc length s from its known pair j1: at the angle s / l (the angle a
    loop assumes), with the rates of s (the leg's length is a link's, constant)."""
    j1 = b.point("j1")
    ln, s = b.record("l", "VARIABLE"), b.record("s", "VARIABLE")
    il = b.let("il", 1 / ln.v)
    r = b.vec("r", b.direction("t", s.v * il).scaled(ln.v))
    b.output_point("j2", j1 + b.rotating("r", r, s.dv * il, s.ddv * il))
    return b.build()


@primitive
def loop_residual(b: PlaneBuilder) -> Primitive:
    """The loop's residual f = l wrap(theta' - s / l): the angle theta' of j2 - j1 that comes back round the loop
    less the angle assumed (the arc length s of the leg of length l), as an arc of the leg, wrapped to
    (-pi l, pi l], with its rates.  Fails where the two points coincide."""
    j1, j2 = b.points("j1", "j2")
    ln, s = b.record("l", "VARIABLE"), b.record("s", "VARIABLE")
    d = b.difference(j1, j2)
    r2 = b.let("r2", d.p.dot(d.p))
    th = b.wrapped("th", atan2(d.p.y, d.p.x) - s.v / ln.v)
    om, al = b.angle_rates(d, r2)
    b.output("f", "VARIABLE", v=ln.v * th, dv=ln.v * om - s.dv, ddv=ln.v * al - s.ddv)
    return b.build(status=select(r2.eq(0), status.CANNOT_CLOSE, 0), fail=r2.eq(0))


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
