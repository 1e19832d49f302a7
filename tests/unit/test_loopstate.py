"""loopstate: the loop blocks of a step log and a loop's arc length read off a configuration (by hand)."""

from __future__ import annotations

import math
from pathlib import Path

from linkgen.loopstate import arc_state, loop_flags
from linkgen.pipeline import build_log
from linkgen.rowsolver import _scalar_call

FIG14 = Path(__file__).resolve().parents[2] / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"


def test_only_the_loop_strategy_has_loop_blocks_the_last_two_of_the_group():
    newton = build_log(str(FIG14), sweep=False)
    looped = build_log(str(FIG14), options={"strategy": "loop"}, sweep=False)
    assert set(loop_flags(newton)) == {0}
    assert loop_flags(looped) == (0,) * (1 + len(newton.groups[0].variants)) + (1, 1)


def test_the_arc_length_is_unwrapped_from_the_last_rows():
    call = _scalar_call(1)
    k, arm = (0.0, 0.0, 0.0, 0.0), (2.0, 0.0)
    x = (-2.0, -1e-9, 0.0, 2.0)  # just past -pi, turning at omega = -1 (v = (0, 2) at angle -pi: x' = -omega r sin)
    s, ds = arc_state(call, k, x, arm, 2 * 3.1, 1)  # the last row's arc at 3.1 rad: the angle past pi, not -pi
    assert math.isclose(s, 2 * (2 * math.pi + math.atan2(-1e-9, -2.0)), rel_tol=1e-15)
    assert math.isclose(ds, 2 * (-2.0 * 2.0) / 4.0, rel_tol=1e-15)
