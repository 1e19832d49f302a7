"""What the validator refuses or rewrites before anything is generated: names the programs cannot
carry (with the message and advice; the lists themselves are tests/unit/test_names.py's), text that
reaches comments and headings, the supported magnitudes, and the file name as the banners give it."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from linkgen.backends.c import words as c_words
from linkgen.backends.m import words as m_words
from linkgen.errors import InputError
from linkgen.loader import parse
from linkgen.topology import analyse
from linkgen.validate import file_label, validate

PATH = "m.yaml"
FOURBAR = """linkgen: 1
name: fourbar
title: Test linkage
units: {length: mm, angle: deg}
joints:
  O1: [0, 0]
  A: [20, 0]
  B: [80, 50]
  O2: [90, 0]
links:
  frame: {joints: [O1, O2], fixed: true}
  crank: [O1, A]
  coupler: {joints: [A, B], points: {P: [60, 70]}}
  rocker: [O2, B]
inputs:
  - {joint: O1, link: crank, relative_to: frame, range: [0, 360], speed: 360}
"""


def fourbar(**renamed: str) -> str:
    """The four-bar with names replaced (whole words: O1=..., fourbar=..., ...)."""
    text = FOURBAR
    for old, new in renamed.items():
        text = re.sub(rf"\b{old}\b", new, text)
    return text


def check(text: str):
    return analyse(validate(parse(text, PATH), PATH))


def refused(text: str) -> InputError:
    with pytest.raises(InputError) as info:
        check(text)
    return info.value


# -- the mechanism name ---------------------------------------------------------

@pytest.mark.parametrize("name, reason", [
    ("zeros", "is a MATLAB/Octave function, which the script zeros.m would hide"),
    ("size", "is a MATLAB/Octave function, which the script size.m would hide"),
    ("fprintf", "is a MATLAB/Octave function, which the script fprintf.m would hide"),
    ("json", "is a module of Python's standard library, which json.py would hide"),
    ("random", "is a module of Python's standard library, which random.py would hide"),
    ("until", "is a MATLAB/Octave keyword, so the script until.m cannot be run"),
    ("row", "is a variable of the sweep script row.m, which after one run would hide the script"),
    ("None", "is a Python keyword, so the module None.py cannot be imported"),
    ("isinstance", "is a Python built-in, which `import isinstance` would hide in the importing module"),
    ("String", "makes String.h, which would hide the C header <string.h> from a compiler given -I"),
    ("features", "makes features.h, which would hide the C header <features.h> from a compiler given -I"),
    ("Com1", "is a device name on Windows, which cannot create a file named Com1.c"),
])
def test_a_refused_mechanism_name_says_why_and_suggests_one(name: str, reason: str):
    error = refused(fourbar(fourbar=name))
    assert (error.line, error.key) == (2, "name")
    assert error.message == f"{name} {reason}; choose another name for the mechanism, such as {name}_linkage"
    check(fourbar(fourbar=f"{name}_linkage"))


@pytest.mark.parametrize("name", ["auto", "register", "typedef", "NAN", "linux", "EOF", "new", "zeros_linkage",
                                  "solve", "strandbeest"])
def test_c_words_and_near_misses_are_fine_mechanism_names(name: str):
    """The mechanism name is never a C identifier by itself (NAME_state, NAME_solve, ...)."""
    assert check(fourbar(fourbar=name)).mechanism.name == name


# -- pair, point and link names ---------------------------------------------------

ENTITY_REFUSED = {
    "state field": c_words.STATE_FIELDS | m_words.STATE_FIELDS,
    "header name": c_words.header_names("fourbar"),
    "macro of NAME.c": c_words.SOURCE_MACROS,
}


@pytest.mark.parametrize("listed", sorted(ENTITY_REFUSED))
def test_every_name_of_every_refused_list_is_refused_as_a_link_name(listed: str):
    for name in sorted(ENTITY_REFUSED[listed]):
        error = refused(fourbar(rocker=name))
        assert (error.line, error.key) == (14, f"links.{name}")
        assert error.message.startswith(f"{name} is "), error.message
        assert error.message.endswith(f"; call the link {name}_link or similar"), error.message
        check(fourbar(rocker=f"{name}_link"))


def test_a_state_field_names_the_structures_that_have_it():
    assert refused(fourbar(P="sigma")).message == (
        "sigma is a field of the generated state (C fourbar_state, MATLAB/Octave out); "
        "call the point sigma_point or similar")
    assert refused(fourbar(B="status")).message == (
        "status is a field of the generated state (C fourbar_state); call the pair status_pair or similar")
    assert refused(fourbar(crank="columns")).message == (
        "columns is a field of the generated state (MATLAB/Octave out); call the link columns_link or similar")


def test_a_renamed_name_and_its_spelling_cannot_both_be_given():
    error = refused(fourbar(crank="do", rocker="do_"))
    assert (error.line, error.key) == (14, "links.do_")
    assert error.message == ("do_ is written do_ in the generated C program, as is do (line 12), because do is a C "
                             "keyword and gets a trailing _ there; call the link do_link or similar")
    error = refused(fourbar(rocker="until", O2="until_"))
    assert (error.line, error.key) == (14, "links.until")
    assert "until is written until_ in the generated MATLAB/Octave program, as is until_ (line 9)" in error.message


@pytest.mark.parametrize("name, key, reason, better", [
    ("_B", "joints._B", "starts with _, which a MATLAB struct field cannot (out._B) and C reserves", "pair B"),
    ("B__1", "joints.B__1", "contains __, which C++ reserves (the generated header is C++ too)", "pair B_1"),
    ("B" * 64, "joints." + "B" * 64, "has 64 characters; a MATLAB struct field has at most 63", ""),
])
def test_names_no_language_allows_are_refused(name: str, key: str, reason: str, better: str):
    error = refused(fourbar(B=name))
    assert (error.line, error.key) == (8, key)
    advice = f"call the {better} or similar" if better else "choose another name for the pair"
    assert error.message == f"{name} {reason}; {advice}"


def test_names_are_checked_whether_outputs_lists_them_or_not():
    text = fourbar(P="sigma") + "outputs: [B]\n"
    assert refused(text).key == "links.coupler.points.sigma"


# -- text that reaches comments and headings ---------------------------------------

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


# -- magnitudes ---------------------------------------------------------------------

def scaled(factor: float, speed: str = "360") -> str:
    text = fourbar().replace("speed: 360", f"speed: {speed}")
    return re.sub(r"(?<!range: )\[(-?\d+), (-?\d+)\]",
                  lambda g: f"[{float(g[1]) * factor!r}, {float(g[2]) * factor!r}]", text)


def test_the_supported_magnitudes_are_accepted_at_both_ends():
    length = check(FOURBAR).length_scale
    small, large = 1e-30 / length, 1e30 / length
    assert check(scaled(small * (1 + 1e-15))).length_scale >= 1e-30
    assert check(scaled(large * (1 - 1e-15))).length_scale <= 1e30
    assert check(scaled(1.0, "1e30")).mechanism.inputs[0].speed == pytest.approx(1e30 * 3.141592653589793 / 180)
    assert check(scaled(1.0, "-1e30"))
    corner = scaled(1e28).replace("[8.999999999999999e+29, 0.0]", "[1e30, 0.0]")
    assert check(corner).length_scale == 1e30
    mirrored = re.sub(r"(?<!range: )\[(-?[0-9.e+]+), (-?[0-9.e+]+)\]",
                      lambda g: f"[{-float(g[1])!r}, {-float(g[2])!r}]", corner)
    assert "[-1e+30, -0.0]" in mirrored
    assert check(mirrored).length_scale == 1e30
    ranged = fourbar().replace("[0, 360]", "[-1e30, 1e30]")
    assert validate(parse(ranged, PATH), PATH).inputs[0].stop == pytest.approx(1e30 * 3.141592653589793 / 180)


@pytest.mark.parametrize("text, key, what", [
    (scaled(1e-32), "joints.B", "the sketch measures 9.43e-31 mm (from O1 to B"),
    (scaled(1.1e28), "joints.B", "the sketch measures 1.04e30 mm (from O1 to B"),
    (fourbar().replace("[60, 70]", "[1.0000001e30, 70]"), "links.coupler.points.P[0]",
     "the x coordinate of point P is 1.0000001e30, outside the range linkgen supports: at most 1e30 in size (in mm)"),
    (fourbar().replace("[0, 360]", "[-2e30, 360]"), "inputs[0].range[0]",
     "the start of the range is -2e30, outside the range linkgen supports: at most 1e30 in size (in degrees)"),
    (fourbar().replace("speed: 360", "speed: 1.5e30"), "inputs[0].speed",
     "the input speed is 1.5e30, outside the range linkgen supports: at most 1e30 in size (in degrees per second)"),
])
def test_magnitudes_outside_the_range_are_refused(text: str, key: str, what: str):
    error = refused(text)
    assert error.key == key
    assert error.message.startswith(what), error.message
