"""linkgen.mobility: Grübler's count 3(n - 1) - 2 j1 - j2... here with revolute and prismatic pairs
(one freedom each, a compound hinge on k links being k - 1 pairs), against the rank of the constraints
at the sketch, which sees an exactly drawn parallelogram's redundant constraint and dead centres."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

from linkgen.errors import InputError
from linkgen.loader import parse
from linkgen.mobility import _clearly_driven, _Jacobian, _rank, check_mobility, grubler
from linkgen.model import Mechanism
from linkgen.topology import analyse
from linkgen.validate import read_mechanism, validate

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "bench"))
from ladders import ladder  # noqa: E402

FOURBAR = """linkgen: 1
name: fourbar
joints: {O1: [0, 0], A: [20, 0], B: [80, 50], O2: [90, 0]}
links:
  frame: {joints: [O1, O2], fixed: true}
  crank: [O1, A]
  coupler: [A, B]
  rocker: [O2, B]
inputs:
  - {joint: O1, link: crank, relative_to: frame, range: [0, 360]}
"""
# A parallelogram O1 A B O2 with a third crank O3 C parallel to the other two: C on the coupler.
DOUBLE_PARALLELOGRAM = """linkgen: 1
name: double_parallelogram
joints: {O1: [0, 0], A: [20, 20], C: [50, 20], B: [80, 20], O2: [60, 0], O3: [30, 0]}
links:
  frame: {joints: [O1, O2, O3], fixed: true}
  crank: [O1, A]
  coupler: [A, C, B]
  rocker: [O2, B]
  third: [O3, C]
inputs:
  - {joint: O1, link: crank, relative_to: frame, range: [0, 90]}
"""
# The four-bar with a dyad B-C-O3 hinged at B, which is then on three links.
COMPOUND = FOURBAR.replace("O2: [90, 0]}", "O2: [90, 0], C: [120, 60], O3: [140, 0]}").replace(
    "frame: {joints: [O1, O2]", "frame: {joints: [O1, O2, O3]").replace(
    "  rocker: [O2, B]\n", "  rocker: [O2, B]\n  dyad1: [B, C]\n  dyad2: [C, O3]\n")
SLIDER_CRANK = """linkgen: 1
name: slider_crank
joints: {O: [0, 0], A: [10, 8], B: [45, -5], S: {type: prismatic, at: [45, -5], axis: 0}}
links:
  frame: {joints: [O, S], fixed: true}
  crank: [O, A]
  rod: [A, B]
  block: [B, S]
inputs:
  - {joint: O, link: crank, relative_to: frame, range: [0, 360]}
"""
FIVEBAR = """linkgen: 1
name: fivebar
joints: {O1: [0, 0], A: [15, 0], P: [45, 40], B: [75, 0], O2: [60, 0]}
links:
  frame: {joints: [O1, O2], fixed: true}
  crank1: [O1, A]
  link1: [A, P]
  link2: [P, B]
  crank2: [O2, B]
inputs:
  - {joint: O1, link: crank1, relative_to: frame, range: [0, 360]}
  - {joint: O2, link: crank2, relative_to: frame, range: [0, 360]}
"""


def mechanism(text: str) -> Mechanism:
    return validate(parse(text, "m.yaml"), "m.yaml")


@pytest.mark.parametrize("text, links, pairs, count, mobility", [
    (FOURBAR, 4, 4, 1, 1),
    (DOUBLE_PARALLELOGRAM, 5, 6, 0, 1),  # rigid by the count; the third crank's constraint is redundant
    (COMPOUND, 6, 7, 1, 1),  # B is two pairs
    (SLIDER_CRANK, 4, 4, 1, 1),
    (FIVEBAR, 5, 5, 2, 2),
])
def test_the_count_and_the_mobility_at_the_sketch(text: str, links: int, pairs: int, count: int, mobility: int):
    m = mechanism(text)
    assert 3 * (links - 1) - 2 * pairs == count == grubler(m)
    assert check_mobility(m, 100.0) == (count, mobility)


def test_a_double_parallelogram_drawn_off_parallel_is_a_structure():
    m = mechanism(DOUBLE_PARALLELOGRAM.replace("O3: [30, 0]", "O3: [31, 0]"))
    with pytest.raises(InputError, match="the mechanism cannot move: its links form a rigid structure"):
        check_mobility(m, 100.0)


def test_a_four_bar_drawn_in_line_is_at_a_dead_centre_and_fine_just_off_it():
    text = FOURBAR.replace("A: [20, 0], B: [80, 50], O2: [90, 0]", "A: [20, 0], B: [70, 0], O2: [40, 0]")
    with pytest.raises(InputError, match="drawn at a dead centre") as info:
        check_mobility(mechanism(text), 70.0)
    assert (info.value.line, info.value.key) == (3, "joints.A")
    assert check_mobility(mechanism(text.replace("A: [20, 0]", "A: [20, 1]")), 70.0) == (1, 1)


@pytest.mark.parametrize("text, inputs, message", [
    (FIVEBAR, 1, "the mechanism has 2 degrees of freedom (Grübler's count gives 2), but only 1 input is given"),
    (FOURBAR, 2, "the mechanism has 1 degree of freedom (Grübler's count gives 1), but 2 inputs are given"),
])
def test_one_input_per_degree_of_freedom(text: str, inputs: int, message: str):
    lines = text.splitlines(keepends=True)
    given = [k for k, line in enumerate(lines) if line.startswith("  - {joint:")]
    if inputs < len(given):
        del lines[given[-1]]
    else:
        lines.append("  - {joint: O2, link: rocker, relative_to: frame, range: [0, 10]}\n")
    with pytest.raises(InputError, match=message.replace("(", r"\(").replace(")", r"\)")):
        check_mobility(mechanism("".join(lines)), 100.0)


TWO_FOURBARS = """linkgen: 1
name: two_fourbars
joints: {O1: [0, 0], A: [20, 0], B: [80, 50], O2: [90, 0], O3: [0, -100], C: [20, -100], D: [80, -50], O4: [90, -100]}
links:
  frame: {joints: [O1, O2, O3, O4], fixed: true}
  crank1: [O1, A]
  coupler1: [A, B]
  rocker1: [O2, B]
  crank2: [O3, C]
  coupler2: [C, D]
  rocker2: [O4, D]
inputs:
  - {joint: O1, link: crank1, relative_to: frame, range: [0, 360]}
  - {joint: O3, link: crank2, relative_to: frame, range: [0, 360]}
"""


def test_two_inputs_must_drive_independent_motions():
    """Two four-bars on one frame: one input on each, not two on one (the other is left free)."""
    assert check_mobility(mechanism(TWO_FOURBARS), 150.0) == (2, 2)
    same = TWO_FOURBARS.replace("{joint: O3, link: crank2,", "{joint: O2, link: rocker1,")
    with pytest.raises(InputError, match="the input on O2 drives the same motion as the input on O1, so links "
                                         "crank2, coupler2 and rocker2 are left free"):
        check_mobility(mechanism(same), 150.0)


ROOT = Path(__file__).resolve().parents[2]
FILES = sorted([*ROOT.glob("samples/*/*.yaml"), *ROOT.glob("tests/mechanisms/*.yaml")])


def _dense_verdict(m: Mechanism, scale: float) -> tuple[int, bool]:
    """The mobility by the singular values of the whole Jacobian, and whether each input raises its rank."""
    jac = _Jacobian(m, scale)
    c = jac.dense(jac.constraints())
    rows = [jac.dense([jac.input_row(i)])[0] for i in m.inputs]
    ranks = [_rank(np.vstack([c, *rows[:k]])) for k in range(len(rows) + 1)]
    return jac.n - ranks[0], all(b == a + 1 for a, b in zip(ranks, ranks[1:]))


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.stem)
def test_the_sparse_elimination_agrees_with_the_singular_values(path: Path):
    """Every sample and test mechanism is driven without redundancy: the sparse elimination says so, and
    so do the dense singular values (the mobility is Grübler's count, each input raises the rank)."""
    m = read_mechanism(str(path))
    scale = analyse(m).length_scale
    assert _clearly_driven(_Jacobian(m, scale))
    assert _dense_verdict(m, scale) == (grubler(m), True)


def test_a_redundant_constraint_is_left_to_the_singular_values():
    m = mechanism(DOUBLE_PARALLELOGRAM)
    assert not _clearly_driven(_Jacobian(m, 100.0))
    assert _dense_verdict(m, 100.0) == (1, True)


def test_a_long_chain_is_driven_by_its_crank():
    """60 dyads hung one on the next (bench/ladders.py): 361 columns, decided by the sparse elimination
    as by the singular values."""
    m = mechanism(ladder(60))
    scale = analyse(m).length_scale
    assert _clearly_driven(_Jacobian(m, scale))
    assert _dense_verdict(m, scale) == (1, True) and check_mobility(m, scale) == (1, 1)
