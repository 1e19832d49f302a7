"""A row's own pass from the warm start reads only its solving block's state off the solved pairs (a row
followed by continuation reads every block's): the other blocks' states are stale (nan lengths and
branches, orientation 0), the warm start is judged on the blocks both rows hold (on_path), and a stale
block is not tried until a continuation pass reads every block's state again.  The wrong-assembly guard
keeps its form on the solving block: its Add-link length fixes the group's configuration on its
branches, so a jump to another assembly is a correction of that length, refused beyond its share of
the predicted move (hand-computed cases below; the programs' rows against the 50-digit reference:
tests/test_properties.py, test_accuracy.py)."""

from __future__ import annotations

import math
from pathlib import Path
from types import SimpleNamespace

from linkgen.pipeline import build_log
from linkgen.rowsolver import RowSolver, runtime

ROOT = Path(__file__).resolve().parents[2]
NAN = math.nan
POLICY = SimpleNamespace(path_share=0.1, turn_share=0.01)
STALE = [NAN, NAN, NAN, 0.0]


def test_on_path_judges_the_blocks_with_a_state_only():
    on_path = runtime()["on_path"]
    prev = [[10.0, 1.0, 1.0, 1.0], list(STALE)]
    guess = [[11.0, 1.0, 1.0, 1.0], list(STALE)]
    assert on_path(prev, guess, [[11.05, 1.0, 1.0, 1.0], list(STALE)], [1, 1], 0.0, POLICY)  # 0.05 <= 0.1 * 1
    assert not on_path(prev, guess, [[11.2, 1.0, 1.0, 1.0], list(STALE)], [1, 1], 0.0, POLICY)  # a jump
    both = [[10.0, 1.0, 1.0, 1.0], [5.0, 1.0, 1.0, 0.0]]  # the last row read both blocks' states (a continuation)
    guess2 = [[11.0, 1.0, 1.0, 1.0], [5.5, 1.0, 1.0, 0.0]]
    assert on_path(both, guess2, [[11.05, 1.0, 1.0, 1.0], list(STALE)], [1, 1], 0.0, POLICY)  # the solver's alone
    assert not on_path(both, guess2, [[11.05, 1.0, 1.0, 1.0], [5.7, 1.0, 1.0, 0.0]], [1, 1], 0.0, POLICY)
    turned = [[11.05, 1.0, 1.0, -1.0], list(STALE)]  # the block's orientation turned: within 0.01 of the move
    assert not on_path(prev, guess, turned, [1, 1], 0.0, POLICY)
    assert on_path(prev, guess, turned, [1, 1], 0.05, POLICY)


def test_a_rows_state_holds_the_solving_block_and_a_continuation_reads_every_one():
    log = build_log(str(ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"), sweep=False)
    solver = RowSolver(log, log.order)
    sizes = solver.mech.sizes
    followed: list[bool] = []
    run = solver.run

    def spy(inputs, rates, accs, order, a, used, row):
        out = run(inputs, rates, accs, order, a, used, row)
        if not row:  # a continuation pass: every block's state read off its solution
            assert all(s[0] == s[0] for s in a)
            followed[-1] = True
        return out

    solver.run = spy  # type: ignore[method-assign]
    for k in range(8):
        followed.append(False)
        assert solver.solve([1.5 + 0.02 * k], [1.0], [0.0]).code == 0
        _, _, a, _, used, _ = solver.warm
        for j, s in enumerate(a):  # a row followed by continuation reads every block's state, else the solver's
            stale = all(x != x for x in s[:-1]) and s[-1] == 0.0
            assert stale == (not followed[k] and j != used[0]), (k, j, s)
            assert stale or all(x == x for x in s[:sizes[j]]), (k, j, s)
    assert followed[0] and not all(followed), followed  # the first row follows the sketch; the others, mostly not
