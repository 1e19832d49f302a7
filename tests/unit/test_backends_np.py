"""linkgen.backends.np: NAME_np.py carries the printed primitives the procedure calls, branch_at and
reach_at only where a chain needs them, cos_sin where a primitive turns by an angle, and for a resolver
mechanism also the primitives of its blocks at order 1 (its Newton passes) and the resolver and the
sweep on lanes; in float it computes in float32."""

from __future__ import annotations

from pathlib import Path

from linkgen.backends.np import BACKEND, FAST, RUNTIME, printed, runtime_sources
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
        assert (f"def {name}(" in text or f"def {name}_still_" in text) == (name in called), name
    # the frame's pairs and the links' lengths hold still: the crank's and the rocker's angles and B's chain to O2
    # (with the coupler's and the rocker's lengths) take them so
    assert printed("RRR_links", view.record_order, still=("j2", "l1", "l2")).rstrip("\n") in text
    assert "def RRR_links(" not in text
    assert printed("link_angle", view.record_order).rstrip("\n") in text  # the coupler's: A and B move
    assert printed("link_angle", view.record_order, still=("j1",)).rstrip("\n") in text
    assert "def reach_at(" not in text and "def branch_at(" not in text


def test_reach_at_comes_with_a_reach():
    view = _view("tests/mechanisms/watt_circuit.yaml")
    assert view.log.reach is not None
    assert RUNTIME.source("reach").rstrip("\n") in "\n".join(runtime_sources(view))


def test_a_resolver_kernel_carries_its_blocks_primitives_at_order_1_and_the_sweep():
    view = _view("samples/sixbar_fig14/sixbar_fig14.yaml")
    text = "\n".join(runtime_sources(view))
    inside = {s.function for b in view.blocks for s in b.steps if s.function} | {"link_residual"}
    held_only = {"crank_input", "crank_angle"}  # outside the blocks, from the frame pivot J7 and the frame's angle
    for name in PRIMITIVES:
        assert (f"def {name}(" in text) == (name in view.log.runtime and name not in held_only), name
        assert (f"def {name}{FAST}(" in text) == (name in inside), name
    assert printed("RRR_links", 1, FAST).rstrip("\n") in text
    assert "def crank_input_still_j1_phi(" in text and "def crank_angle_still_phi(" in text
    assert "def link_angle(" in text and "def link_angle_still_j1(" in text  # J2 from J4; J2 from the pivot J1
    for name in ("driver", "resolver", "group", "sweep", "trig"):
        assert RUNTIME.source(name).rstrip("\n") in text


def test_the_kernel_computes_in_float32_for_float():
    from linkgen.render import render_backend

    for real, numpy_type in (("float", "float32"), ("double", "float64"), ("long double", "float64")):
        log = build_log(str(ROOT / "samples/fourbar/fourbar.yaml"), sweep=False, options={"real": real})
        text = render_backend(BACKEND, build_view(log))["fourbar_np.py"].decode()
        assert f"REAL = np.{numpy_type}" in text
        assert ("Real type: float." in text.splitlines()[0]) == (real == "float")


def test_the_backend_writes_one_file():
    view = _view("samples/slider_crank/slider_crank.yaml")
    assert BACKEND.files == ("NAME_np.py",)
    from linkgen.render import render_backend

    files = render_backend(BACKEND, view)
    assert list(files) == ["slider_crank_np.py"]
    compile(files["slider_crank_np.py"], "slider_crank_np.py", "exec")


def test_a_resolver_setting_the_lanes_lack_leaves_every_row_to_the_python_module():
    from linkgen.render import render_backend

    for options, lanes in (({}, True), ({"predictor": 0}, False), ({"polish": False}, False),
                           ({"strategy": "fixed-point"}, False), ({"tolerance": 1e-8}, True)):
        log = build_log(str(ROOT / "samples/sixbar_fig14/sixbar_fig14.yaml"), sweep=False, options=options)
        text = render_backend(BACKEND, build_view(log))["sixbar_fig14_np.py"].decode()
        assert f"lanes={lanes}," in text, options
