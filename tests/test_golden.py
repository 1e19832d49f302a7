"""Golden files: every sample's generated files are checked in under expected/.

Rebuild in memory and compare byte for byte.  After an intended change run
`make regen` (or LINKGEN_UPDATE_GOLDEN=1 pytest tests/test_golden.py) and review
the diff like source code: it is what users see in their own CI.
"""

from __future__ import annotations

import difflib
import os
from pathlib import Path

import pytest

from linkgen.pipeline import build_log
from linkgen.render import render_all

ROOT = Path(__file__).resolve().parents[1]
SAMPLES = sorted(ROOT.glob("samples/*/*.yaml"))


@pytest.mark.parametrize("sample", SAMPLES, ids=lambda p: p.stem)
def test_sample_matches_its_golden_files(sample: Path):
    files = render_all(build_log(str(sample)), motion=True)
    expected = sample.parent / "expected"
    if os.environ.get("LINKGEN_UPDATE_GOLDEN"):
        expected.mkdir(exist_ok=True)
        for old in expected.iterdir():
            old.unlink()
        for name, data in files.items():
            (expected / name).write_bytes(data)
    on_disk = {p.name: p.read_bytes() for p in expected.iterdir()} if expected.is_dir() else {}
    assert sorted(on_disk) == sorted(files), "the set of generated files changed; run `make regen`"
    for name, data in files.items():
        if on_disk[name] != data:
            diff = "".join(difflib.unified_diff(on_disk[name].decode().splitlines(True), data.decode().splitlines(True),
                                                f"expected/{name}", f"rebuilt/{name}", n=2))
            pytest.fail(f"{sample.stem}/{name} differs from its golden file (run `make regen` if intended):\n"
                        f"{diff[:4000]}")


@pytest.mark.parametrize("sample", SAMPLES, ids=lambda p: p.stem)
def test_output_hygiene(sample: Path):
    for name, data in render_all(build_log(str(sample)), motion=True).items():
        text = data.decode("utf-8")
        assert "\r" not in text, name
        assert text.endswith("\n") and not text.endswith("\n\n"), name
        assert not [n for n, line in enumerate(text.splitlines(), 1) if line != line.rstrip()], name
        if not name.endswith((".md", ".json", ".svg")):
            assert "\t" not in text, name
        if name.endswith((".c", ".h", ".m", ".py")):
            assert text.isascii(), name
