"""What each status a step log's programs report means: the table the manual and the
programs' headers print (status.py is the encoding)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from . import status

if TYPE_CHECKING:
    from .steplog import Step, StepLog


@dataclass(frozen=True)
class StatusCode:
    code: int
    step: int
    meaning: str


def _reasons(s: Step, strategy: str) -> dict[int, str]:
    """What each failure of a step means, by reason (a resolver's by its strategy)."""
    if s.action == "resolve":
        stuck = {status.NOT_CONTRACTING: "the resolver's fixed-point iteration does not contract"
                 + (" (neither loop, and no Add-link block converges)" if strategy == "loop" else "")}
        return {status.NOT_CONVERGED: "the resolver did not converge",
                status.SINGULAR: "the resolver's Jacobian is singular",
                status.NEAR_SINGULAR: "the resolver's Jacobian is near singular",
                **(stuck if strategy in ("fixed-point", "loop") else {})}
    if s.action == "residual":
        return {status.SINGULAR: f"the pairs of {s.target} coincide, so the resolver has no rate"}
    if s.function == "loop_turn":
        return {status.CANNOT_CLOSE: f"the loop's body {s.target} is turned over (its mirror image, no assembly)"}
    if s.function in ("link_angle", "link_direction"):
        return {status.CANNOT_CLOSE: f"the two points of {s.target} coincide"}
    if s.function in ("link_point", "pair_point"):
        return {status.CANNOT_CLOSE: f"the two pairs {s.target} is placed from coincide"}
    return {status.CANNOT_CLOSE: "the chain cannot close", status.SINGULAR: "singular position (toggle)",
            status.NEAR_SINGULAR: "near a singular position"}


def status_codes(log: StepLog) -> tuple[StatusCode, ...]:
    """Every status the log's programs can report, with its meaning, by step and reason: a
    refused input, each failing step's reasons, and a resolver's limit positions of the reach."""
    out = [StatusCode(status.code(0, status.BAD_INPUT), 0,
                      f"step 0: an input is not finite (nan or inf) or larger than {log.policy.max_input!r} in size; "
                      f"C only: `{log.name}_solve` returns `{log.name.upper()}_STATUS_BAD_INPUT`, Python and MATLAB "
                      "refuse the call with an error")]
    for s in log.steps:
        if s.fails:
            out += [StatusCode(status.code(s.number, r), s.number, f"step {s.number} ({s.target}): {meaning}")
                    for r, meaning in _reasons(s, log.options.strategy).items()]
    limits = {log.reach.low_step, log.reach.high_step} - {0} if log.reach is not None else set()
    for number in sorted(limits):
        s = log.step(number)
        if s.action == "resolve":
            out.append(StatusCode(status.code(number, status.CANNOT_CLOSE), number,
                                  f"step {number} ({s.target}): cannot assemble past a limit position"))
    return tuple(sorted(out, key=lambda c: (c.step, status.reason(c.code))))
