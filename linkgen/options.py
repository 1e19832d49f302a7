"""The knobs a user turns (the file's ``options:`` and the command line's flags): what the
programs compute in and how, one record that the step log, the manual and every program's
header state.  The numbers they set reach the resolver through the log's policy."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, fields, replace
from types import SimpleNamespace

from .policy import DEFAULT_REAL, POLICY, REAL_TYPES, Policy

STRATEGIES = ("newton", "fixed-point", "closure", "loop")  # the resolver strategies (see Options.strategy)
PREDICTORS = (0, 1, 2)  # the warm start's order: the last row's state, along its rates, along the parabola
# with those rates through the row before
ANGLE_FORMS = ("angle", "unit")  # angle outputs as angles (atan2) or as unit vectors (no trigonometry)
UNIT_SYSTEMS = ("si", "file")  # the programs' inputs and outputs in radians (SI) or in the file's angle unit
MAX_ITERATIONS = 100  # the largest iteration cap a user may set
MAX_TOLERANCE = 1e-3  # the loosest resolver tolerance a user may set, relative to the length scale


@dataclass(frozen=True)
class Options:
    """The programs' settings; the defaults are what linkgen builds without options."""

    real: str = DEFAULT_REAL  # the real type: float, double or long double (C; numpy: float32 for float)
    strategy: str = "newton"  # resolver: newton on the Add-link lengths (the paper's), fixed-point
    # iteration on the decomposed group, closure: Newton on the group's loop-closure equations, or loop: the
    # literature's fixed-point iteration on one assumed angle of a class-III group (extraction.loops)
    tolerance: float = POLICY.tolerance  # the resolver stops at this residual, relative to the length scale
    iterations: int = POLICY.max_iterations  # the resolver's iteration cap
    polish: bool = True  # one resolver step more once the tolerance is met
    predictor: int = 2  # the warm start's order (PREDICTORS): the parabola takes fewer Newton steps than the
    # tangent for the same statuses (docs/mechanism-format.md)
    checks: bool = True  # conditioning and status per step; off: positions and rates only
    angles: str = "angle"  # angle outputs as angles or as unit vectors (ANGLE_FORMS)
    assembly: int = 0  # the assembly the programs follow (linkgen assemblies' number at the sketch's
    # inputs); 0: the sketch's
    units: str = "si"  # inputs and outputs in SI radians, or in the file's units (degrees; linkgen.units)


CHOICES: dict[str, tuple[object, ...]] = {"real": REAL_TYPES, "strategy": STRATEGIES, "predictor": PREDICTORS,
                                          "angles": ANGLE_FORMS, "units": UNIT_SYSTEMS}


def overridden(options: Options, given: Mapping[str, object]) -> Options:
    """``options`` with the settings in ``given`` (Options' field names, checked by the command line) replaced."""
    unknown = set(given) - set(Options.__dataclass_fields__)
    if unknown:
        raise ValueError(f"no such option: {', '.join(sorted(unknown))}")
    return replace(options, **given)  # type: ignore[arg-type]


def policy_for(options: Options, policy: Policy = POLICY) -> Policy:
    """The policy of the step log built with ``options``: the resolver's tolerance (the path
    slack in proportion) and iteration cap (a program in float raises the tolerance to its
    type's floor when it is rendered: policy.for_real)."""
    return replace(policy, tolerance=options.tolerance, max_iterations=options.iterations,
                   path_slack=policy.path_slack * options.tolerance / policy.tolerance)


def reference(options: Options) -> Options:
    """``options`` with the resolver's default iteration (Newton, polish, second-order
    predictor) and every check on: the build follows the mechanism with them to find its motion
    facts (the reach, the conditioning over the sweep), which are the mechanism's, whatever the
    programs run."""
    default = Options()
    return replace(options, strategy=default.strategy, polish=default.polish, predictor=default.predictor,
                   checks=default.checks)


def runtime_policy(policy: Policy, options: Options) -> SimpleNamespace:
    """The resolver policy as the runtime reads it (the programs' POLICY): the policy's numbers
    with the options' strategy, polish and predictor."""
    numbers = {f.name: getattr(policy, f.name) for f in fields(policy)}  # asdict's deep copy of numbers: 20x slower
    return SimpleNamespace(**numbers, strategy=options.strategy, polish=options.polish, predictor=options.predictor)


def describe(options: Options, resolver: Policy | None) -> str:
    """The settings besides the real type, as the files' first lines state them; the resolver's
    only where the mechanism has one (its tolerance and cap as its program's ``resolver`` policy has them)."""
    words = [f"checks {'on' if options.checks else 'off'}",
             f"angles as {'angles' if options.angles == 'angle' else 'unit vectors'}"]
    if options.units == "file":
        words.append("units the file's")
    if options.assembly:
        words.append(f"assembly {options.assembly}")
    if resolver:
        words.insert(0, f"resolver {options.strategy} (tolerance {resolver.tolerance:g}, at most "
                        f"{resolver.max_iterations} iterations, polish {'on' if options.polish else 'off'}, "
                        f"predictor order {options.predictor})")
    return "Settings: " + ", ".join(words) + "."
