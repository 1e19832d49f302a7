"""The step log's record of the assemblies is plain data: it goes to NAME.json and back as written."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from linkgen.pipeline import build_log

ROOT = Path(__file__).resolve().parents[2]
FOURBAR = str(ROOT / "samples" / "fourbar" / "fourbar.yaml")


def test_the_record_is_in_the_step_log_json():
    log = build_log(FOURBAR, sweep=False)
    doc = json.loads(log.to_json())["assemblies"]
    assert doc["counted"] and doc["follows"] == 1 and [a["number"] for a in doc["listing"]] == [1, 2]
    second = dict(doc["listing"][1]["values"])
    # B mirrored in A-O2, the x axis: by hand, to a few ulps (RRR_links rounds 0.5 / q^2 and its product with q)
    assert (second["B.x"], second["B.y"]) == (pytest.approx(80.0, abs=4e-14), pytest.approx(-50.0, abs=4e-14))
    assert doc["listing"][1]["choices"] == [{"step": 3, "target": "B", "value": -1, "of": 2, "theta": 0.0}]
