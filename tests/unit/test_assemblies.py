"""The package's entry: the whole procedure's log, and groups it cannot count refused as errors that
name the file (input values in the file's units: tests/unit/test_units.py)."""

from __future__ import annotations

from pathlib import Path

import pytest

from linkgen.assemblies import assemblies, whole_log
from linkgen.errors import ProcedureError

ROOT = Path(__file__).resolve().parents[2]


def test_the_whole_procedure_is_walked_whatever_the_files_outputs():
    path = str(ROOT / "samples" / "jansen_foot" / "jansen_foot.yaml")  # outputs: [foot], steps pruned in builds
    log = whole_log(path)
    assert log.order == 0 and not log.omitted
    c = assemblies(path, log)
    assert len(c.assemblies) == 8 and all("C.x" in a.values for a in c.assemblies)


@pytest.mark.parametrize("name, reason", [("assemblies/moving_slot", "not a block on a slide fixed to the frame")])
def test_a_group_it_cannot_reduce_is_an_error_naming_the_file(name, reason):
    path = str(ROOT / "tests" / f"{name}.yaml")
    with pytest.raises(ProcedureError) as info:
        assemblies(path, whole_log(path))
    text = str(info.value)
    assert text.startswith(f"{path}:1: links: linkgen cannot count the assemblies")
    assert reason in text and "not counted" in text
