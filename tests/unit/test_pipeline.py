"""pipeline: the draft of the whole procedure, made into the log once, then pruned."""

from __future__ import annotations

from pathlib import Path

import pytest
from mechanism_text import SLIDER_TRIAD

from linkgen.errors import InputError
from linkgen.pipeline import analyse_file, build_log, draft

ROOT = Path(__file__).resolve().parents[2]
PARALLELOGRAM = ROOT / "tests" / "mechanisms" / "parallelogram.yaml"
JANSEN = ROOT / "samples" / "jansen" / "jansen.yaml"
PARTIAL = ROOT / "tests" / "mechanisms" / "sixbar_partial.yaml"


def test_the_draft_has_no_motion_facts():
    _, topo, proc = analyse_file(str(PARALLELOGRAM))
    flat = draft(topo, proc)
    assert not any(s.change_points for s in flat.steps)
    assert (flat.gaps, flat.reach, flat.conditioning, flat.omitted) == ((), None, (), ())
    assert flat.steps == proc.steps and flat.variables == proc.variables


def test_a_build_for_some_outputs_keeps_the_whole_builds_facts_of_its_steps():
    """Jansen's leg for its foot at order 1: the columns asked for, fewer steps, and of them the
    conditioning the whole build found."""
    whole = build_log(str(JANSEN))
    log = build_log(str(JANSEN), ("foot",), 1)
    kept = {s.number for s in log.steps}
    assert {c.name.split(".")[0] for c in log.columns[1:]} == {"foot"} and log.order == 1
    assert len(kept) < len(whole.steps) and [o.number for o in log.omitted] == sorted(set(range(1, 15)) - kept)
    assert log.conditioning == tuple(c for c in whole.conditioning if c.step in kept) and log.conditioning


def test_an_unknown_output_is_refused():
    with pytest.raises(InputError, match="nope is not a pair, point or link of parallelogram"):
        build_log(str(PARALLELOGRAM), ("nope",))


def test_the_motion_facts_are_the_mechanisms_whatever_the_resolver_runs():
    """sixbar_partial's limit positions and conditioning, found with the default iteration, are the
    same in a build whose programs run the fixed-point iteration from the last row's state without
    polish (found with it, its reach would end where that iteration first fails)."""
    default = build_log(str(PARTIAL))
    log = build_log(str(PARTIAL), options={"strategy": "fixed-point", "predictor": 0, "polish": False})
    assert log.reach == default.reach and log.reach is not None
    assert log.conditioning == default.conditioning
    assert (log.options.strategy, log.options.predictor, log.options.polish) == ("fixed-point", 0, False)


def test_the_closure_strategy_is_refused_where_it_was_asked_for(tmp_path: Path):
    """A resolver group with a prismatic pair (tests/unit/test_extraction_closure.py's slider triad): the
    error names the file's options.strategy, or the command line's --strategy."""
    path = tmp_path / "slider_triad.yaml"
    path.write_text(SLIDER_TRIAD + "options:\n  strategy: closure\n")
    with pytest.raises(InputError) as info:
        build_log(str(path), sweep=False)
    assert (info.value.path, info.value.line, info.value.key) == (str(path), 21, "options.strategy")
    assert info.value.message.startswith("the closure strategy cannot resolve this mechanism: it handles resolver "
                                         "groups of revolute pairs only")
    assert info.value.message.endswith("; use strategy newton")
    path.write_text(SLIDER_TRIAD)
    with pytest.raises(InputError) as info:
        build_log(str(path), sweep=False, options={"strategy": "closure"})
    assert (info.value.path, info.value.line, info.value.key) == ("command line", 0, "--strategy")
    assert build_log(str(path), sweep=False).groups  # the default strategy resolves it
