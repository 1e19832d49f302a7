"""The step log is plain data: builtins only, JSON that reads back to the same log, deterministic
across processes; its status codes and runtime functions are made from its steps and reach."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
import types
import typing
from dataclasses import fields, is_dataclass, replace
from pathlib import Path

import pytest

from linkgen.pipeline import build_log
from linkgen.render import render_all
from linkgen.steplog import StepLog
from linkgen.writer import write_all

ROOT = Path(__file__).resolve().parents[2]
FIG14 = ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"
SAMPLES = sorted(ROOT.glob("samples/*/*.yaml"))


def _walk(obj, path="log"):
    if is_dataclass(obj):
        for f in fields(obj):
            yield from _walk(getattr(obj, f.name), f"{path}.{f.name}")
    elif isinstance(obj, tuple):
        for i, x in enumerate(obj):
            yield from _walk(x, f"{path}[{i}]")
    else:
        yield path, obj


def test_only_builtins_cross_the_boundary():
    for path, value in _walk(build_log(str(FIG14))):
        assert value is None or type(value) in (str, int, float, bool), (path, type(value))


def _decode(kind, data):
    """JSON data as the declared type ``kind`` of a step-log field (dataclasses, tuples, X | None, builtins)."""
    if is_dataclass(kind):
        hints = typing.get_type_hints(kind)
        assert sorted(data) == sorted(f.name for f in fields(kind)), kind.__name__
        decoded = {f.name: _decode(hints[f.name], data[f.name]) for f in fields(kind)}
        obj = kind(**{f.name: decoded[f.name] for f in fields(kind) if f.init})
        derived = [f.name for f in fields(kind) if not f.init]  # made from the others: as written
        assert [getattr(obj, name) for name in derived] == [decoded[name] for name in derived], kind.__name__
        return obj
    args = typing.get_args(kind)
    if typing.get_origin(kind) is tuple:
        assert isinstance(data, list), (kind, data)
        if len(args) == 2 and args[1] is Ellipsis:
            return tuple(_decode(args[0], x) for x in data)
        assert len(args) == len(data), (kind, data)
        return tuple(_decode(a, x) for a, x in zip(args, data))
    if typing.get_origin(kind) in (typing.Union, types.UnionType):
        if data is None:
            assert type(None) in args, kind
            return None
        (other,) = (a for a in args if a is not type(None))
        return _decode(other, data)
    assert type(data) is kind or (kind is float and type(data) is int), (kind, data)
    return data


@pytest.mark.parametrize("sample", SAMPLES, ids=lambda p: p.stem)
def test_json_file_reads_back_to_the_same_log(sample: Path, tmp_path: Path):
    """NAME.json as written by a build, read back by the StepLog's own field types, is the StepLog."""
    log = build_log(str(sample))
    write_all(render_all(log), str(tmp_path))
    text = (tmp_path / f"{log.name}.json").read_text(encoding="utf-8")
    assert text.endswith("}\n")
    back = _decode(StepLog, json.loads(text))
    differ = [(p, a, b) for (p, a), (_, b) in zip(_walk(log), _walk(back)) if a != b]
    assert back == log, differ[:5]
    numbers = [s.number for s in back.steps] + [o.number for o in back.omitted]  # kept steps keep theirs
    assert sorted(numbers) == list(range(1, len(numbers) + 1))


def test_json_is_identical_under_other_hash_seeds(tmp_path: Path):
    code = "import sys; from linkgen.pipeline import build_log; sys.stdout.write(build_log(sys.argv[1]).to_json())"
    outs = []
    for seed in ("0", "1", "12345"):
        env = dict(os.environ, PYTHONHASHSEED=seed)
        outs.append(subprocess.run([sys.executable, "-c", code, str(FIG14)], capture_output=True, text=True,
                                   env=env, cwd=tmp_path, check=True).stdout)
    assert outs[0] == outs[1] == outs[2] == build_log(str(FIG14)).to_json()


def test_runtime_and_status_codes_are_made_from_the_steps_and_reach():
    """A change made to a log's steps or reach changes its runtime functions and status codes
    with it: the parallelogram without its change points needs no branch_at; sixbar_partial
    without its reach has no code for rows past a limit position (81)."""
    flat = build_log(str(ROOT / "tests" / "mechanisms" / "parallelogram.yaml"), sweep=False)
    assert "branch_at" in flat.runtime
    assert "branch_at" not in replace(flat, steps=tuple(replace(s, change_points=()) for s in flat.steps)).runtime
    partial = build_log(str(ROOT / "tests" / "mechanisms" / "sixbar_partial.yaml"), sweep=False)
    assert "reach_at" in partial.runtime and 81 in [c.code for c in partial.status_codes]
    free = replace(partial, reach=None)
    assert "reach_at" not in free.runtime and 81 not in [c.code for c in free.status_codes]


def test_a_direction_is_published_without_the_origin():
    """A direction record is a POINT record, but no position: the programs add no origin to it, and a
    constant one is held as drawn."""
    from linkgen.steplog import held

    log = build_log(str(SAMPLES[0].parent.parent / "slider_crank" / "slider_crank.yaml"), sweep=False,
                    options={"angles": "unit"})
    assert log.shifted
    ux = next(c for c in log.columns if c.name == "rod.ux")
    assert log.offset(ux) == 0.0 and log.offset(next(c for c in log.columns if c.name == "B.x")) != 0.0
    frame, angle = log.variable("u_frame"), next(k.angle for k in log.links if k.name == "frame")
    assert held(frame, log.origin) == frame.value == pytest.approx((math.cos(angle), math.sin(angle)), abs=2e-16)


def test_a_closure_log_reads_back_and_its_programs_carry_the_closure_runtime():
    """With strategy closure every group records its equations (steplog.Closure), NAME.json reads back
    to the same log, and the runtime names the closure strategy's; the default build does neither."""
    log = build_log(str(FIG14), sweep=False, options={"strategy": "closure"})
    assert log.groups[0].closure is not None and "closure" in log.runtime
    assert _decode(StepLog, json.loads(log.to_json())) == log
    default = build_log(str(FIG14), sweep=False)
    assert default.groups[0].closure is None and "closure" not in default.runtime
