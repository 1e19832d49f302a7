"""The walk along the procedure: branches that cannot close end their subtree, a toggle's two
branches are one, a redundant link drops the walks that break it, the sketch's assembly marked."""

from __future__ import annotations

import math
from pathlib import Path

from linkgen.assemblies import whole_log
from linkgen.assemblies.enumerate import census, distance

ROOT = Path(__file__).resolve().parents[2]


def _closes(d, r1, r2):
    return abs(r1 - r2) < d < r1 + r2


def test_jansen_at_half_a_turn_loses_the_walks_whose_last_chain_cannot_close():
    """F is joined to D by rod_f and to E by the leg: of the four (D, E) from the branches of C and E,
    exactly those whose distance the two links cannot span have no assembly (checked by hand)."""
    log = whole_log(str(ROOT / "samples" / "jansen" / "jansen.yaml"))
    c = census(log, [math.pi])
    lengths = {(a, b): length for lk in log.links for a, b, length in lk.lengths}
    rod_f, leg = lengths["D", "F"], lengths["E", "F"]
    ds = {a.choices[0].value: (a.values["D.x"], a.values["D.y"]) for a in c.assemblies}
    es = {a.choices[1].value: (a.values["E.x"], a.values["E.y"]) for a in c.assemblies}
    assert len(ds) == len(es) == 2  # both branches of C and of E occur
    closing = [(bc, be) for bc in ds for be in es if _closes(math.dist(ds[bc], es[be]), rod_f, leg)]
    assert len(c.assemblies) == 2 * len(closing) == 6
    assert c.cannot_close == {6: 2 * (4 - len(closing))}  # F is step 6
    assert sorted({(a.choices[0].value, a.choices[1].value) for a in c.assemblies}) == sorted(closing)
    assert [a.number for a in c.assemblies] == list(range(1, 7))


def test_at_its_limit_position_a_chain_has_one_assembly_a_toggle():
    """fourbar_partial: bisected in doubles to the last input where its chain closes, the chain is at
    its toggle there (both branches one assembly), and cannot close one double further."""
    log = whole_log(str(ROOT / "tests" / "mechanisms" / "fourbar_partial.yaml"))
    lo, hi = 0.0, math.pi / 2
    assert len(census(log, [lo]).assemblies) == 2 and not census(log, [hi]).assemblies
    while (mid := (lo + hi) / 2) not in (lo, hi):
        lo, hi = (mid, hi) if census(log, [mid]).assemblies else (lo, mid)
    at = census(log, [lo])
    assert len(at.assemblies) == 1 and at.toggles == [3] and at.assemblies[0].choices[0].of == 1
    past = census(log, [hi])
    assert not past.assemblies and past.cannot_close == {3: 2}
    # the programs (the numpy kernel: its cosines round otherwise) may close a few doubles further
    assert "does not reach this input" in census(log, [hi + 1e-9]).sketch_note


def test_walks_that_break_a_redundant_link_are_dropped():
    """Two parallelograms on one coupler: the crossed branch of the first breaks the second rocker."""
    log = whole_log(str(ROOT / "tests" / "assemblies" / "double_parallelogram.yaml"))
    c = census(log, [math.radians(60)])
    assert len(c.assemblies) == 1 and c.assemblies[0].sketch
    ((link, error),) = c.broken
    assert link == "rocker2" and error > 0.1
    a = c.assemblies[0].values
    assert math.dist((a["A.x"], a["A.y"]), (a["B.x"], a["B.y"])) == math.dist((20, 20), (80, 20))
    assert abs((a["B.x"] - a["A.x"]) - 60) < 1e-12  # a parallelogram stays one


def test_fig14s_sketch_is_the_root_where_the_ternary_has_not_turned():
    log = whole_log(str(ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"))
    c = census(log, [log.inputs[0].sketch])
    (marked,) = [a for a in c.assemblies if a.sketch]
    (choice,) = marked.choices
    assert choice.target == "group 1" and choice.theta == 0.0 and choice.of == 4
    assert all(a.error < 1e-15 for a in c.assemblies)
    (solve,) = c.solves
    assert solve.thetas == tuple(a.choices[0].theta for a in c.assemblies)


def test_distance_wraps_angles_and_scales_lengths():
    log = whole_log(str(ROOT / "samples" / "fourbar" / "fourbar.yaml"))
    base = census(log, [0.3]).assemblies[0].values
    turned = {**base, "rocker.phi": base["rocker.phi"] + 2 * math.pi}
    assert distance(log, base, turned) < 1e-15
    moved = {**base, "B.x": base["B.x"] + log.length_scale * 1e-3}
    assert abs(distance(log, base, moved) - 1e-3) < 1e-12
