"""primitives.vectors: the plane-vector helpers, checked on small primitives built here (sympy does the
calculus; the library's own primitives are proved in tests/test_primitives.py)."""

from __future__ import annotations

import math

import pytest
import sympy as sp
from sympy_oracle import convert, time_derivative, to_sympy

from linkgen import policy, status
from linkgen.primitives.dsl import Primitive, Sym, record_fields
from linkgen.primitives.vectors import Motion, PlaneBuilder, Vec, chain_status, primitive


def _body_point() -> Primitive:
    """A point at (gsi, eta) in the frame of a body turning with phi."""
    b = PlaneBuilder("body_point", "doc")
    phi = b.record("phi", "ANGLE")
    gsi, eta = b.scalars("gsi", "eta")
    r = b.local("r", b.direction("u", phi.the), gsi, eta)
    b.output_point("q", b.rotating("r", r, phi.dthe, phi.ddthe))
    return b.build()


def test_local_is_gsi_along_the_direction_and_eta_to_its_left():
    q = to_sympy(_body_point()).results["q"]
    phi, gsi, eta = sp.symbols("phi_the gsi eta", real=True)
    assert q["x"].subs(phi, sp.pi / 2) == -eta and q["y"].subs(phi, sp.pi / 2) == gsi
    assert sp.simplify(q["x"] - (gsi * sp.cos(phi) - eta * sp.sin(phi))) == 0


def test_rotating_gives_the_time_derivatives_of_a_vector_fixed_in_the_body():
    prim = _body_point()
    q = to_sympy(prim).results["q"]
    for pos, vel, acc in (("x", "dx", "ddx"), ("y", "dy", "ddy")):
        assert sp.simplify(time_derivative(prim, q[pos]) - q[vel]) == 0
        assert sp.simplify(time_derivative(prim, q[vel]) - q[acc]) == 0


def test_difference_names_its_lets_d_dv_and_da():
    b = PlaneBuilder("diff", "doc")
    j1, j2 = b.points("j1", "j2")
    d = b.difference(j1, j2)
    assert [let.name for let in b.body] == ["dx", "dy", "dvx", "dvy", "dax", "day"]
    assert repr(d.a.y) == repr(Sym("day"))


def test_motion_fields_are_the_point_records_fields_in_order():
    m = Motion(Vec(Sym("a"), Sym("b")), Vec(Sym("c"), Sym("d")), Vec(Sym("e"), Sym("f")))
    fields = m.fields()
    assert tuple(fields) == record_fields("POINT", 2)
    assert [e.name for e in fields.values() if isinstance(e, Sym)] == list("abcdef")


def test_vector_algebra_by_hand():
    u, w = Vec(Sym("ux"), Sym("uy")), Vec(Sym("wx"), Sym("wy"))
    env = {"ux": sp.Integer(3), "uy": sp.Integer(4), "wx": sp.Integer(-2), "wy": sp.Integer(5)}
    assert convert(u.dot(w), env) == 3 * -2 + 4 * 5
    assert convert(u.cross(w), env) == 3 * 5 - 4 * -2
    assert convert(u.norm(), env) == 5
    s = (u + w).scaled(Sym("ux"))
    assert (convert(s.x, env), convert(s.y, env)) == (3 * (3 - 2), 3 * (4 + 5))


@pytest.mark.parametrize("fail, sigma, code", [
    (True, 1.0, status.CANNOT_CLOSE),
    (False, policy.SINGULAR / 2, status.SINGULAR),
    (False, policy.SINGULAR, status.NEAR_SINGULAR),  # the thresholds are strict
    (False, math.sqrt(policy.SINGULAR * policy.NEAR_SINGULAR), status.NEAR_SINGULAR),
    (False, policy.NEAR_SINGULAR, 0),
    (False, 1.0, 0),
])
def test_chain_status_by_conditioning(fail: bool, sigma: float, code: int):
    e = chain_status(Sym("fail"), Sym("sigma"))
    assert convert(e, {"fail": sp.true if fail else sp.false, "sigma": sp.Float(sigma)}) == code


def test_a_primitive_is_named_and_described_by_its_definition():
    @primitive
    def Two_lines(b: PlaneBuilder) -> Primitive:
        """First line,
        second line.  Two spaces stay.
        """
        k = b.scalar("k")
        b.output("v", "VARIABLE", v=k, dv=k, ddv=k)
        return b.build()

    assert Two_lines.name == "Two_lines"
    assert Two_lines.doc == "First line, second line.  Two spaces stay."
