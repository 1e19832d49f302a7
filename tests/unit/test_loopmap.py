"""loopmap: the loop's map and its fixed points on a triad built by hand (a ternary link whose drawn pose is
one fixed point), and the listing's words."""

from __future__ import annotations

import math
from pathlib import Path

from linkgen import loopmap
from linkgen.pipeline import build_log

FIG14 = Path(__file__).resolve().parents[2] / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"


def _triad() -> loopmap.Loop:
    """An equilateral body X1 (0, 1), X2 (1, 1), X3 (0.5, 1 + sqrt 3 / 2) on legs from K1 (0, 0), K2 (1, 0),
    K3 = X3 + (1, 0), each leg 1 long (leg 3 across the others: no singular position)."""
    h = math.sqrt(3) / 2
    return loopmap.Loop(1, ("X1", "X2", "X3"), ((0.0, 0.0), (1.0, 0.0), (1.5, 1 + h)), (1.0, 1.0, 1.0),
                        (1.0, 1.0, 1.0), 1)


def test_the_drawn_pose_comes_back_to_itself_and_is_a_fixed_point():
    loop = _triad()
    # X3 lies left of X1 -> K3 (K3 - X1 = (1.5, h), X3 - X1 = (0.5, h): 1.5 h - 0.5 h > 0), X2 left of X3 -> K2
    # ((0.5, -1 - h) x (0.5, -h) = -h / 2 + (1 + h) / 2 > 0), X1 right of X2 -> K1 ((-1, -1) x (-1, 0) = -1)
    back, pairs = loop.around(math.pi / 2, (1, 1, -1))
    assert abs(back - math.pi / 2) < 1e-15
    assert math.dist(pairs["X2"], (1.0, 1.0)) < 1e-15 and math.dist(pairs["X3"], (0.5, 1 + math.sqrt(3) / 2)) < 1e-15
    found = [p for p in loopmap.fixed_points(loop) if math.dist(p.pairs["X1"], (0.0, 1.0)) < 1e-12]
    assert [p.branches for p in found] == [(1, 1, -1)]


def test_every_fixed_point_closes_the_six_lengths_and_keeps_the_bodys_side():
    loop = _triad()
    for p in loopmap.fixed_points(loop):
        x1, x2, x3 = (p.pairs[n] for n in ("X1", "X2", "X3"))
        for (a, b), want in (((x1, loop.ks[0]), 1), ((x2, loop.ks[1]), 1), ((x3, loop.ks[2]), 1), ((x1, x2), 1),
                             ((x1, x3), 1), ((x2, x3), 1)):
            assert abs(math.dist(a, b) - want) < 1e-9
        assert (x2[0] - x1[0]) * (x3[1] - x1[1]) - (x2[1] - x1[1]) * (x3[0] - x1[0]) > 0
        assert math.isfinite(p.slope)


def test_the_listing_names_the_loop_and_which_way_contracts():
    log = build_log(str(FIG14), order=0, sweep=False, options={"strategy": "loop"})
    text = loopmap.text(log, [math.pi / 2])
    assert text.startswith("group 1: the forward loop assumes the angle of the leg at J2 and places J5, J4, then J2")
    assert "4 fixed points" in text and "theta 90 deg, |g'| 0.4893 (forward loop contracts)" in text


def test_the_slopes_at_the_sketch_are_the_sketch_fixed_points_and_reciprocal_for_the_reverse_loop():
    log = build_log(str(FIG14), order=0, sweep=False, options={"strategy": "loop"})
    slopes = loopmap.sketch_slopes(log)
    forward, reverse = (b.variant for b in log.groups[0].variants[-2:])
    (loop,) = loopmap.loops(log, [math.pi / 2])  # the crank as drawn: the known pairs from the procedure
    (drawn,) = [p for p in loopmap.fixed_points(loop) if math.dist(p.pairs["J2"], (0.0, 70.0)) < 1e-9]
    assert abs(slopes[forward] - abs(drawn.slope)) < 1e-6 and abs(slopes[forward] * slopes[reverse] - 1) < 1e-15
