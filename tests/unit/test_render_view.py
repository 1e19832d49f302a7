"""render.view: the blocks a program is made of, read off small step logs whose procedures are known
(tests/unit/test_extraction_placement.py and the samples' manuals list them)."""

from __future__ import annotations

from pathlib import Path

import pytest

from linkgen.pipeline import build_log
from linkgen.render.view import View, build_view

ROOT = Path(__file__).resolve().parents[2]
FOURBAR = str(ROOT / "samples" / "fourbar" / "fourbar.yaml")
FIG14 = str(ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml")


def _view(path: str, order: int | None = None) -> View:
    return build_view(build_log(path, order=order, sweep=False))


def test_fourbar_constants_records_and_status_steps():
    v = _view(FOURBAR)
    # steps: 1 frame, 2 crank_input, 3 RRR_links (B), 4 pair_point P, 5 crank_angle crank (the input's: no
    # status), 6-7 link_angle coupler and rocker.  The frame's angle is a constant no step reads: the program
    # leaves it out.
    assert [c.name for c in v.constants] == ["p_O1", "p_O2", "ref_O1", "l_coupler", "l_rocker"]
    assert [r.name for r in v.records] == ["in1", "p_A", "p_B", "p_P", "phi_crank", "phi_coupler", "phi_rocker"]
    assert v.sigma_steps == (3, 4, 6, 7)  # the chain, pair_point (P) and the link angles report a status
    assert [s.number for s in v.run] == [1, 2, 3, 4, 5, 6, 7] and v.last_step == 7
    assert v.groups == v.blocks == () and v.nmax == 1


def test_outputs_group_the_columns_of_each_pair_point_and_link():
    v = _view(str(ROOT / "tests" / "mechanisms" / "slider_crank.yaml"))
    kinds = {o.name: (o.kind, [f for f, _, _ in o.fields]) for o in v.outputs}
    assert kinds["A"] == ("point", ["x", "y", "vx", "vy", "ax", "ay"])
    assert kinds["S"] == ("prismatic", ["x", "y", "vx", "vy", "ax", "ay", "s", "ds", "dds"])  # with its slide
    assert kinds["rod"] == ("angle", ["phi", "omega", "alpha"])
    assert [(c.owner, c.field) for c in v.cells][:2] == [("O", "x"), ("O", "y")]
    assert len(v.cells) == sum(len(o.columns) for o in v.outputs)


def test_a_resolver_group_is_its_chosen_block_then_its_fallbacks():
    log = build_log(FIG14, sweep=False)
    v = build_view(log)
    (group,) = log.groups
    assert len(v.blocks) == 1 + len(group.variants) and v.groups == v.blocks[:1]
    assert [b.suffix for b in v.blocks] == ["1"] + [f"1_v{k}" for k in range(1, len(group.variants) + 1)]
    assert [b.index for b in v.blocks] == list(range(len(v.blocks)))
    assert all((b.slot, b.first, b.count) == (0, 0, len(v.blocks)) for b in v.blocks)
    assert v.blocks_of(v.groups[0]) == v.blocks and v.resolver(group.step) is v.groups[0]
    # group 1 iterates steps 4-7 (3 installs its Add-link, 8 resolves it, 9-13 are link angles, fallbacks
    # from 14 on): the run is the steps outside its block, the resolve step standing for the block
    assert group.steps == (4, 5, 6, 7) and group.step == 8
    assert [s.number for s in v.run] == [1, 2, 3, 8, 9, 10, 11, 12, 13]
    # the largest block state: one Add-link length, the branches of its two 3R chains, an orientation
    assert len(group.add_links) == 1 and len(group.branches) == 2 and v.nmax == 4


@pytest.mark.parametrize("path, order, record_order", [(FOURBAR, 0, 0), (FIG14, 0, 1), (FIG14, 2, 2)])
def test_a_resolver_needs_velocities_for_its_jacobian(path: str, order: int, record_order: int):
    assert _view(path, order).record_order == record_order


def test_a_links_direction_is_an_output_of_its_own_kind():
    """angles: unit: a link's columns read a direction record (a POINT record of role direction)."""
    v = build_view(build_log(FOURBAR, sweep=False, options={"angles": "unit"}))
    kinds = {o.name: (o.kind, [f for f, _, _ in o.fields]) for o in v.outputs}
    assert kinds["rocker"] == ("direction", ["ux", "uy", "dux", "duy", "ddux", "dduy"])
    assert kinds["P"][0] == "point"


def test_only_a_fixed_point_resolver_adds_its_failure():
    assert _view(FOURBAR).failures == _view(FIG14).failures == (1, 2)
    assert build_view(build_log(FIG14, sweep=False, options={"strategy": "fixed-point"})).failures == (1, 2, 6)
    assert build_view(build_log(FOURBAR, sweep=False, options={"strategy": "fixed-point"})).failures == (1, 2)


def test_the_closure_strategy_gives_each_group_its_rows():
    v = build_view(build_log(FIG14, sweep=False, options={"strategy": "closure"}))
    (g,) = v.groups
    assert v.closure and not _view(FIG14).closure
    p = v.closure_plan(g)  # four lengths on J4 and J2, J5 derived from them (fixed to the ternary)
    assert len(p.rows) == 4 == 2 * len(p.unknowns) == v.nmax
