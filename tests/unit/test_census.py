"""The step log's record of the assemblies is plain data: it goes to NAME.json and back as written."""

from __future__ import annotations

import json
from pathlib import Path

from linkgen.pipeline import build_log

ROOT = Path(__file__).resolve().parents[2]
FOURBAR = str(ROOT / "samples" / "fourbar" / "fourbar.yaml")


def test_the_record_is_in_the_step_log_json():
    log = build_log(FOURBAR, sweep=False)
    doc = json.loads(log.to_json())["assemblies"]
    assert doc["counted"] and doc["follows"] == 1 and [a["number"] for a in doc["listing"]] == [1, 2]
    second = dict(doc["listing"][1]["values"])
    assert (second["B.x"], second["B.y"]) == (80.0, -50.0)  # B mirrored in A-O2, the x axis: by hand
    assert doc["listing"][1]["choices"] == [{"step": 3, "target": "B", "value": -1, "of": 2, "theta": 0.0}]
