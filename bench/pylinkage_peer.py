"""pylinkage on a sample, as a peer: run as its own process, with or without numba.

    python bench/pylinkage_peer.py samples/fourbar/fourbar.yaml [--no-numba]

Builds the mechanism from the file's sketch (a crank, RRR dyads, fixed dyads for the points on
ternary links) with its joints at their sketch places, turns the crank to the range's start in
LEAD_IN steps, so that each dyad follows the sketch's assembly (pylinkage takes the intersection
nearest the joint's last place), and sweeps the file's range in its rows.  Prints JSON: numba in
use, seconds per configuration of ``step_fast`` (positions) and ``step_fast_with_kinematics``
(with velocities and accelerations; the median of RUNS sweeps after one), and the first sweep's
rows (the input's value: the crank's angle, which turns relative to the fixed link, from the x
axis; then every pair's and point's position, velocity and acceleration by the format's column
names).  Only mechanisms made of dyads: pylinkage has no class-III group (the Fig. 14 six-bar's
triad).
"""

from __future__ import annotations

import json
import math
import statistics
import sys
import time

if "--no-numba" in sys.argv:
    sys.modules["numba"] = None  # type: ignore[assignment]  (pylinkage then runs its Python code)

from pathlib import Path  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from linkgen.validate import read_mechanism  # noqa: E402

RUNS = 5
LEAD_IN = 36  # crank steps from the sketch to the range's start (the dyads follow the nearest solution)
# Each sample's construction: (kind, joint, anchor1, anchor2): a crank's pin about its pivot, an
# RRR dyad's middle pair from its two ends, a fixed dyad's point from two pairs of its link.
MODELS = {
    "fourbar": [("crank", "A", "O1", ""), ("rrr", "B", "A", "O2"), ("fixed", "P", "A", "B")],
    "jansen": [("crank", "A", "O", ""), ("rrr", "C", "A", "B"), ("rrr", "E", "A", "B"), ("fixed", "D", "B", "C"),
               ("rrr", "F", "D", "E"), ("fixed", "foot", "E", "F")],
}


def build(path: str):
    """The pylinkage Linkage of the sample, its components' names and the mechanism."""
    from pylinkage.actuators import Crank
    from pylinkage.components import Ground
    from pylinkage.dyads import FixedDyad, RRRDyad
    from pylinkage.simulation import Linkage

    m = read_mechanism(path)
    at = {j.name: (j.x, j.y) for j in m.joints} | {p.name: (p.x, p.y) for p in m.points}
    fixed = next(lk for lk in m.links if lk.fixed)
    parts = {name: Ground(*at[name], name=name) for name in fixed.joints}
    inp = m.inputs[0]
    step = (inp.stop - inp.start) / (m.samples - 1)
    crank = None
    for kind, name, a, b in MODELS[m.name]:
        (x, y), (ax, ay) = at[name], at[a]
        if kind == "crank":
            # the input's value is the crank's angle (from the x axis: it turns relative to the fixed link)
            sketch = math.atan2(y - ay, x - ax)
            start = inp.start - step  # step_fast moves the crank before each row
            lead = math.remainder(start - sketch, 2 * math.pi) / LEAD_IN
            crank = Crank(parts[a], math.hypot(x - ax, y - ay), angular_velocity=lead, initial_angle=sketch, name=name)
            parts[name] = crank
            continue
        anchor1 = parts[a].output if parts[a] is crank else parts[a]
        anchor2 = parts[b].output if parts[b] is crank else parts[b]
        bx, by = at[b]
        if kind == "rrr":
            parts[name] = RRRDyad(anchor1, anchor2, math.hypot(x - ax, y - ay), math.hypot(x - bx, y - by), x=x, y=y,
                                  name=name)
        else:
            angle = math.atan2(y - ay, x - ax) - math.atan2(by - ay, bx - ax)
            parts[name] = FixedDyad(anchor1, anchor2, math.hypot(x - ax, y - ay), angle, name=name)
    linkage = Linkage(list(parts.values()), name=m.name)
    for _ in linkage.step(iterations=LEAD_IN):  # from the sketch to the range's start, on the sketch's assembly
        pass
    crank.angular_velocity = step
    linkage.set_input_velocity(crank, omega=inp.speed)
    return linkage, list(parts), m


def main() -> None:
    from pylinkage._numba_compat import HAS_NUMBA

    linkage, names, m = build(sys.argv[1])
    pos, vel, acc = linkage.step_fast_with_kinematics(iterations=m.samples)
    pivot = names.index(MODELS[m.name][0][2])
    pin = names.index(MODELS[m.name][0][1])
    rows = []
    for p, v, a in zip(pos, vel, acc):
        theta = math.atan2(p[pin][1] - p[pivot][1], p[pin][0] - p[pivot][0])
        row = {"theta": theta}
        for k, name in enumerate(names):
            for key, rec in (("x", p), ("vx", v), ("ax", a)):
                row[f"{name}.{key}"], row[f"{name}.{key[:-1]}y"] = float(rec[k][0]), float(rec[k][1])
        rows.append(row)
    times = {}
    for label, call in (("positions", linkage.step_fast), ("full", linkage.step_fast_with_kinematics)):
        call(iterations=m.samples)
        sweeps = []
        for _ in range(RUNS):
            t = time.perf_counter()
            call(iterations=m.samples)
            sweeps.append((time.perf_counter() - t) / m.samples)
        times[label] = statistics.median(sweeps)
    print(json.dumps({"numba": HAS_NUMBA, "times": times, "rows": rows}))


if __name__ == "__main__":
    main()
