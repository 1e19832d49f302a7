"""linkgen.backends.np.spelling: the design parameters NAME_np.py offers are the sketch's constants under
the manual's names, with the values a hand measurement of the drawing gives."""

from __future__ import annotations

import math
from pathlib import Path

from linkgen.backends.np.spelling import Numpy
from linkgen.pipeline import build_log
from linkgen.render.view import build_view

ROOT = Path(__file__).resolve().parents[2]


def test_the_four_bar_parameters_are_its_drawn_lengths_and_pairs():
    log = build_log(str(ROOT / "samples" / "fourbar" / "fourbar.yaml"), sweep=False)
    view = build_view(log)
    params = {name: value for name, value, _ in Numpy(view).params()}
    assert params["O2.x"] == 90.0 and params["O2.y"] == 0.0
    assert math.isclose(params["l_coupler"], math.hypot(60, 50), rel_tol=1e-15)  # A(20,0) to B(80,50)
    assert math.isclose(params["l_rocker"], math.hypot(10, 50), rel_tol=1e-15)  # B(80,50) to O2(90,0)
    assert params["step2.l"] == 20.0  # the crank O1-A
    # P from B along B -> A: (r.d, d x r) / |d|^2 with r = (-20, 20), d = (-60, -50): 200/6100, -2200/6100
    assert (params["step4.along"], params["step4.across"]) == (2 / 61, -22 / 61)
