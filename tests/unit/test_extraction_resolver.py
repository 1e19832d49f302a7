"""extraction.resolver: residual bookkeeping, hoisting, levers and branch signs."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from linkgen.extraction import extract
from linkgen.extraction.resolver import close_group, placement_lever
from linkgen.extraction.solver import start
from linkgen.extraction.state import GroupDraft, Unsupported
from linkgen.steplog import Arg, Step, Variable
from linkgen.topology import analyse
from linkgen.validate import read_mechanism

ROOT = Path(__file__).resolve().parents[2]
FIG14 = ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"


def _step(number: int, function: str, args: tuple[Arg, ...], outputs: tuple[str, ...]) -> Step:
    return Step(number, "point", function, args, outputs, "", "", (), (), 0, "", "", (), 0, False)


def test_lever_is_the_base_over_the_arm_of_the_worst_placement():
    """A link angle measured on a base 2 long places a point 8 away: lever 2 / 8."""
    variables = {"a": Variable("a", "POINT", "pair", "a", (0.0, 0.0), (0.0, 0.0)),
                 "b": Variable("b", "POINT", "pair", "b", (), (2.0, 0.0)),
                 "phi": Variable("phi", "ANGLE", "link", "l", (), (0.0,))}
    angle = _step(1, "link_angle", (Arg("var", "a"), Arg("var", "b"), Arg("real", value=0.0)), ("phi",))
    near = _step(2, "coupler_point", (Arg("var", "a"), Arg("var", "phi"), Arg("real", value=1.0),
                                      Arg("real", value=1.0)), ("p",))
    far = _step(3, "coupler_point", (Arg("var", "a"), Arg("var", "phi"), Arg("real", value=6.4),
                                     Arg("real", value=4.8)), ("q",))
    steps = [angle, near, far]
    assert placement_lever([near], steps, variables) == 1.0  # the arm sqrt(2) is shorter than the base
    assert placement_lever([near, far], steps, variables) == pytest.approx(2 / math.hypot(6.4, 4.8), rel=1e-15)


def test_a_group_with_more_residuals_than_add_links_is_refused():
    ws = start(analyse(read_mechanism(str(FIG14))))
    ws.groups.append(GroupDraft(1, ("add1",), ("f1", "f2")))
    ws.group = 1
    with pytest.raises(Unsupported, match="more unused links than Add-links"):
        close_group(ws)


def test_fig14_blocks_read_their_branches_off_the_solution():
    proc = extract(analyse(read_mechanism(str(FIG14))))
    (group,) = proc.groups
    steps = {s.number: s for s in proc.steps}
    for block in (group, *group.variants):
        assert block.lever == 1.0
        for sign in block.branches:
            chain = steps[sign.step]
            assert chain.function == "RRR_links" and sign.kind == "side" and sign.sketch == chain.branch
            assert sign.points == (chain.args[0].var, chain.args[1].var, chain.outputs[0])
    # the crank is hoisted out of the group: it does not depend on the Add-link
    assert all(steps[n].target != "J6" for n in group.steps)
    assert steps[group.step].action == "resolve" and max(group.steps) < group.step
