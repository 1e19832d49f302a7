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
    names, placed = refresh(ws)
    ws.set_determines(index, ws.newly_known(names, placed))
    close_group(ws)


def refresh(ws: Workspace) -> tuple[list[str], list[str]]:
    """Propagate orientation through prismatic pairs, place links, find unused links; tell
    the Solver's frontier which pairs to try again.  Returns the names that came into pos
    since the last refresh and the links placed since (in the order placed).

    Only the links that know a new name or turned since are looked at, in links order, and
    then the links that a newly placed guide or slider couples; every other link is as the
    last refresh left it (its known names tied, not placeable)."""
    names = ws.unseen("pos")
    look = {lk for n in names for lk in ws.index.owners.get(n, ())}
    look.update(ws.unseen("orient"))
    fresh = before = ws.newly_placed()  # placed outside a refresh (the frame, by start)
    while True:
        look.update(_couple(ws, fresh))
        fresh = [lk for lk in sorted(look - ws.placed, key=ws.index.link_order.__getitem__) if _tie(ws, lk)]
        if not fresh:
            break
        look = set()
    placed = before + ws.newly_placed()
    for c in ws.extra_carriers():
        unused = c.name not in ws.used and c.name not in ws.residual_links
        if unused and all(p in ws.pos for p in c.pairs):
            add_residual(ws, c.name, c.pairs[0], c.pairs[1], c.length)
    _retry(ws, names, placed)
    return names, placed


def _couple(ws: Workspace, placed: list[str]) -> list[str]:
    """A link sliding on a placed link turns with it: the links coupled now."""
    out = []
    for joint in sorted({p for lk in placed for p in ws.index.slides.get(lk, ())}, key=ws.index.order.__getitem__):
        p = ws.m.prismatic_of(joint)
        for a, b in ((p.guide, p.slider), (p.slider, p.guide)):
            if a in ws.placed and not ws.oriented(b):
                ws.coupled[b] = a
                out.append(b)
    return out


def _tie(ws: Workspace, link: str) -> bool:
    """Tie the link's known names to it (a second one on a link that is already determined
    is a residual, or a state this procedure cannot express); place it when it can be."""
    tied = ws.tied[link]
    for n in ws.own(link):
        if n in ws.pos and n not in tied:
            if not tied:
                tied.append(n)
            elif ws.oriented(link) or ws.distinct(tied):
                raise Unsupported(f"link {link} is over-determined at {n}")
            else:
                add_residual(ws, link, tied[0], n, ws.member_length(link, tied[0], n))
                tied.append(n)
    if tied and (ws.oriented(link) or ws.distinct(tied)):
        ws.place(link)
        return True
    return False


def _retry(ws: Workspace, names: list[str], placed: list[str]) -> None:
    """The pairs whose chains may have changed: those on a carrier of a newly known pair,
    on a newly placed link or on the slider of a slide it guides, and on new or newly
    used actuators and Add-links."""
    carriers = {c.name: c for n in names if n in ws.joint_names for c in ws.carriers_with(n)}
    for lk in placed:
        carriers[lk] = ws.carrier(lk)
        carriers.update((c.name, c) for p in ws.index.guided.get(lk, ()) for c in ws.carriers_with(p))
    if len(ws.carriers) != ws.seen["carriers"] or len(ws.used) != ws.seen["used"]:
        ws.seen["carriers"], ws.seen["used"] = len(ws.carriers), len(ws.used)
        carriers.update((c.name, c) for c in ws.extra_carriers())
    for c in carriers.values():
        ws.frontier.push(c.pairs)
