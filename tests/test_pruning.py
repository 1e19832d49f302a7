"""Outputs and order prune the procedure (issue 5): the kept columns are bit for bit those
of the whole build in every language, and the pruned programs contain none of the rest."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from programs import SAMPLES, parse, run_c, run_octave, run_python

from linkgen.pipeline import build_log
from linkgen.render import render_all
from linkgen.steplog import StepLog
from linkgen.writer import write_all

ROOT = Path(__file__).resolve().parents[1]
RUNNERS = {"C": run_c, "Python": run_python, "Octave": run_octave}
FIG14 = ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"
LEVEL = {"position": 0, "angle": 0, "velocity": 1, "angular_velocity": 1, "acceleration": 2,
         "angular_acceleration": 2}


def _selections(log: StepLog) -> list[tuple[tuple[str, ...], int]]:
    """Output selections drawn from the whole build: the output its last step finds (order 0),
    the first computed one with a link (order 1), one link angle (order 2)."""
    columns = [c.name.split(".")[0] for c in log.columns[len(log.inputs):]]
    names = list(dict.fromkeys(columns))
    by_var = {c.variable: c.name.split(".")[0] for c in log.columns[len(log.inputs):]}
    found = [by_var[o] for s in log.steps if not s.variant for o in s.outputs if o in by_var]
    links = [n for n in names if n in {lk.name for lk in log.links}]
    picks = [((found[-1],), 0), ((found[0], *links[:1]), 1), ((links[-1] if links else names[-1],), 2)]
    return [(tuple(dict.fromkeys(p)), order) for p, order in picks]


def _full(path: Path, lang: str, tmp: Path) -> tuple[StepLog, str]:
    """The whole build (the file's outputs at order 2): its log and CSV in one language."""
    log = build_log(str(path), order=2, sweep=False)
    out = tmp / "full"
    write_all(render_all(log), str(out))
    return log, RUNNERS[lang](log, out)


def _compare(full: str, pruned: str, log: StepLog) -> int:
    """Kept columns text-identical on every row both builds assemble; rows the pruned build
    fails, the whole build fails with the same code.  Returns the rows compared."""
    hf, _, sf = parse(full)
    hp, _, sp = parse(pruned)
    index = [hf.index(name) for name in hp[:-1]]
    rows_f = [r.split(",") for r in full.splitlines()[1:]]
    rows_p = [r.split(",") for r in pruned.splitlines()[1:]]
    kept = {s.number for s in log.steps}
    compared = 0
    for k, (a, b) in enumerate(zip(rows_f, rows_p)):
        if sf[k] > 0 and sf[k] // 10 in kept:
            assert sp[k] == sf[k], (k, sf[k], sp[k])
        if sp[k] > 0:
            assert sf[k] == sp[k], (k, sf[k], sp[k])
            continue
        if sf[k] > 0:
            continue
        assert [a[j] for j in index] == b[:-1], (k, [(hp[i], a[j], b[i]) for i, j in enumerate(index) if a[j] != b[i]])
        compared += 1
    return compared


@pytest.mark.parametrize("lang", ["C", "Python", pytest.param("Octave", marks=pytest.mark.long)])
@pytest.mark.parametrize("path", SAMPLES, ids=[p.stem for p in SAMPLES])
def test_kept_columns_equal_the_whole_build(path, lang, tmp_path_factory):
    tmp = tmp_path_factory.mktemp(f"{path.stem}_{lang}")
    whole, full = _full(path, lang, tmp)
    for n, (outputs, order) in enumerate(_selections(whole)):
        log = build_log(str(path), outputs, order, sweep=False)
        want = [i.column for i in whole.inputs] + [c.name for o in outputs for c in whole.columns[len(whole.inputs):]
                                                   if c.name.split(".")[0] == o and LEVEL[c.quantity] <= order]
        assert [c.name for c in log.columns] == want
        out = tmp / f"pruned{n}"
        write_all(render_all(log), str(out))
        pruned = RUNNERS[lang](log, out)
        assert _compare(full, pruned, log) > 0, f"{outputs}: no row assembles in both builds"


PROGRAMS = ("{name}.c", "{name}.h", "{name}.py", "{name}_solve.m")
VELOCITY = re.compile(r"\b(DP|dthe|dv|vx|vy|omega)\b")
ACCELERATION = re.compile(r"\b(DDP|ddthe|ddv|ax|ay|alpha)\b")


def _programs(outputs: tuple[str, ...], order: int) -> tuple[StepLog, dict[str, str]]:
    log = build_log(str(FIG14), outputs, order, sweep=False)
    files = render_all(log)
    return log, {p.format(name=log.name): files[p.format(name=log.name)].decode() for p in PROGRAMS}


def test_one_pair_of_the_six_bar_emits_only_its_steps():
    """J6 (the crank's end) needs steps 1 and 2: no chain, no Add-link, no resolver in any language."""
    whole = build_log(str(FIG14), sweep=False)
    log, programs = _programs(("J6",), 0)
    assert [s.number for s in log.steps] == [1, 2]
    gone = [s for s in whole.steps if s.number > 2 and not s.variant]
    for name, text in programs.items():
        for word in ("RRR_links", "link_angle", "coupler_point", "link_residual", "resolve", "newton", "group_",
                     "add1", "continuation"):
            assert word not in text, f"{name} has {word}"
        for s in gone:
            assert not re.search(rf"Step {s.number}\b", text), f"{name} has step {s.number}"
        if not name.endswith(".h"):
            assert "Step 2" in text and "crank_input" in text, name


@pytest.mark.parametrize("outputs", [("J6",), ("J5", "coupler")])
def test_order_zero_emits_no_rates_and_order_one_no_accelerations(outputs):
    """Without a resolver, order 0 has no velocity code at all; order 1 never has acceleration code.
    (A resolver keeps the velocity channel: its Jacobian and warm starts need it.)"""
    for order in (0, 1):
        log, programs = _programs(outputs, order)
        for name, text in programs.items():
            assert not ACCELERATION.search(text), f"{name} at order {order}: {ACCELERATION.search(text)}"
            if order == 0 and not log.groups:
                assert not VELOCITY.search(text), f"{name} at order 0: {VELOCITY.search(text)}"


def test_manual_says_what_was_left_out(tmp_path):
    log, _ = _programs(("J6", "crank"), 0)
    text = render_all(log)[f"{log.name}.md"].decode()
    assert "steps 3-12 (add1, J4, J2, J5, coupler, group1, rocker1, ternary, rocker2, coupler)" in text
    assert "not needed for them" in text and "displacements only (order 0)" in text
    assert "### Step 4" not in text and "### Step 13" in text
