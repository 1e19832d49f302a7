"""primitives.dsl: expression nodes, derivative orders, dead-code removal and the Builder's checks.

The expected orders and live sets are worked out by hand from the small primitives built here.
"""

from __future__ import annotations

import pytest

from linkgen.primitives.dsl import (
    Bin,
    Builder,
    Call,
    Cmp,
    Neg,
    Num,
    Primitive,
    Sym,
    field_order,
    fmax,
    fmin,
    record_fields,
    select,
    wrap,
)


def _sample() -> Primitive:
    """j: a POINT, k: a REAL.  a = k j.x (order 0), b = a j.dx (1), c = b + j.ddy (2), unused = k k (0);
    the output q has x = a, dx = b, ddx = c and the rest from j; sigma reads only sig = 2 k."""
    b = Builder("sample", "A made-up primitive.")
    j = b.record("j", "POINT")
    k = b.scalar("k")
    a = b.let("a", k * j.x)
    v = b.let("b", a * j.dx)
    c = b.let("c", v + j.ddy)
    b.let("unused", k * k)
    sig = b.let("sig", 2 * k)
    b.output("q", "POINT", x=a, y=j.y, dx=v, dy=j.dy, ddx=c, ddy=j.ddy)
    return b.build(status=select(sig < 1, 3, 0), sigma=sig)


def test_operators_keep_the_operand_order_as_written():
    x = Sym("x")
    assert _same(2 - x, Bin("-", Num(2), x)) and _same(x - 2, Bin("-", x, Num(2)))
    assert _same(1 / x, Bin("/", Num(1), x)) and _same(x * 3.5, Bin("*", x, Num(3.5)))
    assert _same(x < 1, Cmp("<", x, Num(1))) and _same(x.eq(0), Cmp("==", x, Num(0)))
    assert _same(-x, Neg(x))


def _same(e: object, f: object) -> bool:
    """Structural equality (nodes compare by identity, so that sets and dicts of them work)."""
    return repr(e) == repr(f)


@pytest.mark.parametrize("value", [True, "1", None, [1.0]])
def test_only_numbers_and_expressions_enter_an_expression(value: object):
    with pytest.raises(TypeError):
        wrap(value)
    with pytest.raises(TypeError):
        Sym("x") + value


def test_record_fields_by_order():
    assert record_fields("POINT", 1) == ("x", "y", "dx", "dy")
    assert record_fields("ANGLE", 2) == ("the", "dthe", "ddthe")
    assert [field_order("VARIABLE", f) for f in ("v", "dv", "ddv")] == [0, 1, 2]
    with pytest.raises(KeyError):
        field_order("POINT", "the")


def test_an_assignment_has_the_highest_derivative_order_it_reads():
    assert [(let.name, let.order) for let in _sample().body] == [
        ("a", 0), ("b", 1), ("c", 2), ("unused", 0), ("sig", 0)]


def test_live_keeps_what_the_outputs_of_an_order_read():
    prim = _sample()
    assert [let.name for let in prim.live(0)] == ["a", "sig"]
    assert [let.name for let in prim.live(0, with_sigma=False)] == ["a", "sig"]  # the status reads sig too
    assert [let.name for let in prim.live(1)] == ["a", "b", "sig"]
    assert [let.name for let in prim.live(2)] == ["a", "b", "c", "sig"]
    assert prim.params_used(0) == {"k", "j_x", "j_y"}
    assert prim.params_used(1) == {"k", "j_x", "j_y", "j_dx", "j_dy"}


def test_sigma_alone_is_dropped_without_sigma():
    b = Builder("s", "doc")
    k = b.scalar("k")
    b.let("sig", k * k)
    b.output("v", "VARIABLE", v=k, dv=k, ddv=k)
    prim = b.build(sigma=Sym("sig"))
    assert [let.name for let in prim.live(0)] == ["sig"]
    assert prim.live(0, with_sigma=False) == ()


def test_a_record_has_only_its_kinds_fields():
    b = Builder("r", "doc")
    phi = b.record("phi", "ANGLE")
    assert _same(phi.dthe, Sym("phi_dthe"))
    with pytest.raises(KeyError):
        phi.x  # noqa: B018


def _builder() -> tuple[Builder, Sym]:
    b = Builder("bad", "doc")
    return b, b.scalar("k")


def test_a_name_is_assigned_once():
    b, k = _builder()
    b.let("t", k)
    with pytest.raises(ValueError, match="t assigned twice"):
        b.let("t", k + 1)
    with pytest.raises(ValueError, match="k assigned twice"):
        b.let("k", k)


def test_a_local_may_not_be_named_like_an_output():
    b, k = _builder()
    b.let("out", k)
    b.output("out", "VARIABLE", v=k, dv=k, ddv=k)
    with pytest.raises(ValueError, match="locals named like arguments"):
        b.build()


@pytest.mark.parametrize("fields, status, message", [
    ({"v": "v", "dv": "dv"}, "", "output f needs fields"),
    ({"v": "dv", "dv": "dv", "ddv": "ddv"}, "", "f.v reads a higher derivative"),
    ({"v": "v", "dv": "dv", "ddv": "ddv"}, "dv", "status and sigma must come from displacements"),
])
def test_build_refuses_what_a_program_of_a_lower_order_could_not_compute(fields: dict[str, str], status: str,
                                                                         message: str):
    b = Builder("bad", "doc")
    s = b.record("s", "VARIABLE")
    b.output("f", "VARIABLE", **{k: getattr(s, f) for k, f in fields.items()})
    with pytest.raises(ValueError, match=message):
        b.build(status=select(getattr(s, status) < 0, 3, 0) if status else None)


def test_a_status_from_displacements_is_taken():
    b = Builder("good", "doc")
    s = b.record("s", "VARIABLE")
    b.output("f", "VARIABLE", v=s.v, dv=s.dv, ddv=s.ddv)
    assert b.build(status=select(s.v.eq(0), 1, 0)).status is not None


def test_unchecked_keeps_only_the_failure_and_drops_the_conditioning():
    """RRR-like: fail when k < 0, singular (3) or near (4) by sigma; unchecked: 1 where it fails, else 0."""
    b = Builder("chain", "A made-up chain.")
    k = b.scalar("k")
    fail = b.let("fail", k < 0)
    sig = b.let("sig", 2 * k)
    b.output("q", "VARIABLE", v=k, dv=k, ddv=k)
    prim = b.build(status=select(fail, 1, select(sig < 1, 3, select(sig < 2, 4, 0))), sigma=sig, fail=fail)
    lean = prim.unchecked()
    assert prim.codes() == {1, 3, 4} and lean.codes() == {1}
    assert lean.sigma is None and _same(lean.status, select(fail, 1, 0))
    assert {let.name for let in lean.live(2)} == {"fail"}  # sigma's let is dead without the checks
    assert _sample().unchecked().status is None  # a function with no failure of its own reports nothing
    b = Builder("segment", "A made-up angle: fails where its length is 0.")
    k = b.scalar("k")
    b.output("q", "VARIABLE", v=k, dv=k, ddv=k)
    alone = b.build(status=select(k.eq(0), 1, 0))  # a failure alone, not named as fail: kept
    assert alone.unchecked().status is alone.status


def test_max_and_min_take_names_or_numbers_only():
    x, y = Sym("x"), Sym("y")
    assert _same(fmax(x, 0), Call("max", (x, Num(0)))) and _same(fmin(x, y), Call("min", (x, y)))
    with pytest.raises(TypeError, match="let-bind"):
        fmax(x + y, 1)
