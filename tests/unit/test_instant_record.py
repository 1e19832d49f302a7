"""linkgen.instant.record: a centre at the sketch is plain data, written into NAME.json (None at infinity)."""

from __future__ import annotations

import json
from pathlib import Path

from linkgen.instant.record import CentreAt
from linkgen.pipeline import build_log

SAMPLES = Path(__file__).resolve().parents[2] / "samples"


def test_the_step_log_writes_every_centre():
    log = build_log(str(SAMPLES / "slider_crank" / "slider_crank.yaml"))
    assert all(isinstance(c, CentreAt) for c in log.centres) and len(log.centres) == 6
    doc = {c["name"]: c for c in json.loads(log.to_json())["centres"]}
    far = doc["ic:frame:block"]
    assert far["status"] == 1 and far["x"] is None and far["y"] is None and (far["ux"], far["uy"]) == (0.0, 1.0)
    assert doc["ic:frame:crank"]["kind"] == "first" and doc["ic:frame:crank"]["pair"] == "O"


def test_a_build_without_the_sweep_has_none():
    assert build_log(str(SAMPLES / "fourbar" / "fourbar.yaml"), sweep=False).centres == ()
