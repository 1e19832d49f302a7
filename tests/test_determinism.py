"""Byte-identical output: across processes, hash seeds, working folders and path forms."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from click.testing import CliRunner

from linkgen.cli import cli

ROOT = Path(__file__).resolve().parents[1]
FIG14 = ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"


def _build(cwd: Path, source: str, out: str, seed: str) -> dict[str, bytes]:
    env = dict(os.environ, PYTHONHASHSEED=seed)
    subprocess.run([sys.executable, "-m", "linkgen", "build", source, "-o", out], cwd=cwd, env=env, check=True,
                   capture_output=True)
    folder = cwd / out
    return {p.name: p.read_bytes() for p in sorted(folder.iterdir())}


def test_builds_are_identical_everywhere(tmp_path: Path):
    (tmp_path / "a").mkdir()
    (tmp_path / "b" / "deeper").mkdir(parents=True)
    local = tmp_path / "b" / "deeper" / FIG14.name
    local.write_bytes(FIG14.read_bytes())
    first = _build(tmp_path / "a", str(FIG14), "out", "0")
    second = _build(tmp_path / "b" / "deeper", FIG14.name, "elsewhere", "1")
    third = _build(tmp_path / "b", str(local.relative_to(tmp_path / "b")), "x/y", "4242")
    assert first == second == third
    assert len(first) == 16  # json, svg, md, h, c, main.c, py, _np.py, m, _solve.m; html and four plots; centres
    for data in first.values():
        assert str(tmp_path).encode() not in data  # no absolute paths


def test_check_passes_on_a_fresh_build_and_shows_a_diff_otherwise(tmp_path: Path):
    runner = CliRunner()
    out = str(tmp_path / "out")
    assert runner.invoke(cli, ["build", str(FIG14), "-o", out]).exit_code == 0
    assert runner.invoke(cli, ["build", "--check", str(FIG14), "-o", out]).exit_code == 0
    manual = tmp_path / "out" / "sixbar_fig14.md"
    manual.write_text(manual.read_text().replace("## The procedure", "## A procedure"))
    result = runner.invoke(cli, ["build", "--check", str(FIG14), "-o", out])
    assert result.exit_code == 1
    assert "-## A procedure" in result.output and "+## The procedure" in result.output
    (tmp_path / "out" / "sixbar_fig14.c").unlink()
    result = runner.invoke(cli, ["build", "--check", str(FIG14), "-o", out])
    assert result.exit_code == 1 and "sixbar_fig14.c" in result.output
