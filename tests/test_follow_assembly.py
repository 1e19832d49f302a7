"""``linkgen build --assembly K`` (``options: assembly``): the programs follow assembly K.

For every assembly K of the four-bar and of the Fig. 14 six-bar at the sketch's inputs (and
assemblies of the class-IV class4_slot and quaternary_fold, long):

* the programs' first solve (a fresh state, at the sketch's inputs) is assembly K: its pairs
  where an independent route puts them at 50 digits (the closed form for the four-bar, the
  multistart Newton search of tests/assembly_oracle.py for the six-bar's triad), each K a
  different one of them, and the one ``linkgen assemblies`` numbers K;
* the sweep follows it: every row agrees with the 50-digit reference (tests/reference.py)
  continued from assembly K as listed, row to row, in small steps;
* C, Octave and numpy give the Python program's sweep (long tier).
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from assembly_oracle import MP, tree_assemblies, triad_search
from programs import compare, parse, run_c, run_numpy, run_octave, run_python
from reference import Reference

from linkgen.errors import InputError
from linkgen.evaluate import evaluate
from linkgen.pipeline import build_log
from linkgen.render import render_all
from linkgen.table import csv
from linkgen.writer import write_all

ROOT = Path(__file__).resolve().parents[1]
FOURBAR = ROOT / "samples" / "fourbar" / "fourbar.yaml"
FIG14 = ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"
LONG = pytest.mark.long
CASES = [(FOURBAR, 1), (FOURBAR, 2), (FIG14, 1), (FIG14, 2), (FIG14, 3), (FIG14, 4)]
QUICK = ((FOURBAR, 2),)  # in `make test`, every 12th row; the long tier every case, every row
IDS = [f"{p.stem}-{k}" for p, k in CASES]
STEP = math.radians(1)  # the reference's continuation step


def _built(path: Path, k: int, outdir: Path):
    log = build_log(str(path), options={"assembly": k})
    write_all(render_all(log), str(outdir))
    return log


def _first_solve(log, outdir: Path) -> dict:
    """NAME.solve at the sketch's inputs from a fresh state (the Python program, stdlib only)."""
    code = (f"import json, sys; sys.path.insert(0, {str(outdir)!r}); import {log.name} as m; "
            f"r = m.solve({[i.sketch for i in log.inputs]!r}, {[i.speed for i in log.inputs]!r}, "
            f"{[0.0] * len(log.inputs)!r}); print(json.dumps({{k: v for k, v in r.items() if k != 'sigma'}}))")
    done = subprocess.run([sys.executable, "-I", "-c", code], capture_output=True, text=True, check=True)
    return json.loads(done.stdout)


def _oracle(path: Path) -> list[dict]:
    """Every assembly at the sketch's inputs by an independent route, pair -> (x, y) at 50 digits."""
    ref = Reference(str(path))
    if path == FOURBAR:
        return tree_assemblies(str(path), [float(MP.degrees(v)) for v in ref.sketch_inputs(exact=True)])
    m = ref.m
    sketch = {k: (MP.mpf(x), MP.mpf(y)) for k, (x, y) in m.positions.items()}
    pairs, bases = ("J2", "J4", "J5"), ("J1", "J3", "J6")  # the ternary and its legs' known ends
    first = sketch[pairs[0]]
    local = [(sketch[p][0] - first[0], sketch[p][1] - first[1]) for p in pairs]
    lengths2 = [(sketch[p][0] - sketch[b][0]) ** 2 + (sketch[p][1] - sketch[b][1]) ** 2 for p, b in zip(pairs, bases)]
    out = []
    for x, y, t in triad_search([sketch[b] for b in bases], local, lengths2):
        c, s = MP.cos(t), MP.sin(t)
        placed = {p: (x + c * ax - s * ay, y + s * ax + c * ay) for p, (ax, ay) in zip(pairs, local)}
        out.append({**sketch, **placed})
    return out


def _which(row: dict, found: list[dict], scale: float) -> int:
    """The oracle assembly the row's pairs are (to 1e-12 L), or -1."""
    for k, a in enumerate(found):
        if all(abs(row[f"{p}.x"] - float(x)) + abs(row[f"{p}.y"] - float(y)) <= 1e-12 * scale
               for p, (x, y) in a.items() if f"{p}.x" in row):
            return k
    return -1


@pytest.mark.parametrize("path", [FOURBAR, FIG14], ids=lambda p: p.stem)
def test_each_assembly_is_the_programs_first_solve(tmp_path, path):
    found = _oracle(path)
    seen = []
    for k in range(1, len(found) + 1):
        log = _built(path, k, tmp_path / str(k))
        assert log.assemblies is not None and log.assemblies.follows == k and len(log.assemblies.listing) == len(found)
        row = _first_solve(log, tmp_path / str(k))
        assert row["status"] == 0
        which = _which(row, found, log.length_scale)
        assert which >= 0, f"assembly {k}'s first solve is none of the {len(found)} assemblies"
        listed = dict(log.assemblies.listing[k - 1].values)
        assert _which(listed, found, log.length_scale) == which, "the programs follow another assembly than K"
        seen.append(which)
    assert sorted(seen) == list(range(len(found))), "two choices of K give the same assembly"


def _reference_sweep(path: Path, first: dict, values: list[list[float]]) -> list[dict | None]:
    """The reference (50 digits) at every row's inputs, continued in float from the configuration
    ``first`` at the sketch's inputs (steps of at most STEP), each row then polished at 50 digits."""
    ref = Reference(str(path))
    start = ref.sketch_inputs()[0]
    q = ref.newton(ref.guess(first), [start], exact=False)[0]
    u, out = start, []
    for target in (v[0] for v in values):
        n = max(1, math.ceil(abs(target - u) / STEP))
        for j in range(1, n + 1):
            q = ref.newton(q, ref.turned_inputs(q, [u + (target - u) * j / n]), exact=False)[0]
        u = target
        out.append(ref.solve([target], [ref.m.inputs[0].speed], q).columns)
    return out


@pytest.mark.parametrize(("path", "k"), [pytest.param(p, k, marks=[] if (p, k) in QUICK else [LONG]) for p, k in CASES],
                         ids=IDS)
def test_the_sweep_follows_assembly_k(tmp_path, path, k):
    """Every row of the Python program's sweep is the 50-digit reference continued from assembly K (1e-9 of
    the length scale; angles to 1e-9 rad)."""
    log = _built(path, k, tmp_path)
    assert log.assemblies is not None
    first = dict(log.assemblies.listing[k - 1].values)  # assembly K as listed (the oracle's: test above)
    names, data, statuses = parse(run_python(log, tmp_path))
    assert statuses == [0] * log.samples
    rows = list(range(0, log.samples, 12 if (path, k) in QUICK else 1))
    want = _reference_sweep(path, first, [data[r][:1] for r in rows])
    _agree(names, data, rows, want, log.length_scale)


@LONG
@pytest.mark.parametrize(("path", "k"), CASES, ids=IDS)
def test_every_language_follows_assembly_k(tmp_path, path, k):
    log = _built(path, k, tmp_path)
    py = run_python(log, tmp_path)
    for other in (run_c(log, tmp_path), run_octave(log, tmp_path), run_numpy(log, tmp_path)):
        compare(log, py, other)


def test_an_assembly_out_of_range_is_an_error(tmp_path):
    text = FOURBAR.read_text(encoding="utf-8") + "options:\n  assembly: 3\n"
    bad = tmp_path / "fourbar.yaml"
    bad.write_text(text, encoding="utf-8")
    line = text.count("\n")
    with pytest.raises(InputError, match=rf"fourbar.yaml:{line}: options.assembly: there is no assembly 3: the "
                                         "mechanism has 2 assemblies"):
        build_log(str(bad))
    with pytest.raises(InputError, match=r"command line: --assembly: there is no assembly 5"):
        build_log(str(FOURBAR), options={"assembly": 5})
    bad.write_text(FOURBAR.read_text(encoding="utf-8") + "options:\n  assembly: 0\n", encoding="utf-8")
    with pytest.raises(InputError, match=rf"fourbar.yaml:{line}: options.assembly: options: assembly is a number "
                                         "from 1"):
        build_log(str(bad))


def test_a_group_linkgen_cannot_count_cannot_be_followed():
    path = ROOT / "tests" / "assemblies" / "moving_slot.yaml"  # a block in a slot of a moving rocker
    with pytest.raises(InputError, match=r"--assembly: linkgen cannot count the assemblies"):
        build_log(str(path), options={"assembly": 1})
    log = build_log(str(path), sweep=False)
    assert log.assemblies is not None and not log.assemblies.counted and log.assemblies.listing == ()


def test_the_step_log_and_the_banners_record_the_assembly(tmp_path):
    log = _built(FOURBAR, 2, tmp_path)
    assert json.loads((tmp_path / "fourbar.json").read_text())["options"]["assembly"] == 2
    for name in ("fourbar.c", "fourbar.py", "fourbar.m", "fourbar.md"):
        assert "assembly 2." in (tmp_path / name).read_text().splitlines()[0], name
    manual = (tmp_path / "fourbar.md").read_text()
    assert "The programs follow assembly 2 (`options: assembly`" in manual
    assert "![assembly 1 of 2](fourbar_assembly_1.svg)" in manual and (tmp_path / "fourbar_assembly_2.svg").is_file()
    assert log.options.assembly == 2


def test_the_flag_of_build_and_run(tmp_path):
    linkgen = Path(sys.executable).with_name("linkgen")
    rows = {}
    for flags in ([], ["--assembly", "2"]):
        done = subprocess.run([str(linkgen), "run", str(FOURBAR), "--samples", "2", *flags], capture_output=True,
                              text=True, check=True)
        names, data, _ = parse(done.stdout)
        rows[len(flags)] = dict(zip(names, data[0]))
    # B mirrored in the frame line A-O2 at 0 deg (to its last bit: the branch's sign alone differs)
    assert rows[0]["B.y"] == pytest.approx(50.0, rel=4 * sys.float_info.epsilon) and rows[2]["B.y"] == -rows[0]["B.y"]
    done = subprocess.run([str(linkgen), "build", str(FOURBAR), "--assembly", "3", "-o", str(tmp_path)],
                          capture_output=True, text=True)
    assert done.returncode == 1 and done.stderr == ("linkgen: error: command line: --assembly: there is no assembly "
                                                    "3: the mechanism has 2 assemblies at the sketch's inputs (linkgen "
                                                    "assemblies lists them)\n")
    assert not any(tmp_path.iterdir())


@LONG
@pytest.mark.parametrize("path", sorted(ROOT.glob("samples/*/*.yaml")), ids=lambda p: p.stem)
def test_every_assembly_of_every_sample_is_the_first_solve(path):
    """For each K, the evaluator's solve at the sketch's inputs is assembly K as listed (whose
    poses tests/test_assemblies.py checks against the independent routes) to 1e-14 L."""
    listing = build_log(str(path), sweep=False).assemblies
    assert listing is not None and listing.counted
    for k, a in enumerate(listing.listing, 1):
        log = build_log(str(path), sweep=False, options={"assembly": k})
        rows = np.array([[i.sketch for i in log.inputs]])
        result = evaluate(log, rows, np.array([[i.speed for i in log.inputs]]), np.zeros_like(rows))
        assert int(result.status[0]) == 0, (k, int(result.status[0]))
        got = dict(zip(csv(log, result).splitlines()[0].split(","), csv(log, result).splitlines()[1].split(",")))
        want = dict(a.values)
        worst = max(abs(float(got[n]) - want[n]) for n in want if n.endswith((".x", ".y")) and n in got)
        assert worst <= 1e-14 * log.length_scale, (k, worst)


SLOT = ROOT / "tests" / "regressions" / "class4_slot.yaml"  # class IV: two links on their own pivots, a slot
QUATERNARY = ROOT / "tests" / "mechanisms" / "quaternary_fold.yaml"  # class IV: two Add-links at once
CLASS4 = [(SLOT, 1), (SLOT, 2), (QUATERNARY, 3)]  # quaternary_fold: the sketch's is 9 of 18; 3 reaches 0 to 143 deg


def test_a_build_lists_every_assembly_of_a_class_iv_group():
    """quaternary_fold's build, no assembly asked for, counts its class-IV group (two Add-links at once):
    the manual's listing has the 18 assemblies the 50-digit multistart search of tests/test_assemblies.py
    finds (long), distinct, the sketch's among them and followed, each keeping every constraint of the
    reference model (tests/reference.py, written from the file) to 1e-12 L."""
    log = build_log(str(QUATERNARY), sweep=False)
    found = log.assemblies
    assert found is not None and found.counted and len(found.listing) == 18
    assert [a.number for a in found.listing if a.sketch] == [found.follows]
    ref = Reference(str(QUATERNARY))
    poses = []
    for a in found.listing:
        q = ref.guess(dict(a.values))
        res = ref.constraints([MP.mpf(v) for v in q], ref.turned_inputs([MP.mpf(v) for v in q], ref.sketch_inputs()))
        assert max(float(abs(r)) / s for r, s in zip(res, ref.constraint_scales())) < 1e-12, a.number
        poses.append([v for n, v in a.values if n.endswith((".x", ".y"))])
    assert min(max(abs(x - y) for x, y in zip(p, q)) for i, p in enumerate(poses) for q in poses[i + 1:]) \
        > 1e-6 * log.length_scale


def _agree(names: list[str], data: list[list[float]], rows: list[int], want: list[dict], scale: float) -> None:
    """The program's rows against the reference's: positions to 1e-9 L, angles to 1e-9 rad (mod a turn)."""
    for r, w in zip(rows, want):
        for name, x in zip(names[1:], data[r][1:]):
            if name in w and name.endswith((".x", ".y")):
                assert abs(x - float(w[name])) <= 1e-9 * scale, (r, name, x, float(w[name]))
            elif name in w and name.endswith(".phi"):
                assert abs(math.remainder(x - float(w[name]), 2 * math.pi)) <= 1e-9, (r, name, x, float(w[name]))


def _reached(statuses: list[int], values: list[list[float]], sketch: float) -> list[int]:
    """The rows the programs reach from the sketch without crossing a failed row: the run of rows of
    status 0 between the failures on either side of the sketch's input (all rows if none fails)."""
    if all(s == 0 for s in statuses):
        return list(range(len(statuses)))
    below = [r for r, v in enumerate(values) if v[0] <= sketch]
    start = max((r for r in below if statuses[r] != 0), default=-1) + 1
    stop = min((r for r in range(start, len(values)) if statuses[r] != 0), default=len(values))
    return list(range(start, stop))


@LONG  # class4_slot: 10 s a case (the reference's continuation over the turn); quaternary_fold: about 2 min
@pytest.mark.parametrize(("path", "k"), CLASS4, ids=[f"{p.stem}-{k}" for p, k in CLASS4])
def test_a_class_iv_assembly_is_followed(tmp_path, path, k):
    """Assembly K of a class-IV group (quaternary_fold: counted at every build, about 6 s): the programs'
    first solve is assembly K as listed to 1e-12 L, which keeps every constraint of the reference model
    to 1e-12 L (its count and poses are checked against the multistart searches in tests/
    test_assemblies_pivots.py and tests/test_assemblies.py); every row the programs reach from the
    sketch is the 50-digit reference continued from assembly K; C, Octave and numpy give the Python
    program's sweep."""
    log = _built(path, k, tmp_path)
    assert log.assemblies is not None and log.assemblies.counted and log.assemblies.follows == k
    listed = dict(log.assemblies.listing[k - 1].values)
    row = _first_solve(log, tmp_path)
    assert row["status"] == 0
    assert all(abs(row[n] - x) <= 1e-12 * log.length_scale for n, x in listed.items() if n.endswith((".x", ".y")))
    ref = Reference(str(path))
    q = ref.guess(listed)
    res = ref.constraints([MP.mpf(v) for v in q], ref.turned_inputs([MP.mpf(v) for v in q], ref.sketch_inputs()))
    assert max(float(abs(r)) / s for r, s in zip(res, ref.constraint_scales())) < 1e-12
    py = run_python(log, tmp_path)
    names, data, statuses = parse(py)
    rows = _reached(statuses, data, log.inputs[0].sketch)
    assert rows and all(statuses[r] == 0 for r in rows)
    want = _reference_sweep(path, listed, [data[r][:1] for r in rows])
    _agree(names, data, rows, want, log.length_scale)
    for other in (run_c(log, tmp_path), run_octave(log, tmp_path), run_numpy(log, tmp_path)):
        compare(log, py, other)
