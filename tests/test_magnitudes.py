"""The supported magnitudes (docs/mechanism-format.md), tested at both ends: a four-bar, a
slider-crank and a resolver mechanism (the six-bar of Fig. 14) scaled to a length scale of
1e-30 and 1e30, driven at their own speed and at 1e30 and 1e-30 degrees per second.

Scaling a sketch by s and its input speed by k scales every position by s, velocity by s k,
acceleration by s k^2, angular velocity by k and angular acceleration by k^2, and keeps angles
and status codes: the scaled sweeps must be the unscaled one so transformed (the evaluator, the
generated C and Python; Octave on a few rows), and no row of status 0 holds a nan.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest
from programs import ROOT, build, compare, parse, run_c, run_octave, run_python, scales

from linkgen.evaluate import evaluate
from linkgen.pipeline import build_log
from linkgen.rows import input_rows
from linkgen.table import csv

MECHANISMS = ("fourbar", "slider_crank", "sixbar_fig14")
LENGTHS = {"tiny": 1e-30, "huge": 1e30}
SPEEDS = (None, 1e30, 1e-30)  # degrees per second; None: the sample's own
POWER = {"position": (1, 0), "velocity": (1, 1), "acceleration": (1, 2), "angle": (0, 0),
         "angular_velocity": (0, 1), "angular_acceleration": (0, 2)}  # (power of s, power of k)


def _sample(name: str) -> Path:
    return ROOT / "samples" / name / f"{name}.yaml"


def _scaled(name: str, length: float, speed: float | None, samples: int, folder: Path) -> tuple[Path, float, float]:
    """The sample drawn at the given length scale (just inside the range) and speed: the file,
    its factors s and k."""
    text = _sample(name).read_text(encoding="utf-8")
    s = length / build_log(str(_sample(name)), sweep=False).length_scale * (1 + 1e-12 if length < 1 else 1 - 1e-12)
    text = re.sub(r"(?<!range: )\[(-?[0-9.]+), (-?[0-9.]+)\]", lambda g: f"[{float(g[1]) * s!r}, {float(g[2]) * s!r}]",
                  text)
    own = float(re.search(r"speed: ([0-9.e+-]+)", text)[1])
    if speed is not None:
        text = text.replace(f"speed: {re.search(r'speed: ([0-9.e+-]+)', text)[1]}", f"speed: {speed!r}")
    text = re.sub(r"samples: \d+", f"samples: {samples}", text)
    path = folder / f"{name}.yaml"
    path.write_text(text, encoding="utf-8")
    return path, s, (speed if speed is not None else own) / own


@pytest.fixture(scope="module")
def references():
    """The unscaled sweeps, by the evaluator."""
    out = {}
    for name in MECHANISMS:
        log = build_log(str(_sample(name)))
        out[name] = (log, csv(log, evaluate(log, *input_rows(log, log.samples))))
    return out


def _check_scaled(reference, scaled_log, text: str, s: float, k: float) -> None:
    """The scaled sweep is the reference transformed; no status-0 row holds a nan."""
    ref_log, ref_text = reference
    _, ref_rows, ref_status = parse(ref_text)
    header, rows, status = parse(text)
    assert header == [c.name for c in scaled_log.columns] + ["status"]
    assert status == ref_status
    scale = scales(ref_log, ref_rows)
    factors = [s ** POWER[c.quantity][0] * k ** POWER[c.quantity][1] for c in scaled_log.columns]
    factors[0] = 1.0  # the input angle itself
    for row, ref, st in zip(rows, ref_rows, status):
        if st != 0:
            continue
        assert not any(math.isnan(x) for x in row), row
        for j, (x, want, f) in enumerate(zip(row, ref, factors)):
            assert abs(x / f - want) <= 1e-9 * max(scale[j], abs(want)), (header[j], x / f, want)


@pytest.mark.parametrize("speed", SPEEDS, ids=lambda v: "own" if v is None else f"{v:g}")
@pytest.mark.parametrize("length", sorted(LENGTHS), ids=str)
@pytest.mark.parametrize("name", MECHANISMS)
def test_a_scaled_sweep_is_the_sweep_scaled(name: str, length: str, speed: float | None, references, tmp_path):
    path, s, k = _scaled(name, LENGTHS[length], speed, 361, tmp_path)
    log = build(path, tmp_path / "out")
    assert LENGTHS[length] / 1.001 < log.length_scale < LENGTHS[length] * 1.001
    evaluator = csv(log, evaluate(log, *input_rows(log, log.samples)))
    _check_scaled(references[name], log, evaluator, s, k)
    c = run_c(log, tmp_path / "out")
    _check_scaled(references[name], log, c, s, k)
    compare(log, run_python(log, tmp_path / "out"), c)


@pytest.mark.parametrize("name", MECHANISMS)
def test_octave_at_both_ends(name: str, tmp_path):
    for length, speed in (("tiny", 1e-30), ("huge", 1e30)):
        folder = tmp_path / length
        folder.mkdir()
        path, s, k = _scaled(name, LENGTHS[length], speed, 7, folder)
        log = build(path, folder / "out")
        unscaled = build_log(str(_sample(name)))
        reference = (unscaled, csv(unscaled, evaluate(unscaled, *input_rows(unscaled, 7))))
        _check_scaled(reference, log, run_octave(log, folder / "out"), s, k)
