"""extraction.loops: the class-III shape of a group, the forward and reverse loop blocks, and the groups
left to Newton; checked by hand on Fig. 14's six-bar (ternary J2 J4 J5 on legs J1-J2, J3-J4, J6-J5)."""

from __future__ import annotations

import math
from pathlib import Path

from linkgen.extraction.loops import triad, with_loops
from linkgen.pipeline import analyse_file

ROOT = Path(__file__).resolve().parents[2]
FIG14 = ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"
SLIDER = ROOT / "samples" / "sixbar_slider" / "sixbar_slider.yaml"


def test_fig14s_group_is_a_ternary_on_three_legs():
    m, _, proc = analyse_file(str(FIG14))
    t = triad(m, proc.groups[0], {v.name: v for v in proc.variables})
    assert t is not None and t.body == "ternary" and t.xs == ("J2", "J4", "J5")
    assert t.legs == ("rocker1", "rocker2", "coupler") and t.ks == ("J1", "J3", "J6")


def test_the_loop_blocks_close_at_the_sketch_and_start_at_the_legs_arc():
    m, _, proc = analyse_file(str(FIG14))
    steps, variables, groups, unlooped = with_loops(m, proc.steps, proc.variables, proc.groups)
    assert unlooped == ()
    by_name = {v.name: v for v in variables}
    forward, reverse = groups[0].variants[-2:]
    assert forward.lengths == reverse.lengths == (70.0 * math.pi / 2,)  # rocker1 (70) upright in the sketch
    chains = [[s for s in steps if s.number in b.steps and s.function == "RRR_links"] for b in (forward, reverse)]
    assert [s.target for s in chains[0]] == ["J5", "J4", "J2"] and [s.target for s in chains[1]] == ["J4", "J5", "J2"]
    sketch = {v.entity: v.sketch for v in variables if v.role == "pair"}
    for s in chains[0] + chains[1]:  # every chain's branch is the side its pair lies on in the sketch
        (ax, ay), (bx, by), (cx, cy) = (sketch[p][:2] for p in (*s.pairs, s.target))
        assert s.branch == (1 if (bx - ax) * (cy - ay) - (by - ay) * (cx - ax) >= 0 else -1)
        side, leg = (by_name[a.var].value[0] for a in s.args[2:4])
        assert math.isclose(side, math.dist(sketch[s.pairs[0]][:2], (cx, cy)))
        assert math.isclose(leg, math.dist((bx, by), (cx, cy)))
    assert any("strategy loop" in s.reason for s in steps if s.action == "resolve")


def test_a_group_of_another_shape_is_left_to_newton_and_says_so():
    m, _, proc = analyse_file(str(SLIDER))
    steps, _, groups, unlooped = with_loops(m, proc.steps, proc.variables, proc.groups)
    assert unlooped == tuple(g.number for g in proc.groups)
    assert all(g.variants == h.variants for g, h in zip(groups, proc.groups))
    assert all("so Newton on its Add-links" in s.reason for s in steps if s.action == "resolve")
