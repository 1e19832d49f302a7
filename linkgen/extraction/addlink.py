"""The Add-link process (the paper's section 3.3.1) and its ranking (section 6).

Where the Solver stops, a temporary binary link joins a known pair K to an unknown
pair U (K and U on no common link, U joined by a link to another known pair).  Every
candidate is tried from the same frozen state; the one with the smallest norm of the
residuals at a probe input wins, except that a block whose lever is poor ranks last.
"""

from __future__ import annotations

import math
from typing import NamedTuple

from ..policy import GOOD_LEVER, MAX_VARIANTS, PROBE_ANGLE, PROBE_LENGTH
from ..primitives.interpret import constant_record, run_steps
from ..steplog import Candidate, LJColumn
from ..topology import Topology
from .chains import carriers_of, ends, try_chain
from .emit import emit
from .resolver import placement_lever
from .solver import solve
from .state import AddLinkDraft, Carrier, GroupDraft, SolverState, Unsupported, VariantDraft, Workspace


def probe(topo: Topology) -> tuple[float, ...]:
    """The input values at which candidates are ranked: the paper's +5 degrees."""
    return tuple(
        v + (PROBE_ANGLE if i.kind == "revolute" else PROBE_LENGTH * topo.length_scale)
        for i, v in zip(topo.mechanism.inputs, topo.sketch_inputs)
    )


def candidates(ws: Workspace | SolverState) -> list[tuple[str, str]]:
    """Add-link candidates by section 3.3.1: a known pair K and an unknown pair U already
    joined to another known pair by a link, K and U on no common link; K first."""
    if isinstance(ws, SolverState):
        ws = Workspace.thaw(ws)
    joints = ws.m.joints
    known = [j.name for j in joints if j.revolute and j.name in ws.pos]
    out = []
    for k in known:
        for u in (j.name for j in joints if j.revolute and j.name not in ws.pos):
            carriers = carriers_of(ws, u)
            if any(k in c.pairs for c in carriers):
                continue
            if any(e != k for c in carriers for e, _ in ends(ws, c, u)):
                out.append((k, u))
    return out


def install(ws: Workspace, k: str, u: str) -> None:
    """Install the Add-link k-u and compute u through it."""
    if not ws.group:
        ws.groups.append(GroupDraft(len(ws.groups) + 1))
        ws.group = ws.groups[-1].number
    (xk, yk), (xu, yu) = ws.xy(k), ws.xy(u)
    length = math.hypot(xu - xk, yu - yk)
    name = f"add{len(ws.add_links) + 1}"
    var = ws.new_var(name, "VARIABLE", "addlink", name, sketch=(length,))
    ws.carriers.append(Carrier(name, "addlink", (k, u), var))
    ws.columns.append(LJColumn(name, "addlink", (k, u), ""))
    ws.add_links.append(AddLinkDraft(name, var, (k, u), length, ws.group))
    g = ws.groups[-1]
    ws.groups[-1] = GroupDraft(g.number, g.add_links + (var,), g.residuals)
    emit(ws, "add_link", "", [], [var], name, pairs=(k, u), links=(name,),
         reason=f"no two-link chain is computable, so the Add-link {name} joins the known {k} to the unknown {u}")
    if not try_chain(ws, u, only=name):
        raise Unsupported(f"the Add-link {k}-{u} does not complete a chain")


def _rounded(norm: float | None) -> float | None:
    """Norms to 33 significant bits (10 digits): the runtime's trigonometry differs in the
    last digits between machines, and candidates with equal norms must tie everywhere.
    Binary digits, so that a sketch scaled by 2^k ranks its candidates the same (decimal
    digits broke a four-way tie differently at two scales: triad_1953)."""
    if norm is None:
        return None
    mantissa, exponent = math.frexp(norm)
    return math.ldexp(round(mantissa * 2.0**33) / 2.0**33, exponent)


def residual_norm(ws: Workspace, values: tuple[float, ...]) -> float | None:
    """|f| of the open group's residuals with every Add-link at its sketch length (the
    paper's ranking of candidates); None where a chain cannot close."""
    env = {v.name: constant_record(v, 0, ws.topo.origin) for v in ws.variables.values() if v.constant}
    env.update((name, (value,)) for name, value in zip(ws.inputs, values))
    env.update((v.name, (v.sketch[0],)) for v in ws.variables.values() if v.role == "addlink")
    if not run_steps(ws.steps, env, 0):
        return None
    return math.sqrt(sum(env[f][0] ** 2 for f in ws.groups[-1].residuals))


MAX_AT_ONCE = 3  # the most Add-links one group is searched for at once (a class-IV group needs two)


class _Trial(NamedTuple):
    """One Add-link candidate tried (with the candidates installed after it where its group needs
    several at once): its rank key first (usable, a norm, a good lever, the norm, order)."""

    unusable: bool
    no_norm: bool
    poor_lever: bool
    norm_key: float
    order: tuple[int, ...]
    pairs: tuple[str, str]
    norm: float | None
    usable: bool
    lever: float | None
    workspace: Workspace | None
    also: tuple[tuple[str, str], ...] = ()  # the Add-links installed with it, in order


def _try(state: SolverState, order: tuple[int, ...], k: str, u: str, at: tuple[float, ...],
         start: int) -> list[_Trial]:
    """Install candidate k-u from the state and run the Solver until its group closes; where the
    group stays open, every candidate for the next Add-link of the group in turn (up to
    MAX_AT_ONCE Add-links at once): one trial per combination."""
    trial = Workspace.thaw(state)
    try:
        install(trial, k, u)
        solve(trial, stop_at_close=True)
    except Unsupported:
        return [_Trial(True, True, True, 0.0, order, (k, u), None, False, None, None)]
    if trial.group and len(order) < MAX_AT_ONCE:
        inner = trial.frozen()
        out = [t._replace(pairs=(k, u), also=(t.pairs, *t.also))
               for n, (k2, u2) in enumerate(candidates(inner)) for t in _try(inner, (*order, n), k2, u2, at, start)]
        return out or [_Trial(True, True, True, 0.0, order, (k, u), None, False, None, trial)]
    norm, lever = None, None
    if not trial.group:
        norm = _rounded(residual_norm(trial, at))
        lever = placement_lever(trial.steps[start:], trial.steps, trial.variables)
    usable = not trial.group
    return [_Trial(not usable, norm is None, lever is None or lever < GOOD_LEVER, norm if norm is not None else 0.0,
                   order, (k, u), norm, usable, lever, trial)]


def rank(state: SolverState) -> SolverState:
    """Try every candidate (every combination of candidates where the group needs several
    Add-links at once); continue with the one with the smallest norm of f at the probe among
    those whose lever is at least GOOD_LEVER (else among all), keeping the other usable ones
    with as many Add-links as fallback blocks of its group."""
    at = probe(state.topo)
    start = len(state.steps)
    tried = _distinct(sorted((t for order, (k, u) in enumerate(candidates(state))
                              for t in _try(state, (order,), k, u, at, start)), key=lambda t: t[:5]))
    if not tried:
        raise Unsupported("no Add-link candidate exists")
    best = tried[0]
    if best.workspace is None:
        raise Unsupported("no Add-link candidate completes a chain")
    chosen = best.workspace
    k = next(i for i, d in enumerate(chosen.add_links) if d.pairs == best.pairs and not d.candidates)
    d = chosen.add_links[k]
    chosen.add_links[k] = AddLinkDraft(d.name, d.var, d.pairs, d.length, d.group,
                                       tuple(Candidate(t.pairs, t.norm, t.usable, t.lever, t.also) for t in tried),
                                       at)
    others = [t for t in tried[1:] if t.usable and t.workspace is not None
              and len(t.workspace.add_links) == len(chosen.add_links)]
    group = chosen.add_links[k].group
    for t in others[:MAX_VARIANTS]:
        trial = t.workspace
        assert trial is not None
        new = tuple(v for name, v in trial.variables.items() if name not in state.variables)
        adds = [a for a in trial.add_links if a.group == group]
        chosen.variants.append(VariantDraft(group, tuple(a.pairs for a in adds), tuple(a.length for a in adds),
                                            tuple(trial.steps[start:]), new))
    return chosen.frozen()


def _distinct(tried: list[_Trial]) -> list[_Trial]:
    """The trials with each combination of Add-links once (the first, best ranked, of its orders)."""
    seen: set[frozenset[tuple[str, str]]] = set()
    out = []
    for t in tried:
        key = frozenset((t.pairs, *t.also))
        if key not in seen:
            seen.add(key)
            out.append(t)
    return out
