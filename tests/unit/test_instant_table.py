"""linkgen.instant.table: every centre at one row from the evaluator, the table and the JSON."""

from __future__ import annotations

import json
import math
from pathlib import Path

from linkgen.instant.table import centre_outputs, locate, text, to_json, where
from linkgen.pipeline import analyse_file, build_log

SAMPLES = Path(__file__).resolve().parents[2] / "samples"


def located(name: str, values=None, rates=None):
    path = str(SAMPLES / name / f"{name}.yaml")
    m = analyse_file(path)[0]
    log = build_log(path, outputs=centre_outputs(m), order=1, sweep=False)
    return log, locate(log, m, values, rates)


def test_fourbar_at_a_right_angle():
    """Crank at 90 deg: the first centres are the pairs; frame-coupler on the crank's line x = 0."""
    log, table = located("fourbar", (90.0,), (math.degrees(1.0),))  # the file's units: degrees
    by = {c.centre.name: c for c in table.centres}
    assert (by["ic:frame:crank"].x, by["ic:frame:crank"].y) == (0.0, 0.0)
    assert abs(by["ic:frame:coupler"].x) < 1e-9 and by["ic:frame:coupler"].status == 0
    assert table.inputs == (90.0,) and table.rates == (math.degrees(1.0),)  # as given, not through radians
    assert where(by["ic:frame:crank"]) == "(0, 0)"


def test_text_and_json():
    log, table = located("slider_crank")
    printed = text(log, table)
    assert printed.splitlines()[0].startswith("Instant centres of slider_crank (6)")
    assert "at infinity, direction (0, 1)" in printed
    doc = json.loads(to_json(log, table))
    assert [c["centre"] for c in doc["centres"]] == list(centre_outputs(analyse_file(
        str(SAMPLES / "slider_crank" / "slider_crank.yaml"))[0]))
