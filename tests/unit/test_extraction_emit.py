"""extraction.emit: what follows from a step (orientation through prismatic pairs, links placed, the pairs
it determines), and the states it refuses."""

from __future__ import annotations

from pathlib import Path

import pytest

from linkgen.extraction.emit import emit, refresh
from linkgen.extraction.solver import solve, start
from linkgen.extraction.state import Unsupported, Workspace
from linkgen.steplog import Arg
from linkgen.topology import analyse
from linkgen.validate import read_mechanism

ROOT = Path(__file__).resolve().parents[2]
FOURBAR = ROOT / "samples" / "fourbar" / "fourbar.yaml"


def _start(path: Path) -> Workspace:
    return start(analyse(read_mechanism(str(path))))


def test_a_slider_turns_with_its_placed_guide():
    ws = _start(ROOT / "tests" / "mechanisms" / "slider_crank.yaml")
    # the block slides in the frame's slot S: its angle is the frame's plus a constant, before any chain
    assert ws.coupled == {"block": "frame"} and ws.placed == {"frame"}


def test_a_link_is_placed_once_two_of_its_points_apart_are_known():
    ws = _start(FOURBAR)
    assert "crank" not in ws.placed and ws.tied["crank"] == ["O1"]
    ws.pos["A"] = ws.point_var("A")
    emit(ws, "input", "crank_input", [Arg("var", "p_O1")], ["p_A"], "A", pairs=("O1",), links=("crank",))
    assert "crank" in ws.placed and ws.tied["crank"] == ["O1", "A"]
    assert ws.steps[-1].determines == ("A",) and ws.steps[-1].number == len(ws.steps)


def test_a_step_determines_the_prismatic_pairs_whose_guide_it_places():
    ws = _start(Path(__file__).with_name("slotted_coupler.yaml"))
    assert solve(ws)
    (chain,) = [s for s in ws.steps if s.target == "B"]
    # B places the coupler A-B, and with it the slot S the coupler carries
    assert chain.determines == ("B", "S")


def test_a_link_with_a_known_angle_and_point_cannot_take_another_point():
    ws = _start(FOURBAR)
    ws.orient["coupler"] = "phi_x"  # pretend something turned the coupler
    ws.pos["A"], ws.pos["B"] = "p_A", "p_B"
    with pytest.raises(Unsupported, match="link coupler is over-determined at B"):
        refresh(ws)
