"""The shared flags: the settings flags on a command and the comma-separated list parsers."""

from __future__ import annotations

import click
import pytest
from click.testing import CliRunner

from linkgen import flags
from linkgen.options import Options
from linkgen.policy import MAX_MAGNITUDE


def test_settings_cover_every_option_but_none_other():
    names = {p.opts[0].lstrip("-") for p in _command().params if p.name != "settings"}
    assert names == {f.name.replace("_", "-") for f in Options.__dataclass_fields__.values()}


def _command() -> click.Command:
    @click.command()
    @flags.settings
    def cmd(**settings: object) -> None:
        click.echo(repr(sorted(flags.given(settings).items())))

    return cmd


def test_given_keeps_only_the_flags_on_the_command_line():
    result = CliRunner().invoke(_command(), ["--real", "float", "--no-polish", "--iterations", "3"])
    assert result.exit_code == 0
    assert result.output.strip() == "[('iterations', 3), ('polish', False), ('real', 'float')]"


def test_a_value_out_of_range_is_a_usage_error():
    assert CliRunner().invoke(_command(), ["--predictor", "3"]).exit_code == 2


def test_units_is_si_or_file():
    assert CliRunner().invoke(_command(), ["--units", "file"]).output.strip() == "[('units', 'file')]"
    result = CliRunner().invoke(_command(), ["--units", "deg"])
    assert result.exit_code == 2 and "'deg' is not one of 'si', 'file'" in result.output


def test_outputs_splits_on_commas_and_drops_blanks():
    assert flags.outputs(" P, rocker,,") == ("P", "rocker")
    assert flags.outputs("") is None and flags.outputs(None) is None


@pytest.mark.parametrize("text, expected", [("90", (90.0,)), ("10,-20.5", (10.0, -20.5)), ("1e3", (1000.0,))])
def test_values_reads_finite_numbers(text, expected):
    assert flags.values(None, None, text) == expected  # type: ignore[arg-type]


@pytest.mark.parametrize("text", ["ninety", "1,,2", "nan", "inf", f"{MAX_MAGNITUDE * 10:g}"])
def test_values_refuses_what_is_no_finite_number(text):
    with pytest.raises(click.BadParameter):
        flags.values(None, None, text)  # type: ignore[arg-type]
