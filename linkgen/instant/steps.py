"""The steps that compute the instant centres an output asks for (``ic:LINK1:LINK2``).

Each centre is one ``instant_centre`` call after the procedure's last step (the fallback blocks'
numbers move up by as many, as for directions), reading one point and the angle record of each
link.  Where a revolute pair joins the two links, that pair is the point of both, so the centre
is the pair to the last bit; otherwise each link gives its first revolute pair, else a
prismatic pair it slides on (the pair's record moves with the slider), else one of its points,
else the guide's copy of a pair it guides.
"""

from __future__ import annotations

from dataclasses import replace
from typing import TypeVar

from ..directions import renumbered
from ..errors import InputError
from ..extraction import Procedure
from ..model import Mechanism
from ..steplog import Arg, Step, Variable
from .names import field_name, links_of

P = TypeVar("P", bound=Procedure)


def record_name(name: str, taken: set[str]) -> str:
    """A record name for the centre of output ``name`` that no record has yet."""
    out = field_name(name)
    while out in taken:
        out += "_"
    return out


def centre_records(proc: Procedure, outputs: tuple[str, ...]) -> dict[str, str]:
    """The record of every centre among the outputs."""
    taken = {v.name for v in proc.variables}
    made: dict[str, str] = {}
    for name in outputs:
        made[name] = record_name(name, taken)
        taken.add(made[name])
    return made


def _point(proc: Procedure, m: Mechanism, link: str, other: str) -> tuple[str, str]:
    """The pair or point whose record stands for ``link`` (a pair it shares with ``other`` first), and
    that record: a revolute pair, a prismatic pair it slides on (the record is the slider's copy), a
    point of it, else the guide's copy of a pair it guides."""
    own = m.link(link)
    revolute = [j for j in own.joints if m.joint(j).revolute]
    shared = [j for j in revolute if any(lk.name == other for lk in m.links_of(j))]
    slides = [j for j in own.joints if not m.joint(j).revolute and m.prismatic_of(j).slider == link]
    found = [(n, proc.positions[n]) for n in shared + revolute + slides + [p.name for p in own.points]]
    guides = {v.entity: v.name for v in proc.variables if v.role == "guide"}
    found += [(j, guides[j]) for j in own.joints if j in guides and m.prismatic_of(j).guide == link]
    if not found:
        raise InputError(f"link {link} has no revolute pair or point and no record of a pair on it: "
                         f"its instant centres cannot be computed", m.path, own.where.line, "outputs")
    return found[0]


def _step(proc: Procedure, m: Mechanism, number: int, name: str, record: str) -> Step:
    a, b = links_of(name)
    (pa, ra), (pb, rb) = _point(proc, m, a, b), _point(proc, m, b, a)
    args = (Arg("var", ra), Arg("var", proc.angles[a]), Arg("var", rb), Arg("var", proc.angles[b]))
    return Step(number, "centre", "instant_centre", args, (record,), name, "", (pa, pb), (a, b), 0,
                f"the velocities of links {a} and {b} are known, so their instant centre is", "", (), 0, False)


def with_centres(proc: P, m: Mechanism, records: dict[str, str]) -> P:
    """The procedure with one step per centre in ``records`` (output name -> record) after its last step."""
    if not records:
        return proc
    last = max((s.number for s in proc.steps if not s.variant), default=0)
    added = [_step(proc, m, last + k + 1, name, rec) for k, (name, rec) in enumerate(records.items())]
    variables = tuple(Variable(rec, "CENTRE", "centre", name, (), ()) for name, rec in records.items())
    moved = renumbered(replace(proc, variables=proc.variables + variables), last, len(added))
    steps = [s for s in moved.steps if not s.variant] + added + [s for s in moved.steps if s.variant]
    return replace(moved, steps=tuple(steps))
