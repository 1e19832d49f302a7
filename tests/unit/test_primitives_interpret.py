"""primitives.interpret: steps run on scalar records, checked against the four-bar's closed form."""

from __future__ import annotations

import math
from pathlib import Path

from linkgen.extraction import extract
from linkgen.primitives.interpret import constant_record, run_steps
from linkgen.topology import analyse
from linkgen.validate import read_mechanism

ROOT = Path(__file__).resolve().parents[2]


def test_fourbar_positions_close_every_link():
    topo = analyse(read_mechanism(str(ROOT / "samples" / "fourbar" / "fourbar.yaml")))
    proc = extract(topo)
    ox, oy = topo.origin
    env = {v.name: constant_record(v, 0, topo.origin) for v in proc.variables if v.constant}
    theta = math.radians(37.0)
    env["in1"] = (theta,)
    assert run_steps(proc.steps, env, 0)
    a, b = env[proc.positions["A"]], env[proc.positions["B"]]
    # the crank O1 (0, 0) - A is 20 long at theta; the coupler A-B 78.1..., the rocker O2 (90, 0) - B 50.99...
    assert math.isclose(a[0] + ox, 20 * math.cos(theta), rel_tol=1e-14)
    assert math.isclose(a[1] + oy, 20 * math.sin(theta), rel_tol=1e-14)
    assert math.isclose(math.hypot(b[0] - a[0], b[1] - a[1]), math.hypot(60, 50), rel_tol=1e-14)
    assert math.isclose(math.hypot(b[0] + ox - 90, b[1] + oy), math.hypot(10, 50), rel_tol=1e-14)


def test_a_chain_that_cannot_close_stops_the_run():
    topo = analyse(read_mechanism(str(ROOT / "tests" / "mechanisms" / "fourbar_partial.yaml")))
    proc = extract(topo)
    env = {v.name: constant_record(v, 0, topo.origin) for v in proc.variables if v.constant}
    closes = []
    for deg in range(0, 360, 5):
        env["in1"] = (math.radians(deg),)
        closes.append(run_steps(proc.steps, dict(env), 0))
    assert any(closes) and not all(closes)


def test_constant_records_have_zero_rates():
    topo = analyse(read_mechanism(str(ROOT / "samples" / "fourbar" / "fourbar.yaml")))
    proc = extract(topo)
    point = next(v for v in proc.variables if v.constant and v.kind == "POINT")
    rec = constant_record(point, 2, topo.origin)
    assert rec[2:] == (0.0, 0.0, 0.0, 0.0)
    assert (rec[0] + topo.origin[0], rec[1] + topo.origin[1]) == point.value
