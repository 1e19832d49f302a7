"""The Python API's assemblies and instant centres (linkgen.api.Mechanism.assemblies, .centres)
are what ``linkgen assemblies`` and ``linkgen ic`` print: their records equal the commands' JSON
read back field by field, and a slider-crank's are the
hand calculation."""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

import linkgen
from linkgen.api import InputCountError
from linkgen.cli import cli

ROOT = Path(__file__).resolve().parents[1]
LINKGEN = Path(sys.executable).with_name("linkgen")
SLIDER = ROOT / "samples" / "slider_crank" / "slider_crank.yaml"
FIVEBAR = ROOT / "samples" / "fivebar" / "fivebar.yaml"
FIG14 = ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"


def _cli(*args: object) -> dict:
    done = CliRunner().invoke(cli, [*map(str, args), "--json"])
    assert (done.exit_code, done.stderr) == (0, ""), done.output
    out: dict = json.loads(done.stdout)
    return out


def _same(got: float, want: float | None) -> bool:
    return (want is None and not math.isfinite(got)) or got == want


@pytest.mark.parametrize("path, at", [(SLIDER, [90]), (FIVEBAR, [-30, 400]), (FIG14, None)],
                         ids=["slider_crank", "fivebar", "sixbar_fig14_sketch"])
def test_assemblies_are_the_commands_json(path: Path, at: list[float] | None):
    doc = _cli("assemblies", path, *(["--at", ",".join(map(str, at))] if at else []))
    found = linkgen.load(path).assemblies(at=at)
    census, log = found.census, found.log
    assert doc["mechanism"] == log.name and doc["count"] == len(census.assemblies)
    assert list(doc["inputs"].values()) == (at if at else [pytest.approx(math.degrees(i.sketch), abs=1e-12)
                                                           for i in log.inputs])
    assert doc["sketch"] == next((a.number for a in census.assemblies if a.sketch), None)
    for a, shown in zip(census.assemblies, doc["assemblies"], strict=True):
        assert (a.number, a.sketch, a.error) == (shown["number"], shown["sketch"], shown["length_error"])
        for name, (x, y) in shown["positions"].items():
            assert (a.values[f"{name}.x"], a.values[f"{name}.y"]) == (x, y)
        for name, s in shown["slides"].items():
            assert a.values[f"{name}.s"] == s
        for name, angle in shown["angles"].items():  # degrees: the file's unit
            assert math.degrees(a.values[f"{name}.phi"]) == pytest.approx(angle, abs=1e-12)
    assert found.json() == json.dumps(doc, indent=2) + "\n"


@pytest.mark.parametrize("path, at, rates", [(SLIDER, [90], [-360]), (SLIDER, None, None), (FIVEBAR, None, [1, 2]),
                                             (FIG14, [250], None)],
                         ids=["slider_crank", "slider_crank_sketch", "fivebar", "sixbar_fig14"])
def test_centres_are_the_commands_json(path: Path, at: list[float] | None, rates: list[float] | None):
    given = [(flag, ",".join(map(str, v))) for flag, v in (("--at", at), ("--rates", rates)) if v]
    doc = _cli("ic", path, *(x for pair in given for x in pair))
    found = linkgen.load(path).centres(at=at, rates=rates)
    table = found.table
    assert doc["mechanism"] == found.log.name and doc["row_status"] == table.row_status
    if at:  # through radians and back: to rounding
        assert doc["inputs"] == pytest.approx(at, rel=1e-15)
    if rates:
        assert doc["rates"] == pytest.approx(rates, rel=1e-15)
    for c, shown in zip(table.centres, doc["centres"], strict=True):
        assert (c.centre.name, c.centre.kind, list(c.centre.links), c.status) == \
            (shown["centre"], shown["class"], shown["links"], shown["status"])
        assert all(_same(getattr(c, f), shown[f]) for f in ("x", "y", "ux", "uy", "sigma")), (c, shown)
        assert found.by_name(shown["centre"]) == c
    assert found.json() == json.dumps(doc, indent=2) + "\n"


def test_slider_crank_by_hand():
    """Crank 20 at 90 deg, rod 65, slide 13 below the crank's pivot: B at x = +-sqrt(65^2 - 33^2) = +-56,
    the block's slide x - 76 (drawn at 76); the crank's centre with the frame at its pivot, the rod's
    at infinity (the crank is parallel to the normal of the slide at B: the rod translates)."""
    m = linkgen.load(SLIDER)
    found = m.assemblies(at=[90]).census.assemblies
    assert [(a.values["B.x"], a.values["B.y"], a.values["S.s"]) for a in found] == [(56, -13, -20), (-56, -13, -132)]
    centres = m.centres(at=[90])
    crank, rod = centres.by_name("ic:frame:crank"), centres.by_name("ic:frame:rod")
    assert (crank.x, crank.y, crank.status) == (0, 0, 0)
    assert rod.status == 1 and math.isnan(rod.x) and abs(rod.ux) < 1e-15 and abs(abs(rod.uy) - 1) < 1e-15


@pytest.mark.parametrize("call, argument", [(lambda m: m.assemblies(at=[1]), "at"),
                                            (lambda m: m.centres(at=[1, 2, 3]), "at"),
                                            (lambda m: m.centres(rates=[1]), "rates")])
def test_one_value_per_input(call, argument):
    with pytest.raises(InputCountError, match=r"given; fivebar has 2 inputs \(theta_O1, theta_O2\)") as exc:
        call(linkgen.load(FIVEBAR))
    assert exc.value.argument == argument


def test_the_commands_name_the_option_given_a_wrong_count():
    """As a user runs them: a usage error (exit 2) naming the option."""
    for args, option in ((["assemblies", FIVEBAR, "--at", "1"], "--at"), (["ic", FIVEBAR, "--rates", "1"], "--rates")):
        done = subprocess.run([str(LINKGEN), *map(str, args)], capture_output=True, text=True)
        assert done.returncode == 2 and done.stdout == ""
        assert f"invalid value for '{option}': 1 value given; fivebar has 2 inputs" in done.stderr
