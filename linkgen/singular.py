"""Stage 5b: the sweep's singular positions, found by root finding, and change points.

Along the sweep (all inputs moving together, lambda from 0 to 1) every step's
conditioning is recorded; where a chain reaches a singular position the input
value is located by zooming in on it: a limit position (the chain cannot close
beyond it), a change point (its two assemblies cross and the motion goes on), or
a near-singular minimum.

A change point is a double root of the chain's closing margin (for a 3R chain the
Kahan factor z - (x - y), zero at a toggle): the margin touches zero and comes
back, as in a parallelogram four-bar with all pivots in line.  There the smooth
motion continues on the other branch, so the chain's branch flips at every change
point between the sketch and the input (mechanisms with one input).
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import NamedTuple

import numpy as np

from . import status
from .evaluate import Result, RowSolver, evaluate, reach_side
from .primitives import PRIMITIVES
from .steplog import Conditioning, Reach, Singular, StatusCode, Step, StepLog

ZOOMS = 10  # refinements of a bracket around a minimum, each to 1/16 of the last
EDGE_ZOOMS = 5  # refinements of a limit position, each to 1/32 of the last
GRID = 33  # points per refinement
TOUCH = 1e-9  # a margin within this of zero, relative to the length scale, touches zero
SMALL = 1e-3  # minima of the margin or of sigma below this are examined
FOLLOW = 180  # rows of a turn (or of the span of a sliding input) that the search for limit positions follows
REFINE = 60  # values tried at most to locate a limit position once a value past it failed
FEW_HALVINGS = 4  # the search's continuation halves a step this often (a cut is then checked as the programs cut)
AIM = 0.9  # the search tries this share of the way to the limit position it expects (less after a miss)
PROBE = 0.125  # without a root ahead, the value tried lies this far into the bracket (a row past a limit costs more)
PRECISION = 1e-12  # a limit position is located to this, relative to its input value (or to 1 rad, or the length scale)


def _lambdas(log: StepLog, lam: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    start = np.array([i.start for i in log.inputs])
    stop = np.array([i.stop for i in log.inputs])
    values = start + lam[:, None] * (stop - start)
    rates = np.tile([i.speed for i in log.inputs], (len(lam), 1)).astype(float)
    return values, rates, np.zeros_like(values)


def _run(log: StepLog, lam: np.ndarray, warm=None, stop: int = 0) -> Result:
    """Evaluate at sweep positions lam (in order); with resolvers, ``stop`` ends the rows at
    the first one that fails at or before that step (the rest of a zoom grid would too)."""
    with np.errstate(all="ignore"):
        return evaluate(log, *_lambdas(log, lam), order=0, warm=warm, stop=stop)


def _rec(result: Result, var: str, field: int = 0) -> np.ndarray:
    return result.values[var][field]


def margin(step: Step, result: Result) -> np.ndarray | None:
    """The chain's closing margin per row: zero at a toggle, negative where it cannot close."""
    a = {arg.label or f"#{k}": arg for k, arg in enumerate(step.args)}
    args = step.args
    if step.function == "RRR_links":
        x1, y1 = _rec(result, args[0].var), _rec(result, args[0].var, 1)
        x2, y2 = _rec(result, args[1].var), _rec(result, args[1].var, 1)
        sides = np.stack([np.sqrt((x2 - x1) ** 2 + (y2 - y1) ** 2), _rec(result, args[2].var),
                          _rec(result, args[3].var)])
        big, small = sides.max(axis=0), sides.min(axis=0)
        return small - (big - (sides.sum(axis=0) - big - small))
    if step.function == "PRR_links":
        jx, jy = _rec(result, args[0].var), _rec(result, args[0].var, 1)
        length = _rec(result, args[1].var)
        px, py = _rec(result, args[2].var), _rec(result, args[2].var, 1)
        psi = _rec(result, args[3].var)
        gsi, eta = float(a["gsi"].value), float(a["eta"].value)
        c, s = np.cos(psi), np.sin(psi)
        wx, wy = px + gsi * c - eta * s - jx, py + gsi * s + eta * c - jy
        return length - np.abs(wx * s - wy * c)
    if step.function == "RPR_links":
        dx = _rec(result, args[1].var) - _rec(result, args[0].var)
        dy = _rec(result, args[1].var, 1) - _rec(result, args[0].var, 1)
        return np.sqrt(dx * dx + dy * dy) - abs(float(a["bg"].value) - float(a["bs"].value))
    return None


def _closes(result: Result, step: int) -> np.ndarray:
    """Rows where the procedure gets past this step."""
    st = result.status
    return ~(status.failed(st) & (status.step(st) <= step))


def _zoom_min(log: StepLog, lo: float, hi: float, value, warm=None) -> tuple[float, float]:
    """(lambda, minimum) of value(result) on [lo, hi], by repeated grid refinement."""
    best = (lo, np.inf)
    for _ in range(ZOOMS):
        lam = np.linspace(lo, hi, GRID)
        v = value(_run(log, lam, warm))
        if not np.any(np.isfinite(v)):
            break
        k = int(np.nanargmin(np.where(np.isfinite(v), v, np.nan)))
        best = (float(lam[k]), float(v[k]))
        step = (hi - lo) / (GRID - 1)
        lo, hi = max(lo, lam[k] - step), min(hi, lam[k] + step)
    return best


def _vertex(log: StepLog, lam: float, delta: float, value) -> float:
    """The vertex of the parabola through value at lam - delta, lam, lam + delta.

    A double root's margin is smooth and quadratic: its vertex locates the root to
    rounding / (curvature * delta), where the minimum itself is only good to sqrt(eps).
    """
    lo, mid, hi = value(_run(log, np.array([lam - delta, lam, lam + delta])))
    curve = lo - 2 * mid + hi
    return lam if not curve > 0 else lam + delta * (lo - hi) / (2 * curve)


def _zoom_edge(log: StepLog, good: float, bad: float, number: int, sigma: float, warm=None) -> tuple[float, float]:
    """The last lambda from good towards bad where the procedure gets past step number, and
    the step's conditioning there (sigma: at good), by repeated grid refinement."""
    for _ in range(EDGE_ZOOMS):
        lam = np.linspace(good, bad, GRID)
        result = _run(log, lam, warm, stop=number)
        fine = _closes(result, number)
        if not fine[0]:
            break
        k = int(np.argmin(fine)) if not fine.all() else GRID - 1
        last = result.sigma[number][max(k - 1, 0)] if number in result.sigma else np.nan
        sigma = float(last) if np.isfinite(last) else sigma
        good, bad = float(lam[max(k - 1, 0)]), float(lam[k])
    return good, sigma


def _local_minima(v: np.ndarray, usable: np.ndarray, periodic: bool = False) -> list[int]:
    """Rows where v has a local minimum; across the seam too when the grid closes on itself
    (its last row is its first)."""
    n = len(v)
    out = []
    for k in range(n - 1 if periodic else n - 1):
        if not periodic and k == 0:
            continue
        before, after = (k - 1) % (n - 1) if periodic else k - 1, k + 1
        if usable[before] and usable[k] and usable[after] and v[k] <= v[before] and v[k] <= v[after]:
            out.append(k)
    return out


def _input_values(log: StepLog, lam: float) -> tuple[float, ...]:
    return tuple(float(f"{i.start + lam * (i.stop - i.start):.10g}") for i in log.inputs)


def _span(log: StepLog) -> tuple[float, float, bool]:
    """The input interval searched for change points: a full turn around the sketch for an
    angle (so the change points are complete modulo 2 pi), else the sweep and the sketch."""
    inp = log.inputs[0]
    if inp.kind == "revolute":
        return inp.sketch - np.pi, inp.sketch + np.pi, True
    return min(inp.start, inp.stop, inp.sketch), max(inp.start, inp.stop, inp.sketch), False


def change_points(log: StepLog) -> StepLog:
    """Find the chains that pass change points and give them the flipping branch policy."""
    if len(log.inputs) != 1 or log.groups:
        return log
    lo, hi, periodic = _span(log)
    n = max(2 * log.samples, 721)
    span = replace(log, inputs=(replace(log.inputs[0], start=lo, stop=hi),))
    grid = np.linspace(0.0, 1.0, n)
    done: set[int] = set()
    while True:
        result = _run(span, grid)
        for step in span.steps:
            if step.number in done or step.branch == 0:
                continue
            m = margin(step, result)
            if m is None:
                continue
            done.add(step.number)
            usable = _closes(result, step.number - 1) & np.isfinite(m)
            points = []
            for k in _local_minima(m, usable, periodic):
                if m[k] > SMALL * log.length_scale:
                    continue
                a, b = grid[k] - grid[1], grid[k] + grid[1]
                lam, low = _zoom_min(span, a, b, lambda r, s=step: margin(s, r))
                if abs(low) <= TOUCH * log.length_scale:
                    lam = _vertex(span, lam, grid[1] / 8, lambda r, s=step: margin(s, r))
                    value = lo + lam * (hi - lo)
                    points.append(0.0 if abs(value) < 1e-10 * (hi - lo) else float(f"{value:.12g}"))
            if points:
                span = _with_points(span, step, tuple(sorted(set(points))))
                break
        else:
            return replace(span, inputs=log.inputs)


def _gaps(log: StepLog, span: StepLog, grid: np.ndarray, periodic: bool) -> list[tuple[float, int]]:
    """(input value, step) of every gap of the span where a chain with two assemblies cannot
    close: the middle of a run of failing grid rows (its ends located by root finding; of a
    run cut by the span's end, its failing row next to the rows that close), and the deepest
    point of a chain's closing margin where it dips below zero between two rows.  A chain
    with one assembly (PRP, PPR) fails only where it is singular, and passes through."""
    result = _run(span, grid)
    st = result.status
    margins = {s.number: margin(s, result) for s in span.steps}
    two = [number for number, m in margins.items() if m is not None]
    fails = status.failed(st) & np.isin(status.step(st), two)
    n = len(grid) - 1 if periodic else len(grid)  # a full turn: the last row is the first
    first, width = span.inputs[0].start, span.inputs[0].stop - span.inputs[0].start

    def lam(j: int) -> float:  # grid position of row j, counted on past the end of a turn
        return float(grid[j % n] + j // n)

    def edge(good: int, bad: int) -> float:  # the last position from row good towards row bad that closes
        return _zoom_edge(span, lam(good), lam(bad), int(status.step(st[bad % n])), 0.0)[0]

    out = []
    for k in range(n):
        if not fails[k] or (fails[(k - 1) % n] if periodic else k > 0 and fails[k - 1]):
            continue  # not the first row of a run of failing rows
        end = k
        while fails[(end + 1) % n] and (end + 1 < k + n if periodic else end + 1 < n):
            end += 1
        opens, closes = periodic or k > 0, periodic or end < n - 1  # whether the run has each end in the span
        if opens and closes:
            a, b = edge(k - 1, k), edge(end + 1, end)
            middle = a + (b - a) / 2
        else:
            middle = lam(k) if opens else lam(end)
        out.append((first + middle * width, int(status.step(st[k]))))
    for s in span.steps:
        m = margins[s.number]
        if m is None:
            continue
        usable = _closes(result, s.number) & np.isfinite(m)
        for k in _local_minima(m, usable, periodic):
            at, low = _zoom_min(span, grid[k] - grid[1], grid[k] + grid[1], lambda r, s=s: margin(s, r))
            if low < -TOUCH * log.length_scale:
                out.append((first + at * width, s.number))
    return out


def reach_interval(log: StepLog) -> StepLog:
    """The input values the mechanism reaches from the sketch (one input): between the nearest
    gaps, below and above the sketch's value, where a chain cannot close (the middles of the
    gaps), or, with resolvers, the nearest limit positions."""
    if len(log.inputs) != 1:
        return log
    found = _resolver_reach(log) if log.groups else _closed_form_reach(log)
    if found is None or (found.low is None and found.high is None):
        return log
    codes = list(log.status_codes)
    for step in {found.low_step, found.high_step} - {0}:
        if log.step(step).action == "resolve":  # a resolver's limit position: its own reason 1
            codes.append(StatusCode(status.code(step, status.CANNOT_CLOSE), step,
                                    f"step {step} ({log.step(step).target}): cannot assemble past a limit position"))
    return replace(log, reach=found, runtime=tuple(sorted(set(log.runtime) | {"reach_at"})),
                   status_codes=tuple(sorted(codes, key=lambda c: (c.step, status.reason(c.code)))))


def _closed_form_reach(log: StepLog) -> Reach | None:
    """Without resolvers: between the middles of the nearest gaps, below and above the sketch's
    value, where a chain cannot close.  Past a gap a chain can close again, on another circuit
    that the mechanism cannot reach without being taken apart."""
    lo, hi, periodic = _span(log)
    span = replace(log, inputs=(replace(log.inputs[0], start=lo, stop=hi),))
    gaps = _gaps(log, span, np.linspace(0.0, 1.0, max(2 * log.samples, 721) | 1), periodic)
    if len(gaps) < (2 if periodic else 1):
        return None  # an angle with one gap is reached all round but in the gap (where rows fail anyway)
    theta0, turn = log.inputs[0].sketch, 2 * np.pi
    if periodic:  # every gap bounds the reach on both sides, a turn apart
        gaps = [(g + k * turn, step) for g, step in gaps for k in (-1, 0, 1)]
    high, high_step = min(((g, step) for g, step in gaps if g > theta0), default=(None, 0))
    low, low_step = max(((g, step) for g, step in gaps if g < theta0), default=(None, 0))
    return Reach(None if low is None else float(f"{low:.12g}"), low_step,
                 None if high is None else float(f"{high:.12g}"), high_step, periodic)


def _resolver_reach(log: StepLog) -> Reach | None:
    """With resolvers: the nearest limit positions below and above the sketch's value, where
    the sketch's assembly, followed from the sketch as the programs follow it, cannot be
    continued.  An angle is followed at most a turn in all: a mechanism that gets that far has
    no reach (it turns fully, or its circuit covers a turn); nor has one whose way is cut
    where it is not at a limit position (see _limit), on either side for an angle."""
    inp = log.inputs[0]
    solver = RowSolver(log, 1)
    if inp.kind == "revolute":
        high = _limit(log, solver, inp.sketch + 2 * np.pi)
        low = None if high is None or high[0] is None else _limit(log, solver, high[0] - 2 * np.pi)
        if low is None or low[0] is None:
            return None
    else:
        lo, hi, _ = _span(log)
        high, low = _limit(log, solver, hi) or (None, 0), _limit(log, solver, lo) or (None, 0)
    return Reach(low[0], low[1], high[0], high[1], inp.kind == "revolute")


class _Point(NamedTuple):
    """A value the search for a limit position reached: the solver's warm start there, the
    fastest point's speed per unit input rate, relative to the length scale, and the
    conditioning of the steps outside the resolver blocks."""

    value: float
    warm: tuple
    speed: float
    sigma: dict


def _limit(log: StepLog, solver: RowSolver, stop: float) -> tuple[float | None, int] | None:
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
    lo, hi, periodic = _span(log)
    unit = 1.0 if periodic else log.length_scale
    rows = int(np.ceil(FOLLOW * abs(stop - theta0) / ((2 * np.pi) if periodic else max(hi - lo, unit))))
    row, sign = abs(stop - theta0) / max(rows, 1), np.sign(stop - theta0)
    inner = {n for g in log.groups for b in (g, *g.variants) for n in b.steps}
    points = {v.name for v in log.variables if v.kind == "POINT" and not v.constant}

    def attempt(value: float, warm, halvings: int) -> _Point | None:
        solver.warm, solver.halvings = warm, halvings
        out = solver.solve([value], [1.0], [0.0], one_way=True)
        solver.halvings = full
        if not out.ok:
            return None
        speed = max((math.hypot(*out.env[p][2:4]) for p in points), default=0.0) / log.length_scale
        sigma = {n: s for n, (_, s) in out.report.items() if n not in inner and np.isfinite(s)}
        return _Point(value, solver.warm, speed, sigma)

    full = solver.halvings
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


def _at_limit(attempt, theta0: float, reached: list[_Point], bad: float, unit: float, finest: float) -> bool:
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


def _with_points(log: StepLog, step: Step, points: tuple[float, ...]) -> StepLog:
    note = (f"{step.branch_reason}; the chain passes change points, where its two assemblies cross, at input "
            f"{', '.join(f'{p:.10g}' for p in points)}, and its branch flips at each of them")
    new = replace(step, change_points=points, branch_reason=note)
    steps = tuple(new if s.number == step.number else s for s in log.steps)
    runtime = tuple(sorted(set(log.runtime) | {"branch_at"}))
    return replace(log, steps=steps, runtime=runtime)


def _warm(result: Result, row: int):
    """The resolver's warm start after a sweep row (None without resolvers)."""
    return result.warm[row] if result.warm else None


def _reach_limit(log: StepLog, good: float, bad: float) -> float | None:
    """The sweep position of the resolver mechanism's limit position between sweep positions
    good (reached) and bad (past the reach), or None (no resolver, or the reach not between)."""
    reach, inp = log.reach, log.inputs[0] if log.inputs else None
    if not log.groups or reach is None or inp.start == inp.stop:
        return None
    before, after = (inp.start + lam * (inp.stop - inp.start) for lam in (good, bad))
    if reach_side(reach, np.array([before]))[0] or not reach_side(reach, np.array([after]))[0]:
        return None
    bound = reach.high if after > before else reach.low
    if reach.periodic:  # the bound's turn between the two
        bound += 2 * np.pi * np.floor((before - reach.low) / (2 * np.pi))
    return (bound - inp.start) / (inp.stop - inp.start)


def conditioning(log: StepLog) -> StepLog:
    """Every step's conditioning over the sweep, and the input values where it reaches zero."""
    grid = np.linspace(0.0, 1.0, log.samples)
    result = _run(log, grid)
    inner = {n for g in log.groups for b in (g, *g.variants) for n in b.steps}
    out = []
    for number in sorted(result.sigma):
        step = log.step(number)
        if step.action != "resolve" and PRIMITIVES[step.function].sigma is None:
            continue
        sigma = result.sigma[number]
        closes = _closes(result, number)
        usable = closes & np.isfinite(sigma)
        if not usable.any():
            continue
        found = [Singular((p,), "change point", 0.0) for p in step.change_points]
        for k in range(len(grid) - 1):
            # a resolver block's chain fails only as its group does: the group's step has the limit
            if usable[k] != usable[k + 1] and closes[k] != closes[k + 1] and number not in inner:
                good, bad = (k, k + 1) if usable[k] else (k + 1, k)
                lam = _reach_limit(log, grid[good], grid[bad])
                if lam is not None:  # located when the reach was: sigma is 0 there
                    found.append(Singular(_input_values(log, lam), "limit", 0.0))
                    continue
                lam, s = _zoom_edge(log, grid[good], grid[bad], number, float(sigma[good]), _warm(result, good))
                found.append(Singular(_input_values(log, lam), "limit", float(f"{s:.3g}")))
        for k in _local_minima(sigma, usable):
            if sigma[k] >= SMALL or step.change_points:
                continue
            lam, low = _zoom_min(log, grid[k - 1], grid[k + 1], lambda r, n=number: r.sigma.get(n),
                                 _warm(result, k - 1))
            found.append(Singular(_input_values(log, lam), "minimum", float(f"{low:.3g}")))
        found.sort(key=lambda s: s.inputs)
        out.append(Conditioning(number, float(f"{sigma[usable].min():.3g}"), float(f"{sigma[usable].max():.3g}"),
                                tuple(found)))
    return replace(log, conditioning=tuple(out))
