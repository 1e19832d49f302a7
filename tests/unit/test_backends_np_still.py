"""linkgen.backends.np.still: which records of a step's call the kernel holds still (the sketch's
constant records, whose rates are 0, where that saves an operation), the variants' names, and a
variant printed once equal to the printer's own (its bits: tests/unit/test_backends_np_printer.py)."""

from __future__ import annotations

from pathlib import Path

from linkgen.backends.np.printer import numpy_function
from linkgen.backends.np.still import held_params, printed, still_suffix
from linkgen.backends.still import held_still
from linkgen.pipeline import build_log
from linkgen.primitives import PRIMITIVES

ROOT = Path(__file__).resolve().parents[2]


def _held(sample: str, order: int) -> dict[int, tuple[str, ...]]:
    log = build_log(str(ROOT / "samples" / sample / f"{sample}.yaml"), sweep=False)
    return {s.number: held_params(log, order, s) for s in log.steps if held_params(log, order, s)}


def test_the_four_bars_constant_records_are_held_still_where_their_zero_rates_enter_a_call():
    # the sketch: A from the frame pivot O1 (step 2, j1: its rates added to A's) at the crank angle plus
    # the frame's angle (phi: its rates added to the input's), B from A and the frame pivot O2 (step 3,
    # j2) with the coupler's and rocker's lengths (l1, l2: their rates multiply), the crank's angle (step 5,
    # phi again), the rocker's angle from O2 to B (step 7, O2 its first); A and B move (steps 4, 6: none)
    want = {2: ("j1", "phi"), 3: ("j2", "l1", "l2"), 5: ("phi",), 7: ("j1",)}
    assert _held("fourbar", 2) == want
    assert _held("fourbar", 1) == want


def test_nothing_is_held_at_order_0_or_in_a_mechanism_with_resolver_groups():
    assert _held("fourbar", 0) == {}
    assert _held("sixbar_fig14", 2) == {}


def test_a_variant_is_named_after_the_records_it_holds_and_printed_as_the_printer_prints_it():
    assert still_suffix(()) == "" and still_suffix(("j1",)) == "_still_j1"
    assert still_suffix(("j1", "j2")) == "_still_j1_j2"
    prim = PRIMITIVES["RRR_links"]
    want = numpy_function(held_still(prim, ("j2",))[0], 2, "", "RRR_links_still_j2")
    assert printed("RRR_links", 2, still=("j2",)) == want
    assert "def RRR_links_still_j2(" in want and printed("RRR_links", 2) == numpy_function(prim, 2, "")
