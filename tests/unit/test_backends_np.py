"""linkgen.backends.np: NAME_np.py carries the printed primitives the procedure calls, branch_at and
reach_at only where a chain needs them, and for a resolver mechanism no primitive at all (it runs the
standard-library module row by row)."""

from __future__ import annotations

from pathlib import Path

from linkgen.backends.np import BACKEND, RUNTIME, printed, runtime_sources
from linkgen.pipeline import build_log
from linkgen.primitives import PRIMITIVES
from linkgen.render.view import build_view

ROOT = Path(__file__).resolve().parents[2]


def _view(path: str):
    return build_view(build_log(str(ROOT / path), sweep=False))


def test_a_closed_form_kernel_carries_the_primitives_it_calls():
    view = _view("samples/fourbar/fourbar.yaml")
    text = "\n".join(runtime_sources(view))
    called = {s.function for s in view.log.steps if s.function}
    for name in PRIMITIVES:
        assert (f"def {name}(" in text) == (name in called), name
    assert printed("RRR_links", view.record_order).rstrip("\n") in text
    assert "def reach_at(" not in text and "def branch_at(" not in text


def test_reach_at_comes_with_a_reach():
    view = _view("tests/mechanisms/watt_circuit.yaml")
    assert view.log.reach is not None
    assert RUNTIME.source("reach").rstrip("\n") in "\n".join(runtime_sources(view))


def test_a_resolver_kernel_prints_no_primitive():
    view = _view("samples/sixbar_fig14/sixbar_fig14.yaml")
    text = "\n".join(runtime_sources(view))
    assert not any(f"def {name}(" in text for name in PRIMITIVES)
    assert RUNTIME.source("driver").rstrip("\n") in text


def test_the_backend_writes_one_file():
    view = _view("samples/slider_crank/slider_crank.yaml")
    assert BACKEND.files == ("NAME_np.py",)
    from linkgen.render import render_backend

    files = render_backend(BACKEND, view)
    assert list(files) == ["slider_crank_np.py"]
    compile(files["slider_crank_np.py"], "slider_crank_np.py", "exec")
