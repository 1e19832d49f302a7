"""The summary's records (linkgen.summary.records) are plain: frozen, builtins only, in the step log's JSON."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import pytest

from linkgen.pipeline import build_log
from linkgen.summary import records

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("record", [records.InputRange, records.FourBar, records.Position, records.Transmission,
                                    records.Travel, records.Failure, records.Summary])
def test_records_are_frozen_dataclasses(record):
    assert dataclasses.is_dataclass(record) and record.__dataclass_params__.frozen  # type: ignore[attr-defined]


def test_the_step_log_json_carries_the_summary():
    log = build_log(str(ROOT / "samples" / "fourbar" / "fourbar.yaml"))
    data = json.loads(log.to_json())
    assert data["summary"] == json.loads(json.dumps(dataclasses.asdict(log.summary)))
    assert data["summary"]["four_bars"][0]["kind"] == "crank-rocker"
