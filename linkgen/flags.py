"""The flags several commands share: the settings that override the file's options, and the
parsers of comma-separated lists (--outputs, --at, --rates)."""

from __future__ import annotations

import math
from typing import Any

import click

from .options import ANGLE_FORMS, MAX_ITERATIONS, MAX_TOLERANCE, PREDICTORS, STRATEGIES, UNIT_SYSTEMS
from .policy import MAX_MAGNITUDE, REAL_TYPES

SETTINGS = (  # the flags that override the file's options (linkgen.options.Options), all of build and run
    click.option("--real", type=click.Choice(REAL_TYPES), help="The programs' real type (C; numpy float32 for float)."),
    click.option("--strategy", type=click.Choice(STRATEGIES),
                 help="The resolver: Newton on the Add-link lengths, fixed-point iteration on the decomposed group, "
                      "or Newton on the group's closure equations."),
    click.option("--tolerance", type=click.FloatRange(0.0, MAX_TOLERANCE, min_open=True),
                 help="The resolver's tolerance, relative to the length scale."),
    click.option("--iterations", type=click.IntRange(1, MAX_ITERATIONS), help="The resolver's iteration cap."),
    click.option("--polish/--no-polish", default=None, help="One resolver step more once the tolerance is met."),
    click.option("--predictor", type=click.IntRange(min(PREDICTORS), max(PREDICTORS)),
                 help="The warm start's order: 0 the last row, 1 along its rates, 2 (default) along the "
                      "parabola with those rates through the row before."),
    click.option("--checks/--no-checks", default=None,
                 help="Conditioning and status per step (off: positions and rates only)."),
    click.option("--angles", type=click.Choice(ANGLE_FORMS), help="Angle outputs as angles or as unit vectors."),
    click.option("--units", type=click.Choice(UNIT_SYSTEMS),
                 help="Angle inputs and outputs in radians (SI) or in the file's unit (degrees where it uses them)."),
    click.option("--assembly", type=click.IntRange(min=1),
                 help="Follow assembly K at the sketch's inputs (linkgen assemblies numbers them), not the sketch's."),
)


def settings(fn: Any) -> Any:
    """The SETTINGS flags on a command; it gets them as one mapping ``settings`` of those given."""
    for flag in reversed(SETTINGS):
        fn = flag(fn)
    return fn


def given(flags: dict[str, Any]) -> dict[str, object]:
    """The settings given on the command line (the others stay the file's)."""
    return {k: v for k, v in flags.items() if v is not None}


def outputs(value: str | None) -> tuple[str, ...] | None:
    """--outputs: comma-separated names (blank ones dropped); None where not given."""
    return tuple(v.strip() for v in value.split(",") if v.strip()) if value else None


def values(ctx: click.Context, param: click.Parameter, value: str | None) -> tuple[float, ...] | None:
    """--at, --rates: comma-separated finite numbers."""
    if value is None:
        return None
    try:
        out = tuple(float(v) for v in value.split(","))
    except ValueError:
        raise click.BadParameter(f"{value!r} is not a list of numbers: give one value per input, "
                                 "separated by commas (e.g. 90 or 10,20)") from None
    if not all(math.isfinite(v) and abs(v) <= MAX_MAGNITUDE for v in out):
        raise click.BadParameter(f"{value!r}: every value must be finite and at most {MAX_MAGNITUDE:g} in size")
    return out
