"""Large mechanisms: the test ladders of bench/ladders.py extract dyad by dyad, their chains keep the
conditioning the geometry gives them, and the manual grows linearly with the number of dyads (the
LJ-matrix is shown where it changes).  Timings are benchmarks (bench/scaling.py), never tests."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

from linkgen.analysis import Facts, with_facts
from linkgen.evaluate import evaluate
from linkgen.pipeline import analyse_file, draft
from linkgen.prune import prune
from linkgen.render import render_all
from linkgen.rows import input_rows

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "bench"))
from ladders import ladder, write_ladder  # noqa: E402


@pytest.mark.parametrize("kind", ["chain", "frame"])
def test_a_ladder_is_computed_dyad_by_dyad(tmp_path: Path, kind: str):
    n = 12
    _, topo, proc = analyse_file(str(write_ladder(n, tmp_path, kind)))
    assert (topo.grubler, topo.mobility) == (1, 1) and not proc.add_links
    chains = [s for s in proc.steps if s.function == "RRR_links"]
    assert [s.target for s in chains] == [f"A{k}" for k in range(1, n + 1)]
    assert all(s.branch == 1 for s in chains)
    if kind == "chain":  # then its two ternary links place the pairs the next dyad hangs on
        points = [s.target for s in proc.steps if s.function == "link_point"]
        assert points == [p for k in range(1, n) for p in (f"X{k}", f"Y{k}")]
        assert len(topo.members) == 1 + 1 + 6 * (n - 1) + 2
    else:  # the frame carries n + 1 pairs: its truss has n (n + 1) / 2 members (rule i)
        assert len(topo.members) == n * (n + 1) // 2 + 1 + 2 * n


def test_the_chain_ladder_keeps_the_first_cells_conditioning(tmp_path: Path):
    """By the mirror symmetry of the cells: |Xk Yk| = |X0 Y0| in every other cell, and every 3R chain has
    sigma = sin a, where a is the angle at A1 of the isosceles triangle X0 A1 Y0 (legs 20 sqrt 2),
    X0 on the crank (O at (-30, 20), length 30), Y0 at (0, -20): a closed form of the input angle."""
    n = 40
    _, topo, proc = analyse_file(str(write_ladder(n, tmp_path)))
    log = with_facts(draft(topo, proc), Facts())
    values, rates, accs = input_rows(log, 41)
    result = evaluate(log, values, rates, accs)
    assert not result.status.any()

    def at(name: str) -> np.ndarray:
        return np.array(result.values[proc.positions[name]][:2]) + np.array(log.origin)[:, None]

    theta = values[:, 0]
    x0 = np.array([-30 + 30 * np.cos(theta), 20 + 30 * np.sin(theta)])
    s0 = np.hypot(x0[0], x0[1] + 20)
    for k in range(2, n, 2):
        np.testing.assert_allclose(np.hypot(*(at(f"X{k}") - at(f"Y{k}"))), s0, rtol=1e-12)
    sigma = np.sin(2 * np.arcsin(s0 / (2 * 20 * math.sqrt(2))))
    for s in log.steps:
        if s.function == "RRR_links":
            np.testing.assert_allclose(result.sigma[s.number], sigma, rtol=1e-12)
    assert sigma.min() > 0.96


def _manual_bytes(n: int, folder: Path) -> int:
    _, topo, proc = analyse_file(str(write_ladder(n, folder)))
    return len(render_all(prune(with_facts(draft(topo, proc), Facts())))[f"ladder{n}.md"])


@pytest.mark.long  # two ladder manuals: about 15 s
def test_the_manual_grows_linearly_with_the_dyads(tmp_path: Path):
    """Bytes per dyad at 100 dyads within a tenth of those at 25 (a whole LJ-matrix per step grew as n^3);
    the change points, reach and conditioning are left out (their sections are a line per step)."""
    small, large = (_manual_bytes(n, tmp_path) / n for n in (25, 100))
    assert abs(large / small - 1) < 0.1


def test_a_ladder_file_names_its_kind_and_size():
    assert ladder(3).splitlines()[1] == "name: ladder3"
    assert ladder(3, "frame").splitlines()[1] == "name: frame_ladder3"
    with pytest.raises(ValueError):
        ladder(0)


def test_a_chain_of_dyads_is_counted_while_its_assemblies_are_few(tmp_path: Path):
    """A chain of n dyads has both branches of each of its n chains, 2^n assemblies, all of them
    closing at the sketch (each dyad's triangle is a right angle at A): the census lists them up
    to pipeline.LISTED and the build does not walk it beyond (2^11 = 2048), saying why."""
    from linkgen.pipeline import LISTED, build_log

    few = build_log(str(write_ladder(3, tmp_path)), sweep=False).assemblies
    assert few is not None and few.counted and len(few.listing) == 2 ** 3
    n = 11
    assert 2 ** n > LISTED >= 2 ** 3
    many = build_log(str(write_ladder(n, tmp_path)), sweep=False).assemblies
    assert many is not None and not many.counted and not many.listing
    assert f"its {n} two-link chains" in many.notes[0]


def test_a_large_mechanism_lists_no_instant_centres_but_says_why(tmp_path: Path):
    """Ten dyads: the frame, the crank and two links a dyad, 22 links and 231 centres, past the 20
    links the manual lists them for; its manual says so instead of a table."""
    from linkgen.pipeline import build_log
    from linkgen.render.view import CENTRE_LINKS

    log = build_log(str(write_ladder(10, tmp_path)))
    assert len(log.links) == 22 > CENTRE_LINKS and log.centres == ()
    manual = render_all(log)["ladder10.md"].decode()
    assert "The mechanism has 22 links, so 231 instant centres" in manual
