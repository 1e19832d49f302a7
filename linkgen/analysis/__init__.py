"""Stage 5b: the motion facts of a procedure, found by evaluating it (stage 6).

``motion_facts`` reads a draft (a step log without its motion facts) and returns the facts:
the change points of each chain (``change_points``), where each chain cannot close
(``gaps``), the reach from the sketch (between the nearest gaps, or with resolvers the
nearest limit positions: ``reach``) and every step's conditioning over the sweep
(``conditioning``).  Each is found with the ones before it in force, as the programs
will have them; ``with_facts`` makes the step log from the draft and its facts.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from ..motion import Conditioning, Gap, Reach, reach_between
from ..options import reference
from ..steplog import Draft, StepLog
from .change_points import ChangePoints, change_points, with_change_points
from .conditioning import conditioning
from .gaps import gaps
from .reach import resolver_reach

__all__ = ["Facts", "motion_facts", "with_facts"]


@dataclass(frozen=True)
class Facts:
    """What the analysis finds: each chain's change points and gaps, and the reach (with one
    input), and every step's conditioning over the sweep."""

    change_points: ChangePoints = ()
    gaps: tuple[Gap, ...] = ()
    reach: Reach | None = None
    conditioning: tuple[Conditioning, ...] = ()


def with_facts(draft: Draft, facts: Facts) -> StepLog:
    """The step log of a draft and its motion facts."""
    return replace(with_change_points(draft, dict(facts.change_points)), gaps=facts.gaps, reach=facts.reach,
                   conditioning=facts.conditioning)


def motion_facts(draft: Draft, sweep: bool = True) -> Facts:
    """The motion facts of a draft: with ``sweep``, the conditioning over the sweep too (for
    the manual; it takes a sweep and root finding).  They are the mechanism's: found with the
    reference settings (options.reference), whatever the programs will run."""
    draft = Draft(replace(draft, options=reference(draft.options)))
    facts = Facts()
    if len(draft.inputs) == 1:
        facts = Facts(change_points(draft))
        found = gaps(with_facts(draft, facts))
        inp = draft.inputs[0]
        reach = (resolver_reach(with_facts(draft, facts)) if draft.groups
                 else reach_between(found, inp.sketch, inp.kind == "revolute"))
        facts = replace(facts, gaps=found, reach=reach)
    if sweep:
        facts = replace(facts, conditioning=conditioning(with_facts(draft, facts)))
    return facts
