"""linkgen.units: input values and rates between the file's units and the procedure's, by hand."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from linkgen.assemblies import whole_log
from linkgen.units import from_file, to_file

ROOT = Path(__file__).resolve().parents[2]


def test_input_values_convert_between_the_files_units_and_radians():
    fivebar = whole_log(str(ROOT / "samples" / "fivebar" / "fivebar.yaml"))  # degrees
    assert from_file(fivebar, [90.0, -30.0]) == (math.pi / 2, math.radians(-30.0))
    assert to_file(fivebar, from_file(fivebar, [90.0, -30.0])) == pytest.approx((90.0, -30.0), abs=1e-13)
    actuator = whole_log(str(ROOT / "samples" / "actuator" / "actuator.yaml"))  # a length input
    assert from_file(actuator, [1500.0]) == (1500.0,) == to_file(actuator, [1500.0])
    watt = whole_log(str(ROOT / "tests" / "mechanisms" / "watt_circuit.yaml"))  # radians
    assert from_file(watt, [1.75]) == (1.75,) == to_file(watt, [1.75])
