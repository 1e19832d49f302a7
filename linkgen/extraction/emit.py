"""Emitting a step, and what follows from it: links placed, residuals found, groups closed."""

from __future__ import annotations

from typing import TYPE_CHECKING, TypedDict

from ..steplog import Arg
from .resolver import add_residual, close_group
from .state import Unsupported, Workspace

if TYPE_CHECKING:
    from typing_extensions import Unpack


class StepDetails(TypedDict, total=False):
    """The keywords of ``Workspace.append``: what a step records besides its call."""

    chain: str
    pairs: tuple[str, ...]
    links: tuple[str, ...]
    branch: int
    reason: str
    branch_reason: str
    fails: bool


def emit(ws: Workspace, action: str, function: str, args: list[Arg], outputs: list[str], target: str,
         **details: Unpack[StepDetails]) -> None:
    """Append a step, then place what it makes placeable and record the pairs it determines."""
    index = ws.append(action, function, args, outputs, target, **details)
    refresh(ws)
    ws.set_determines(index, ws.newly_known())
    close_group(ws)


def refresh(ws: Workspace) -> None:
    """Propagate orientation through prismatic pairs, place links, find unused links."""
    m = ws.m
    changed = True
    while changed:
        changed = False
        for p in m.prismatic:
            for a, b in ((p.guide, p.slider), (p.slider, p.guide)):
                if a in ws.placed and not ws.oriented(b):
                    ws.coupled[b] = a
                    changed = True
        for lk in m.links:
            if lk.name in ws.placed:
                continue
            tied = ws.tied[lk.name]
            for n in ws.own(lk.name):
                if n in ws.pos and n not in tied:
                    if not tied:
                        tied.append(n)
                    elif ws.oriented(lk.name) or ws.distinct(tied):
                        raise Unsupported(f"link {lk.name} is over-determined at {n}")
                    else:
                        add_residual(ws, lk.name, tied[0], n, ws.member_length(lk.name, tied[0], n))
                        tied.append(n)
            if tied and (ws.oriented(lk.name) or ws.distinct(tied)):
                ws.placed.add(lk.name)
                changed = True
    for c in ws.carriers:
        unused = c.kind != "link" and c.name not in ws.used and c.name not in ws.residual_links
        if unused and all(p in ws.pos for p in c.pairs):
            add_residual(ws, c.name, c.pairs[0], c.pairs[1], c.length)
