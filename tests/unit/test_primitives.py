"""linkgen.primitives: the runtime library printed as Python and exec'd once per order (what the
generated Python and the evaluator run): every primitive there, equal to the DSL's own evaluation
(tests/dsl_walk.py), its source shown in tracebacks, the numpy twin returning (status, sigma, ...) for a
whole column at once."""

from __future__ import annotations

import inspect
import linecache
import traceback

import numpy as np
import pytest
from dsl_walk import evaluate, rows, same

from linkgen.primitives import PRIMITIVES, numpy_backend, python_backend
from linkgen.primitives.dsl import record_fields


@pytest.mark.parametrize("order", [0, 1, 2])
def test_every_primitive_is_there_at_every_order_and_made_once(order: int):
    fns = python_backend(order)
    assert list(fns) == list(PRIMITIVES) == list(numpy_backend(order))
    assert python_backend(order) is fns  # cached: exec'd once a process


@pytest.mark.parametrize("name", list(PRIMITIVES))
def test_the_python_backend_is_the_dsl(name: str):
    prim = PRIMITIVES[name]
    for order in (0, 2):
        for row in rows(name, 10):
            st, sigma, fields = evaluate(prim, order, row)
            args = [tuple(row[f"{p.name}_{f}"] for f in record_fields(p.kind, order)) if p.is_record
                    else row[p.name] for p in prim.params]
            res = python_backend(order)[name](*args)
            res = (res,) if prim.status is None and len(prim.outputs) == 1 else res
            head = [x for x in (st, sigma) if x is not None]
            assert all(same(a, b) for a, b in zip(res, head))
            got = [x for record in res[len(head):] for x in record]
            assert len(got) == len(fields) and all(same(a, b) for a, b in zip(got, fields))


def test_the_source_is_shown_where_a_primitive_fails():
    """Under its own file name (linecache): a traceback quotes the line of the generated code."""
    fn = python_backend(2)["link_angle"]
    source = inspect.getsource(fn)
    assert source.startswith("def link_angle(j1, j2, off):")
    with pytest.raises(ValueError) as info:
        fn((0.0, 0.0), (1.0, 1.0, 0.0, 0.0, 0.0, 0.0), 0.0)  # j1 short of its rates
    frame = traceback.extract_tb(info.value.__traceback__)[-1]
    assert frame.filename == "<linkgen runtime python order 2>" and frame.line == linecache.getline(
        frame.filename, frame.lineno).strip() and "j1" in frame.line


def test_the_numpy_backend_always_gives_status_and_sigma():
    """A function that cannot fail gives status 0 and sigma 1 (broadcast over the column)."""
    x = np.array([0.0, 1.0, 2.0])
    zero = np.zeros(3)
    st, sigma, (the, dthe, ddthe) = numpy_backend(2)["offset_angle"]((x, zero + 1.0, zero), 0.5)
    assert np.array_equal(np.broadcast_to(st, (3,)), [0, 0, 0])
    assert np.array_equal(np.broadcast_to(sigma, (3,)), [1.0] * 3)
    assert np.array_equal(the, x + 0.5) and np.array_equal(dthe, [1.0] * 3)
