"""Stage 4: extract the systematic-analysis procedure.

The Solver (``solver``) computes pairs in a computable order; where it stops, the
Add-link process (``addlink``) installs a temporary binary link; each link the
Solver then leaves unused gives a residual, and the over-constraint resolver
(``resolver``) iterates the Add-link lengths until every residual vanishes.  The
stages pass a frozen ``SolverState``; ``extract`` returns the ``Procedure``.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from .. import steplog
from ..errors import ProcedureError
from ..steplog import AddLink, LJMatrix
from ..topology import Topology
from .addlink import candidates, rank
from .resolver import resolver_groups
from .solver import finish, solve, start
from .state import SolverState, Unsupported, Workspace

__all__ = ["Procedure", "SolverState", "candidates", "extract", "stuck"]


@dataclass(frozen=True)
class Procedure(steplog.Procedure):
    """What extraction hands the step log: the procedure (the numbered steps with their
    records, the log's own part), and where the outputs are found."""

    positions: dict[str, str]  # pair/point -> POINT variable
    angles: dict[str, str]  # link -> ANGLE variable of its angle
    slides: dict[str, str]  # prismatic pair -> VARIABLE of its displacement


def stuck(topo: Topology) -> SolverState | None:
    """The state where the Solver first stops (None when it completes without an Add-link)."""
    ws = start(topo)
    return None if solve(ws) else ws.frozen()


class _LeftOpen(Unsupported):
    """Every pair is known but an Add-link group has fewer residuals than Add-links."""


def extract(topo: Topology) -> Procedure:
    """Run the Solver, installing Add-links where it stops, and finish with angles and points.
    Where a group is left open (the constraint left unused is a slide line, which gives no
    residual), extract again with chains on a slide first inside groups (``slides_first``):
    the unused constraint is then a link, whose length is a residual.  A mechanism that
    extracts in the first pass keeps its procedure."""
    try:
        try:
            ws = _solved(start(topo))
        except _LeftOpen:
            first = start(topo)
            first.slides_first = True
            ws = _solved(first)
        finish(ws)
    except Unsupported as exc:
        m = topo.mechanism
        raise ProcedureError(f"linkgen cannot extract a procedure for this mechanism: {exc}",
                             m.path, m.where.line, "links") from None
    return _procedure(ws)


def _solved(ws: Workspace) -> Workspace:
    """The Solver run to the end, an Add-link installed wherever it stops."""
    while not solve(ws):
        ws = Workspace.thaw(rank(ws.frozen()))
    if ws.group:
        raise _LeftOpen("an Add-link group is left open")
    return ws


def _procedure(ws: Workspace) -> Procedure:
    """Number the steps and turn the drafts into step-log records."""
    steps = [replace(s, number=i + 1) for i, s in enumerate(ws.steps)]
    made = {o: s.number for s in reversed(steps) for o in s.outputs}  # the first step that outputs each
    installs = {s.target: s.number for s in reversed(steps) if s.action == "add_link"}
    residuals = tuple(replace(r, step=made[r.name]) for r in ws.residuals)
    add_links = tuple(AddLink(d.name, d.pairs, d.length, installs[d.name], d.candidates, d.probe) for d in ws.add_links)
    variables = dict(ws.variables)
    groups = resolver_groups(ws, steps, variables, add_links)
    m = ws.m
    lj = LJMatrix(tuple(j.name for j in m.joints), tuple(not j.revolute for j in m.joints), tuple(ws.columns), ())
    return Procedure(tuple(variables.values()), tuple(steps), lj, add_links, residuals, tuple(groups),
                     dict(ws.pos), dict(ws.angles), dict(ws.slides))
