"""linkgen.evaluate: a chain mechanism's rows evaluated a block at a time are, bit for bit, the rows of one
call of its kernel over them all (the row solver's own tests: test_rowsolver.py)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from linkgen import evaluate as evaluator
from linkgen.pipeline import build_log
from linkgen.rows import input_rows
from linkgen.rowsolver import Row

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("name", ["fourbar", "jansen"])
def test_blocks_of_rows_are_one_call_over_all_rows(name, monkeypatch):
    log = build_log(str(ROOT / "samples" / name / f"{name}.yaml"), sweep=False)
    values, rates, accs = input_rows(log, 101)
    whole = evaluator.evaluate(log, values, rates, accs)
    monkeypatch.setattr(evaluator, "BLOCK", 16)  # 7 blocks, the last of 5 rows
    blocks = evaluator.evaluate(log, values, rates, accs)
    assert np.array_equal(whole.status, blocks.status) and whole.status.shape == (101,)
    assert whole.sigma.keys() == blocks.sigma.keys()
    for n in whole.sigma:
        assert np.array_equal(whole.sigma[n], blocks.sigma[n], equal_nan=True)
    assert list(whole.values) == list(blocks.values)
    for v in whole.values:
        for a, b in zip(whole.values[v], blocks.values[v], strict=True):
            assert a.shape == b.shape == (101,) and np.array_equal(a, b, equal_nan=True)


def test_row_records_are_the_rows_fields_with_nan_where_a_row_has_none():
    rows = [Row({"a": (1.0, 2.0), "b": (5.0,)}, {}, {}, 0), Row({"a": (3.0, 4.0)}, {}, {}, 31)]
    records = evaluator.RowRecords(rows, {"b": 1, "a": 2})
    assert list(records) == ["a", "b"] and len(records) == 2
    assert [f.tolist() for f in records["a"]] == [[1.0, 3.0], [2.0, 4.0]]
    b, = records["b"]
    assert b[0] == 5.0 and np.isnan(b[1]) and records["b"] is records["b"]
