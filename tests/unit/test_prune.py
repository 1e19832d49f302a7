"""prune: a final log cut to the steps its outputs need equals the log of the pruned procedure.

The independent route is the order main used: prune the draft first, then find the facts of
what is left (change points, gaps, reach, conditioning) by evaluating it."""

from __future__ import annotations

from pathlib import Path

import pytest

from linkgen.analysis import motion_facts, with_facts
from linkgen.pipeline import analyse_file, build_log, draft
from linkgen.prune import keep, prune

ROOT = Path(__file__).resolve().parents[2]
MECHANISMS = ROOT / "tests" / "mechanisms"
FIG14 = ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"

CASES = [
    ("stephenson_circuit", ("B",)),  # its first four-bar: the reach of its own gaps, not the six-bar's
    ("stephenson_circuit", ("D",)),
    ("watt_circuit", ("D",)),  # one gap left: an angle with one gap has no reach
    ("parallelogram", ("B",)),  # change points
    ("fourbar_partial", ("coupler",)),
]


@pytest.mark.parametrize(("name", "outputs"), CASES, ids=[f"{n}-{o[0]}" for n, o in CASES])
def test_prune_after_analysis_equals_analysis_after_prune(name, outputs):
    _, topo, proc = analyse_file(str(MECHANISMS / f"{name}.yaml"))
    whole = draft(topo, proc, outputs)
    pruned = prune(whole)
    assert len(pruned.steps) < len(whole.steps)
    assert prune(with_facts(whole, motion_facts(whole))) == with_facts(pruned, motion_facts(pruned))


def test_the_reach_of_a_pruned_log_is_its_own():
    """stephenson_circuit's six-bar stops below where its second dyad (step 5) cannot close, its
    first four-bar (steps 1-3) where its own chain cannot: farther."""
    whole = build_log(str(MECHANISMS / "stephenson_circuit.yaml"), sweep=False)
    four_bar = build_log(str(MECHANISMS / "stephenson_circuit.yaml"), ("B",), sweep=False)
    assert whole.reach is not None and four_bar.reach is not None
    assert (whole.reach.low_step, four_bar.reach.low_step) == (5, 3)
    assert four_bar.reach.low > whole.reach.low and four_bar.reach.high == whole.reach.high
    assert {g.step for g in four_bar.gaps} == {3} and {g.step for g in whole.gaps} == {3, 5}


def test_one_pair_of_the_six_bar_drops_the_resolver_and_what_it_needs():
    """J6, the crank's end, needs the frame and the crank input (steps 1 and 2): no resolver,
    no reach, status codes of step 0 only, the crank input alone at run time."""
    whole = build_log(str(FIG14), sweep=False)
    log = build_log(str(FIG14), ("J6",), 0, sweep=False)
    assert [s.number for s in log.steps] == [1, 2] and log.groups == () and log.add_links == ()
    assert log.reach is None and log.residuals == () and log.runtime == ("crank_input",)
    assert [c.code for c in log.status_codes] == [5]
    assert [o.number for o in log.omitted] == [s.number for s in whole.steps if not s.variant][2:]
    assert {v.name for v in log.variables} < {v.name for v in whole.variables}


def test_keep_leaves_a_log_that_needs_everything_as_it_is():
    log = build_log(str(FIG14), sweep=False)
    assert keep(log, {c.variable for c in log.columns}) is log and prune(log) is log
