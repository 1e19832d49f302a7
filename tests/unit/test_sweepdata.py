"""A build evaluates the file's sweep once (linkgen.sweepdata.file_rows): the conditioning over
the sweep, the engineering summary and the plots read one result where their logs compute the
same steps with the same settings, and what they read is what evaluating the sweep anew gives.
sweep_of's places against the partial four-bar's closed forms, and thin on sweeps made by hand."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

import linkgen.analysis.sweep  # noqa: F401 - the modules whose evaluations are counted
import linkgen.evaluate
import linkgen.summary.compute  # noqa: F401
from linkgen import status, sweepdata
from linkgen.evaluate import evaluate
from linkgen.pipeline import build_log
from linkgen.render import render_all
from linkgen.rows import input_rows
from linkgen.table import columns

ROOT = Path(__file__).resolve().parents[2]
FIG14 = ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"
FOURBAR = ROOT / "samples" / "fourbar" / "fourbar.yaml"


def _sweeps(monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """Counts the evaluations of the file's whole sweep (its samples' rows) from here on."""
    sweeps: list[int] = []
    real = linkgen.evaluate.evaluate

    def counted(log, values, *args, **kwargs):  # type: ignore[no-untyped-def]
        if values.shape[0] == log.samples:
            sweeps.append(values.shape[0])
        return real(log, values, *args, **kwargs)

    for module in (sweepdata, sys.modules["linkgen.analysis.sweep"], sys.modules["linkgen.summary.compute"]):
        monkeypatch.setattr(module, "evaluate", counted)  # every evaluation of the analysis, summary and plots
    sweepdata._rows.cache_clear()
    return sweeps


@pytest.mark.parametrize("path, settings, evaluations", [(FIG14, {}, 1), (FOURBAR, {}, 1),
                                                          (FIG14, {"predictor": 0, "polish": False}, 2)],
                         ids=["sixbar_fig14", "fourbar", "sixbar_fig14_other_settings"])
def test_a_build_evaluates_the_sweep_once_per_settings(monkeypatch, path: Path, settings: dict, evaluations: int):
    """With the reference settings one evaluation serves all three; with others the plots have
    their own (the conditioning and the summary are the mechanism's, found with the reference ones)."""
    sweeps = _sweeps(monkeypatch)
    log = build_log(str(path), options=settings)
    files = render_all(log, motion=True)
    assert len(sweeps) == evaluations and f"{log.name}.html" in files

    values, rates, accs = input_rows(log, log.samples)
    with np.errstate(all="ignore"):
        anew = evaluate(log, values, rates, accs)  # the plots' rows evaluated again, with the log's settings
    sweep = sweepdata.sweep_of(log)
    names, data = columns(log, anew)
    assert sweep.names == tuple(names)
    assert np.array_equal(sweep.data, data, equal_nan=True) and np.array_equal(sweep.status, anew.status)
    for step, sigma in anew.sigma.items():  # nan where the step failed (a gap in the plot)
        kept = ~np.isnan(sweep.sigma[step])
        assert np.array_equal(sweep.sigma[step][kept], sigma[kept])


PARTIAL = ROOT / "tests" / "mechanisms" / "fourbar_partial.yaml"  # crank 40, coupler 50, rocker sqrt(2000), frame 90


def test_the_sweep_holds_the_closed_form_positions_and_fails_beyond_the_limit():
    """The partial four-bar: A on the crank circle (40 cos t, 40 sin t), B at the coupler's and the
    rocker's lengths, fixed pivots as drawn on every row; the rows beyond the crank's limit position
    (law of cosines: |A O2| = coupler + rocker) fail, and their moving places are nan."""
    log = build_log(str(PARTIAL))
    sweep = sweepdata.sweep_of(log)
    a, b, c, d = 40.0, 50.0, math.sqrt(2000.0), 90.0
    limit = math.acos((a * a + d * d - (b + c) ** 2) / (2 * a * d))
    theta = np.linspace(-math.pi, math.pi, 73)
    assert sweep.rows == 73 and np.array_equal(sweep.index, np.arange(73))
    assert np.allclose(sweep.column("theta_O1"), theta, rtol=0, atol=1e-12)
    assert sweep.names[0] == "theta_O1" and np.array_equal(sweep.column("B.x"), sweep.data[:, sweep.names.index("B.x")],
                                                           equal_nan=True)
    beyond = np.abs(theta) > limit
    assert 0 < beyond.sum() < 73
    assert np.array_equal(status.failed(sweep.status), beyond)
    for name, (x, y) in (("O1", (0.0, 0.0)), ("O2", (90.0, 0.0))):
        assert np.all(sweep.places[name][0] == x) and np.all(sweep.places[name][1] == y)
    (ax, ay), (bx, by) = sweep.places["A"], sweep.places["B"]
    assert np.all(np.isnan(ax[beyond])) and np.all(np.isnan(bx[beyond])) and np.all(np.isnan(by[beyond]))
    ok = ~beyond
    assert np.allclose(ax[ok], a * np.cos(theta[ok]), atol=1e-9)
    assert np.allclose(ay[ok], a * np.sin(theta[ok]), atol=1e-9)
    assert np.allclose(np.hypot(bx - ax, by - ay)[ok], b, atol=1e-9)
    assert np.allclose(np.hypot(bx - d, by)[ok], c, atol=1e-9)
    for step, sigma in sweep.sigma.items():  # a failed step is a gap; every step runs on a solved row
        assert np.all(np.isfinite(sigma[ok])) and np.all(sigma[ok] >= 0), step


def _hand_sweep(rows: int, data_nan: tuple[int, ...] = (), sigma_nan: tuple[int, ...] = (),
                place_nan: tuple[int, ...] = ()) -> sweepdata.Sweep:
    """A sweep made by hand: column 0 the row number, a second column, one sigma and one place,
    each with nan at the rows given."""
    k = np.arange(rows, dtype=float)
    data = np.column_stack([k, 2 * k])
    data[list(data_nan), 1] = np.nan
    sigma = 0.5 + 0 * k
    sigma[list(sigma_nan)] = np.nan
    x, y = k.copy(), -k
    x[list(place_nan)] = np.nan
    return sweepdata.Sweep(("u", "v"), data, np.zeros(rows, dtype=np.int64), {3: sigma}, {"P": (x, y)},
                           np.arange(rows))


@pytest.mark.parametrize("rows, limit, kept", [
    (21, 6, [0, 4, 8, 12, 16, 20]),  # every ceil(20 / 5) = 4th row
    (21, 5, [0, 5, 10, 15, 20]),  # every 5th
    (22, 6, [0, 5, 10, 15, 20, 21]),  # every ceil(21 / 5) = 5th, and the last row
])
def test_thin_keeps_every_kth_row_and_the_last(rows: int, limit: int, kept: list[int]):
    thinned = sweepdata.thin(_hand_sweep(rows), limit)
    assert thinned.index.tolist() == kept and thinned.rows <= limit
    assert thinned.data[:, 0].tolist() == kept and thinned.places["P"][1].tolist() == [-float(k) for k in kept]


def test_thin_leaves_a_short_sweep_alone():
    sweep = _hand_sweep(6)
    assert sweepdata.thin(sweep, 6) is sweep


def test_thin_keeps_both_ends_of_every_nan_run():
    """21 rows, every 4th kept (6 rows, the limit), and the nan runs of a column (rows 6-7), of a sigma
    (row 10 alone) and of a place (rows 13-15): both ends of each run stay, so every gap stays a gap
    (the limit bounds the every-k-th rows; the ends of the runs come on top)."""
    sweep = _hand_sweep(21, data_nan=(6, 7), sigma_nan=(10,), place_nan=(13, 14, 15))
    thinned = sweepdata.thin(sweep, 6)
    regular = [0, 4, 8, 12, 16, 20]
    assert thinned.index.tolist() == sorted(regular + [6, 7, 10, 13, 15])
    blank = (np.isnan(sweep.data).any(axis=1) | np.isnan(sweep.sigma[3]) | np.isnan(sweep.places["P"][0]))
    kept = thinned.index.tolist()
    for a, b in zip(kept, kept[1:]):  # no line between two kept rows across a left-out row with a nan
        assert not blank[a + 1:b].any() or blank[a] or blank[b], (a, b)
    assert np.isnan(thinned.data[thinned.index.tolist().index(6), 1])
    assert np.isnan(thinned.sigma[3][kept.index(10)]) and np.isnan(thinned.places["P"][0][kept.index(15)])
    assert thinned.sigma[3][kept.index(8)] == 0.5 and thinned.status.shape == (len(kept),)
