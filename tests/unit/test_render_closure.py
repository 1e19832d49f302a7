"""render.closure: a group's closure equations as the programs compute them (the unknowns placed by
chains, the points fixed in a frame derived from them, the distance rows with their Jacobian entries)
and their values in-process, on a small hand-made closure and on the Fig. 14 six-bar's."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from linkgen.closurelog import Closure, Distance, Frame
from linkgen.pipeline import build_log
from linkgen.render.closure import End, derived, in_process, plan, values

ROOT = Path(__file__).resolve().parents[2]
FIG14 = str(ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml")
# B 5 from the known A and D (a 3R chain); C fixed to the link A-B: C = B + w (B - A) with w = i / 2; E 5
# from C and from the known F (another chain, on the derived C): unknowns B and E, C derived.
SMALL = Closure(("b", "c", "e"), (Distance(("a", "b"), 5.0, 1, "l"), Distance(("d", "b"), 5.0, 1, "m"),
                                  Distance(("c", "e"), 5.0, 3, "n"), Distance(("f", "e"), 5.0, 3, "o")),
                (Frame("c", "b", ("a", "b"), (0.0, 0.5), 2, "l"),))
KNOWN = {"a": (1.0, 2.0), "d": (7.0, 2.0), "f": (5.0, 7.5)}


def _known(name: str, i: int) -> float:
    return KNOWN[name][i]


def test_a_point_fixed_in_a_frame_is_derived_from_the_unknowns():
    p = plan(SMALL)
    assert p.unknowns == ("b", "e")
    (c,) = p.derived
    # C = B + (i/2)(B - A) = (1 + i/2) B - (i/2) A: B an unknown, A known
    assert [(t.end, t.w) for t in c.terms] == [(End("b", 0, -1), (1.0, 0.5)), (End("a"), (-0.0, -0.5))]
    rows = p.rows
    assert [r.ends for r in rows] == [(End("a"), End("b", 0)), (End("d"), End("b", 0)),
                                      (End("c", -1, 0), End("e", 1)), (End("f"), End("e", 1))]
    assert [(e.column, e.fx, e.fy) for e in rows[0].entries] == [(0, 1.0, 0.0), (1, 0.0, 1.0)]  # A is known
    # E - C: +1 on E's coordinates; -(1 + i/2) on B's: d(dx + i dy)/dBx = -(1 + i/2), /dBy = -i (1 + i/2)
    assert [(e.column, e.fx, e.fy) for e in rows[2].entries] == [(0, -1.0, -0.5), (1, 0.5, -1.0), (2, 1.0, 0.0),
                                                                 (3, 0.0, 1.0)]


def test_values_by_hand_and_the_jacobian_by_central_differences():
    p = plan(SMALL)
    e = (2.0 + 0.0, 7.5 + 5.0)  # E 5 above C; F = (5, 7.5) is (3, -5) from E: not 5, so row 3 is off
    x = [4.0, 6.0, *e]
    g, _ = values(p, x, _known)
    assert g[:3] == [0.0, 0.0, 0.0]
    assert g[3] == pytest.approx((3 ** 2 + 5 ** 2 - 25) / 10, abs=1e-15)
    x = [4.5, 5.0, 1.0, 9.0]
    g, jac = values(p, x, _known)
    h = 1e-6
    for j in range(4):
        up, down = list(x), list(x)
        up[j] += h
        down[j] -= h
        column = [(a - b) / (2 * h) for a, b in zip(values(p, up, _known)[0], values(p, down, _known)[0])]
        assert [r[j] for r in jac] == pytest.approx(column, abs=1e-8)


def test_in_process_reads_the_records_and_adopts_a_solution():
    records = {**{k: (*v, 0.0, 0.0) for k, v in KNOWN.items()}, "b": (4.0, 6.0, 7.0, 8.0), "c": (0.0, 0.0, 0.0, 0.0),
               "e": (0.0, 0.0, 0.0, 0.0)}
    adopted = []
    c = in_process(SMALL, records, adopted.append)
    assert c.place() == [4.0, 6.0, 0.0, 0.0]
    states = [[1.0]]
    c.adopt([4.0, 6.0, 2.0, 12.5], states)
    assert records["b"] == (4.0, 6.0, 7.0, 8.0) and records["c"] == (2.0, 7.5, 0.0, 0.0)  # the rates kept
    assert records["e"] == (2.0, 12.5, 0.0, 0.0) and adopted == [states]


def test_a_length_that_changes_with_the_inputs_is_read_from_its_record():
    """The first length an actuator's (the record s, 5 in the sketch) set to 6: B at (4, 6) is then 1 short,
    its row (25 - 36) / 12."""
    closure = Closure(SMALL.unknowns, (Distance(("a", "b"), 5.0, 1, "l", "s"), *SMALL.distances[1:]), SMALL.frames)
    p = plan(closure)
    assert p.rows[0].variable == "s"
    known = {**KNOWN, "s": (6.0, 0.0, 0.0)}
    g, jac = values(p, [4.0, 6.0, 2.0, 12.5], lambda name, i: known[name][i])
    assert g[0] == (25 - 36) / 12 and g[1:3] == [0.0, 0.0]
    assert jac[0] == [3 / 6, 4 / 6, 0.0, 0.0]


def test_fig14_rows_vanish_at_the_sketch():
    log = build_log(FIG14, options={"strategy": "closure"}, sweep=False)
    (group,) = log.groups
    assert group.closure is not None
    p = plan(group.closure)
    assert p.unknowns == ("p_J4", "p_J2") and [d.var for d in p.derived] == ["p_J5"] and len(p.rows) == 4
    sketch = {v.name: v.sketch for v in log.variables if v.kind == "POINT"}
    x = [sketch[u][i] for u in p.unknowns for i in (0, 1)]
    g, jac = values(p, x, lambda name, i: sketch[name][i])
    assert max(abs(v) for v in g) <= 8 * math.ulp(log.length_scale)
    assert len(jac) == 4 and all(len(r) == 4 for r in jac)
    # J5, placed by link_point on J4 and J2, is derived from them at its sketch place
    ((x5, y5),) = derived(p, x, lambda name, i: sketch[name][i])
    assert (x5, y5) == pytest.approx(sketch["p_J5"][:2], abs=8 * math.ulp(log.length_scale))
