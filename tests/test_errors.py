"""Every malformed or impossible mechanism file fails with one clear message.

Each case is ``tests/errors/<case>.yaml`` (``missing_file`` has none, on purpose) with
the exact expected standard error in ``tests/errors/<case>.stderr``.  Beyond the exact
text, every message must name the file, the line and the key the case is about
(``EXPECT``), so an expectation cannot be updated into a message without substance.

Set ``LINKGEN_UPDATE_ERRORS=1`` to rewrite the .stderr files from the current messages
(then review the diff).
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from click.testing import CliRunner

from linkgen.cli import cli

ROOT = Path(__file__).resolve().parent.parent
CASES = ROOT / "tests" / "errors"
UPDATE = os.environ.get("LINKGEN_UPDATE_ERRORS") == "1"

# case: (line, key) that the message must name; None where the file has no line or the
# problem concerns the whole file rather than one key
EXPECT: dict[str, tuple[int | None, str | None]] = {
    "actuator_coinciding_pairs": (14, "inputs[0].between"),
    "actuator_on_one_link": (14, "inputs[0].between"),
    "actuator_prismatic_end": (14, "inputs[0].between[1]"),
    "actuator_same_pair": (14, "inputs[0].between"),
    "actuator_three_pairs": (14, "inputs[0].between"),
    "actuator_with_joint": (14, "inputs[0].joint"),
    "bad_version": (1, "linkgen"),
    "comments_only": (1, None),
    "control_character": (3, None),
    "coordinate_inf": (6, "joints.B[0]"),
    "coordinate_mapping": (6, "joints.B.at"),
    "coordinate_nan": (6, "joints.B[1]"),
    "coordinate_null": (6, "joints.B[1]"),
    "coordinate_one_number": (6, "joints.B"),
    "coordinate_overflow": (6, "joints.B[1]"),
    "coordinate_overflow_integer": (6, "joints.B[0]"),
    "coordinate_quoted": (6, "joints.B[1]"),
    "coordinate_text": (6, "joints.B[1]"),
    "coordinate_three_numbers": (6, "joints.B"),
    "coordinate_too_large": (6, "joints.B[1]"),
    "coordinate_underscore": (6, "joints.B[0]"),
    "dead_centre_two_inputs": (5, "joints.A"),
    "disconnected": (15, "links.arm1"),
    "duplicate_key_in_input": (14, "inputs[0].range"),
    "duplicate_link_key": (13, "links.crank"),
    "duplicate_pair_key": (8, "joints.A"),
    "duplicate_top_key": (8, "name"),
    "empty_file": (1, None),
    "input_columns_alike": (17, "inputs[1]"),
    "input_direction_undefined": (12, "links.block"),
    "input_drives_fixed_link": (14, "inputs[0].link"),
    "input_item_text": (14, "inputs[0]"),
    "input_link_not_on_pair": (14, "inputs[0].link"),
    "input_missing_range": (14, "inputs[0].range"),
    "input_missing_relative_to": (14, "inputs[0].relative_to"),
    "input_no_joint": (14, "inputs[0]"),
    "input_on_locked_pair": (18, "inputs[0]"),
    "input_range_one_number": (14, "inputs[0].range"),
    "input_range_text": (14, "inputs[0].range"),
    "input_reference_not_on_pair": (14, "inputs[0].relative_to"),
    "input_same_link": (14, "inputs[0].relative_to"),
    "input_speed_text": (14, "inputs[0].speed"),
    "input_unknown_key": (14, "inputs[0].rnage"),
    "input_unknown_link": (14, "inputs[0].link"),
    "input_unknown_pair": (14, "inputs[0].joint"),
    "inputs_mapping": (13, "inputs"),
    "inputs_same_motion": (22, "inputs[1]"),
    "joints_empty": (3, "joints"),
    "joints_list": (3, "joints"),
    "link_all_coincide": (11, "links.wheel.joints"),
    "link_fixed_yes": (9, "links.frame.fixed"),
    "link_missing_joints": (11, "links.coupler.joints"),
    "link_no_pairs": (12, "links.rocker"),
    "link_one_pair": (13, "links.arm"),
    "link_pair_twice": (12, "links.rocker[2]"),
    "link_pairs_key": (11, "links.coupler.pairs"),
    "link_points_list": (11, "links.coupler.points"),
    "link_text": (10, "links.crank"),
    "link_unknown_key": (9, "links.frame.fix"),
    "link_unknown_pair": (12, "links.rocker[1]"),
    "links_list": (8, "links"),
    "missing_file": (None, None),
    "missing_inputs": (1, "inputs"),
    "missing_joints": (1, "joints"),
    "name_c_header": (2, "name"),
    "name_double_underscore": (10, "links.crank__arm"),
    "name_field_too_long": (12, "links.rocker_" + "x" * 57),
    "name_header_macro": (12, "links.FOURBAR_N_STEPS"),
    "name_header_type": (12, "links.fourbar_state"),
    "name_leading_underscore": (6, "joints._B"),
    "name_module": (2, "name"),
    "name_not_identifier": (2, "name"),
    "name_null": (2, "name"),
    "name_octave_function": (2, "name"),
    "name_pair_and_link": (12, "links.B"),
    "name_pair_and_point": (11, "links.coupler.points.A"),
    "name_point_and_link": (12, "links.P"),
    "name_point_twice": (12, "links.rocker.points.P"),
    "name_python_builtin": (2, "name"),
    "name_python_keyword": (2, "name"),
    "name_reserved": (2, "name"),
    "name_script_variable": (2, "name"),
    "name_source_macro": (11, "links.coupler.points.LINKGEN_NMAX"),
    "name_state_field": (12, "links.status"),
    "name_state_field_matlab": (11, "links.coupler.points.sigma"),
    "name_too_long": (2, "name"),
    "name_true": (2, "name"),
    "name_underscore": (2, "name"),
    "name_windows_device": (2, "name"),
    "name_written_alike_c": (11, "links.coupler.points.NAN_"),
    "name_written_alike_matlab": (12, "links.end_"),
    "no_fixed_link": (8, "links"),
    "no_inputs": (13, "inputs"),
    "not_utf8": (3, None),
    "order_fraction": (15, "order"),
    "order_too_high": (15, "order"),
    "outputs_empty": (15, "outputs"),
    "outputs_text": (15, "outputs"),
    "outputs_twice": (15, "outputs[2]"),
    "outputs_unknown": (15, "outputs[1]"),
    "pair_bad_type": (6, "joints.B.type"),
    "pair_complex_key": (6, "joints"),
    "pair_missing_at": (6, "joints.B.at"),
    "pair_name_not_identifier": (6, "joints.B-1"),
    "pair_name_number": (6, "joints.1"),
    "pair_number": (6, "joints.B"),
    "pair_on_no_link": (8, "joints.C"),
    "pair_on_one_link": (8, "joints.C"),
    "pair_unknown_key": (6, "joints.B.axis"),
    "parallelogram_too_many_inputs": (18, "inputs[1]"),
    "point_coordinate_text": (11, "links.coupler.points.P[1]"),
    "point_coordinate_too_large": (11, "links.coupler.points.P[0]"),
    "prismatic_axis_text": (7, "joints.S.axis"),
    "prismatic_input_same_link": (14, "inputs[0].relative_to"),
    "prismatic_missing_axis": (7, "joints.S.axis"),
    "prismatic_three_links": (7, "joints.S"),
    "range_too_large": (14, "inputs[0].range[1]"),
    "samples_one": (15, "samples"),
    "samples_text": (15, "samples"),
    "samples_too_many": (17, "samples"),
    "sweep_grid_too_many": (21, "sweep"),
    "sweep_unknown": (16, "sweep"),
    "sketch_in_line": (5, "joints.A"),
    "sketch_too_large": (7, "joints.O2"),
    "sketch_too_small": (6, "joints.B"),
    "slider_input_at_dead_centre": (14, "inputs[0]"),
    "speed_too_large": (14, "inputs[0].speed"),
    "structure_cannot_move": (12, "inputs[0]"),
    "title_bidi_control": (3, "title"),
    "title_list": (3, "title"),
    "title_newline": (3, "title"),
    "too_few_inputs": (15, "inputs"),
    "too_many_inputs": (15, "inputs[1]"),
    "top_level_list": (1, None),
    "top_level_text": (1, None),
    "two_documents": (16, None),
    "two_fixed_links": (12, "links.rocker"),
    "two_hinges_at_one_point": (13, "links.rocker"),
    "two_inputs_on_one_pair": (17, "inputs[1].joint"),
    "units_bad_angle": (3, "units.angle"),
    "units_line_separator": (3, "units.length"),
    "units_text": (3, "units"),
    "units_unknown_key": (3, "units.angles"),
    "unknown_top_key": (13, "sample"),
    "version_text": (1, "linkgen"),
    "yaml_bad_indent": (6, "joints"),
    "yaml_tab_indent": (6, "joints"),
    "yaml_tag": (6, "joints.B[0]"),
    "yaml_two_colons": (6, "joints"),
    "yaml_unclosed_list": (6, "joints.B"),
    "yaml_unclosed_quote": (3, "title"),
    "yaml_undefined_alias": (7, "joints.O2"),
}


def _case_path(case: str) -> str:
    """The mechanism file as the user gives it: relative to the repository root."""
    return f"tests/errors/{case}.yaml"


def _invoke(args: list[str], monkeypatch: pytest.MonkeyPatch):
    monkeypatch.chdir(ROOT)
    result = CliRunner().invoke(cli, args)
    if result.exception is not None and not isinstance(result.exception, SystemExit):
        raise result.exception
    return result


def _where(case: str) -> str:
    """The start of the message: file, line and key."""
    line, key = EXPECT[case]
    where = f"linkgen: error: {_case_path(case)}"
    if line is not None:
        where += f":{line}"
    return where + (f": {key}: " if key else ": ")


def test_every_case_has_a_file_an_expectation_and_a_stderr():
    yaml = {p.stem for p in CASES.glob("*.yaml")}
    stderr = {p.stem for p in CASES.glob("*.stderr")}
    assert yaml | {"missing_file"} == set(EXPECT)
    assert "missing_file" not in yaml
    if not UPDATE:
        assert stderr == set(EXPECT)


@pytest.mark.parametrize("case", sorted(EXPECT))
@pytest.mark.parametrize("command", ["run", "build"])
def test_error_message(case: str, command: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    outdir = tmp_path / "out"
    args = [command, _case_path(case)] + (["-o", str(outdir)] if command == "build" else [])
    result = _invoke(args, monkeypatch)
    assert result.exit_code != 0
    assert result.stdout == ""
    assert result.stderr.count("\n") == 1, "one message, on one line"
    assert result.stderr.startswith(_where(case)), "the message names the file, the line and the key"
    assert not outdir.exists(), "a failed build writes nothing"
    expected = CASES / f"{case}.stderr"
    if UPDATE:
        expected.write_text(result.stderr, encoding="utf-8")
    else:
        assert result.stderr == expected.read_text(encoding="utf-8")


def _snapshot(folder: Path) -> dict[str, tuple[bytes, int]]:
    return {str(p.relative_to(folder)): (p.read_bytes(), p.stat().st_mtime_ns)
            for p in sorted(folder.rglob("*")) if p.is_file()}


BROKEN = {
    "syntax": ("  B: [80, 50]\n", "  B: [80, 50\n"),
    "validation": ("  rocker: [O2, B]\n", "  rocker: [O2, B]\noutputs: [Q]\n"),
    "topology": ("speed: 360}\n", "speed: 360}\n  - {joint: O2, link: rocker, relative_to: frame, range: [0, 9]}\n"),
}


@pytest.mark.parametrize("stage", sorted(BROKEN))
def test_failed_build_leaves_earlier_outputs_untouched(stage: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    good = (ROOT / "samples" / "fourbar" / "fourbar.yaml").read_text(encoding="utf-8")
    outdir = tmp_path / "build" / "fourbar"
    first = _invoke(["build", str(ROOT / "samples" / "fourbar" / "fourbar.yaml"), "-o", str(outdir)], monkeypatch)
    assert first.exit_code == 0, first.output
    before = _snapshot(outdir)
    assert before
    old, new = BROKEN[stage]
    assert old in good
    broken = tmp_path / "fourbar.yaml"
    broken.write_text(good.replace(old, new), encoding="utf-8")
    result = _invoke(["build", str(broken), "-o", str(outdir)], monkeypatch)
    assert result.exit_code != 0
    assert result.stderr.startswith(f"linkgen: error: {broken}:")
    assert _snapshot(outdir) == before
