"""Every assembly of a mechanism at one input, the count certified (``linkgen assemblies``).

``enumerate`` walks the procedure as a tree (both branches of every two-link chain, every
real root of every class-III group's characteristic polynomial, every assembly of a class-IV
group); ``triad`` reads a group's shape off the step log, ``polynomial`` reduces it to one
polynomial and isolates its roots; ``bodies`` and ``resultant`` do the same for a class-IV group
of two links on four-bars tied by two couplers (resultants, back-substitution);
``report`` writes the table and the JSON, ``render`` one SVG per assembly.
"""

from __future__ import annotations

from collections.abc import Sequence

from ..errors import ProcedureError
from ..pipeline import build_log
from ..steplog import StepLog
from ..units import from_file, to_file
from ..validate import read_mechanism
from .enumerate import Census, census
from .triad import NotReducible

__all__ = ["Census", "assemblies", "whole_log"]


def whole_log(path: str) -> StepLog:
    """The step log of the whole procedure, every output at order 0 (what ``assemblies`` walks), from
    the sketch as drawn (``options: assembly`` redraws it for the programs only)."""
    return build_log(path, outputs=(), order=0, sweep=False, options={"assembly": 0})


def assemblies(path: str, log: StepLog, at: Sequence[float] | None = None) -> Census:
    """Every assembly of the mechanism file ``path`` (its ``whole_log``) at the input values ``at``
    in file units (default: the sketch's)."""
    values = tuple(i.sketch for i in log.inputs) if at is None else from_file(log, at)
    try:
        out = census(log, values)
    except (NotReducible, ArithmeticError) as exc:
        m = read_mechanism(path)
        what = "its assemblies are not counted" if isinstance(exc, NotReducible) else "the count is not certified"
        raise ProcedureError(f"linkgen cannot count the assemblies of this mechanism: {exc} ({what})", m.path,
                             m.where.line, "links") from None
    out.at = to_file(log, values) if at is None else tuple(float(v) for v in at)
    return out
