"""The samples' golden files (samples/*/expected/): what the generated programs define, read as text."""

from __future__ import annotations

import json as js
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SAMPLES = sorted(p for p in (ROOT / "samples").glob("*/expected/*.json"))  # one step log a sample


def generated(json: Path, suffix: str) -> str:
    """The sample's generated file NAME<suffix> beside its step log."""
    return json.with_name(json.stem + suffix).read_text(encoding="utf-8")


def outputs(json: Path) -> list[str]:
    """The pair, point and link names of a sample (the C state's and out's own fields besides these)."""
    log = js.loads(json.read_text(encoding="utf-8"))
    return [c["name"].split(".")[0] for c in log["columns"] if "." in c["name"]]
