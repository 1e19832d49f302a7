"""The numbers that steer extraction, the resolver and the status rules, each defined once.

``POLICY`` is the step log's record of them (the programs and the manual read it there);
the primitives (linkgen/primitives/vectors.py, dyads.py) take their thresholds from here too.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

RESOLVER_TOLERANCE = 1e-10  # relative to the length scale; one Newton step is taken past it
RESOLVER_MAX_ITERATIONS = 8
CONTINUATION_HALVINGS = 20
NEWTON_HALVINGS = 3  # a Newton step that makes a chain fail to close is halved this often, then the block fails
WALK_PASSES = 1000  # a continuation walk gives up after this many passes of the procedure
PATH_SHARE = 0.1  # a solution may sit off the predicted path by this share of the largest predicted move
TURN_SHARE = 0.01  # ... and by this share where a block's orientation turned (a singular position crossed)
RESOLVER_MAX_MOVE = 0.1  # relative to the length scale: farther from the start lengths is another assembly
RESOLVER_MIN_CHAIN_SIGMA = 0.05  # below it, a block's Add-links are a poor coordinate of the assembly
STEP_ANGLE = 0.1  # continuation: the largest step of an angle input (radians)
STEP_LENGTH = 0.05  # ... and of a length input, times the length scale
PATH_SLACK = 1e3 * RESOLVER_TOLERANCE  # a solution may sit off the predicted path beyond a tenth of the move
NEAR_SINGULAR = 1e-3  # sigma below this: derivatives grow without bound (status 4)
SINGULAR = 1e-7  # sigma below this: derivatives are not given (status 3)
TOGGLE_SLACK = 8  # a chain's closing factor in [-8 eps x, 0) is a toggle, not a failure
MAX_VARIANTS = 8  # fallback Add-link candidates per resolver group
GOOD_LEVER = 0.25  # a block that magnifies its frame angle's error more than fourfold ranks after the others
PROBE_ANGLE = math.radians(5.0)  # the paper's +5 degrees for ranking Add-link candidates
PROBE_LENGTH = 0.05  # times the length scale, for prismatic and distance inputs
MAX_MAGNITUDE = 1e30  # the largest coordinate, range bound, speed and program input, in size (file units)
LENGTH_SCALES = (1e-30, 1e30)  # the sketch sizes linkgen supports, in file units
REAL_TYPES = ("float", "double", "long double")  # the real types a program can compute in (options: real)
DEFAULT_REAL = "double"
EPSILON = {"float": 2.0**-23, "double": 2.0**-52, "long double": 2.0**-52}  # long double: at least double's
TOLERANCE_EPS = 64  # a resolver tolerance below this many eps of the real type cannot be met
SINGULAR_EPS = 8  # a sigma below this many eps of the real type is rounding, not a measure


@dataclass(frozen=True)
class Policy:
    """Every number the resolver, the continuation and the status rules use (linkgen/policy.py
    makes it); lengths are relative to the length scale."""

    tolerance: float  # the resolver stops once every residual is at most this, then takes one step more
    max_iterations: int  # Newton steps at most
    max_halvings: int  # continuation: how often in a row a step may be halved
    max_move: float  # a Newton solution farther from its start is another assembly, and a continuation
    # step moves no predicted Add-link length farther
    min_chain_sigma: float  # a block whose chains are worse conditioned yields to a better one
    step_angle: float  # continuation: the largest step of an angle input (radians)
    step_length: float  # ... and of a length input
    path_slack: float  # how far a solution may sit off the predicted path beyond a tenth of the predicted move
    near_singular: float  # sigma below this: status 4, derivatives grow without bound
    singular: float  # sigma below this: status 3, derivatives not given
    toggle_slack: float  # a chain's closing factor in [-toggle_slack eps x, 0) is a toggle, not a failure
    good_lever: float  # a block whose lever is below this ranks after the others
    max_input: float  # the largest input, rate or acceleration a program accepts, in size
    newton_halvings: int  # a Newton step that makes a chain fail to close is halved at most this often
    walk_passes: int  # a continuation walk gives up after this many passes of the procedure
    path_share: float  # a solution may sit off the predicted path by this share of the largest predicted move
    turn_share: float  # ... by this share where a block's orientation turned (it crossed a singular position)


POLICY = Policy(RESOLVER_TOLERANCE, RESOLVER_MAX_ITERATIONS, CONTINUATION_HALVINGS, RESOLVER_MAX_MOVE,
                RESOLVER_MIN_CHAIN_SIGMA, STEP_ANGLE, STEP_LENGTH, PATH_SLACK, NEAR_SINGULAR, SINGULAR, TOGGLE_SLACK,
                GOOD_LEVER, MAX_MAGNITUDE, NEWTON_HALVINGS, WALK_PASSES, PATH_SHARE, TURN_SHARE)


def for_real(policy: Policy, real: str) -> Policy:
    """The policy of a program computing in ``real``: the resolver tolerance at least 64 eps of
    the type (the path slack a thousand times it, as POLICY's), the singular threshold at least
    8 eps.  The same policy for double and long double (eps taken as double's)."""
    eps = EPSILON[real]
    tolerance = max(policy.tolerance, TOLERANCE_EPS * eps)
    return replace(policy, tolerance=tolerance, path_slack=policy.path_slack * tolerance / policy.tolerance,
                   singular=max(policy.singular, SINGULAR_EPS * eps))
