"""The step log is plain data: builtins only, JSON deterministic across processes."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from dataclasses import fields, is_dataclass
from pathlib import Path

from linkgen.pipeline import build_log

ROOT = Path(__file__).resolve().parents[2]
FIG14 = ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"


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


def test_json_round_trips_and_names_every_step():
    log = build_log(str(FIG14))
    data = json.loads(log.to_json())
    assert [s["number"] for s in data["steps"]] == list(range(1, len(log.steps) + 1))
    assert data["add_links"][0]["candidates"][0]["pairs"] == list(log.add_links[0].pairs)
    assert log.to_json().endswith("}\n")


def test_json_is_identical_under_other_hash_seeds(tmp_path: Path):
    code = "import sys; from linkgen.pipeline import build_log; sys.stdout.write(build_log(sys.argv[1]).to_json())"
    outs = []
    for seed in ("0", "1", "12345"):
        env = dict(os.environ, PYTHONHASHSEED=seed)
        outs.append(subprocess.run([sys.executable, "-c", code, str(FIG14)], capture_output=True, text=True,
                                   env=env, cwd=tmp_path, check=True).stdout)
    assert outs[0] == outs[1] == outs[2] == build_log(str(FIG14)).to_json()
