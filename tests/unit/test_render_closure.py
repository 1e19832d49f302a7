"""render.closure: a group's closure equations as rows (residual terms, nonzero Jacobian entries) and
their values in-process, on a small hand-made closure (two positions, one length, one frame) and on
the Fig. 14 six-bar's."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from linkgen.pipeline import build_log
from linkgen.render.closure import in_process, rows, values
from linkgen.steplog import Closure, Distance, Frame

ROOT = Path(__file__).resolve().parents[2]
FIG14 = str(ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml")
# B 5 from the known A and D (a 3R chain); C fixed to the link A-B: C = B + w (B - A), w = i / 2
SMALL = Closure(("b", "c"), (Distance(("a", "b"), 5.0, 1, "l"), Distance(("d", "b"), 5.0, 1, "m")),
                (Frame("c", "b", ("a", "b"), (0.0, 0.5), 2, "l"),))
KNOWN = {"a": (1.0, 2.0), "d": (7.0, 2.0)}


def _known(name: str, i: int) -> float:
    return KNOWN[name][i]


def test_rows_of_a_length_and_a_frame():
    d, _, fx, fy = rows(SMALL)
    assert (d.kind, d.index, [(c.var, c.axis, c.unknown) for c in d.coords]) == (
        "distance", 0, [("a", "x", -1), ("a", "y", -1), ("b", "x", 0), ("b", "y", 1)])
    assert (d.constants, d.variable) == ((5.0,), "")
    assert [(e.column, e.factor, e.term) for e in d.entries] == [(0, 1.0, "dx"), (1, 1.0, "dy")]  # A is known
    # x: c.x - b.x - (0 (b.x - a.x) - 0.5 (b.y - a.y)); the origin b is also the base's end: -1 - 0 at b.x
    assert (fx.index, fx.constants) == (2, (0.0, -0.5))
    assert [(e.column, e.factor) for e in fx.entries] == [(0, -1.0), (1, 0.5), (2, 1.0)]
    assert (fy.index, fy.constants) == (3, (0.5, 0.0))
    assert [(e.column, e.factor) for e in fy.entries] == [(0, -0.5), (1, -1.0), (3, 1.0)]


def test_values_by_hand_and_the_jacobian_by_central_differences():
    x = [4.0, 6.0, 2.0, 7.5]  # B = A + (3, 4) = D + (-3, 4); C = B + i (3, 4) / 2 = B + (-2, 1.5)
    g, jac = values(rows(SMALL), x, _known)
    assert g == [0.0, 0.0, 0.0, 0.0]
    x = [4.5, 5.0, 1.0, 9.0]  # B - A = (3.5, 3), B - D = (-2.5, 3)
    g, jac = values(rows(SMALL), x, _known)
    assert g == pytest.approx([(3.5 ** 2 + 3 ** 2 - 25) / 10, (2.5 ** 2 + 3 ** 2 - 25) / 10, 1.0 - 4.5 + 0.5 * 3,
                               9.0 - 5.0 - 0.5 * 3.5], abs=1e-15)
    h = 1e-6
    for j in range(4):
        up, down = list(x), list(x)
        up[j] += h
        down[j] -= h
        column = [(a - b) / (2 * h) for a, b in zip(values(rows(SMALL), up, _known)[0],
                                                       values(rows(SMALL), down, _known)[0])]
        assert [r[j] for r in jac] == pytest.approx(column, abs=1e-8)


def test_in_process_reads_the_records_and_adopts_a_solution():
    records = {"a": (1.0, 2.0, 0.0, 0.0), "d": (7.0, 2.0, 0.0, 0.0), "b": (4.0, 6.0, 7.0, 8.0),
               "c": (0.0, 0.0, 0.0, 0.0)}
    adopted = []
    c = in_process(SMALL, records, adopted.append)
    assert c.place() == [4.0, 6.0, 0.0, 0.0]
    assert c.equations([4.0, 6.0, 2.0, 7.5])[0] == [0.0, 0.0, 0.0, 0.0]  # D is read from the records too

    states = [[1.0]]
    c.adopt([4.0, 6.0, 2.0, 7.5], states)
    assert records["b"] == (4.0, 6.0, 7.0, 8.0) and records["c"] == (2.0, 7.5, 0.0, 0.0) and adopted == [states]


def test_fig14_rows_vanish_at_the_sketch():
    log = build_log(FIG14, options={"strategy": "closure"}, sweep=False)
    (group,) = log.groups
    assert group.closure is not None
    sketch = {v.name: v.sketch for v in log.variables if v.kind == "POINT"}
    x = [sketch[u][i] for u in group.closure.unknowns for i in (0, 1)]
    g, jac = values(rows(group.closure), x, lambda name, i: sketch[name][i])
    assert max(abs(v) for v in g) <= 8 * math.ulp(log.length_scale)
    assert len(jac) == 6 and all(len(r) == 6 for r in jac)


def test_a_length_that_changes_with_the_inputs_is_read_from_its_record():
    """The small closure with A-B an actuator's length (the record s, 5 in the sketch) set to 6: B at
    (4, 6) is then 1 short, its row (25 - 36) / 12."""
    closure = Closure(("b", "c"), (Distance(("a", "b"), 5.0, 1, "l", "s"), *SMALL.distances[1:]), SMALL.frames)
    assert rows(closure)[0].variable == "s"
    known = {**KNOWN, "s": (6.0, 0.0, 0.0)}
    g, jac = values(rows(closure), [4.0, 6.0, 2.0, 7.5], lambda name, i: known[name][i])
    assert g == [(25 - 36) / 12, 0.0, 0.0, 0.0]
    assert jac[0] == [3 / 6, 4 / 6, 0.0, 0.0]
