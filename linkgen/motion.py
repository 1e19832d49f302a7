"""The motion facts a step log records: where chains cannot close, the reach, the conditioning.

``linkgen.analysis`` finds them by evaluating the procedure.  A gap belongs to one step
and holds for every procedure that contains the step (it depends only on the steps the
step reads from), so a pruned log keeps its steps' gaps and ``reach_between`` combines
them, for a whole log and a pruned one alike.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

from . import status


@dataclass(frozen=True)
class Singular:
    """An input value where a step's conditioning reaches zero, found by root finding."""

    inputs: tuple[float, ...]
    kind: str  # limit (the chain cannot close beyond) | change point (two branches cross) | minimum
    sigma: float  # the conditioning there


@dataclass(frozen=True)
class Conditioning:
    """A step's conditioning over the sweep (assembled rows only)."""

    step: int
    low: float
    high: float
    singular: tuple[Singular, ...]


@dataclass(frozen=True)
class Gap:
    """Values of the one input where a step's chain cannot close while the steps it reads
    from close: from the last value where it closes to the next where it closes again (both
    located by root finding), or one value (``low == high``) where its closing margin dips
    below zero between two values where it closes.  A side is None where the gap runs past
    the end of a sliding input's span; the other side is then the first value found failing."""

    step: int
    low: float | None
    high: float | None

    @property
    def point(self) -> bool:
        return self.low is not None and self.low == self.high


@dataclass(frozen=True)
class Reach:
    """The values of a mechanism's one input that it reaches from the sketch: between the
    middles of the nearest gaps, below and above the sketch's value, where a chain cannot
    close, or, with resolvers, between the nearest limit positions (None: none on that
    side).  An angle is reached modulo whole turns.  Beyond a gap a chain can close again,
    on another circuit of the mechanism; beyond a limit position the sketch's assembly does
    not go on: rows there fail with the code of the gap's or the limit's step."""

    low: float | None
    low_step: int  # the step whose chain cannot close in the gap below (0: none)
    high: float | None
    high_step: int
    periodic: bool

    def codes(self) -> tuple[int, int]:
        """The status of a row past the gap or limit below and above (a side without one takes
        the other's code: its check never fires); reason 1, the chain cannot close (or the
        resolver cannot assemble past a limit position)."""
        return (status.code(self.low_step or self.high_step, status.CANNOT_CLOSE),
                status.code(self.high_step or self.low_step, status.CANNOT_CLOSE))


def _merged(gaps: Sequence[Gap], periodic: bool) -> list[Gap]:
    """Gaps that overlap as one: the input values where some chain cannot close, each run
    named by the step whose gap starts it.  Points stay as they are.  An angle's runs are
    merged across the turn too (the last one with the first, a turn on)."""
    out: list[Gap] = []
    for g in sorted((g for g in gaps if not g.point), key=lambda g: (_before(g), g.step)):
        if out and _before(g) <= _after(out[-1]):
            last = out[-1]
            high = None if last.high is None or g.high is None else max(last.high, g.high)
            out[-1] = Gap(last.step, last.low, high)
        else:
            out.append(g)
    while periodic and len(out) > 1 and _after(out[-1]) >= _before(out[0]) + 2 * math.pi:
        first, last = out.pop(0), out[-1]
        out[-1] = Gap(last.step, last.low, max(_after(last), _after(first) + 2 * math.pi))
    return out + [g for g in gaps if g.point]


def _before(g: Gap) -> float:
    return -math.inf if g.low is None else g.low


def _after(g: Gap) -> float:
    return math.inf if g.high is None else g.high


def _middle(g: Gap) -> float:
    if g.low is None or g.high is None:
        side = g.low if g.high is None else g.high
        assert side is not None, "a gap over the whole span"
        return side
    return g.low + (g.high - g.low) / 2


def reach_between(gaps: Sequence[Gap], sketch: float, periodic: bool) -> Reach | None:
    """The reach from the sketch's input value: between the middles of the nearest gaps below
    and above it (None without a gap on either side).  An angle with one gap is reached all
    round but in the gap (where rows fail anyway): no reach.  Past a gap a chain can close
    again, on another circuit that the mechanism cannot reach without being taken apart."""
    middles = [(_middle(g), g.step) for g in _merged(gaps, periodic)]
    if len(middles) < (2 if periodic else 1):
        return None
    if periodic:  # every gap bounds the reach on both sides, a turn apart
        middles = [(m + k * 2 * math.pi, step) for m, step in middles for k in (-1, 0, 1)]
    high, high_step = min(((m, step) for m, step in middles if m > sketch), default=(None, 0))
    low, low_step = max(((m, step) for m, step in middles if m < sketch), default=(None, 0))
    if low is None and high is None:
        return None
    return Reach(None if low is None else float(f"{low:.12g}"), low_step,
                 None if high is None else float(f"{high:.12g}"), high_step, periodic)
