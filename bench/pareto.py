"""The Pareto plot: time per configuration against the worst error of the pairs' and points' positions
(which every peer computes), log-log, for the mechanisms
the peers run on: one mark per knob setting (linkgen's C program), per linkgen language at the
default setting, and per peer, each labelled.

    python bench/run.py pareto     # after knobs and peers (it reads bench/out/knobs.json, peers.json)

Writes docs/performance-pareto.svg (bench/svg.py: the same numbers give the same bytes).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import svg

ROOT = Path(__file__).resolve().parents[1]
KNOBS = ROOT / "bench" / "out" / "knobs.json"
PEERS = ROOT / "bench" / "out" / "peers.json"
PLOT = ROOT / "docs" / "performance-pareto.svg"
FLOOR = 1e-17  # an error of 0 is drawn here


def _fine(*values: float) -> bool:
    return all(isinstance(v, float) and math.isfinite(v) and v > 0 for v in values)


def marks(sample: str, knobs: dict, peers: dict) -> list[tuple[str, str, str, float, float]]:
    """(label, colour, shape, seconds, error) of the sample's settings and peers."""
    out = []
    for m in knobs.get(sample, []):
        e = (m["errors"].get("C") or {}).get("points", math.nan)
        if "C" in m["same"] or m["label"].startswith("most accurate"):
            continue  # the default's program, or a setting measured above: its mark is there
        if _fine(m["c"]) and isinstance(e, float) and math.isfinite(e):
            out.append((f"C {m['label']}", svg.COLOURS[0], "circle", m["c"], max(e, FLOOR)))
    for k, p in enumerate(peers.get(sample, [])):
        if p["program"].startswith("linkgen C"):
            continue  # the knobs' default
        if _fine(p["full"]) and isinstance(p["position_error"], float) and math.isfinite(p["position_error"]):
            linkgen = p["program"].startswith("linkgen")
            colour = svg.COLOURS[0] if linkgen else svg.COLOURS[1 + k % (len(svg.COLOURS) - 1)]
            out.append((p["program"], colour, "triangle" if linkgen else "square", p["full"],
                        max(p["position_error"], FLOOR)))
    return out


def merged(points: list[tuple[str, str, str, float, float]]) -> list[tuple[str, str, str, float, float]]:
    """Marks at the same place (the same program measured under two names) as one, their labels joined."""
    out: dict[tuple[float, float], tuple[str, str, str, float, float]] = {}
    for label, colour, shape, x, y in points:
        if (x, y) in out:
            old = out[(x, y)]
            out[(x, y)] = (f"{old[0]} = {label.removeprefix('C ').split(':')[0]}", *old[1:])
        else:
            out[(x, y)] = (label, colour, shape, x, y)
    return list(out.values())


def plot() -> None:
    if not (KNOBS.exists() and PEERS.exists()):
        print("pareto: run the knobs and peers groups first")
        return
    knobs = json.loads(KNOBS.read_text(encoding="utf-8"))
    peers = json.loads(PEERS.read_text(encoding="utf-8"))
    panels = []
    for sample in peers:
        pts = merged(marks(sample, knobs, peers))
        if not pts:
            continue
        x = svg.log_axis("seconds per configuration (with velocities and accelerations)", [p[3] for p in pts])
        y = svg.log_axis("worst error of the pairs and points / L", [p[4] for p in pts])
        panels.append(svg.Panel(sample, x, y, marks=pts))
    svg.write(PLOT, panels, f"errors of 0 drawn at {FLOOR:g}; linkgen C per knob setting (circles), linkgen's "
                            "other programs at the default (triangles), peers (squares)", width=760, height=460)
    print(f"wrote {PLOT.relative_to(ROOT)}")
