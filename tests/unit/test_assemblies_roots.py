"""linkgen.assemblies.roots: a triad's solution is polynomial.solve's to the bit, made once and read
back by a later process (a new store on the same folder) without solving again; a solve that raises
is never kept."""

from __future__ import annotations

from fractions import Fraction
from typing import Any

import pytest

from linkgen import textcache
from linkgen.assemblies import polynomial, roots
from linkgen.assemblies.triad import NotReducible

# the Fig. 14 triad at its sketch (as in test_assemblies_polynomial.py): bases, the ternary's offsets, legs squared
FIG14 = ([(Fraction(0), Fraction(0)), (Fraction(100), Fraction(0)), (Fraction(-60), Fraction(100))],
         [(Fraction(0), Fraction(0)), (Fraction(105), Fraction(-5)), (Fraction(60), Fraction(10))],
         [Fraction(70**2), Fraction(5**2 + 65**2), Fraction(120**2 + 20**2)])
# a ternary similar to its base, every leg one length: a self-motion, no count (a special position)
BASES = [(Fraction(0), Fraction(0)), (Fraction(50), Fraction(0)), (Fraction(10), Fraction(40))]
SPECIAL = (BASES, [(bx, by) for bx, by in BASES], [Fraction(30**2)] * 3)


def _new_process(monkeypatch: pytest.MonkeyPatch, folder: str) -> None:
    """The store a new process opens on ``folder``."""
    monkeypatch.setattr(textcache, "store", lambda: textcache.Store(folder))


def _solves(monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """Counts polynomial.solve's calls (the exact route) from now on."""
    calls: list[int] = []
    exact = polynomial.solve

    def counted(*args: Any) -> roots.Solution:
        calls.append(1)
        return exact(*args)

    monkeypatch.setattr(polynomial, "solve", counted)
    return calls


def test_the_kept_solution_is_the_exact_routes_to_the_bit_and_is_not_solved_again(tmp_path, monkeypatch):
    expected = polynomial.solve(*FIG14, 200.0)
    assert expected.real_roots >= 2  # the Fig. 14 triad has more than one assembly: the roots are worth comparing
    calls = _solves(monkeypatch)
    _new_process(monkeypatch, str(tmp_path))
    first = roots.solve(*FIG14, 200.0)
    _new_process(monkeypatch, str(tmp_path))
    later = roots.solve(*FIG14, 200.0)
    assert first == expected and later == expected and calls == [1]
    assert [repr(r.theta) for r in later.roots] == [repr(r.theta) for r in expected.roots]
    assert roots.solve(*FIG14, 100.0) == polynomial.solve(*FIG14, 100.0) and calls == [1, 1, 1]  # another key


def test_a_solve_that_raises_is_not_kept(tmp_path, monkeypatch):
    calls = _solves(monkeypatch)
    for _ in range(2):
        _new_process(monkeypatch, str(tmp_path))
        with pytest.raises(NotReducible, match="special position"):
            roots.solve(*SPECIAL, 60.0)
    assert calls == [1, 1]
