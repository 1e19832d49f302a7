"""render.svgwriter: numbers, escapes, attributes, path data, ticks and labels worked out by hand,
and a document that parses as SVG."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from linkgen.render.svgwriter import Svg, attrs, esc, fit, label, num, path_data, ticks

SVG = "{http://www.w3.org/2000/svg}"


def test_the_writer_by_hand():
    assert [num(x) for x in (2.0, -0.04, 12.34, -3.06, 0.0)] == ["2", "0", "12.3", "-3.1", "0"]
    nan = math.nan
    xs, ys = np.array([0.04, nan, 1.25, 2.0, 3.0, -0.06]), np.array([0.0, 1.0, -1.0, 2.0, nan, 5.0])
    assert path_data(xs, ys) == "M0 0L0 0M1.2 -1L2 2M-0.1 5L-0.1 5"
    assert ticks(0.0, 360.0, 6, (1.5, 3.0, 4.5, 9.0)) == [0.0, 90.0, 180.0, 270.0, 360.0]
    assert ticks(-25.0, 25.0, 4) == [-20.0, 0.0, 20.0]
    assert ticks(0.0, 1.05, 4) == [0.0, 0.5, 1.0]  # a step of at least 1.05 / 4 = 0.2625: 0.5
    assert [label(v, s) for v, s in ((90.0, 90.0), (0.25, 0.25), (-5e6, 2.5e6), (2.5e-5, 1e-5), (0.0, 1e6))] == [
        "90", "0.25", "-5e6", "2.5e-5", "0"]
    assert fit("abcdefghij", 55.0, 10.0) == "abcdefghij" and fit("abcdefghij", 44.0, 10.0) == "abcdefg…"


@pytest.mark.parametrize("x, digits, text", [
    (3.14159, 2, "3.14"), (2.5001, 0, "3"), (-0.4, 0, "0"), (-0.004, 2, "0"), (100.0, 1, "100"), (0.10, 3, "0.1"),
])
def test_num_keeps_the_digits_asked_and_drops_trailing_zeros(x: float, digits: int, text: str):
    assert num(x, digits) == text


def test_escapes_and_attributes():
    assert esc('a<b & "c">') == "a&lt;b &amp; &quot;c&quot;&gt;"
    # names: _ to -, a trailing _ dropped; numbers to 0.1, a data- one to 10 digits; None left out; order kept
    text = attrs({"stroke_width": 1.26, "data_x0": 1 / 3, "class_": "panel", "skip": None, "title": "x<y", "r": 3})
    assert text == ' stroke-width="1.3" data-x0="0.3333333333" class="panel" title="x&lt;y" r="3"'


def test_path_data_of_no_finite_point_is_empty_and_a_lone_point_is_a_dot():
    nan = math.nan
    assert path_data(np.array([nan, 1.0]), np.array([2.0, nan])) == ""
    assert path_data(np.array([1.0, nan, 2.0, 3.0]), np.array([-1.0, 0.0, 0.26, -0.26])) == "M1 -1L1 -1M2 0.3L3 -0.3"
    assert path_data(np.array([12.34]), np.array([-1234.56])) == "M12.3 -1234.6L12.3 -1234.6"


@pytest.mark.parametrize("width, size, bold, text", [
    (50.0, 10.0, False, "abcdefgh…"),  # room int(50 / 5.5) = 9: eight letters and the ellipsis
    (50.0, 10.0, True, "abcdefg…"),  # room int(50 / 6.2) = 8
    (24.0, 10.0, False, "ab…"),  # room 4: "ab " cut, its space dropped
    (5.0, 10.0, False, "a…"),  # room 0: one letter at least
])
def test_fit_cuts_with_an_ellipsis(width: float, size: float, bold: bool, text: str):
    source = "abcdefghij" if width != 24.0 else "ab cdefghij"
    assert fit(source, width, size, bold) == text


@pytest.mark.parametrize("low, high, count, steps, out", [
    (0.0, 10.0, 5, (1.0, 2.0, 2.5, 5.0), [0.0, 2.0, 4.0, 6.0, 8.0, 10.0]),  # raw step 2
    (0.0, 475.0, 5, (1.5, 3.0, 4.5, 9.0), [0.0, 150.0, 300.0, 450.0]),  # raw 95 beyond 90: 10 * 10 * 1.5
    (-7.0, 7.0, 3, (1.0, 2.0, 2.5, 5.0), [-5.0, 0.0, 5.0]),  # raw 4.67: 5
    (3.0, 3.0, 5, (1.0, 2.0, 2.5, 5.0), [3.0]),  # one value
    (math.nan, 1.0, 5, (1.0, 2.0, 2.5, 5.0), []),
])
def test_ticks_are_multiples_of_a_round_step(low: float, high: float, count: int, steps: tuple[float, ...],
                                             out: list[float]):
    assert ticks(low, high, count, steps) == pytest.approx(out, abs=1e-12)


def test_ticks_of_a_tenth_step_land_on_zero_exactly():
    values = ticks(-0.3, 0.3, 3)  # raw 0.2: step 0.2, zero written as 0.0 not as a rounding residue
    assert values == pytest.approx([-0.2, 0.0, 0.2], abs=1e-15) and 0.0 in values


@pytest.mark.parametrize("value, step, text", [
    (1.5, 0.5, "1.5"), (0.125, 0.025, "0.125"), (-0.00001, 0.1, "0"), (1.5e6, 5e5, "1.5e6"), (3.0, 0.0, "3"),
    (3.0, math.nan, "3"), (45.0, 15.0, "45"),
])
def test_labels_have_the_decimals_the_step_needs(value: float, step: float, text: str):
    assert label(value, step) == text


def test_a_document_parses_and_keeps_the_order_of_its_elements():
    svg = Svg(100.0, 50.26, 'a "<b>"')
    svg.open("g", class_="panel")
    svg.line(0, 1.26, 10, 2, stroke="red")
    svg.text(5, 6, "x & y", font_size="9")
    svg.curve(np.array([math.nan]), np.array([math.nan]))  # nothing: no finite point
    svg.curve(np.array([0.0, 1.0]), np.array([2.0, 3.0]), stroke="blue")
    svg.close("g")
    out = svg.text_out()
    assert out.endswith("</svg>\n") and out.count("<path") == 1
    root = ET.fromstring(out)
    assert root.tag == f"{SVG}svg" and (root.get("width"), root.get("height")) == ("100", "50.3")
    assert root.get("viewBox") == "0 0 100 50.3"
    assert [e.tag[len(SVG):] for e in root] == ["title", "rect", "g"]
    assert root.find(f"{SVG}title").text == 'a "<b>"'
    line, text, path = list(root.find(f"{SVG}g"))
    assert (line.get("x1"), line.get("y1"), line.get("x2"), line.get("y2")) == ("0", "1.3", "10", "2")
    assert text.text == "x & y" and text.get("font-size") == "9"
    assert path.get("d") == "M0 2L1 3" and path.get("fill") == "none" and path.get("stroke") == "blue"
