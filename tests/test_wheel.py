"""The wheel carries the templates: build it, install it in a fresh venv, build a sample."""

from __future__ import annotations

import subprocess
import sys
import sysconfig
import venv
from pathlib import Path

import pytest

from linkgen.pipeline import build_log
from linkgen.render import render_all

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.long
def test_installed_wheel_builds_a_sample(tmp_path: Path):
    pytest.importorskip("hatchling")
    wheels = tmp_path / "wheels"
    subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation", "-q", "-w",
                    str(wheels), str(ROOT)], check=True, capture_output=True)
    (wheel,) = wheels.glob("linkgen-*.whl")
    env_dir = tmp_path / "venv"
    venv.create(env_dir, with_pip=True)
    python = env_dir / "bin" / "python"
    # the dependencies come from the environment running the tests (a path line in a .pth file adds
    # its folder only: the editable linkgen installed there is not seen)
    purelib = subprocess.run([str(python), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
                             check=True, capture_output=True, text=True).stdout.strip()
    Path(purelib, "dependencies.pth").write_text(sysconfig.get_paths()["purelib"] + "\n", encoding="utf-8")
    subprocess.run([str(python), "-m", "pip", "install", "--no-deps", "-q", str(wheel)], check=True,
                   capture_output=True)
    where = subprocess.run([str(python), "-c", "import linkgen.render as r; print(r.template_dir())"],
                           cwd=tmp_path, check=True, capture_output=True, text=True).stdout.strip()
    assert where.startswith(str(env_dir)), where
    sample = ROOT / "samples" / "fourbar" / "fourbar.yaml"
    subprocess.run([str(env_dir / "bin" / "linkgen"), "build", str(sample), "-o", "out"], cwd=tmp_path, check=True,
                   capture_output=True)
    built = {p.name: p.read_bytes() for p in (tmp_path / "out").iterdir()}
    assert built == render_all(build_log(str(sample)), motion=True)
