"""The evaluator's view of the loop strategy's blocks (extraction.loops): which blocks are loops, and a loop
block's state read off a configuration, as the generated programs' _lengths_N read it."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from .steplog import ResolverGroup, StepLog


def loop_flags(log: StepLog) -> tuple[int, ...]:
    """1 for every loop block of the log's groups (their state an arc length, role loop), 0 for an Add-link block."""
    return tuple(int(log.variable(b.add_links[0]).role == "loop") for g in log.groups for b in (g, *g.variants))


def arc_state(call: Callable[..., Any], k: Any, x: Any, arm: Any, old: float, width: int) -> tuple[float, ...]:
    """A loop block's arc length record off the pairs k and x of its leg (length record arm), unwrapped from the
    last row's ``old``: old + l wrap(theta - old / l) (loop_residual), with its rates."""
    r = call("loop_residual", [k, x, arm, (old, *(0.0,) * width)])[2][0]
    return (old + r[0], *r[1:])


def lengths(call: Callable[..., Any], env: dict[Any, Any], pos: dict[str, str], log: StepLog, b: ResolverGroup,
            old: list[float], width: int) -> list[tuple[float, ...]]:
    """A block's state records off a configuration (env; pos: pair -> its position record): its Add-link lengths
    (link_residual at a zero length), or a loop block's arc length (arc_state)."""
    first = log.step(b.steps[0])
    if first.function == "loop_point":
        (k, x), = b.pairs
        return [arc_state(call, env[pos[k]], env[pos[x]], env[first.args[1].var], old[0], width)]
    return [call("link_residual", [env[pos[k]], env[pos[u]], (0.0,) * (width + 1)])[2][0] for k, u in b.pairs]
