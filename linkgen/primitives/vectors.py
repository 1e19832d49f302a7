"""The plane-vector vocabulary the runtime library is written in.

``Vec`` is a pair of expressions, ``Motion`` a point's position, velocity and
acceleration; ``u`` is a unit direction, ``n`` its left normal.  Each operation builds
exactly the expression tree its formula reads left to right, so the printed programs
round the same way in every language.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from .. import status
from ..policy import NEAR_SINGULAR, SINGULAR
from .dsl import NAN, PI, Builder, Expr, Primitive, cos, select, sin, sqrt


@dataclass(frozen=True, eq=False)
class Vec:
    x: Expr
    y: Expr

    def __add__(self, other: Vec) -> Vec:
        return Vec(self.x + other.x, self.y + other.y)

    def __sub__(self, other: Vec) -> Vec:
        return Vec(self.x - other.x, self.y - other.y)

    def scaled(self, k: Expr) -> Vec:
        """k times the vector (k the left operand)."""
        return Vec(k * self.x, k * self.y)

    def dot(self, other: Vec) -> Expr:
        return self.x * other.x + self.y * other.y

    def cross(self, other: Vec) -> Expr:
        return self.x * other.y - self.y * other.x

    def norm(self) -> Expr:
        """sqrt(x^2 + y^2): correctly rounded sqrt makes it the same bits in every language
        (hypot implementations differ in the last bit between libraries)."""
        return sqrt(self.x * self.x + self.y * self.y)


@dataclass(frozen=True, eq=False)
class Motion:
    """A point's position p, velocity v and acceleration a (or a vector's, with its rates)."""

    p: Vec
    v: Vec
    a: Vec

    def __add__(self, other: Motion) -> Motion:
        return Motion(self.p + other.p, self.v + other.v, self.a + other.a)

    def fields(self) -> dict[str, Expr]:
        """The fields of a POINT record."""
        return {"x": self.p.x, "y": self.p.y, "dx": self.v.x, "dy": self.v.y, "ddx": self.a.x, "ddy": self.a.y}


def chain_status(fail: Expr, sigma: Expr) -> Expr:
    """A chain's status: it cannot close, or its conditioning sigma is singular or nearly."""
    return select(fail, status.CANNOT_CLOSE,
                  select(sigma < SINGULAR, status.SINGULAR, select(sigma < NEAR_SINGULAR, status.NEAR_SINGULAR, 0)))


class PlaneBuilder(Builder):
    """A Builder that also declares points and assigns vectors (as ``{name}x``, ``{name}y``)."""

    def point(self, name: str) -> Motion:
        """A POINT parameter."""
        j = self.record(name, "POINT")
        return Motion(Vec(j.x, j.y), Vec(j.dx, j.dy), Vec(j.ddx, j.ddy))

    def points(self, *names: str) -> tuple[Motion, ...]:
        return tuple(self.point(name) for name in names)

    def output_point(self, name: str, m: Motion) -> None:
        self.output(name, "POINT", **m.fields())

    def vec(self, name: str, v: Vec) -> Vec:
        return Vec(self.let(f"{name}x", v.x), self.let(f"{name}y", v.y))

    def direction(self, name: str, angle: Expr) -> Vec:
        """The unit vector at ``angle``, as ``c{name}`` and ``s{name}``."""
        return Vec(self.let(f"c{name}", cos(angle)), self.let(f"s{name}", sin(angle)))

    def local(self, name: str, u: Vec, gsi: Expr, eta: Expr) -> Vec:
        """The vector gsi*u + eta*n in global coordinates."""
        return self.vec(name, Vec(gsi * u.x - eta * u.y, gsi * u.y + eta * u.x))

    def wrapped(self, name: str, angle: Expr) -> Expr:
        """Angle wrapped to (-pi, pi] (the angle computed once, as ``{name}0``: a C compiler may not
        merge repeated atan2 calls, which can set errno)."""
        raw = self.let(f"{name}0", angle)
        return self.let(name, select(raw > PI, raw - 2 * PI, select(raw <= -PI, raw + 2 * PI, raw)))

    def difference(self, j1: Motion, j2: Motion) -> Motion:
        """j2 - j1 with its rates, as d, dv and da."""
        return Motion(self.vec("d", j2.p - j1.p), self.vec("dv", j2.v - j1.v), self.vec("da", j2.a - j1.a))

    def rotating(self, name: str, r: Vec, om: Expr, al: Expr) -> Motion:
        """A vector r fixed in a body turning at om, al, with its velocity and acceleration."""
        vel = self.vec(f"{name}v", Vec(-om * r.y, om * r.x))
        om2 = om * om
        return Motion(r, vel, self.vec(f"{name}a", Vec(-al * r.y - om2 * r.x, al * r.x - om2 * r.y)))

    def sliding_velocity(self, name: str, v: Vec, ds: Expr, s_om: Expr, u: Vec) -> Vec:
        """Velocity of the point at s along a line of direction u turning at om, through a
        point moving at v: v + s' u + (s om) n."""
        return self.vec(name, Vec(v.x + ds * u.x - s_om * u.y, v.y + ds * u.y + s_om * u.x))

    def sliding_acceleration(self, name: str, a: Vec, dds: Expr, tn: Expr, tu: Expr, u: Vec) -> Vec:
        """Its acceleration: a + s'' u + tn n - tu u, with tn = 2 s' om + s al and tu = s om^2."""
        return self.vec(name, Vec(a.x + dds * u.x - tn * u.y - tu * u.x, a.y + dds * u.y + tn * u.x - tu * u.y))

    def angle_rates(self, d: Motion, r2: Expr) -> tuple[Expr, Expr]:
        """omega and alpha of the direction of a segment d moving with its rates (r2 = |d|^2)."""
        ir2 = self.let("ir2", select(r2.eq(0), NAN, 1 / r2))
        om = self.let("om", d.p.cross(d.v) * ir2)
        al = self.let("al", (d.p.cross(d.a) - 2 * om * d.p.dot(d.v)) * ir2)
        return om, al


def primitive(define: Callable[[PlaneBuilder], Primitive]) -> Primitive:
    """Build a primitive from its definition: the function's name and docstring (its lines
    joined) name and describe the printed function."""
    doc = " ".join(line.strip() for line in (define.__doc__ or "").strip().splitlines())
    return define(PlaneBuilder(define.__name__, doc))
