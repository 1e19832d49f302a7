"""A build evaluates the file's sweep once (linkgen.sweepdata.file_rows): the conditioning over
the sweep, the engineering summary and the plots read one result where their logs compute the
same steps with the same settings, and what they read is what evaluating the sweep anew gives."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

import linkgen.analysis.sweep  # noqa: F401 - the modules whose evaluations are counted
import linkgen.evaluate
import linkgen.summary.compute  # noqa: F401
from linkgen import sweepdata
from linkgen.evaluate import evaluate, input_rows
from linkgen.pipeline import build_log
from linkgen.render import render_all
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
