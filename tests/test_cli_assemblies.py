"""linkgen assemblies on the command line: the table, the JSON, the SVGs, and its faults (one
``linkgen: error:`` line; a bad --at is a usage error, exit 2; a group it cannot count, exit 1)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

from linkgen.cli import cli

ROOT = Path(__file__).resolve().parents[1]
LINKGEN = Path(sys.executable).with_name("linkgen")
FIG14 = ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"
FIVEBAR = ROOT / "samples" / "fivebar" / "fivebar.yaml"


def _run(*args) -> tuple[int, str, str]:
    result = CliRunner().invoke(cli, ["assemblies", *map(str, args)])
    if result.exception is not None and not isinstance(result.exception, SystemExit):
        raise result.exception
    return result.exit_code, result.stdout, result.stderr


def test_the_table_and_the_json_agree():
    code, text, err = _run(FIG14, "--at", "250")
    assert (code, err) == (0, "")
    assert text.splitlines()[0] == "sixbar_fig14 at theta_J7 = 250 deg: 4 assemblies"
    code, out, err = _run(FIG14, "--at", "250", "--json")
    doc = json.loads(out)
    assert (code, err, doc["count"], doc["inputs"]) == (0, "", 4, {"theta_J7": 250.0})
    for a in doc["assemblies"]:
        row = next(line for line in text.splitlines() if line.split()[:1] == [str(a["number"])])
        assert (" * " in f" {row} ") == a["sketch"]
        assert f"{a['positions']['J4'][0]:.6g}, {a['positions']['J4'][1]:.6g}" in row


def test_a_negative_input_and_two_inputs_are_read():
    code, out, _ = _run(FIVEBAR, "--at=-30,400", "--json")
    assert code == 0 and json.loads(out)["inputs"] == {"theta_O1": -30.0, "theta_O2": 400.0}


def test_the_svgs_are_written_all_at_once_and_the_same_every_time(tmp_path: Path):
    code, out, err = _run(FIG14, "-o", tmp_path / "figs")
    names = sorted(p.name for p in (tmp_path / "figs").iterdir())
    assert (code, err) == (0, "") and names == [f"sixbar_fig14_assembly_{k}.svg" for k in range(1, 5)]
    assert out.splitlines()[-4:] == [str(tmp_path / "figs" / n) for n in names]
    first = {n: (tmp_path / "figs" / n).read_bytes() for n in names}
    assert _run(FIG14, "-o", tmp_path / "figs", "--json")[0] == 0
    assert {n: (tmp_path / "figs" / n).read_bytes() for n in names} == first


@pytest.mark.parametrize("at, message", [
    ("30", "invalid value for '--at': 1 value given; fivebar has 2 inputs (theta_O1, theta_O2)"),
    ("30,x", "invalid value for '--at': '30,x' is not a list of numbers: give one value per input, separated by "
             "commas (e.g. 90 or 10,20)"),
    ("30,nan", "invalid value for '--at': '30,nan': every value must be finite and at most 1e+30 in size"),
])
def test_a_bad_at_is_a_usage_error(at, message):
    assert _run(FIVEBAR, "--at", at) == (2, "", f"linkgen: error: {message}. See 'linkgen assemblies --help'.\n")


def test_a_group_it_cannot_count_is_an_error_and_nothing_is_written(tmp_path: Path):
    path = ROOT / "tests" / "assemblies" / "moving_slot.yaml"  # a block in a slot of a moving rocker
    code, out, err = _run(path, "-o", tmp_path / "figs")
    assert (code, out) == (1, "")
    assert err.startswith(f"linkgen: error: {path}:1: links: linkgen cannot count the assemblies")
    assert err.count("\n") == 1 and "the prismatic pair S" in err
    assert not (tmp_path / "figs").exists()


@pytest.mark.long
def test_the_command_runs_as_a_process():
    done = subprocess.run([str(LINKGEN), "assemblies", str(FIG14), "--json"], capture_output=True, text=True)
    assert (done.returncode, done.stderr, json.loads(done.stdout)["count"]) == (0, "", 4)


def test_help():
    code, out, err = _run("--help")
    assert (code, err) == (0, "") and out.startswith("Usage: linkgen assemblies [OPTIONS] MECHANISM")
    assert "--at" in out and "--json" in out and "-o, --outdir" in out
