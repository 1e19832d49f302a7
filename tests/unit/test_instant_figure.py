"""linkgen.instant.figure: NAME_centres.svg, the finite centres marked and labelled, the Kennedy lines
clipped to the view, the centres it cannot draw listed."""

from __future__ import annotations

import re
from pathlib import Path

from linkgen.instant.figure import LABEL_GAP, _clip, label, render_centres_svg
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


def test_centres_on_one_spot_get_their_labels_one_under_the_other():
    """The four-bar's sketch has its crank along the frame: by the textbook construction I13 (the lines O1-A
    and O2-B) falls on O2 with I14, and I24 (the lines A-B and O1-O2) on A with I23."""
    log = build_log(str(SAMPLES / "fourbar" / "fourbar.yaml"))
    svg = render_centres_svg(log)
    at = {m.group(3): (float(m.group(1)), float(m.group(2)))
          for m in re.finditer(r'<text x="([\d.]+)" y="([\d.]+)" fill="#[0-9a-f]+">(I\d\d)</text>', svg)}
    for a, b in (("I13", "I14"), ("I23", "I24")):
        assert at[a][0] == at[b][0] and at[b][1] - at[a][1] == LABEL_GAP
    spots = sorted(at.values())
    assert all(p != q for p, q in zip(spots, spots[1:]))  # no two labels on one place
