"""extraction.state: the frozen SolverState and its working copies."""

from __future__ import annotations

from pathlib import Path

import pytest

from linkgen.extraction import stuck
from linkgen.extraction.state import SolverState, Workspace
from linkgen.topology import analyse
from linkgen.validate import read_mechanism

ROOT = Path(__file__).resolve().parents[2]
FIG14 = ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"


@pytest.fixture(scope="module")
def state() -> SolverState:
    found = stuck(analyse(read_mechanism(str(FIG14))))
    assert found is not None
    return found


def test_thaw_then_freeze_gives_the_same_state(state: SolverState):
    assert Workspace.thaw(state).frozen() == state


def test_a_working_copy_does_not_change_the_state(state: SolverState):
    ws = Workspace.thaw(state)
    ws.tied["ternary"].append("J9")
    ws.pos["J9"] = "p_J9"
    ws.placed.add("ternary")
    ws.new_var("p_J9", "POINT", "pair", "J9", (1.0, 2.0))
    assert "J9" not in state.tied["ternary"] and "J9" not in state.pos and "ternary" not in state.placed
    assert "p_J9" not in state.variables
    with pytest.raises(TypeError):
        state.pos["J9"] = "p_J9"  # type: ignore[index]


def test_new_names_never_clash(state: SolverState):
    ws = Workspace.thaw(state)
    first = ws.new_var("p_J7", "POINT", "pair", "J7", (0.0, 0.0))
    second = ws.new_var("p_J7", "POINT", "pair", "J7", (0.0, 0.0))
    assert (first, second) == ("p_J7_2", "p_J7_3")


def test_prismatic_copies_are_named_by_their_guide():
    topo = analyse(read_mechanism(str(ROOT / "samples" / "slider_crank" / "slider_crank.yaml")))
    ws = Workspace.thaw(stuck(topo) or _solved(topo))
    p = ws.m.prismatic[0]
    assert ws.copy(p.joint, p.slider) == p.joint
    assert ws.copy(p.joint, p.guide) == f"{p.joint}@{p.guide}"
    assert ws.xy(f"{p.joint}@{p.guide}") == ws.xy(p.joint)


def _solved(topo) -> SolverState:
    from linkgen.extraction.solver import solve, start
    ws = start(topo)
    assert solve(ws)
    return ws.frozen()
