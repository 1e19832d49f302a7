"""linkgen.validate.header: the file's own keys (format version, name, title, units, outputs, order,
samples) read into the Mechanism with their defaults and bounds, text that reaches comments and headings
held to one plain line, and the file name as the banners give it."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from mechanism_text import FOURBAR, PATH, check, fourbar, refused

from linkgen.loader import parse
from linkgen.validate import file_label, validate
from linkgen.validate.header import DEFAULT_ORDER, DEFAULT_SAMPLES, MAX_SAMPLES


def read(text: str):
    return validate(parse(text, PATH), PATH)


def test_the_header_as_the_file_gives_it():
    m = read(FOURBAR + "outputs: [P, rocker]\norder: 1\nsamples: 5\n")
    assert (m.name, m.title, m.length_unit, m.angle_unit) == ("fourbar", "Test linkage", "mm", "deg")
    assert (m.order, m.samples, m.outputs) == (1, 5, ("P", "rocker"))
    assert m.outputs_where is not None and (m.outputs_where.line, m.outputs_where.key) == (17, "outputs")
    assert (m.inputs_where.line, m.inputs_where.key) == (15, "inputs")
    assert (m.source, m.path) == ("m.yaml", PATH)


def test_the_defaults_where_the_file_is_silent():
    text = FOURBAR.replace("title: Test linkage\n", "").replace("units: {length: mm, angle: deg}\n", "")
    m = read(text)
    assert (m.title, m.length_unit, m.angle_unit) == ("fourbar", "", "deg")  # the title is the name
    assert (m.order, m.samples, m.outputs, m.outputs_where) == (DEFAULT_ORDER, DEFAULT_SAMPLES, (), None)
    assert (DEFAULT_ORDER, DEFAULT_SAMPLES) == (2, 361)  # a degree a sample over a turn, both ends
    assert m.inputs[0].stop == 2 * math.pi  # degrees, unless said otherwise


@pytest.mark.parametrize("text, real", [("", "double"), ("options: {}\n", "double"),
                                        ("options: {real: float}\n", "float"),
                                        ("options: {real: long double}\n", "long double"),
                                        ("options:\n  real: double\n", "double")])
def test_the_real_type_from_the_options(text: str, real: str):
    assert read(FOURBAR + text).options.real == real


def test_every_option_as_the_file_gives_it():
    text = ("options: {strategy: fixed-point, tolerance: 1.0e-8, iterations: 20, polish: false, predictor: 2,\n"
            "  checks: false, angles: unit, units: file}\n")
    o = read(FOURBAR + text).options
    assert (o.strategy, o.tolerance, o.iterations, o.polish, o.predictor, o.checks, o.angles, o.units) == (
        "fixed-point", 1e-8, 20, False, 2, False, "unit", "file")


@pytest.mark.parametrize("value, key, message", [
    ("options: {real: quad}", "options.real", "options: real is float, double or long double, got 'quad'"),
    ("options: {precision: float}", "options.precision", "unknown key 'precision' in options; the keys are: real, "
     "strategy, tolerance, iterations, polish, predictor, checks, angles, assembly, units"),
    ("options: {assembly: 0}", "options.assembly",
     "options: assembly is a number from 1 (see linkgen assemblies), got 0"),
    ("options: {assembly: two}", "options.assembly",
     "expected the assembly to follow, a whole number (linkgen assemblies numbers them), got the text 'two'"),
    ("options: [float]", "options", "expected the options as {real: float, strategy: newton, ...}, got a list"),
    ("options: {strategy: bisection}", "options.strategy",
     "options: strategy is newton, fixed-point, closure or loop, got 'bisection'"),
    ("options: {tolerance: 0}", "options.tolerance", "the resolver tolerance is above 0 and at most 0.001, got 0"),
    ("options: {tolerance: 0.1}", "options.tolerance", "the resolver tolerance is above 0 and at most 0.001, got 0.1"),
    ("options: {iterations: 0}", "options.iterations", "the resolver's iteration cap is 1 to 100, got 0"),
    ("options: {predictor: 3}", "options.predictor", "options: predictor is 0, 1 or 2, got 3"),
    ("options: {polish: yes}", "options.polish",
     "expected options: polish: true or false, got the text 'yes' (YAML 1.2 reads yes, no, on and off as text)"),
    ("options: {angles: degrees}", "options.angles", "options: angles is angle or unit, got 'degrees'"),
    ("options: {units: deg}", "options.units", "options: units is si or file, got 'deg'"),
    ("options: {units: [file]}", "options.units", "expected units, got a list"),
])
def test_a_wrong_option_is_refused_at_its_line(value: str, key: str, message: str):
    error = refused(FOURBAR + value + "\n")
    assert (error.line, error.key, error.message) == (17, key, message)


def test_angles_in_radians_are_taken_as_they_are():
    m = read(FOURBAR.replace("angle: deg", "angle: rad").replace("[0, 360], speed: 360", "[0.5, 2], speed: 3"))
    assert m.angle_unit == "rad"
    assert (m.inputs[0].start, m.inputs[0].stop, m.inputs[0].speed) == (0.5, 2.0, 3.0)


@pytest.mark.parametrize("line, value, key, message", [
    ("order: 2", "order: 3", "order", "the order is 0 (displacement), 1 (+ velocity) or 2 (+ acceleration), got 3"),
    ("samples: 5", "samples: 1", "samples", "a sweep needs at least 2 samples, got 1"),
    ("samples: 5", f"samples: {MAX_SAMPLES + 1}", "samples",
     f"a sweep has at most {MAX_SAMPLES} samples, got 10000001"),
    ("outputs: [P]", "outputs: [P, P]", "outputs[1]", "the output P is listed twice"),
    ("outputs: [P]", "outputs: [rocke]", "outputs[0]", "the output rocke is not a pair, point or link of this "
                                                       "mechanism (did you mean rocker?)"),
    ("outputs: [P]", "outputs: []", "outputs", "outputs is empty; leave the key out for the default outputs"),
])
def test_out_of_bounds_scalars_and_outputs_are_refused(line: str, value: str, key: str, message: str):
    assert read(FOURBAR + line + "\n")  # the line as it should be is fine
    error = refused(FOURBAR + value + "\n")
    assert (error.line, error.key, error.message) == (17, key, message)


@pytest.mark.parametrize("edit, line, key, message", [
    (("linkgen: 1", "linkgen: 2"), 1, "linkgen",
     "this file is format version 2, but this linkgen reads format version 1"),
    (("angle: deg", "angle: grad"), 4, "units.angle", "the angle unit is deg (degrees) or rad (radians), got 'grad'"),
])
def test_another_format_version_or_angle_unit_is_refused(edit: tuple[str, str], line: int, key: str, message: str):
    error = refused(FOURBAR.replace(*edit))
    assert (error.line, error.key, error.message) == (line, key, message)


def test_the_samples_bound_is_inclusive():
    assert read(FOURBAR + f"samples: {MAX_SAMPLES}\n").samples == MAX_SAMPLES
    assert read(FOURBAR + "samples: 2\n").samples == 2


@pytest.mark.parametrize("text, code, kind", [
    ('"a\\nb"', 0x0A, "line break"), ('"a\\rb"', 0x0D, "line break"), ('"a\\tb"', 0x09, "control character"),
    ('"a\\x85b"', 0x85, "line break"), ('"a\\u2029b"', 0x2029, "line break"), ('"a\\u2066b"', 0x2066,
                                                                             "control character"),
    ('"a\\x7fb"', 0x7F, "control character"), ("|\n  two\n  lines", 0x0A, "line break"),
])
def test_a_title_holds_one_line_of_plain_text(text: str, code: int, kind: str):
    error = refused(fourbar().replace("title: Test linkage", f"title: {text}"))
    assert (error.line, error.key) == (3, "title")
    assert error.message.startswith(f"the title holds the {kind} U+{code:04X}, ")


def test_a_length_unit_holds_one_line_of_plain_text():
    error = refused(fourbar().replace("length: mm", 'length: "mm\\n"'))
    assert (error.line, error.key) == (4, "units.length")
    assert error.message.startswith("the length unit holds the line break U+000A, ")


def test_quotes_comment_closers_and_other_scripts_are_fine_in_a_title():
    title = """'q' "d" \\ */ /* \"\"\" --> %{ <b>&amp; `x` Überhöhung 四節 🙂"""
    quoted = title.replace("\\", "\\\\").replace('"', '\\"')
    assert check(fourbar().replace("title: Test linkage", f'title: "{quoted}"')).mechanism.title == title


@pytest.mark.parametrize("path, label", [
    ("dir/four-bar (v2).yaml", "four-bar (v2).yaml"),
    ("a\nb.yaml", "a\\x0ab.yaml"),
    ('q"*<!-->&`\\.yaml', "q\\x22\\x2a\\x3c!--\\x3e\\x26\\x60\\x5c.yaml"),
    ("Überhöhung.yaml", "\\xdcberh\\xf6hung.yaml"),
    ("四節🙂.yaml", "\\u56db\\u7bc0\\U0001f642.yaml"),
    ("bad\udcff.yaml", "bad\\udcff.yaml"),
])
def test_the_file_name_is_printable_ascii_in_the_banners(path: str, label: str):
    assert file_label(path) == label
    assert all(0x20 <= ord(c) < 0x7F and c not in '*<>&`"' for c in label)
    assert label.encode("ascii").decode("unicode_escape") == Path(path).name




def test_the_mechanism_keeps_where_the_file_gives_each_option():
    m = read(FOURBAR + "options:\n  real: float\n  strategy: closure\n")
    assert {k: (w.line, w.key) for k, w in m.options_where.items()} == {
        "real": (18, "options.real"), "strategy": (19, "options.strategy")}
    assert read(FOURBAR).options_where == {}
