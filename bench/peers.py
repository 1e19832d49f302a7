"""linkgen side by side with its peers, in one run: time per configuration and worst error.

    python bench/run.py peers

The four-bar, Jansen's leg and the Fig. 14 six-bar, each over its file's sweep: linkgen's C, Python
and numpy programs at order 0 (positions) and at order 2 (with velocities and accelerations; the
default build), pylinkage with numba and without it (bench/pylinkage_peer.py, a process each), and
scipy's fsolve on the loop-closure equations (bench/fsolve_peer.py).  Errors against the 50-digit
reference (bench/exact.py) at the reference's rows, each peer at the input value it computed.
A peer that is not installed (`pip install -e '.[bench]'`) or fails is named, and the rest runs.
Writes the section "Peers" of docs/performance.md and bench/out/peers.json (for the Pareto plot).
"""

from __future__ import annotations

import json
import math
import shutil
import subprocess
import sys
from dataclasses import dataclass
from importlib import metadata
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]

import exact  # noqa: E402
import languages as lang  # noqa: E402
from performance_doc import write_section  # noqa: E402

from linkgen.pipeline import build_log  # noqa: E402
from linkgen.render import render_all  # noqa: E402
from linkgen.rows import input_rows  # noqa: E402
from linkgen.writer import write_all  # noqa: E402

SAMPLES = ("fourbar", "jansen", "sixbar_fig14")
PYLINKAGE_CANNOT = {"sixbar_fig14": "pylinkage cannot: its triad (a class-III group) is no chain of dyads"}
OUT = ROOT / "bench" / "out" / "peers"
RESULTS = ROOT / "bench" / "out" / "peers.json"
NAN = math.nan


@dataclass
class Peer:
    """One program on one mechanism: seconds per configuration and its errors (nan: not measured)."""

    program: str
    positions: float = NAN  # positions only
    full: float = NAN  # with velocities and accelerations
    position_error: float = NAN  # pairs and points
    rate_error: float = NAN
    note: str = ""


def _version(package: str) -> str:
    try:
        return metadata.version(package)
    except metadata.PackageNotFoundError:
        return ""


def linkgen_programs(path: Path, ex: exact.Exact, picked: list[int]) -> list[Peer]:
    """linkgen's C, Python and numpy programs, built at order 0 and at order 2."""
    c, py, np_ = Peer("linkgen C (gcc -O2)"), Peer("linkgen Python"), Peer("linkgen numpy (per row, 1e5 rows)")
    for order in (0, 2):
        log = build_log(str(path), order=order)
        folder = OUT / f"{path.stem}_{order}"
        shutil.rmtree(folder, ignore_errors=True)
        write_all(render_all(log), str(folder))
        tc, c_text = lang.time_c(log, folder)
        tp, py_text = lang.time_python(log, folder, f"peers_{path.stem}_{order}")
        rates, np_text = lang.time_numpy(log, folder, f"peers_{path.stem}_{order}_np")
        tn = 1.0 / rates.get(10**5, rates[max(rates)])
        for peer, t, text in ((c, tc, c_text), (py, tp, py_text), (np_, tn, np_text)):
            setattr(peer, "positions" if order == 0 else "full", t)
            if order == 2:
                e = exact.csv_errors(ex, picked, text, points_only=True)
                peer.position_error, peer.rate_error = e.points, e.rate
    if max(rates) < 10**5:
        np_.program = f"linkgen numpy (per row, {lang.size(max(rates))} rows)"
    return [c, py, np_]


def pylinkage(path: Path, numba: bool) -> Peer:
    """pylinkage in a process of its own; its errors at the crank angles it reached."""
    name = f"pylinkage {_version('pylinkage')} {'with' if numba else 'without'} numba"
    if path.stem in PYLINKAGE_CANNOT:
        return Peer(name, note=PYLINKAGE_CANNOT[path.stem])
    if not _version("pylinkage") or (numba and not _version("numba")):
        return Peer(name, note="not installed (pip install -e '.[bench]')")
    done = subprocess.run([sys.executable, str(ROOT / "bench" / "pylinkage_peer.py"), str(path),
                           *([] if numba else ["--no-numba"])], capture_output=True, text=True)
    if done.returncode != 0:
        return Peer(name, note=f"failed: {done.stderr.strip().splitlines()[-1][:200]}")
    out = json.loads(done.stdout)
    log = build_log(str(path), sweep=False)
    rows = [out["rows"][k] for k in exact.sweep_rows(log.samples)]
    values = np.array([[r.pop("theta")] for r in rows])
    ex = exact.solve(str(path), values, np.full_like(values, log.inputs[0].speed))
    e = exact.worst(ex, rows)
    note = "" if out["numba"] == numba else f"numba in use: {out['numba']}"
    return Peer(name, out["times"]["positions"], out["times"]["full"], e.points, e.rate, note)


def fsolve(path: Path, ex: exact.Exact, picked: list[int]) -> Peer:
    name = f"scipy {_version('scipy')} fsolve"
    if not _version("scipy"):
        return Peer(name, note="not installed (pip install -e '.[bench]')")
    import fsolve_peer

    log = build_log(str(path), sweep=False)
    values = input_rows(log, log.samples)[0][:, 0]
    loops = fsolve_peer.Loops(str(path))
    positions, _, _ = fsolve_peer.sweep(loops, values, log.inputs[0].speed, full=False)
    full, rows, missed = fsolve_peer.sweep(loops, values, log.inputs[0].speed, full=True)
    e = exact.worst(ex, [rows[k] for k in picked])
    note = f"fsolve reports no convergence on {missed} of {len(values)} rows" if missed else ""
    return Peer(name, positions, full, e.points, e.rate, note)


def _cell(seconds: float) -> str:
    if not math.isfinite(seconds):
        return "-"
    return f"{seconds * 1e9:.0f} ns" if seconds < 1e-6 else f"{seconds * 1e6:.3g} us"


def section(results: dict[str, list[Peer]]) -> str:
    lines = ["## Peers", "",
             "`make bench` (`bench/peers.py`) runs linkgen's programs and its peers on the same mechanisms",
             "and sweeps (the file's range and rows), in one run: pylinkage with numba and without it",
             "(`bench/pylinkage_peer.py`: a crank, RRR dyads and fixed dyads built from the sketch; its",
             "`step_fast` for positions, `step_fast_with_kinematics` with velocities and accelerations),",
             "and scipy's fsolve as the generic baseline (`bench/fsolve_peer.py`: the loop-closure",
             "equations of `tests/reference.py`'s pose model with their Jacobian, at scipy's default",
             "tolerance, each row started from the last).  The peers come with `pip install -e '.[bench]'`",
             "(`make bench` installs them); a peer that does not install is named here and the rest runs.",
             "linkgen's times are its default build (order 2, every output; bench/languages.py) and the",
             "build at order 0 for positions only.  Errors as in the knob tables (50-digit reference, the",
             "worst over the reference's rows; a peer compared at the input value it reached), of the",
             "pairs and points alone, which every program here computes (linkgen's link angles are left out).",
             "Medians of repeated sweeps on a shared machine: read the ratios.", "",
             "The Pareto plot puts them together with every knob setting of linkgen's C program (the knob",
             "tables above; `bench/pareto.py`): time per configuration with velocities and accelerations",
             "against the worst error of the pairs' and points' positions, log-log.", "",
             "![time per configuration against worst error](performance-pareto.svg)", ""]
    for sample, peers in results.items():
        lines += [f"### {sample}", "",
                  "| program | positions only | with velocities and accelerations | pairs and points: worst error / L "
                  "| rates: worst error | note |", "| --- | ---: | ---: | ---: | ---: | --- |"]
        for p in peers:
            errors = [f"{e:.1e}" if math.isfinite(e) else "-" for e in (p.position_error, p.rate_error)]
            lines.append(f"| {p.program} | {_cell(p.positions)} | {_cell(p.full)} | {errors[0]} | {errors[1]} | "
                         f"{p.note} |")
        lines.append("")
    return "\n".join(lines)


def bench_peers() -> dict[str, list[Peer]]:
    results = {}
    for sample in SAMPLES:
        print(f"peers: {sample}", flush=True)
        path = ROOT / "samples" / sample / f"{sample}.yaml"
        ex, picked = exact.of_sample(str(path))
        results[sample] = [*linkgen_programs(path, ex, picked), pylinkage(path, True), pylinkage(path, False),
                           fsolve(path, ex, picked)]
    RESULTS.parent.mkdir(parents=True, exist_ok=True)
    RESULTS.write_text(json.dumps({k: [vars(p) for p in v] for k, v in results.items()}, indent=1), encoding="utf-8")
    text = section(results)
    print(text)
    write_section("Peers", text)
    return results
