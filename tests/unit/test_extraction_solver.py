"""extraction.solver: what the Solver starts from (the frame, the LJ-matrix's columns by rules i and ii),
how it drives inputs, and where it stops."""

from __future__ import annotations

import math
from pathlib import Path

from linkgen.extraction import candidates, stuck
from linkgen.extraction.addlink import install
from linkgen.extraction.solver import solve, start
from linkgen.extraction.state import Workspace
from linkgen.topology import analyse
from linkgen.validate import read_mechanism

ROOT = Path(__file__).resolve().parents[2]


def _start(path: Path) -> Workspace:
    return start(analyse(read_mechanism(str(path))))


def test_the_frames_revolute_pairs_are_known_constants_and_its_angle_its_direction():
    ws = _start(ROOT / "tests" / "mechanisms" / "whitworth.yaml")
    # frame: O1 (0, 20), O2 (0, 0) and the prismatic pair R, whose position a chain finds later
    assert ws.pos == {"O1": "p_O1", "O2": "p_O2"}
    assert (ws.variables["p_O1"].value, ws.variables["p_O2"].value) == ((0.0, 20.0), (0.0, 0.0))
    assert ws.variables["phi_frame"].value == (-math.pi / 2,)  # O1 -> O2 points down
    assert [(s.action, s.target, s.determines) for s in ws.steps] == [("fixed", "frame", ("O1", "O2", "R"))]


def test_lj_columns_are_the_truss_members_then_the_inputs():
    ws = _start(ROOT / "samples" / "actuator" / "actuator.yaml")
    # the ternary stick becomes its 3 members (rule i); the distance input S0-K is an actuator (rule ii)
    assert [(c.name, c.kind, c.pairs) for c in ws.columns] == [
        ("stick:S0-R", "member", ("S0", "R")), ("stick:S0-Q", "member", ("S0", "Q")),
        ("stick:R-Q", "member", ("R", "Q")), ("barrel", "member", ("S0", "C")), ("rod", "member", ("C", "K")),
        ("side_link", "member", ("R", "K")), ("power_link", "member", ("K", "M")), ("bucket", "member", ("Q", "M")),
        ("d_S0_K", "actuator", ("S0", "K")),
    ]
    actuator = ws.carrier("d_S0_K")
    assert (actuator.kind, actuator.pairs, actuator.length) == ("actuator", ("S0", "K"), "in1")


def test_a_revolute_inputs_column_joins_the_pairs_its_angle_is_measured_to():
    ws = _start(ROOT / "samples" / "fourbar" / "fourbar.yaml")
    # theta_O1: the crank O1 -> A against the frame O1 -> O2
    assert [(c.name, c.pairs, c.link) for c in ws.columns if c.kind == "input"] == [("theta_O1", ("A", "O2"), "crank")]


def test_a_crank_input_places_its_link_at_the_drawn_length():
    ws = _start(ROOT / "tests" / "mechanisms" / "whitworth.yaml")
    assert solve(ws)
    (crank,) = [s for s in ws.steps if s.function == "crank_input"]
    assert [a.var for a in crank.args if a.kind == "var"] == ["p_O1", "in1", "ref_O1"]
    assert crank.args[1].value == math.hypot(30, 20)  # A (30, 40) from O1 (0, 20)
    assert crank.outputs == ("p_A",) and crank.determines == ("A",)


def test_the_solver_stops_where_a_group_closes_or_nothing_is_computable():
    topo = analyse(read_mechanism(str(ROOT / "samples" / "double_triad" / "double_triad.yaml")))
    state = stuck(topo)
    assert state is not None
    ws = Workspace.thaw(state)
    install(ws, *candidates(state)[0])
    assert solve(ws, stop_at_close=True) and ws.group == 0
    unknown = [j.name for j in ws.m.joints if not ws.is_known(j.name)]
    assert unknown == ["K2", "K4", "K5"]  # the second triad
    assert not solve(ws)  # stuck again: it needs an Add-link of its own


def test_a_group_left_open_by_its_slide_is_solved_again_with_slide_chains_first():
    """tests/regressions/class4_slot.yaml: with the first Add-link installed the Solver knows every
    pair but leaves the slot S unused (no residual), so the group is open; with ``slides_first``
    the same Add-link's group closes, S placed by a chain on its slide and a link left as residual."""
    topo = analyse(read_mechanism(str(ROOT / "tests" / "regressions" / "class4_slot.yaml")))
    ws = start(topo)
    assert not solve(ws)
    state = ws.frozen()
    for slides_first in (False, True):
        trial = Workspace.thaw(state)
        trial.slides_first = slides_first
        install(trial, "O2", "B")
        assert solve(trial, stop_at_close=True)
        assert bool(trial.group) is not slides_first
        assert ("S" in trial.slides) is slides_first
        assert any(s.function == "link_residual" for s in trial.steps) is slides_first
