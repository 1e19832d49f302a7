"""Generated Python is clean under pyflakes' rules (no unused import, no undefined name),
for every sample, for pruned builds, where most of the runtime is left out, and for builds with
the links' directions as unit vectors (angles: unit) or angles in degrees (units: file)."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

import pytest

from linkgen.pipeline import build_log
from linkgen.render import render_all
from linkgen.writer import write_all

ROOT = Path(__file__).resolve().parents[1]


def _ruff() -> str:
    """The ruff binary of the Python running the tests (the `test` extra installs it; a venv's bin folder
    need not be on PATH): skipped locally when missing, a failure under CI."""
    try:
        from ruff import find_ruff_bin

        return find_ruff_bin()
    except (ImportError, FileNotFoundError):
        if os.environ.get("CI"):
            pytest.fail("ruff is required in CI (pip install -e '.[test]')")
        pytest.skip("ruff is not installed")


def test_generated_python_has_no_pyflakes_findings(tmp_path):
    ruff = _ruff()
    files = sorted(ROOT.glob("samples/*/expected/*.py"))
    for outputs, order in ((("J6",), 0), (("J5", "coupler"), 1)):
        log = build_log(str(ROOT / "samples/sixbar_fig14/sixbar_fig14.yaml"), outputs, order, sweep=False)
        out = tmp_path / f"{outputs[0]}_{order}"
        write_all(render_all(log), str(out))
        files.append(out / f"{log.name}.py")
    for name in ("fourbar", "inverted_slider"):  # angles: unit, its direction functions
        log = build_log(str(ROOT / f"samples/{name}/{name}.yaml"), sweep=False, options={"angles": "unit"})
        write_all(render_all(log), str(tmp_path / f"{name}_unit"))
        files += [tmp_path / f"{name}_unit" / f"{log.name}.py", tmp_path / f"{name}_unit" / f"{log.name}_np.py"]
    for name in ("fourbar", "double_triad"):  # units: file, solve() taking degrees (a resolver's too)
        log = build_log(str(ROOT / f"samples/{name}/{name}.yaml"), sweep=False, options={"units": "file"})
        write_all(render_all(log), str(tmp_path / f"{name}_deg"))
        files += [tmp_path / f"{name}_deg" / f"{log.name}.py", tmp_path / f"{name}_deg" / f"{log.name}_np.py"]
    done = subprocess.run([ruff, "check", "--no-cache", "--isolated", "--select", "F", *map(str, files)],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr
