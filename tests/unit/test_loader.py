"""The loader reads YAML 1.2 core-schema scalars and reports every problem with its line and key path."""

from __future__ import annotations

import math
import re

import pytest
from hypothesis import given
from hypothesis import strategies as st

from linkgen.errors import InputError, LinkgenError
from linkgen.loader import Mapping, Reader, Scalar, Sequence, load, parse

PATH = "m.yaml"
READ = Reader(PATH)


def value(text: str):
    """The node of ``v: <text>``."""
    return parse(f"v: {text}\n", PATH).get("v")


def fails(text: str) -> InputError:
    with pytest.raises(InputError) as info:
        parse(text, PATH)
    return info.value


# -- scalars ------------------------------------------------------------------

@pytest.mark.parametrize("text, kind", [
    ("1e-6", "float"), ("1E6", "float"), ("-2.5", "float"), (".5", "float"), ("5.", "float"), ("+1.5e+3", "float"),
    ("12", "int"), ("-12", "int"), ("017", "int"), ("0o17", "int"), ("0x1F", "int"),
    (".inf", "nonfinite"), ("-.Inf", "nonfinite"), ("+.INF", "nonfinite"), (".nan", "nonfinite"), (".NaN", "nonfinite"),
    ("true", "bool"), ("True", "bool"), ("FALSE", "bool"),
    ("~", "null"), ("null", "null"), ("Null", "null"), ("", "null"),
    ("yes", "str"), ("no", "str"), ("on", "str"), ("off", "str"), ("y", "str"), ("tRue", "str"),
    ("1_000", "str"), ("0b101", "str"), ("-0x1F", "str"), ("inf", "str"), ("nan", "str"), ("1,5", "str"),
    ("'12'", "str"), ('"true"', "str"), ('""', "str"),
])
def test_core_schema_kind(text: str, kind: str):
    node = value(text)
    assert isinstance(node, Scalar)
    assert node.kind() == kind


@pytest.mark.parametrize("text, number", [
    ("1e-6", 1e-6), ("1E6", 1e6), ("-2.5", -2.5), (".5", 0.5), ("5.", 5.0), ("+12", 12.0),
    ("0x1F", 31.0), ("0o17", 15.0), ("017", 17.0), ("-0", 0.0), ("1e-400", 0.0),
])
def test_numbers(text: str, number: float):
    assert READ.number(value(text)) == number


@pytest.mark.parametrize("text", ["1_000", "0b101", "-0x1F", "12mm", "1,5", "inf", "NaN", "yes", "true", "[1]"])
def test_not_numbers(text: str):
    with pytest.raises(InputError, match="expected a number, got"):
        READ.number(value(text))


@pytest.mark.parametrize("text", [".inf", "-.inf", "+.Inf", ".INF", ".nan", ".NaN", ".NAN"])
def test_non_finite_numbers_are_rejected(text: str):
    with pytest.raises(InputError, match=f"got {re.escape(text)}, which is not a finite number"):
        READ.number(value(text))


@pytest.mark.parametrize("text", ["1e400", "-1e400", "1" + "0" * 400])
def test_overflowing_numbers_are_rejected(text: str):
    with pytest.raises(InputError, match="which is too large to compute with"):
        READ.number(value(text))


@pytest.mark.parametrize("text", ['"90"', "'90'", '"1e-6"'])
def test_quoted_numbers_are_text(text: str):
    with pytest.raises(InputError, match=r"got the quoted text '.*'; a number is written without quotes"):
        READ.number(value(text))


@given(st.floats(allow_nan=False, allow_infinity=False))
def test_every_finite_float_reads_back_exactly(x: float):
    assert READ.number(Scalar(1, "v", repr(x), False)) == x


@given(st.integers(min_value=-(10**300), max_value=10**300))
def test_every_integer_reads_as_its_nearest_float(n: int):
    assert READ.number(Scalar(1, "v", str(n), False)) == float(n)


@pytest.mark.parametrize("text, number", [
    ("12", 12), ("0x1F", 31), ("0o17", 15), ("017", 17), ("2.0", 2), ("1e3", 1000),
])
def test_integers(text: str, number: int):
    assert READ.integer(value(text)) == number


@pytest.mark.parametrize("text", ["2.5", "1e400", ".inf", "'2'", "two"])
def test_not_integers(text: str):
    with pytest.raises(InputError, match="expected a whole number"):
        READ.integer(value(text))


@pytest.mark.parametrize("text", ["yes", "no", "on", "off", "Yes", "ON", "y", "n", "null_", "_x1", '"true"'])
def test_yaml_1_1_booleans_are_names(text: str):
    assert READ.name(value(text)) == text.strip('"')


@pytest.mark.parametrize("text, flag", [("true", True), ("True", True), ("TRUE", True), ("false", False)])
def test_booleans(text: str, flag: bool):
    assert READ.boolean(value(text), "a flag") is flag


@pytest.mark.parametrize("text", ["yes", "on", "no", "off"])
def test_yes_is_not_a_boolean(text: str):
    with pytest.raises(InputError, match=f"got the text '{text}' \\(YAML 1.2 reads yes, no, on and off as text\\)"):
        READ.boolean(value(text), "a flag")


@pytest.mark.parametrize("text, message", [
    ("true", 'got the boolean true; write "true" in quotes'),
    ("", "got nothing"),
    ("~", "got nothing"),
    ("12", "got '12', which is not a valid name"),
    ("4bar", "got '4bar', which is not a valid name"),
    ("a-b", "got 'a-b', which is not a valid name"),
    ("[a]", "got a list"),
])
def test_bad_names(text: str, message: str):
    with pytest.raises(InputError, match=re.escape(message)):
        READ.name(value(text))


# -- duplicate keys -----------------------------------------------------------

def test_duplicate_key_names_both_lines():
    err = fails("a: 1\nb: 2\na: 3\n")
    assert (err.line, err.key) == (3, "a")
    assert "given twice, at lines 1 and 3" in err.message


def test_nested_duplicate_key_has_its_path():
    err = fails("joints:\n  A: [0, 0]\n  B: [1, 1]\n  A: [2, 2]\n")
    assert (err.line, err.key) == (4, "joints.A")
    assert "at lines 2 and 4" in err.message


def test_duplicate_key_in_a_flow_mapping_on_one_line():
    err = fails("inputs:\n  - {joint: A, range: [0, 1], joint: B}\n")
    assert (err.line, err.key) == (2, "inputs[0].joint")
    assert "given twice, on this line" in err.message


def test_same_key_in_different_mappings_is_fine():
    root = parse("a: {x: 1}\nb: {x: 2}\n", PATH)
    assert [k.text for k, _ in root.items] == ["a", "b"]


# -- marks and key paths ------------------------------------------------------

MECH = """linkgen: 1
joints:
  A: [0, 0]
  S: {type: prismatic, at: [1, 2], axis: 0}
inputs:
  - {joint: A, range: [0, 360]}
  -
    joint: S
    range:
      - 0
      - 10
name:
"""


def test_marks_and_key_paths():
    root = parse(MECH, PATH)
    y = root.get("joints").get("S").get("at").items[1]
    assert (y.line, y.key, y.text) == (4, "joints.S.at[1]", "2")
    second = root.get("inputs").items[1]
    assert isinstance(second, Mapping)
    assert (second.line, second.key) == (8, "inputs[1]")
    assert (second.get("joint").line, second.get("joint").key) == (8, "inputs[1].joint")
    rng = second.get("range")
    assert isinstance(rng, Sequence)
    assert (rng.line, rng.key) == (9, "inputs[1].range")  # a block list is reported at its key
    assert (rng.items[1].line, rng.items[1].key) == (11, "inputs[1].range[1]")
    assert (root.get("name").line, root.get("name").key) == (12, "name")  # an empty value too
    assert root.get("joints").line == 2


def test_error_names_file_line_and_key():
    err = READ.error(parse(MECH, PATH).get("joints").get("S").get("axis"), "bad")
    assert str(err) == "m.yaml:4: joints.S.axis: bad"


def test_error_format_without_line_or_key():
    assert str(LinkgenError("cannot read", "m.yaml")) == "m.yaml: cannot read"
    assert str(LinkgenError("empty", "m.yaml", 1)) == "m.yaml:1: empty"


def test_unknown_key_is_named_with_a_suggestion():
    root = parse("a: 1\nsample: 3\n", PATH)
    with pytest.raises(InputError) as info:
        READ.keys(root, ("a",), ("samples", "order"), "the file")
    err = info.value
    assert (err.line, err.key) == (2, "sample")
    assert "unknown key 'sample' in the file (did you mean 'samples'?); the keys are: a, samples, order" in err.message


def test_missing_key_is_named_at_its_mapping():
    root = parse("joints:\n  S: {type: prismatic, at: [0, 0]}\n", PATH)
    with pytest.raises(InputError) as info:
        READ.keys(root.get("joints").get("S"), ("at", "axis"), ("type",), "prismatic pair S")
    assert (info.value.line, info.value.key) == (2, "joints.S.axis")


# -- whole files --------------------------------------------------------------

@pytest.mark.parametrize("text", ["", "\n\n", "# only a comment\n"])
def test_empty_file(text: str):
    err = fails(text)
    assert err.line == 1
    assert "the file is empty" in err.message


def test_two_documents():
    err = fails("a: 1\n---\nb: 2\n")
    assert err.line == 3
    assert "a second YAML document" in err.message


def test_a_file_must_be_a_mapping():
    assert "got a list" in fails("- a\n- b\n").message


@pytest.mark.parametrize("text, line, key, message", [
    ("joints:\n  A: [0, 0\n  B: [1, 1]\n", 2, "joints.A", "a list opened with [ is not closed with ]"),
    ("joints:\n  A: [0, 0]\n\tB: [1, 1]\n", 3, "joints", "a tab character"),
    ("joints:\n  A: [0, 0]\n   B: [1, 1]\n", 3, "joints", "the indentation does not match"),
    ("title: \"a\nb: 1\n", 1, "title", "a quoted text is not closed"),
    ("joints:\n  A: at: [0, 0]\n", 2, "joints", "an unexpected ':'"),
    ("a: [1, 2]]\n", 1, "", "a ] that closes no list"),
    ("a:\n  b: *nowhere\n", 2, "a.b", "refers to no anchor"),
])
def test_syntax_errors_name_line_and_key(text: str, line: int, key: str, message: str):
    err = fails(text)
    assert (err.line, err.key) == (line, key)
    assert err.message.startswith("not valid YAML: ")
    assert message in err.message
    assert "\n" not in str(err)


def test_tags_are_rejected():
    err = fails("joints:\n  A: [!!str 0, 0]\n")
    assert (err.line, err.key) == (2, "joints.A[0]")
    assert "a YAML tag (!!str)" in err.message


def test_anchors_and_aliases_are_read():
    root = parse("a: &p [1, 2]\nb: *p\nc: &q 1\nd: &q 2\n", PATH)
    b = root.get("b")
    assert isinstance(b, Sequence)
    assert [READ.number(n) for n in b.items] == [1.0, 2.0]
    assert b.key == "b"


def test_complex_keys_are_rejected():
    err = fails("joints:\n  [A, B]: [0, 0]\n")
    assert (err.line, err.key) == (2, "joints")


def test_control_characters_are_rejected():
    err = fails("a: 1\nb: x\x07y\n")
    assert err.line == 2
    assert "U+0007" in err.message


def test_missing_file(tmp_path):
    with pytest.raises(InputError) as info:
        load(str(tmp_path / "nope.yaml"))
    assert str(info.value) == f"{tmp_path / 'nope.yaml'}: cannot read the mechanism file: No such file or directory"


def test_not_utf8_names_the_line(tmp_path):
    path = tmp_path / "m.yaml"
    path.write_bytes("a: 1\nb: 2\ntitle: f\xfcr\n".encode("latin-1"))
    with pytest.raises(InputError) as info:
        load(str(path))
    assert info.value.line == 3
    assert "byte 0xFC" in info.value.message


def test_byte_order_mark_and_crlf_are_read(tmp_path):
    path = tmp_path / "m.yaml"
    path.write_bytes(b"\xef\xbb\xbfa: 1\r\nb: [1e-6, 2]\r\n")
    root = load(str(path))
    b = root.get("b")
    assert isinstance(b, Sequence)
    assert b.line == 2
    assert math.isclose(READ.number(b.items[0]), 1e-6)
