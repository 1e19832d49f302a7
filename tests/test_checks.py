"""options.checks off (docs/mechanism-format.md, Options): the programs compute positions and rates only.

The same mechanism built with the checks on is the independent route: every row it gives, the
unchecked build gives with the same bits (a singular row's positions too, its rates as the formulas
give them), its failures with the same codes; every other status is 0.  C, Python and Octave compute
the same bits, the numpy kernel agrees by the spec's rule, and no language reports a conditioning.
"""

from __future__ import annotations

import importlib.util
import math
import sys
from pathlib import Path

import numpy as np
import pytest
from programs import ROOT, compare, different_bits, parse, run_c, run_numpy, run_octave, run_python

from linkgen import status
from linkgen.pipeline import build_log
from linkgen.render import render_all
from linkgen.writer import write_all

MECHANISMS = {
    "parallelogram": "singular rows at its change points",
    "nongrashof_near_change": "near-singular rows and a failed one",
    "triad_near_singular": "a resolver, a near-singular row",
}
LONG = {"nongrashof_near_change", "triad_near_singular"}  # make test keeps one mechanism (its time budget)


@pytest.fixture(scope="module", params=[pytest.param(n, marks=pytest.mark.long if n in LONG else ()) for n in
                                        MECHANISMS])
def builds(request, tmp_path_factory):
    """(log, folder) of the mechanism built with the checks on and off."""
    path = str(ROOT / "tests" / "mechanisms" / f"{request.param}.yaml")
    out = {}
    for checks in (True, False):
        log = build_log(path, options={"checks": checks})
        folder = tmp_path_factory.mktemp(f"{request.param}_{checks}")
        write_all(render_all(log), str(folder))
        out[checks] = (log, folder)
    return out


def test_the_rows_are_those_of_the_checked_build(builds):
    (on_log, on_dir), (off_log, off_dir) = builds[True], builds[False]
    header, on_rows, on_status = parse(run_c(on_log, on_dir))
    _, off_rows, off_status = parse(run_c(off_log, off_dir))
    assert any(status.reason(s) in (status.SINGULAR, status.NEAR_SINGULAR) for s in on_status)  # a case to drop
    assert off_status == [s if status.failed(s) else 0 for s in on_status]
    levels = [c.quantity in ("position", "angle") for c in on_log.columns]
    for k, (a, b, st) in enumerate(zip(on_rows, off_rows, on_status)):
        for name, x, y, position in zip(header, a, b, levels):
            if position or not status.singular(st):
                assert x == y or (math.isnan(x) and math.isnan(y)), (k, name, x, y)


def test_every_language_computes_the_same_rows(builds):
    log, folder = builds[False]
    c = run_c(log, folder)
    assert not different_bits(c, run_python(log, folder))
    compare(log, c, run_numpy(log, folder))


@pytest.mark.long
def test_octave_computes_the_same_bits(builds):
    log, folder = builds[False]
    assert not different_bits(run_c(log, folder), run_octave(log, folder))


def _module(folder: Path, name: str):
    spec = importlib.util.spec_from_file_location(name, folder / f"{name}.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module  # the numpy kernel of a resolver mechanism imports its Python beside it
    spec.loader.exec_module(module)
    return module


def test_no_language_reports_a_conditioning(builds):
    log, folder = builds[False]
    name = log.name
    one = [i.start for i in log.inputs]
    rates = [i.speed for i in log.inputs]
    row = _module(folder, name).solve(one, rates, [0.0] * len(one))
    rows = _module(folder, f"{name}_np").solve(np.array([one]), np.array(rates), np.zeros(len(one)))
    assert "sigma" not in row and "sigma" not in rows and row["status"] == rows["status"][0] == 0
    header = (folder / f"{name}.h").read_text(encoding="utf-8")
    solve_m = (folder / f"{name}_solve.m").read_text(encoding="utf-8")
    assert "sigma[" not in header and "out.sigma" not in solve_m
    checked = builds[True][1]
    assert "sigma[" in (checked / f"{name}.h").read_text(encoding="utf-8")
    if not log.groups:  # no chain measures its conditioning: the resolver's choice of block needs none
        assert "sigma" not in (folder / f"{name}.c").read_text(encoding="utf-8")
