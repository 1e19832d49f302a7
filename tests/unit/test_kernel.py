"""linkgen.kernel: the evaluator's numpy kernel is the log's NAME_np.py, rendered and executed once per
distinct text (found again by the log itself); a resolver mechanism's kernel carries its NAME.py; a
four-bar row it solves against the closed form (two circles meeting)."""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from linkgen.kernel import Records, at_order, column, kernel, runtime
from linkgen.pipeline import build_log

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def fourbar():
    return build_log(str(ROOT / "samples" / "fourbar" / "fourbar.yaml"), sweep=False)


def test_a_log_at_a_lower_order_keeps_the_columns_of_that_order(fourbar):
    low = at_order(fourbar, 0)
    assert low.order == 0 and at_order(fourbar, fourbar.order) is fourbar
    assert {c.quantity for c in low.columns} <= {"position", "angle"}
    assert len(low.columns) < len(fourbar.columns)


def test_the_kernel_is_made_once_per_text(fourbar):
    assert kernel(fourbar, 2) is kernel(fourbar, 2)
    assert kernel(fourbar, 0) is not kernel(fourbar, 2)
    again = replace(fourbar, samples=fourbar.samples)  # another log, equal: the same text
    assert again is not fourbar and kernel(again, 2) is kernel(fourbar, 2)
    assert kernel(replace(fourbar, samples=fourbar.samples + 1), 2) is not kernel(fourbar, 2)  # SAMPLES differs


def test_a_resolver_kernel_carries_its_standard_library_module():
    log = build_log(str(ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"), sweep=False)
    module = kernel(log, 2)
    assert module.ROWS.__name__ == log.name and module.ROWS.MECHANISM.groups == 1
    row = module.ROWS.solve([0.5], [1.0], [0.0], 2, {})
    out = module.solve(np.array([[0.5]]), [1.0], [0.0])
    assert out["status"][0] == row["status"] == 0
    assert math.isclose(out["J4.x"][0], row["J4.x"], rel_tol=1e-12)


def test_the_four_bar_closes_as_two_circles_meet(fourbar):
    """A at 20 mm from O1 at theta; B on circles of the coupler (78.10 = |AB| drawn) about A and of the
    rocker (50.99 = |O2B|) about O2 = (90, 0), on the sketch's side (B left of the line A->O2)."""
    theta = np.radians([0.0, 30.0, 95.0, 200.0])
    out = kernel(fourbar, 0).solve(theta[:, None], np.zeros((4, 1)), np.zeros((4, 1)), order=0)
    assert list(out["status"]) == [0, 0, 0, 0]
    for k, t in enumerate(theta):
        ax, ay = 20 * math.cos(t), 20 * math.sin(t)
        l1, l2 = math.hypot(60, 50), math.hypot(10, 50)
        dx, dy = 90 - ax, -ay
        d = math.hypot(dx, dy)
        along = (l1 * l1 - l2 * l2 + d * d) / (2 * d)
        h = math.sqrt(l1 * l1 - along * along)
        bx, by = ax + (along * dx - h * dy) / d, ay + (along * dy + h * dx) / d  # left of A->O2, as drawn
        assert math.isclose(out["B.x"][k], bx, rel_tol=0, abs_tol=1e-12 * 90)
        assert math.isclose(out["B.y"][k], by, rel_tol=0, abs_tol=1e-12 * 90)


def test_the_numpy_runtime_reads_a_status_as_linkgen_does():
    from linkgen import status

    codes = np.array([0, 5, 31, 42, 53, -64])
    got = runtime()["reason_of"](codes)
    assert list(np.asarray(got)) == [status.reason(int(c)) if c > 0 else 0 for c in codes]


def test_records_make_a_variables_arrays_when_read_and_keep_the_kernels_own():
    own = np.array([1.0, 2.0, 3.0])
    view = np.arange(6.0)[::2]
    records = Records([({"a": (own, 2.5, view)}, 3)])
    assert list(records) == ["a"] and len(records) == 1 and not records._made
    a = records["a"]
    assert a[0] is own  # the kernel's own array, not a copy
    assert a[1].tolist() == [2.5, 2.5, 2.5] and a[1].flags.writeable  # a number: a column of it
    assert a[2].tolist() == [0.0, 2.0, 4.0] and a[2].base is None  # a view of the caller's: copied
    assert records["a"] is a
    assert column(np.float32([1, 2, 3]), 3).dtype == np.float64  # another type: copied as float


def test_records_of_several_calls_are_their_rows_in_order():
    blocks = Records([({"a": (np.array([1.0, 2.0]), 7.0)}, 2), ({"a": (np.array([3.0]), 8.0)}, 1)])
    assert [f.tolist() for f in blocks["a"]] == [[1.0, 2.0, 3.0], [7.0, 7.0, 8.0]] and list(blocks) == ["a"]
