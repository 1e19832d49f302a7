"""Four-bar loops of a mechanism and their Grashof class (Grashof's law on the four lengths).

A loop is two fixed pivots O1 and O2 and two moving revolute pairs A and B with the
members O1-A, A-B and B-O2 on three different moving links.  With s and l the shortest
and longest of the four lengths and p, q the others, the loop is Grashof where
s + l < p + q (some link turns fully relative to every other), non-Grashof where
s + l > p + q (a triple-rocker) and a change-point mechanism where they are equal.
"""

from __future__ import annotations

import math

from ..steplog import StepLog
from .records import FourBar

SAME = 1e-12  # lengths within this of the length scale are equal (Grashof's equality)


def four_bars(log: StepLog) -> tuple[FourBar, ...]:
    """Every four-bar loop of revolute pairs that closes on the frame, once each (O1 before O2
    in the file's order of pairs)."""
    revolute = {p.name for p in log.pairs if p.kind == "revolute"}
    order = {p.name: k for k, p in enumerate(log.pairs)}
    spot = {p.name: (p.x, p.y) for p in log.pairs}
    frame = next((lk for lk in log.links if lk.fixed), None)
    if frame is None:
        return ()
    pivots = [p for p in frame.pairs if p in revolute]
    members: dict[frozenset[str], list[tuple[str, float]]] = {}
    for lk in log.links:
        if not lk.fixed:
            for a, b, length in lk.lengths:
                if a in revolute and b in revolute:
                    members.setdefault(frozenset((a, b)), []).append((lk.name, length))
    near: dict[str, set[str]] = {}  # the pairs a member joins to each pair (a pair without one closes no loop)
    for ends in members:
        for p in ends:
            near.setdefault(p, set()).update(ends - {p})
    moving = revolute - set(frame.pairs)
    out = []
    for o1 in pivots:
        for o2 in pivots:
            if order[o1] >= order[o2]:
                continue
            for a in sorted(near.get(o1, set()) & moving, key=order.__getitem__):
                for b in sorted(near[a] & near.get(o2, set()) & moving - {a}, key=order.__getitem__):
                    for x, la in members.get(frozenset((o1, a)), []):
                        for y, lb in members.get(frozenset((a, b)), []):
                            for z, lc in members.get(frozenset((b, o2)), []):
                                if len({x, y, z}) == 3:
                                    d = math.dist(spot[o1], spot[o2])
                                    out.append(_classified(log, (o1, a, b, o2), (frame.name, x, y, z), (d, la, lb, lc)))
    return tuple(out)


def grashof_class(lengths: tuple[float, float, float, float], scale: float) -> str:
    """Grashof | non-Grashof | change point, for the four lengths of a loop."""
    s = sorted(lengths)
    excess = (s[0] + s[3]) - (s[1] + s[2])
    if abs(excess) <= SAME * scale:
        return "change point"
    return "Grashof" if excess < 0 else "non-Grashof"


def grashof_kind(lengths: tuple[float, float, float, float], scale: float) -> str:
    """The loop's type from which link is shortest (lengths: frame, the link at O1, coupler, the
    link at O2): the shortest link turns fully relative to its neighbours in a Grashof loop
    (both links at the frame where they tie for it, as in a parallelogram)."""
    if grashof_class(lengths, scale) == "non-Grashof":
        return "triple-rocker"
    least = min(lengths)
    shortest = {k for k, x in enumerate(lengths) if x - least <= SAME * scale}  # ties: a parallelogram's two cranks
    if 0 in shortest or {1, 3} <= shortest:
        return "double-crank"
    return "crank-rocker" if 1 in shortest else "rocker-crank" if 3 in shortest else "double-rocker"


def _classified(log: StepLog, pairs: tuple[str, str, str, str], links: tuple[str, str, str, str],
                lengths: tuple[float, float, float, float]) -> FourBar:
    """The loop, turned round where an input drives the link at O2 rather than the one at O1."""
    driven = _driver(log, pairs, links)
    if not driven:
        flipped = _driver(log, pairs[::-1], (links[0], links[3], links[2], links[1]))
        if flipped:
            pairs, links = pairs[::-1], (links[0], links[3], links[2], links[1])
            lengths, driven = (lengths[0], lengths[3], lengths[2], lengths[1]), flipped
    return FourBar(pairs, links, lengths, grashof_class(lengths, log.length_scale),
                   grashof_kind(lengths, log.length_scale), driven)


def _driver(log: StepLog, pairs: tuple[str, ...], links: tuple[str, ...]) -> str:
    """The input column turning the link at O1 relative to the frame ("" for none)."""
    return next((i.column for i in log.inputs
                 if i.kind == "revolute" and i.joint == pairs[0] and {i.link, i.relative_to} == {links[0], links[1]}),
                "")
