"""Procedure extraction: step order, chains, branches, Add-link candidates (paper Table 2)."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from linkgen.extraction import SolverState, candidates, stuck
from linkgen.pipeline import build_log
from linkgen.topology import analyse
from linkgen.validate import read_mechanism

ROOT = Path(__file__).resolve().parents[2]
FIG14 = ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"
FOURBAR = ROOT / "samples" / "fourbar" / "fourbar.yaml"
TABLE_2 = {("J1", "J4"), ("J1", "J5"), ("J2", "J3"), ("J3", "J5"), ("J2", "J6"), ("J4", "J6"), ("J2", "J7"),
           ("J4", "J7"), ("J5", "J7")}


def _stuck(path: Path) -> SolverState:
    state = stuck(analyse(read_mechanism(str(path))))
    assert state is not None
    return state


def test_fig14_candidates_are_table_2_in_the_papers_order():
    found = candidates(_stuck(FIG14))
    assert {tuple(sorted(c)) for c in found} == TABLE_2
    # the paper lists them by the known pair, then the unknown one
    assert found == [("J1", "J4"), ("J1", "J5"), ("J3", "J2"), ("J3", "J5"), ("J6", "J2"), ("J6", "J4"),
                     ("J7", "J2"), ("J7", "J4"), ("J7", "J5")]


def test_fig14_chosen_add_link_has_the_smallest_norm():
    log = build_log(str(FIG14), sweep=False)
    (add,) = log.add_links
    norms = [c.norm for c in add.candidates]
    assert len(norms) == 9 and all(n is not None for n in norms)
    assert norms == sorted(norms)
    assert add.pairs == add.candidates[0].pairs
    assert add.probe[0] == pytest.approx(log.inputs[0].sketch + math.radians(5))


def test_fig14_resolver_group_covers_the_class_iii_group():
    log = build_log(str(FIG14), sweep=False)
    (group,) = log.groups
    (res,) = log.residuals
    assert group.add_links == ("add1",) and group.residuals == (res.name,)
    inside = {log.step(n).target for n in group.steps}
    assert {"J2", "J4", "J5"} <= inside  # the class-III group is iterated
    assert "J6" not in inside  # the crank is computed once, before the resolver
    assert log.step(group.step).action == "resolve"
    assert max(group.steps) < group.step


def test_fourbar_procedure_is_input_then_3r_chain():
    log = build_log(str(FOURBAR), sweep=False)
    kinds = [(s.action, s.function, s.target) for s in log.steps[:3]]
    assert kinds == [("fixed", "", "frame"), ("input", "crank_input", "A"), ("chain", "RRR_links", "B")]
    rrr = log.steps[2]
    # B (80, 50) lies to the left of A (20, 0) -> O2 (90, 0): branch +1
    assert rrr.branch == 1 and rrr.pairs == ("A", "O2")
    assert [s.determines for s in log.steps[:3]] == [("O1", "O2"), ("A",), ("B",)]


@pytest.mark.parametrize("name, chain", [("slider_crank", "RRP"), ("inverted", "RPR"), ("scotch_yoke", "PPR"),
                                         ("cross_slot", "PRP")])
def test_every_dyad_kind_is_found(name: str, chain: str):
    log = build_log(str(ROOT / "tests" / "mechanisms" / f"{name}.yaml"), sweep=False)
    assert [s.chain for s in log.steps if s.chain] == [chain]


def test_procedure_is_deterministic():
    assert build_log(str(FIG14)).to_json() == build_log(str(FIG14)).to_json()


def _ladder(n: int, tmp: Path) -> Path:
    """A chain of n dyads: each new pair joins the previous one and a ground pivot."""
    lines = ["linkgen: 1", "name: ladder", "joints:", "  G0: [0, 0]", "  A0: [10, 10]"]
    links = ["links:", "  crank: [G0, A0]"]
    frame = ["G0"]
    for k in range(1, n + 1):
        lines += [f"  G{k}: [{40 * k}, 0]", f"  A{k}: [{40 * k + 5}, {30 + 3 * (k % 2)}]"]
        links += [f"  coupler{k}: [A{k - 1}, A{k}]", f"  rocker{k}: [G{k}, A{k}]"]
        frame.append(f"G{k}")
    links.insert(1, f"  frame: {{joints: [{', '.join(frame)}], fixed: true}}")
    body = lines + links + ["inputs:", "  - {joint: G0, link: crank, relative_to: frame, range: [40, 50]}"]
    path = tmp / "ladder.yaml"
    path.write_text("\n".join(body) + "\n")
    return path


def test_a_chain_of_dyads_is_solved_in_order(tmp_path: Path):
    log = build_log(str(_ladder(12, tmp_path)), sweep=False)
    chains = [s.target for s in log.steps if s.chain]
    assert chains == [f"A{k}" for k in range(1, 13)]
    assert not log.add_links
