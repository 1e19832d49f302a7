"""linkgen.instant.figure: NAME_centres.svg, the finite centres marked and labelled, the Kennedy lines
clipped to the view, the centres it cannot draw listed."""

from __future__ import annotations

from pathlib import Path

from linkgen.instant.figure import _clip, label, render_centres_svg
from linkgen.pipeline import build_log

SAMPLES = Path(__file__).resolve().parents[2] / "samples"


def test_clip():
    box = (0.0, 0.0, 10.0, 10.0)
    assert _clip((5.0, 5.0), (1.0, 0.0), box) == ((0.0, 5.0), (10.0, 5.0))
    assert _clip((5.0, 20.0), (1.0, 0.0), box) is None
    assert _clip((0.0, 0.0), (1.0, 1.0), box) == ((0.0, 0.0), (10.0, 10.0))


def test_slider_crank_figure():
    log = build_log(str(SAMPLES / "slider_crank" / "slider_crank.yaml"))
    svg = render_centres_svg(log)
    assert svg == render_centres_svg(log)  # the same bytes
    labels = {label(log, c) for c in log.centres}
    assert labels == {"I12", "I13", "I14", "I23", "I24", "I34"}
    for drawn in ("I12", "I13", "I23", "I24", "I34"):
        assert f">{drawn}</text>" in svg
    assert "not drawn: I14 at infinity" in svg
    assert svg.count('stroke-opacity="0.35"') >= 2  # the Kennedy lines of I13 and I24
