"""The LJ-matrix of the paper's Table 1 and its states."""

from __future__ import annotations

from pathlib import Path

import pytest

from linkgen.ljmatrix import DENSE_COLUMNS, LJTable, states, text
from linkgen.pipeline import build_log
from linkgen.steplog import LJColumn

ROOT = Path(__file__).resolve().parents[2]


def test_slider_crank_states_follow_table_1():
    log = build_log(str(ROOT / "tests" / "mechanisms" / "slider_crank.yaml"), sweep=False)
    seq = states(log)
    assert [c.name for c in seq[0].columns] == ["frame", "crank", "rod", "block", "theta_O"]
    assert seq[0].rows == ("O", "A", "B", "S")
    # before step 1 every pair is unknown: 1 revolute, 2 prismatic
    assert seq[0].entries == ((1, 1, 0, 0, 0), (0, 1, 1, 0, 1), (0, 0, 1, 1, 0), (2, 0, 0, 2, 2))
    # step 1 fixes the frame: O is known, and so is the line of S (its guide is the frame)
    assert seq[1].entries == ((-1, -1, 0, 0, 0), (0, 1, 1, 0, 1), (0, 0, 1, 1, 0), (-2, 0, 0, -2, -2))
    # step 2 turns the crank (A), step 3 closes the 2R1P chain (B)
    assert seq[2].entries[1] == (0, -1, -1, 0, -1)
    assert seq[3].entries[2] == (0, 0, -1, -1, 0)
    assert all(e <= 0 for row in seq[-1].entries for e in row)


def test_add_link_column_appears_at_its_step():
    log = build_log(str(ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"), sweep=False)
    seq = states(log)
    (add,) = log.add_links
    before, after = seq[add.step - 1], seq[add.step]
    assert add.name not in [c.name for c in before.columns]
    assert after.columns[-1].name == add.name
    k, u = add.pairs
    column = [row[-1] for row in after.entries]
    assert column[after.rows.index(k)] == -1 and column[after.rows.index(u)] == 1
    # the ternary link is a truss of three binary links (rule i)
    assert {c.name for c in seq[0].columns} >= {"ternary:J2-J4", "ternary:J2-J5", "ternary:J4-J5"}


def test_text_table_is_aligned():
    log = build_log(str(ROOT / "samples" / "fourbar" / "fourbar.yaml"), sweep=False)
    lines = text(states(log)[0]).splitlines()
    assert lines[0].split() == ["frame", "crank", "coupler", "rocker", "theta_O1"]
    assert lines[1].split() == ["O1", "1", "1", "0", "0", "0"]


def test_text_right_aligns_the_entries_under_their_link():
    columns = (LJColumn("frame", "member", ("O", "S"), "frame"), LJColumn("theta_O", "input", ("O", "A"), "crank"))
    table = LJTable(columns, ("O", "A", "S"), ((-1, -1), (0, 1), (-2, 0)))
    # widths 1, 5 and 7; two spaces between columns; the row names left-aligned
    assert text(table) == ("   frame  theta_O\n"
                           "O     -1       -1\n"
                           "A      0        1\n"
                           "S     -2        0\n")


@pytest.mark.parametrize("path", ["samples/sixbar_fig14/sixbar_fig14.yaml", "samples/double_triad/double_triad.yaml",
                                  "tests/mechanisms/slider_crank.yaml", "samples/jansen/jansen.yaml"])
def test_a_step_changes_only_the_rows_and_columns_it_shows(path: str):
    """Against the whole matrices before and after each step: every entry that differs, and every new
    column, is in the step's change, whose entries are those of the whole matrix after the step."""
    seq = states(build_log(str(ROOT / path), sweep=False))
    for before, after in zip(seq, seq[1:]):
        change = after.change(before)
        whole = dict(zip(after.rows, after.entries))
        names = [c.name for c in after.columns]
        old = {(r, c.name): e for r, es in zip(before.rows, before.entries) for c, e in zip(before.columns, es)}
        differ = {(r, n) for r in after.rows for n, e in zip(names, whole[r]) if old.get((r, n), 0) != e}
        new = set(names) - {c.name for c in before.columns}
        if change is None:
            assert not differ and not new
            continue
        shown = [c.name for c in change.columns]
        assert differ <= {(r, n) for r in change.rows for n in shown} and new <= set(shown)
        assert change.entries == tuple(tuple(whole[r][names.index(n)] for n in shown) for r in change.rows)
        assert all(any(e for e in es) for es in change.entries)  # no row of zeros


def test_a_wide_matrix_is_read_row_by_row():
    """Row by row: each pair's one nonzero entry and the columns where the whole matrix has it."""
    log = build_log(str(ROOT / "samples" / "double_triad" / "double_triad.yaml"), sweep=False)
    for state in (states(log)[0], states(log)[-1]):
        names = [c.name for c in state.columns]
        for (row, entry, on), r, es in zip(state.nonzero(), state.rows, state.entries):
            assert row == r and on == [n for n, e in zip(names, es) if e] and {e for e in es if e} == {entry}
    assert states(log)[0].dense == (len(log.lj.columns) <= DENSE_COLUMNS)
