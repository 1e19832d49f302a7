"""Status codes: the one definition of their encoding, and what each means.

A row's status is 0 when the mechanism assembles; ``10*step + reason`` names the first
step that failed and why; ``-(10*step + 4)`` flags a row computed near a singular
position; 5 (step 0) an input the program refuses.  The generated programs carry the
codes as numbers made here, and one helper per language (``reason_of`` in the runtime)
reads a code's reason back.  The functions work on ints and on numpy arrays alike.
"""

from __future__ import annotations

from typing import Any

CANNOT_CLOSE = 1  # the chain cannot close (at a resolver's step: the row lies past a limit position)
NOT_CONVERGED = 2  # the resolver did not converge
SINGULAR = 3  # a singular position: positions given, derivatives nan
NEAR_SINGULAR = 4  # near a singular position: everything given, the code negative
BAD_INPUT = 5  # step 0: an input the program refuses (not finite, or out of the supported range)
NOT_CONTRACTING = 6  # the resolver's fixed-point iteration does not contract (options: strategy: fixed-point or loop)
FAILED = (CANNOT_CLOSE, NOT_CONVERGED, NOT_CONTRACTING)  # every output of such a row is nan
STEP_WEIGHT = 10  # a code is STEP_WEIGHT * step + reason (each runtime's reason_of reads it back)


def code(step: Any, reason: Any) -> Any:
    """The status of a row that step ``step`` ends with ``reason``."""
    return (STEP_WEIGHT * step + reason) * (1 - 2 * (reason == NEAR_SINGULAR))


def reason(status: Any) -> Any:
    """The reason of a status (0 for status 0)."""
    return abs(status) % STEP_WEIGHT


def step(status: Any) -> Any:
    """The step a status names (0 for status 0 and for a refused input)."""
    return abs(status) // STEP_WEIGHT


def failed(status: Any) -> Any:
    """Whether a row has no outputs: its status is a failure (reason 1, 2 or 6)."""
    r = reason(status)
    return (status > 0) & ((r == CANNOT_CLOSE) | (r == NOT_CONVERGED) | (r == NOT_CONTRACTING))


def failures(strategy: str | None) -> tuple[int, ...]:
    """The reasons of a failed row in a program whose resolvers run ``strategy`` (None: it has
    none): only a fixed-point iteration (fixed-point, loop) can fail to contract."""
    return FAILED if strategy in ("fixed-point", "loop") else (CANNOT_CLOSE, NOT_CONVERGED)


def singular(status: Any) -> Any:
    """Whether a row's derivatives are nan: its status is a singular position."""
    return (status > 0) & (reason(status) == SINGULAR)
