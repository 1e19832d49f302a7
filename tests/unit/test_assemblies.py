"""The package's entry: input values in the file's units, the whole procedure's log, and groups it
cannot count refused as errors that name the file."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from linkgen.assemblies import assemblies, file_units, internal_units, whole_log
from linkgen.errors import ProcedureError

ROOT = Path(__file__).resolve().parents[2]


def test_input_values_convert_between_the_files_units_and_radians():
    fivebar = whole_log(str(ROOT / "samples" / "fivebar" / "fivebar.yaml"))  # degrees
    assert internal_units(fivebar, [90.0, -30.0]) == (math.pi / 2, math.radians(-30.0))
    assert file_units(fivebar, internal_units(fivebar, [90.0, -30.0])) == pytest.approx((90.0, -30.0), abs=1e-13)
    actuator = whole_log(str(ROOT / "samples" / "actuator" / "actuator.yaml"))  # a length input
    assert internal_units(actuator, [1500.0]) == (1500.0,) == file_units(actuator, [1500.0])
    watt = whole_log(str(ROOT / "tests" / "mechanisms" / "watt_circuit.yaml"))  # radians
    assert internal_units(watt, [1.75]) == (1.75,)


def test_the_whole_procedure_is_walked_whatever_the_files_outputs():
    path = str(ROOT / "samples" / "jansen_foot" / "jansen_foot.yaml")  # outputs: [foot], steps pruned in builds
    log = whole_log(path)
    assert log.order == 0 and not log.omitted
    c = assemblies(path, log)
    assert len(c.assemblies) == 8 and all("C.x" in a.values for a in c.assemblies)


@pytest.mark.parametrize("name, reason", [("slider_leg", "prismatic pair S"), ("class4", "class IV or higher")])
def test_a_group_it_cannot_reduce_is_an_error_naming_the_file(name, reason):
    path = str(ROOT / "tests" / "assemblies" / f"{name}.yaml")
    with pytest.raises(ProcedureError) as info:
        assemblies(path, whole_log(path))
    text = str(info.value)
    assert text.startswith(f"{path}:1: links: linkgen cannot count the assemblies")
    assert reason in text and "not counted" in text
