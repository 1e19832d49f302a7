"""The command line: what each command prints, and its faults and usage errors: one
``linkgen: error: ...`` line, no traceback.

File-system faults and bad mechanism files exit 1, command-line usage errors 2 (README,
Usage).  Every case runs in-process through click's CliRunner and as a real process
(``.venv/bin/linkgen``).  Permission faults need a user whom permissions stop: when the
tests run as root they run linkgen as ``nobody``.
"""

from __future__ import annotations

import json
import math
import os
import pwd
import shutil
import stat
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

import pytest
from click.testing import CliRunner

from linkgen.cli import cli
from linkgen.policy import GOOD_LEVER

ROOT = Path(__file__).resolve().parents[1]
LINKGEN = Path(sys.executable).with_name("linkgen")
FOURBAR = ROOT / "samples" / "fourbar" / "fourbar.yaml"
OUTPUTS = sorted(p.name for p in (FOURBAR.parent / "expected").iterdir())
COMMANDS = ["build", "run", "lj", "candidates", "procedure", "check"]


@dataclass
class Outcome:
    code: int
    out: str
    err: str


def _in_process(args: list, cwd: Path, monkeypatch: pytest.MonkeyPatch) -> Outcome:
    monkeypatch.chdir(cwd)
    result = CliRunner().invoke(cli, [str(a) for a in args])
    if result.exception is not None and not isinstance(result.exception, SystemExit):
        raise result.exception
    return Outcome(result.exit_code, result.stdout, result.stderr)


def _in_subprocess(args: list, cwd: Path, **extra) -> Outcome:
    assert LINKGEN.exists(), "the tests run with the virtual environment's python, beside its linkgen script"
    done = subprocess.run([str(LINKGEN), *map(str, args)], cwd=cwd, capture_output=True, text=True, **extra)
    return Outcome(done.returncode, done.stdout, done.stderr)


@pytest.fixture(params=["cli-runner", "subprocess"])
def linkgen(request, monkeypatch):
    """Run linkgen with args in cwd: in-process or as a process."""
    if request.param == "cli-runner":
        return lambda args, cwd: _in_process(args, cwd, monkeypatch)
    return _in_subprocess


def snapshot(folder: Path) -> dict[str, tuple]:
    """Every entry of folder, hidden ones too: kind, mode, inode, and for files the time and bytes."""
    out = {}
    for path in sorted(folder.iterdir()):
        st = path.lstat()
        regular = stat.S_ISREG(st.st_mode)
        out[path.name] = (st.st_mode, st.st_ino) + ((st.st_mtime_ns, path.read_bytes()) if regular else ())
    return out


def assert_error(outcome: Outcome, message: str, code: int = 1) -> None:
    assert (outcome.code, outcome.out, outcome.err) == (code, "", f"linkgen: error: {message}\n")


FAULTS = {
    # name: (set-up in the working directory -> arguments, the message)
    "output directory is a file": (lambda d: (d / "f").touch() or ["build", FOURBAR, "-o", "f"],
                                   "f: not a directory"),
    "output directory inside a file": (lambda d: (d / "f").touch() or ["build", FOURBAR, "-o", "f/out"],
                                       "f: not a directory (the output directory f/out would be inside it)"),
    "csv inside a file": (lambda d: (d / "f").touch() or ["run", FOURBAR, "-o", "f/x.csv"],
                          "f: not a directory"),
    "csv under /proc": (lambda d: ["run", FOURBAR, "-o", "/proc/linkgen.csv"],
                        "/proc: cannot create files in this directory: the file system does not allow it"),
    "output directory under /proc": (lambda d: ["build", FOURBAR, "-o", "/proc/linkgen"],
                                     "/proc/linkgen: cannot create the directory: the file system does not allow it"),
    "csv is a directory": (lambda d: (d / "out").mkdir() or ["run", FOURBAR, "-o", "out"],
                           "out: a directory is in the way of this output file; move or remove it"),
    "csv names a directory": (lambda d: ["run", FOURBAR, "-o", "out/"],
                              "out/: names a directory; give the file to write the CSV to"),
    "output directory no one may write": (lambda d: ["build", FOURBAR, "-o", "/sys/kernel"],
                                          "/sys/kernel: cannot create files in this directory: permission denied"),
    "check without a build": (lambda d: ["build", FOURBAR, "--check", "-o", "none"],
                              "none: no such directory: nothing to check against (linkgen build writes it)"),
    "check against a file": (lambda d: (d / "f").touch() or ["build", FOURBAR, "--check", "-o", "f"],
                             "f: not a directory: nothing to check against (linkgen build writes it)"),
}


@pytest.mark.parametrize("case", sorted(FAULTS))
def test_file_system_fault(linkgen, tmp_path: Path, case: str):
    setup, message = FAULTS[case]
    args = setup(tmp_path)
    before = snapshot(tmp_path)
    assert_error(linkgen(args, tmp_path), message)
    assert snapshot(tmp_path) == before


@pytest.mark.parametrize("command", COMMANDS)
def test_mechanism_file_missing_unreadable_or_a_directory(linkgen, tmp_path: Path, command: str):
    assert_error(linkgen([command, "missing.yaml"], tmp_path),
                 "missing.yaml: cannot read the mechanism file: No such file or directory")
    (tmp_path / "m.yaml").mkdir()
    assert_error(linkgen([command, "m.yaml"], tmp_path), "m.yaml: cannot read the mechanism file: Is a directory")
    # a file no one may read, root included: the first page of the process's memory is not mapped
    assert_error(linkgen([command, "/proc/self/mem"], tmp_path),
                 "/proc/self/mem: cannot read the mechanism file: Input/output error")


def test_a_directory_in_the_way_changes_nothing(linkgen, tmp_path: Path):
    out = tmp_path / "out"
    assert linkgen(["build", FOURBAR, "-o", "out"], tmp_path).code == 0
    (out / "fourbar.c").unlink()  # a file the failed build would have created
    (out / "fourbar.md").unlink()
    (out / "fourbar.md").mkdir()
    before = snapshot(out)
    assert_error(linkgen(["build", FOURBAR, "-o", "out"], tmp_path),
                 "out/fourbar.md: a directory is in the way of this output file; move or remove it")
    assert snapshot(out) == before


def test_full_standard_output():
    with open("/dev/full", "w") as full:
        done = subprocess.run([str(LINKGEN), "run", FOURBAR], stdout=full, stderr=subprocess.PIPE, text=True)
    assert (done.returncode, done.stderr) == (1, "linkgen: error: standard output: no space left on the device\n")


def _unprivileged() -> dict | None:
    """subprocess.run arguments for a user whom permissions stop: nobody when the tests run as root;
    None when nobody cannot run linkgen (its python under /root, say)."""
    if os.geteuid() != 0:
        return {}
    try:
        nobody = pwd.getpwnam("nobody")
        who = {"user": nobody.pw_uid, "group": nobody.pw_gid, "extra_groups": []}
        subprocess.run([str(LINKGEN), "--version"], check=True, capture_output=True, **who)
    except (KeyError, OSError, subprocess.SubprocessError):
        return None
    return who


@pytest.fixture
def as_user(tmp_path: Path):
    """(run linkgen as an ordinary user, a directory that user can reach)."""
    who = _unprivileged()
    if who is None:
        pytest.skip("root is not stopped by permissions, and nobody cannot run this linkgen "
                    "(the root-proof faults under /proc and /sys run instead)")
    if not who:
        yield lambda args, cwd: _in_subprocess(args, cwd), tmp_path
        return
    shared = Path(tempfile.mkdtemp(prefix="linkgen-test-"))  # tmp_path's parents are closed to nobody
    shared.chmod(0o755)
    yield lambda args, cwd: _in_subprocess(args, cwd, **who), shared
    shutil.rmtree(shared)


def test_unwritable_output_directory(as_user):
    run, folder = as_user
    (folder / "out").mkdir(mode=0o555)
    (folder / "out").chmod(0o555)
    assert_error(run(["build", FOURBAR, "-o", "out"], folder),
                 "out: cannot create files in this directory: permission denied")
    assert list((folder / "out").iterdir()) == []
    (folder / "out").chmod(0o755)


def test_read_only_output_file(as_user):
    run, folder = as_user
    out = folder / "out"
    out.mkdir()
    out.chmod(0o777)
    assert run(["build", FOURBAR, "-o", "out"], folder).code == 0
    (out / "fourbar.h").chmod(0o444)
    (out / "fourbar.c").unlink()
    before = snapshot(out)
    assert_error(run(["build", FOURBAR, "-o", "out"], folder),
                 "out/fourbar.h: the file is read-only; make it writable (chmod u+w) or remove it")
    assert snapshot(out) == before


def test_unreadable_mechanism_file(as_user):
    run, folder = as_user
    shutil.copy(FOURBAR, folder / "m.yaml")
    (folder / "m.yaml").chmod(0)
    assert_error(run(["build", "m.yaml", "-o", "out"], folder),
                 "m.yaml: cannot read the mechanism file: Permission denied")
    assert not (folder / "out").exists()


@pytest.mark.parametrize("mask", [0o022, 0o002, 0o077])
def test_modes_follow_the_umask(tmp_path: Path, mask: int):
    old = tmp_path / "out"
    old.mkdir()
    (old / "fourbar.c").write_bytes(b"old\n")
    (old / "fourbar.c").chmod(0o600)
    for args in (["build", FOURBAR, "-o", "out"], ["run", FOURBAR, "-o", "out/sweep.csv"],
                 ["build", FOURBAR, "-o", "new/deeper"]):
        done = subprocess.run([str(LINKGEN), *map(str, args)], cwd=tmp_path, umask=mask, capture_output=True)
        assert done.returncode == 0, done.stderr
    assert sorted(p.name for p in old.iterdir()) == sorted(OUTPUTS + ["sweep.csv"])
    files = [*old.iterdir(), *(tmp_path / "new" / "deeper").iterdir()]
    assert {p.name: stat.S_IMODE(p.stat().st_mode) for p in files} == {p.name: 0o666 & ~mask for p in files}
    for folder in (tmp_path / "new", tmp_path / "new" / "deeper"):
        assert stat.S_IMODE(folder.stat().st_mode) == 0o777 & ~mask


USAGE = {
    # arguments: (what the message names, the command whose help it points to)
    ("build", FOURBAR, "--bogus"): ("'--bogus'", "linkgen build"),
    ("build", FOURBAR, "--order", "3"): ("'--order'", "linkgen build"),
    ("build", FOURBAR, "--real", "half"): ("'--real'", "linkgen build"),
    ("run", FOURBAR, "--samples", "1"): ("'--samples'", "linkgen run"),
    ("lj", FOURBAR, "--step", "x"): ("'--step'", "linkgen lj"),
    ("build",): ("'MECHANISM'", "linkgen build"),
    ("nope", FOURBAR): ("'nope'", "linkgen"),
    ("--bogus",): ("'--bogus'", "linkgen"),
    (): ("missing command", "linkgen"),
}


@pytest.mark.parametrize("args", sorted(USAGE, key=str), ids=lambda a: " ".join(map(str, a)) or "nothing")
def test_usage_error(linkgen, tmp_path: Path, args: tuple):
    named, command = USAGE[args]
    outcome = linkgen(list(args), tmp_path)
    assert (outcome.code, outcome.out) == (2, "")
    assert outcome.err.startswith("linkgen: error: ") and outcome.err.count("\n") == 1
    assert named in outcome.err
    assert outcome.err.endswith(f" See '{command} --help'.\n")


def test_step_out_of_range_names_the_steps(linkgen, tmp_path: Path):
    steps = linkgen(["procedure", FOURBAR], tmp_path).out.count("\n")
    outcome = linkgen(["lj", FOURBAR, "--step", str(steps + 1)], tmp_path)
    assert_error(outcome, f"invalid value for '--step': {steps + 1} is not a step: give 0 (before step 1) to "
                          f"{steps}. See 'linkgen lj --help'.", code=2)
    assert linkgen(["lj", FOURBAR, "--step", str(steps)], tmp_path).code == 0


@pytest.mark.parametrize("args", [["--help"], ["-h"], *([c, "--help"] for c in COMMANDS)], ids=" ".join)
def test_help_still_works(linkgen, tmp_path: Path, args: list):
    outcome = linkgen(args, tmp_path)
    assert (outcome.code, outcome.err) == (0, "")
    assert outcome.out.startswith(f"Usage: linkgen {args[0] + ' ' if len(args) > 1 else ''}[OPTIONS]")


def test_version(linkgen, tmp_path: Path):
    from linkgen import __version__

    outcome = linkgen(["--version"], tmp_path)
    assert (outcome.code, outcome.out, outcome.err) == (0, f"linkgen, version {__version__}\n", "")


# -- what the commands print (in-process) ---------------------------------------------

def _ok(args: list, cwd: Path, monkeypatch: pytest.MonkeyPatch) -> str:
    """stdout of a command that succeeds; build writes its one-line summary to stderr, nothing else."""
    outcome = _in_process(args, cwd, monkeypatch)
    err = outcome.err
    if args[0] == "build" and "--check" not in args:
        lines = err.splitlines()
        assert len(lines) == 1 and lines[0].startswith("linkgen: ") and " rows: " in lines[0], err
        err = ""
    assert (outcome.code, err) == (0, ""), outcome.err
    return outcome.out


def test_procedure_is_the_four_bars_by_the_paper(tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    """Fix the frame, turn the crank to A by the input, close the 3R chain A-B-O2, then angles and P."""
    lines = _ok(["procedure", FOURBAR], tmp_path, monkeypatch).splitlines()
    assert [line[:30].split() for line in lines[:3]] == [["1", "fixed", "frame"], ["2", "crank_input", "A"],
                                                         ["3", "RRR_links", "B"]]
    assert sorted(line[20:30].strip() for line in lines[3:]) == ["P", "coupler", "crank", "rocker"]
    assert all(line[3:5] == "  " and line[19] == " " for line in lines)


def test_build_real_overrides_the_file_and_every_file_says_what_it_computes_in(tmp_path: Path,
                                                                              monkeypatch: pytest.MonkeyPatch):
    _ok(["build", FOURBAR, "-o", "out", "--real", "long double"], tmp_path, monkeypatch)
    out = tmp_path / "out"
    log = json.loads(next(out.glob("*.json")).read_text())
    assert log["options"]["real"] == "long double"
    firsts = {p.name: next(line for line in p.read_text().splitlines() if "Generated by linkgen" in line)
              for p in out.iterdir() if p.suffix not in (".json", ".svg", ".html")}
    assert len(firsts) == 8 and all("Real type: " in line for line in firsts.values()), firsts
    assert sorted(n for n, line in firsts.items() if "Real type: long double." in line) == [
        "fourbar.c", "fourbar.h", "fourbar.md", "fourbar_main.c"]  # the others say double, and why


def test_build_settings_override_the_file_and_every_file_states_them(tmp_path: Path,
                                                                     monkeypatch: pytest.MonkeyPatch):
    _ok(["build", ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml", "-o", "out", "--tolerance", "1e-8",
         "--iterations", "12", "--no-polish", "--predictor", "0",
         "--strategy", "fixed-point"], tmp_path, monkeypatch)
    out = tmp_path / "out"
    options = json.loads(next(out.glob("*.json")).read_text())["options"]
    assert {k: options[k] for k in ("strategy", "tolerance", "iterations", "polish", "predictor")} == {
        "strategy": "fixed-point", "tolerance": 1e-8, "iterations": 12, "polish": False, "predictor": 0}
    stated = "resolver fixed-point (tolerance 1e-08, at most 12 iterations, polish off, predictor order 0)"
    firsts = [next(line for line in p.read_text().splitlines() if "Generated by linkgen" in line)
              for p in out.iterdir() if p.suffix not in (".json", ".svg", ".html")]
    assert len(firsts) == 8 and all(stated in line for line in firsts), firsts


def test_a_setting_out_of_range_is_a_usage_error(tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    outcome = _in_process(["build", FOURBAR, "--tolerance", "0.5"], tmp_path, monkeypatch)
    assert outcome.code == 2 and "'--tolerance'" in outcome.err and not (tmp_path / "build").exists()


def test_run_prints_the_sweep_solved_by_hand(tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    """At theta = pi the crank puts A at (-20, 0); B is where circles of radius sqrt(6100) about A and
    sqrt(2600) about O2 (90, 0) meet above the axis: x = -20 + 15600/220, y = sqrt(6100 - (15600/220)^2)."""
    args = ["run", FOURBAR, "--samples", "3", "--order", "0", "--outputs", "B"]
    text = _ok(args, tmp_path, monkeypatch)
    head, *rows = [line.split(",") for line in text.splitlines()]
    assert head == ["theta_O1", "B.x", "B.y", "status"]
    theta0, x0, y0, status0 = (float(v) for v in rows[0])  # the sketch
    assert (theta0, x0, status0) == (0.0, 80.0, 0.0) and y0 == pytest.approx(50.0, rel=1e-14)
    theta, x, y, status = (float(v) for v in rows[1])
    assert (theta, status) == (math.pi, 0)
    along = 15600 / 220
    assert x == pytest.approx(-20 + along, rel=1e-14) and y == pytest.approx(math.sqrt(6100 - along**2), rel=1e-14)
    assert float(rows[2][0]) == 2 * math.pi and rows[2][1:] == rows[0][1:]
    assert _ok([*args, "-o", "sweep.csv"], tmp_path, monkeypatch) == ""
    assert (tmp_path / "sweep.csv").read_text() == text


def test_lj_prints_the_pairs_on_each_link_before_step_1(tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    """Before step 1 every pair is unknown: 1 where the file lists a pair on a link."""
    legend, text = _ok(["lj", FOURBAR, "--step", "0"], tmp_path, monkeypatch).split("\n\n", 1)
    assert legend.startswith("# Rows are pairs, columns links") and "-1 (-2): a known one" in legend
    title, head, *rows = text.splitlines()
    assert title == "# LJ-matrix before step 1"
    links = head.split()
    assert links[:4] == ["frame", "crank", "coupler", "rocker"]
    on = {"frame": {"O1", "O2"}, "crank": {"O1", "A"}, "coupler": {"A", "B"}, "rocker": {"O2", "B"}}
    for row in rows:
        pair, *entries = row.split()
        assert [int(e) for e in entries[:4]] == [int(pair in on[lk]) for lk in links[:4]]
    last = _ok(["lj", FOURBAR], tmp_path, monkeypatch).split("\n\n")[-1].splitlines()
    assert all(int(e) <= 0 for row in last[2:] for e in row.split()[1:])  # every pair known at the end


def test_candidates_without_and_with_an_add_link(tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    assert _ok(["candidates", FOURBAR, "--json"], tmp_path, monkeypatch) == "[]\n"
    assert "without an Add-link" in _ok(["candidates", FOURBAR], tmp_path, monkeypatch)
    sixbar = ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"
    ranked = json.loads(_ok(["candidates", sixbar, "--json"], tmp_path, monkeypatch))
    usable = [c for c in ranked if c["usable"] and c["lever"] >= GOOD_LEVER]
    assert usable and ranked[: len(usable)] == usable  # a poor lever or no closure after the others
    assert [c["norm"] for c in usable] == sorted(c["norm"] for c in usable)  # ranked by |f|
    lines = _ok(["candidates", sixbar], tmp_path, monkeypatch).splitlines()
    assert lines[0].endswith(f"{len(ranked)} candidates, ranked by |f| at the probe input (a lever below "
                             f"{GOOD_LEVER:g} last)")
    assert lines[1].startswith(f"  1. {'-'.join(ranked[0]['pairs'])}  |f| = ") and lines[1].endswith("<- chosen")


def test_check_passes_on_a_fresh_build_and_shows_a_changed_file(tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    written = _ok(["build", FOURBAR, "-o", "out"], tmp_path, monkeypatch).split()
    assert sorted(Path(p).name for p in written) == OUTPUTS
    assert _ok(["build", FOURBAR, "--check", "-o", "out"], tmp_path, monkeypatch) == ""
    page = tmp_path / "out" / "fourbar.md"
    page.write_text(page.read_text().replace("fourbar", "FOURBAR", 1))
    outcome = _in_process(["build", FOURBAR, "--check", "-o", "out"], tmp_path, monkeypatch)
    assert outcome.code == 1
    assert outcome.out.startswith("--- out/fourbar.md (on disk)\n+++ out/fourbar.md (rebuilt)\n")
    assert "\n-" in outcome.out and "FOURBAR" in outcome.out

