"""linkgen.units: degrees only with units: file and a file in degrees; the angle columns and the revolute
inputs are the ones converted, by the one factor 180/pi; the sweep's ranges as the programs take them; the
commands' input values between the file's units and radians, by hand."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest
from mechanism_text import FOURBAR

from linkgen.assemblies import whole_log
from linkgen.options import Options
from linkgen.pipeline import build_log
from linkgen.units import (
    DEGREE,
    angular_inputs,
    converted,
    factor,
    from_file,
    outputs_from_si,
    sweep_lists,
    to_file,
    to_si,
)

ROOT = Path(__file__).resolve().parents[2]


def _log(tmp_path, text: str = FOURBAR, units: str = "file"):
    path = tmp_path / "m.yaml"
    path.write_text(text, encoding="utf-8")
    log = build_log(str(path), sweep=False)
    return dataclasses.replace(log, options=Options(units=units))


def test_the_factor_is_180_over_pi_as_a_double():
    assert 180 / math.pi == DEGREE and repr(DEGREE) == "57.29577951308232"


def test_degrees_only_with_units_file_and_a_file_in_degrees(tmp_path):
    assert factor(_log(tmp_path)) == DEGREE
    assert factor(_log(tmp_path, units="si")) is None
    radians = FOURBAR.replace("angle: deg", "angle: rad").replace("range: [0, 360]", "range: [0, 6]")
    assert "angle: rad" in radians and factor(_log(tmp_path, radians)) is None


def test_the_angle_columns_and_revolute_inputs_are_converted(tmp_path):
    log = _log(tmp_path)
    names = {c.name for c in log.columns[len(log.inputs):] if converted(log, c)}
    assert names == {f"{lk}.{f}" for lk in ("frame", "crank", "coupler", "rocker") for f in ("phi", "omega", "alpha")}
    assert angular_inputs(log) == (0,) and angular_inputs(_log(tmp_path, units="si")) == ()
    ranges = sweep_lists(log)
    assert ranges["stop"] == [2 * math.pi * DEGREE] and ranges["speed"] == [log.inputs[0].speed * DEGREE]


def test_inputs_in_and_outputs_out_by_the_one_factor(tmp_path):
    log = _log(tmp_path)
    rows = np.array([[90.0], [-45.0]])
    si = to_si(log, rows, rows, rows)
    assert [a.tolist() for a in si] == [[[90 / DEGREE], [-45 / DEGREE]]] * 3
    data = np.ones((1, len(log.columns)))
    out = outputs_from_si(log, data.copy())
    assert [c.name for c, x in zip(log.columns, out[0]) if x != 1.0] == [
        c.name for c in log.columns[1:] if converted(log, c)]
    assert set(out[0]) == {1.0, DEGREE}


def test_input_values_convert_between_the_files_units_and_radians():
    fivebar = whole_log(str(ROOT / "samples" / "fivebar" / "fivebar.yaml"))  # degrees
    assert from_file(fivebar, [90.0, -30.0]) == (math.pi / 2, math.radians(-30.0))
    assert to_file(fivebar, from_file(fivebar, [90.0, -30.0])) == pytest.approx((90.0, -30.0), abs=1e-13)
    actuator = whole_log(str(ROOT / "samples" / "actuator" / "actuator.yaml"))  # a length input
    assert from_file(actuator, [1500.0]) == (1500.0,) == to_file(actuator, [1500.0])
    watt = whole_log(str(ROOT / "tests" / "mechanisms" / "watt_circuit.yaml"))  # radians
    assert from_file(watt, [1.75]) == (1.75,) == to_file(watt, [1.75])
