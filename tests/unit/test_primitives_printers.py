"""linkgen.primitives.printers, what every language's printer shares: literals that read back to the same
double, expressions laid out so that the printed text evaluates in the DSL's order (random trees printed,
eval'd by Python and compared bit for bit with the tree walked node by node, tests/dsl_walk.py), records'
fields as struct members, a function body in statements and the status masks."""

from __future__ import annotations

import math
import random
import struct

import pytest
from dsl_walk import walk

from linkgen.primitives import PRIMITIVES
from linkgen.primitives.dsl import (
    EPS,
    PI,
    Bin,
    Builder,
    Call,
    Cmp,
    Expr,
    Logic,
    Neg,
    Num,
    Primitive,
    Select,
    Sym,
    either,
    select,
)
from linkgen.primitives.printers import MASKS, ExprPrinter, RecordExprs, literal, masks, statements


class Plain(ExprPrinter):
    """The shared layout with Python's spelling of what a language must say itself."""

    consts = {"eps": "EPS", "nan": "NAN", "pi": "PI"}

    def select(self, cond: str, a: str, b: str) -> str:
        return f"{a} if {cond} else {b}"


NAMESPACE = {"EPS": 2.0 ** -52, "NAN": math.nan, "PI": math.pi, "sqrt": math.sqrt, "atan2": math.atan2,
             "cos": math.cos, "sin": math.sin, "abs": abs, "max": max, "min": min}


def random_tree(rng: random.Random, depth: int) -> Expr:
    """Arithmetic, negations, selections, comparisons and calls over x, y, z and a few numbers."""
    if depth == 0 or rng.random() < 0.15:
        return rng.choice([Sym("x"), Sym("y"), Sym("z"), Num(rng.choice([2, 3, -1])), Num(rng.uniform(-3, 3)), PI])
    kind = rng.random()
    if kind < 0.6:
        return Bin(rng.choice("+-*/"), random_tree(rng, depth - 1), random_tree(rng, depth - 1))
    if kind < 0.7:
        return Neg(random_tree(rng, depth - 1))
    if kind < 0.8:
        return Call(rng.choice(["cos", "sin", "abs"]), (random_tree(rng, depth - 1),))
    if kind < 0.9:
        return Call("atan2", (random_tree(rng, depth - 1), random_tree(rng, depth - 1)))
    cond = Cmp(rng.choice(["<", "<=", ">", ">=", "=="]), random_tree(rng, 1), random_tree(rng, 1))
    if rng.random() < 0.5:
        cond = Logic(rng.choice(["and", "or"]), cond, Cmp("<", random_tree(rng, 1), Num(0)))
    return Select(cond, random_tree(rng, depth - 1), random_tree(rng, depth - 1))


def bits(x: float) -> bytes:
    return struct.pack("<d", x)


@pytest.mark.parametrize("seed", range(10))
def test_printed_expressions_evaluate_as_the_tree_bit_for_bit(seed: int):
    """Floating-point + and * are not associative: any parenthesis lost or added shows in the last bits."""
    rng = random.Random(seed)
    compared = 0
    for _ in range(200):
        e = random_tree(rng, 5)
        env = {"x": rng.uniform(-1e3, 1e3), "y": rng.uniform(-1, 1), "z": rng.uniform(-1e-3, 1e-3)}
        try:
            want = walk(e, env)
            got = eval(Plain().expr(e), dict(NAMESPACE), env)
        except (ZeroDivisionError, ValueError):  # Python raises where C gives inf or nan: nothing to compare
            continue
        assert (math.isnan(got) and math.isnan(want)) or bits(float(got)) == bits(float(want)), Plain().expr(e)
        compared += 1
    assert compared > 150


@pytest.mark.parametrize("e, text", [
    (Bin("-", Bin("-", Sym("a"), Sym("b")), Sym("c")), "a - b - c"),
    (Bin("-", Sym("a"), Bin("-", Sym("b"), Sym("c"))), "a - (b - c)"),
    (Bin("+", Sym("a"), Bin("+", Sym("b"), Sym("c"))), "a + (b + c)"),  # not reassociated
    (Bin("*", Bin("+", Sym("a"), Sym("b")), Sym("c")), "(a + b) * c"),
    (Bin("/", Sym("a"), Bin("*", Sym("b"), Sym("c"))), "a / (b * c)"),
    (Bin("+", Sym("a"), Bin("*", Sym("b"), Sym("c"))), "a + b * c"),
    (Neg(Bin("+", Sym("a"), Sym("b"))), "-(a + b)"),
    (Neg(Neg(Sym("a"))), "-(-a)"),
    (Bin("*", Num(-2), Sym("a")), "-2 * a"),
    (Bin("-", Sym("a"), Num(-2.5)), "a - -2.5"),  # a negative number binds as a negation
    (Select(Cmp("<", Sym("a"), Num(0)), Num(1), Select(Sym("c"), Num(2), Num(3))), "1 if a < 0 else 2 if c else 3"),
    (Select(Select(Sym("c"), Sym("p"), Sym("q")), Num(1), Num(2)), "1 if (p if c else q) else 2"),
    (Logic("or", Cmp("<", Sym("a"), Num(0)), Logic("or", Sym("b"), Sym("c"))), "a < 0 or (b or c)"),
    (Call("atan2", (Sym("y"), Bin("-", Sym("x"), EPS))), "atan2(y, x - EPS)"),
])
def test_parentheses_only_where_the_order_needs_them(e: Expr, text: str):
    assert Plain().expr(e) == text


@pytest.mark.parametrize("x", [0.1, 1 / 3, -2.5e-300, 5e-324, 1.7976931348623157e308, -0.0, 123456.789, 2.0 ** 60])
def test_a_literal_is_the_shortest_spelling_that_reads_back(x: float):
    text = literal(x)
    assert bits(float(text)) == bits(x)
    assert len(text) <= len(f"{x:.17g}") + 2  # never longer than 17 digits and a '.0' or exponent sign


def test_literals_of_ints_and_what_has_none():
    assert literal(3) == "3" and literal(-12) == "-12" and literal(2.0) == "2.0"
    with pytest.raises(TypeError):
        literal(True)
    for bad in (math.nan, math.inf, -math.inf):
        with pytest.raises(ValueError):
            literal(bad)


def test_record_fields_are_members_and_other_names_stay():
    class Dotted(RecordExprs):
        def select(self, cond: str, a: str, b: str) -> str:
            return f"{cond} ? {a} : {b}"

    printer = Dotted(PRIMITIVES["RRR_links"])
    assert printer.sym("j1_ddx") == "j1.ddx" and printer.sym("l2_v") == "l2.v" and printer.sym("minv") == "minv"
    assert printer.sym("hn") == "hn"
    assert printer.expr(either(Cmp("<", Sym("q"), Num(0)), Cmp("==", Sym("l1_v"), Num(0)))) == "q < 0 || l1.v == 0"


def _tiny() -> Primitive:
    b = Builder("tiny", "y = |x| + k, with rates; fails where x is 0")
    x = b.record("x", "VARIABLE")
    k = b.scalar("k")
    a = b.let("a", x.v * x.v)
    b.let("unused", k * 2)
    s = b.let("sigma", select(a < 1, a, 1))
    b.output("y", "VARIABLE", v=a + k, dv=2 * x.v * x.dv, ddv=2 * (x.dv * x.dv + x.v * x.ddv))
    return b.build(status=select(x.v.eq(0), 1, select(s < 1e-7, 3, 0)), sigma=s)


def test_a_body_is_its_live_definitions_then_status_and_stores():
    lines = statements(_tiny(), 1, Plain(), lambda name, e, kind: [f"{kind or '?'} {name} = {Plain().expr(e)}"],
                       lambda p, f, e: [f"{p.name}.{f} = {Plain().expr(e)}"])
    # 'unused' is dead, sigma is already a definition (no second assignment), order 1 stores v and dv
    assert lines == ["? a = x_v * x_v", "? sigma = a if a < 1 else 1", "int st = 1 if x_v == 0 else 3 if sigma < 1e-07 "
                     "else 0", "y.v = a + k", "y.dv = 2 * x_v * x_dv"]


def test_the_masks_name_each_failing_status_and_the_fields_it_makes_nan():
    assert MASKS == ((1, 0), (3, 1))  # a chain that cannot close: every field; a singular one: the rates
    got = [(cond, [f"{p.name}.{f}" for p, f in fields]) for cond, fields in masks(_tiny(), 2, "||")]
    assert got == [("st == 1", ["y.v", "y.dv", "y.ddv"]), ("st == 1 || st == 3", ["y.dv", "y.ddv"])]
    assert [cond for cond, _ in masks(_tiny(), 0, "or")] == ["st == 1"]  # order 0 has no rates to mask
