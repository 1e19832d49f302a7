"""linkgen.backends.still: a primitive with records held still gives the values the primitive itself gives on
records whose rates are 0.0 (the Python printer's functions of both, at random arguments), but for a zero's
sign; the operations it leaves out (hand counts); which records a step holds still (the four-bar by hand; a
pruned build's steps as the whole build's, resolver blocks none); what a program carries."""

from __future__ import annotations

import math
import random
import sys
from pathlib import Path

import pytest

from linkgen.backends.py.printer import python_function
from linkgen.backends.still import carried, held_params, held_still, scalar_variants, still_suffix, substituted, variant
from linkgen.pipeline import build_log
from linkgen.primitives import PRIMITIVES, python_backend
from linkgen.primitives.dsl import Bin, Num, Param, Primitive, Sym, record_fields

ROOT = Path(__file__).resolve().parents[2]
SPACE = {"sqrt": math.sqrt, "atan2": math.atan2, "cos": math.cos, "sin": math.sin, "EPS": sys.float_info.epsilon,
         "NAN": math.nan, "PI": math.pi}


def _function(prim: Primitive, order: int):
    space = dict(SPACE)
    exec(python_function(prim, order), space)
    return space[prim.name]


def _argument(p: Param, order: int, still: tuple[str, ...], rng: random.Random):
    """A random argument: a record's displacement fields in -2..2 (a length's in 1..3, so that chains
    close) and its rates (0.0 where held still), a real in -2..2, a flag +1 or -1."""
    if p.kind == "INT":
        return rng.choice((-1, 1))
    if not p.is_record:
        return rng.uniform(-2, 2)
    width = len(record_fields(p.kind, 0))
    fields = record_fields(p.kind, order)
    low, high = (1.0, 3.0) if p.kind == "VARIABLE" else (-2.0, 2.0)
    return tuple(rng.uniform(low, high) if k < width else rng.uniform(-2, 2) if p.name not in still else 0.0
                 for k in range(len(fields)))


def _finite(a: object) -> bool:
    return all(_finite(x) for x in a) if isinstance(a, tuple) else not math.isnan(a)  # type: ignore[arg-type]


def _same_but_a_zeros_sign(a: object, b: object) -> bool:
    if isinstance(a, tuple) and isinstance(b, tuple):
        return len(a) == len(b) and all(_same_but_a_zeros_sign(x, y) for x, y in zip(a, b))
    assert isinstance(a, int | float) and isinstance(b, int | float)
    return a == b or (math.isnan(a) and math.isnan(b))


def _records(name: str) -> list[tuple[str, ...]]:
    records = tuple(p.name for p in PRIMITIVES[name].params if p.is_record)
    return [(r,) for r in records] + [records]


@pytest.mark.parametrize("name", list(PRIMITIVES))
def test_held_still_gives_the_primitives_values_on_records_whose_rates_are_zero(name: str):
    rng = random.Random(name)
    closed = 0
    for order in (1, 2):
        whole = _function(PRIMITIVES[name], order)
        for still in _records(name):
            held = _function(variant(name, True, still), order)
            for _ in range(20):
                args = [_argument(p, order, still, rng) for p in PRIMITIVES[name].params]
                assert _same_but_a_zeros_sign(held(*args), whole(*args)), (name, still, order, args)
                closed += _finite(held(*args))
    assert closed >= 20 * len(_records(name)) // 2, closed  # most calls give numbers, not a failing chain's nan


def test_a_folded_zero_keeps_the_other_operands_sign():
    """crank_angle's rate theta' + phi' with phi held still is theta' itself: -0.0 where IEEE's -0.0 + 0.0 is 0.0."""
    args = ((0.5, -0.0, -0.0), (0.25, 0.0, 0.0), 0.0)
    whole = _function(PRIMITIVES["crank_angle"], 2)(*args)
    held = _function(variant("crank_angle", True, ("phi",)), 2)(*args)
    assert whole == held and [math.copysign(1, x) for x in whole[1:]] == [1, 1]
    assert [math.copysign(1, x) for x in held[1:]] == [-1, -1]


def test_a_primitives_own_zero_is_not_folded():
    """instant_centre's direction is written ``k * (0.0 - gy) / |g| + 0.0`` so that it is never -0.0: held
    still, it still is not (the whole primitive's signs, on records whose rates are zeros of either sign)."""
    rng = random.Random(7)
    whole = _function(PRIMITIVES["instant_centre"], 2)
    ux, uy = record_fields("CENTRE", 2).index("ux"), record_fields("CENTRE", 2).index("uy")
    signed = 0
    for still in _records("instant_centre"):
        held = _function(variant("instant_centre", True, still), 2)
        for _ in range(200):
            args = [tuple(rng.choice((0.0, -0.0, 1.0, -2.0)) if x != 0.0 else x for x in _argument(p, 2, still, rng))
                    for p in PRIMITIVES["instant_centre"].params]
            got, want = held(*args), whole(*args)
            assert [math.copysign(1, got[k]) for k in (ux, uy)] == [math.copysign(1, want[k]) for k in (ux, uy)]
            signed += got[uy] == 0 and got[ux] == 1
    assert signed > 10  # directions along x, where -0.0 would show


@pytest.mark.parametrize(("name", "still", "saved"), [
    ("link_angle", ("j1",), 4),  # j2's rates minus j1's: dvx, dvy, dax, day
    ("crank_input", ("j1",), 4),  # j1's rates plus the rotating arm's: dx, dy, ddx, ddy
    ("crank_angle", ("phi",), 2),  # theta' + phi', theta'' + phi''
    ("offset_angle", ("phi",), 0),  # phi's rates passed on as they are: nothing to leave out
])
def test_the_operations_left_out(name: str, still: tuple[str, ...], saved: int):
    assert held_still(PRIMITIVES[name], still)[1] == saved


def test_a_symbol_read_twice_is_replaced_once_and_an_untouched_tree_kept():
    x, y = Sym("x"), Sym("y")
    e = Bin("+", Bin("*", x, y), Bin("*", x, x))
    memo: dict[int, object] = {}
    out = substituted(e, {"x": Num(0.0)}, memo)  # type: ignore[arg-type]
    assert isinstance(out, Bin) and isinstance(out.a, Bin) and out.a.a is out.b.a is out.b.b  # type: ignore[attr-defined]
    assert substituted(e, {"z": Num(1.0)}, {}) is e


def test_a_variant_is_named_after_its_records_and_is_the_primitive_where_none_are():
    assert still_suffix(()) == "" and still_suffix(("j1",)) == "_still_j1"
    assert still_suffix(("j1", "j2")) == "_still_j1_j2"
    assert variant("RRR_links", True, ("j2", "l1")).name == "RRR_links_still_j2_l1"
    assert variant("RRR_links", True, ()) is PRIMITIVES["RRR_links"]
    assert variant("RRR_links", False, ()).sigma is None


def _log(sample: str, outputs: tuple[str, ...] | None = None, order: int | None = None):
    return build_log(str(ROOT / "samples" / sample / f"{sample}.yaml"), outputs, order, sweep=False)


def _held(log, order: int) -> dict[int, tuple[str, ...]]:
    return {s.number: held_params(log, order, s) for s in log.steps if held_params(log, order, s)}


def test_the_four_bars_constant_records_are_held_still_where_their_zero_rates_enter_a_call():
    # the sketch: A from the frame pivot O1 (step 2, j1: its rates added to A's) at the crank angle plus
    # the frame's angle (phi: its rates added to the input's), B from A and the frame pivot O2 (step 3,
    # j2) with the coupler's and rocker's lengths (l1, l2: their rates multiply), the crank's angle (step 5,
    # phi again), the rocker's angle from O2 to B (step 7, O2 its first); A and B move (steps 4, 6: none)
    log = _log("fourbar")
    want = {2: ("j1", "phi"), 3: ("j2", "l1", "l2"), 5: ("phi",), 7: ("j1",)}
    assert _held(log, 2) == want and _held(log, 1) == want and _held(log, 0) == {}
    # what its programs carry: link_angle (step 6) and pair_point (step 4) as they are, then the variants
    assert carried(log, 2, ["crank_input", "link_angle", "crank_angle", "pair_point", "RRR_links"]) == [
        ("link_angle", ()), ("pair_point", ()), ("crank_input", ("j1", "phi")), ("link_angle", ("j1",)),
        ("crank_angle", ("phi",)), ("RRR_links", ("j2", "l1", "l2"))]


@pytest.mark.parametrize(("sample", "outputs", "order"), [
    ("double_triad", ("J6",), 1), ("double_triad", ("J6",), 2), ("sixbar_fig14", ("J6",), 2),
    ("sixbar_fig14", ("coupler",), 2),
])
def test_a_pruned_build_holds_what_the_whole_build_holds_and_resolver_blocks_nothing(sample, outputs, order):
    """The choice reads the step and the mechanism, never the outputs kept: the whole build has resolver
    groups where a pruned one may have none (the J6 of the triads: steps 1 and 2 only)."""
    whole, pruned = _log(sample, order=2), _log(sample, outputs, order)
    assert whole.groups and _held(pruned, order)
    wanted = _held(whole, order)
    assert _held(pruned, order) == {n: held for n, held in wanted.items() if n in {s.number for s in pruned.steps}}
    inside = {n for g in whole.groups for b in (g, *g.variants) for n in b.steps}
    assert inside and not inside & set(wanted)


def test_the_row_solvers_variants_are_those_a_resolver_program_calls_outside_its_blocks():
    """The triad six-bar: the crank from its frame pivot J7 at the frame's angle, the rocker's angle from J1."""
    log = _log("sixbar_fig14")
    found = scalar_variants(log, 2)
    assert sorted(found) == ["crank_angle_still_phi", "crank_input_still_j1_phi", "link_angle_still_j1"]
    whole = python_backend(2)["crank_angle"]
    assert found["crank_angle_still_phi"]((1.0, -0.0, 0.5), (0.5, 0.0, 0.0), 0.25) == whole((1.0, -0.0, 0.5),
                                                                                             (0.5, 0.0, 0.0), 0.25)
