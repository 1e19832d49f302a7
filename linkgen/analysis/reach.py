"""The reach of a mechanism with resolvers: its limit positions nearest the sketch.

Without resolvers the reach lies between the gaps nearest the sketch (``gaps``,
``motion.reach_between``).  With them the sketch's assembly is followed from the sketch,
as the programs follow it, until it cannot be continued: at a limit position, where the
fastest point's speed grows as one over the square root of the distance to it.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

from ..motion import Reach
from ..steplog import StepLog
from .sweep import span

if TYPE_CHECKING:  # the row solver: imported where a log has resolver groups
    from ..rowsolver import RowSolver

FOLLOW = 90  # rows of a turn (or of the span of a sliding input) that the search for limit positions follows
# (4 degrees apart: 0.7 of the continuation's largest step, policy.STEP_ANGLE; the search solves a row per value)
REFINE = 60  # values tried at most to locate a limit position once a value past it failed
FEW_HALVINGS = 4  # the search's continuation halves a step this often (a cut is then checked as the programs cut)
AIM = 0.9  # the search tries this share of the way to the limit position it expects (less after a miss)
PROBE = 0.125  # without a root ahead, the value tried lies this far into the bracket (a row past a limit costs more)
PRECISION = 1e-12  # a limit position is located to this, relative to its input value (or to 1 rad, or the length scale)


class _Point(NamedTuple):
    """A value the search for a limit position reached: the solver's warm start there, the
    fastest point's speed per unit input rate, relative to the length scale, and the
    conditioning of the steps outside the resolver blocks."""

    value: float
    warm: Any
    speed: float
    sigma: dict[int, float]


Attempt = Callable[[float, Any, int], "_Point | None"]
Limit = tuple[float | None, int]  # (the first value not reached, the limit's step); (None, 0): cut elsewhere


def resolver_reach(log: StepLog) -> Reach | None:
    """The nearest limit positions below and above the sketch's value, where the sketch's
    assembly, followed from the sketch as the programs follow it, cannot be continued.  An
    angle is followed at most a turn in all: a mechanism that gets that far has no reach (it
    turns fully, or its circuit covers a turn); nor has one whose way is cut where it is not
    at a limit position (see _limit), on either side for an angle."""
    from ..rowsolver import RowSolver

    inp = log.inputs[0]
    solver = RowSolver(log, 1)
    if inp.kind == "revolute":
        high = _limit(log, solver, inp.sketch + 2 * np.pi)
        low = None if high is None or high[0] is None else _limit(log, solver, high[0] - 2 * np.pi)
        if high is None or low is None or low[0] is None:
            return None
    else:
        lo, hi, _ = span(log)
        high, low = _limit(log, solver, hi) or (None, 0), _limit(log, solver, lo) or (None, 0)
    if low[0] is None and high[0] is None:
        return None
    return Reach(low[0], low[1], high[0], high[1], inp.kind == "revolute")


def _limit(log: StepLog, solver: RowSolver, stop: float) -> Limit | None:
    """The first limit position from the sketch's input value towards stop: (the first value
    not reached, the limit's step: the one whose conditioning is the smallest before it);
    None where the way to stop is not cut; (None, 0) where it is cut elsewhere (as where the
    mechanism goes straight through a singular position, which the programs pass with longer
    steps, and this search does too: its way is cut only where a row farther on fails too).

    The sketch's assembly is followed one way only, in rows FOLLOW a turn (or a span of a
    sliding input) apart at most.  Near a limit position the fastest point's speed goes as
    one over the square root of the distance, so speed^-2 is linear there, and the secant
    through the last two values reached points at the limit (so does that of the smallest
    sigma^2 of a step): the next value tried is AIM of the way to the nearer (a row past it
    fails, which costs far more; a quarter of the share after a miss, twice after a hit, up
    to AIM), then, within PRECISION, just past it.  Without a root ahead, the next row is
    tried, and once a value has failed, one PROBE of the way into the bracket.  These tries
    halve a continuation step at most FEW_HALVINGS times; the last value is then tried as
    the programs try it, and the cut is a limit position where the speed follows the law
    there (see _at_limit)."""
    theta0 = log.inputs[0].sketch
    lo, hi, periodic = span(log)
    unit = 1.0 if periodic else log.length_scale
    rows = int(np.ceil(FOLLOW * abs(stop - theta0) / ((2 * np.pi) if periodic else max(hi - lo, unit))))
    row, sign = abs(stop - theta0) / max(rows, 1), float(np.sign(stop - theta0))
    inner = {n for g in log.groups for b in (g, *g.variants) for n in b.steps}
    points = {v.name for v in log.variables if v.kind == "POINT" and v.role != "direction" and not v.constant}
    full = solver.halvings

    def attempt(value: float, warm: Any, halvings: int) -> _Point | None:
        solver.warm, solver.halvings = warm, halvings
        out = solver.solve([value], [1.0], [0.0], one_way=True)
        solver.halvings = full
        if not out.ok:
            return None
        speed = max((math.hypot(*out.env[p][2:4]) for p in points if p in out.env),  # a fallback's own: where it ran
                    default=0.0) / log.length_scale
        sigma = {n: float(s) for n, (_, s) in out.report.items() if n not in inner and math.isfinite(s)}
        return _Point(value, solver.warm, speed, sigma)

    first = attempt(theta0, None, full)
    if first is None:
        return None, 0
    reached, bad, root, tries, aim = [first], None, None, 0, AIM  # the values reached, the last one failed
    while True:
        good = reached[-1]
        tol = PRECISION * max(abs(good.value), unit)
        if bad is not None and (abs(bad - good.value) <= 2 * tol or tries >= REFINE):
            past = attempt(bad, good.warm, full)
            if past is None and _at_limit(attempt, theta0, reached, bad, unit, 10 * tol):
                return _outward(bad, sign), min(good.sigma, key=lambda n: (good.sigma[n], n))
            if past is None:  # a hard stretch: a row farther on, as a sweep takes it
                past = attempt(good.value + sign * min(row, abs(stop - good.value)), good.warm, full)
            if past is None:
                return None, 0
            reached, bad, root, tries = [past], None, None, 0
            continue
        if bad is None and good.value == stop:
            return None
        ahead = bad if bad is not None else (stop if abs(stop - good.value) <= row else good.value + sign * row)
        roots = _roots(reached[-2:], sign) if len(reached) > 1 else []
        if roots:
            root = good.value + sign * min(roots)
        elif bad is None:
            root = None  # no limit ahead (in a bracket the last estimate stands: it is rounding there)
        if root is not None and (root - good.value) * sign <= tol:
            trial = good.value + sign * tol  # the limit within rounding: the value just past it
        elif root is not None and (root - good.value) * sign < (ahead - good.value) * sign:
            trial = good.value + aim * (root - good.value)
        else:
            trial = ahead if bad is None else good.value + (bad - good.value) * PROBE
        now = attempt(trial, good.warm, FEW_HALVINGS)
        tries += bad is not None
        if now is not None:
            reached.append(now)
            aim = min(2 * aim, AIM)
        else:
            bad, aim = trial, aim / 4


def _outward(value: float, sign: float) -> float:
    """value to 12 significant digits (as a closed-form reach), rounded away from the sketch
    (sign: the way from it), so the bound stays past the limit position."""
    rounded = float(f"{value:.12g}")
    if (rounded - value) * sign < 0:
        rounded = float(f"{rounded + sign * 10.0 ** (math.floor(math.log10(abs(value))) - 11):.12g}")
    return rounded


def _roots(last: list[_Point], sign: float) -> list[float]:
    """How far ahead of the last of two values reached a limit position lies, by the secant
    through them of speed^-2 and of the sigma^2 of the step whose conditioning is the
    smallest (both linear near a limit position; only those that fall towards it)."""
    (before, good), roots = last, []
    step = min(good.sigma, key=lambda n: (good.sigma[n], n))
    for a, b in ((before.speed ** -2 if before.speed else np.inf, good.speed ** -2 if good.speed else np.inf),
                 (before.sigma.get(step, np.inf) ** 2, good.sigma[step] ** 2)):
        if a > b:
            roots.append(b * (good.value - before.value) / (a - b) * sign)
    return roots


def _at_limit(attempt: Attempt, theta0: float, reached: list[_Point], bad: float, unit: float,
              finest: float) -> bool:
    """Whether the way is cut at bad by a limit position: there speed^2 times the distance
    to it tends to a constant, so it is the same, within a factor two, a millionth of the
    input value (at least 1 rad, or the length scale) before it (or half the way from the
    sketch, nearer the sketch) and a hundredth of that, each followed from the last value
    reached before it.  Elsewhere (a singular position the mechanism goes straight through,
    a hard stretch for the continuation) the speed stays finite and the product tends to 0."""
    far = min(1e-6 * max(abs(bad), unit), abs(bad - theta0) / 2)
    sign = np.sign(bad - theta0)
    laws = []
    for distance in (far, far / 100):
        value = bad - sign * distance
        before = [p for p in reached if (value - p.value) * sign >= 0]
        if distance < finest or not before:
            return False
        point = attempt(value, before[-1].warm, FEW_HALVINGS)
        if point is None:
            return False
        reached = [*before, point]
        laws.append(point.speed ** 2 * distance)
    return 0.5 <= laws[1] / laws[0] <= 2.0 if laws[0] > 0 else False
