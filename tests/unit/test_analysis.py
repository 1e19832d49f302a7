"""analysis: the motion facts of a draft, and the step log made from the draft and them."""

from __future__ import annotations

from pathlib import Path

from linkgen.analysis import Facts, motion_facts, with_facts
from linkgen.pipeline import analyse_file, draft

ROOT = Path(__file__).resolve().parents[2]
MECHANISMS = ROOT / "tests" / "mechanisms"


def _draft(path: Path, outputs: tuple[str, ...] | None = None):
    _, topo, proc = analyse_file(str(path))
    return draft(topo, proc, outputs)


def test_the_facts_are_the_procedures_not_the_outputs():
    """Outputs choose columns; the facts belong to the whole procedure (prune cuts them later)."""
    path = MECHANISMS / "stephenson_circuit.yaml"
    assert motion_facts(_draft(path, ("B",)), sweep=False) == motion_facts(_draft(path), sweep=False)


def test_two_inputs_have_a_conditioning_only():
    facts = motion_facts(_draft(ROOT / "samples" / "fivebar" / "fivebar.yaml"))
    assert (facts.change_points, facts.gaps, facts.reach) == ((), (), None) and facts.conditioning


def test_the_log_carries_the_facts_and_what_follows_from_them():
    """The parallelogram's chain flips at its change points (branch_at at run time); the
    resolver's limit positions of sixbar_partial bound its reach (reach_at, and status 81)."""
    flat = _draft(MECHANISMS / "parallelogram.yaml")
    facts = motion_facts(flat, sweep=False)
    log = with_facts(flat, facts)
    assert [(s.number, s.change_points) for s in log.steps if s.change_points] == list(facts.change_points)
    assert "branch_at" in log.runtime and "branch_at" not in flat.runtime
    partial = _draft(MECHANISMS / "sixbar_partial.yaml")
    facts = motion_facts(partial, sweep=False)
    log = with_facts(partial, facts)
    assert log.reach == facts.reach is not None and "reach_at" in log.runtime
    assert [c.code for c in log.status_codes if "limit position" in c.meaning] == [81]
    assert 81 not in [c.code for c in partial.status_codes]


def test_no_facts_leave_the_draft_as_it_is():
    flat = _draft(MECHANISMS / "parallelogram.yaml")
    assert with_facts(flat, Facts()) == flat
