"""The assemblies at the sketch's inputs as the step log records them, and the mechanism moved
into one of them (``options: assembly``, ``linkgen build --assembly K``).

The programs follow the configuration they start from.  To follow assembly K, linkgen draws
the sketch again in assembly K (every pair and point where K has it, a prismatic pair's line
turned with its guide) and runs the normal pipeline on that sketch: the chains' branches, their
change points, the Add-links and the resolver's warm start all come from assembly K.
"""

from __future__ import annotations

import math
from dataclasses import replace

from ..census import Assemblies, AssemblyChoice, AssemblyInfo
from ..errors import InputError
from ..model import Joint, Link, Mechanism
from ..steplog import StepLog
from .enumerate import Assembly, Census, Choice, census
from .report import notes
from .triad import NotReducible

SAME = 1e-12  # a pair the assembly moves by less (over the length scale) keeps the file's coordinates


def listing(log: StepLog, assembly: int = 0) -> Assemblies:
    """Every assembly of ``log``'s mechanism (its whole procedure at order 0) at the sketch's
    inputs; the programs follow ``assembly``, 0 for the sketch's.  A census linkgen cannot
    make is recorded with its reason (no count rather than a wrong one)."""
    values = tuple(i.sketch for i in log.inputs)
    try:
        found = census(log, values)
    except NotReducible as exc:
        return Assemblies(values, False, 0, (f"linkgen cannot count the assemblies of this mechanism: {exc}",), ())
    except ArithmeticError as exc:
        return Assemblies(values, False, 0, (f"the count of assemblies is not certified: {exc}",), ())
    sketch = next((a.number for a in found.assemblies if a.sketch), 0)
    return Assemblies(values, True, assembly or sketch, tuple(notes(log, found)), tuple(
        AssemblyInfo(a.number, a.sketch, tuple(AssemblyChoice(c.step, c.target, c.value, c.of, c.theta)
                                               for c in a.choices),
                     tuple(a.values.items()), a.error)
        for a in found.assemblies))


def chosen(m: Mechanism, k: int, found: Assemblies, from_flag: bool) -> AssemblyInfo:
    """Assembly ``k`` of the listing, or an error where the option gives it (the flag, else the file)."""
    given = m.options_where.get("assembly")
    where = ("command line", 0, "--assembly") if from_flag else (m.path, given.line if given else 0,
                                                                   "options.assembly")
    if not found.counted:
        raise InputError(f"{found.notes[0]}; the programs can only follow the sketch's assembly", *where)
    if k > len(found.listing):
        n = len(found.listing)
        raise InputError(f"there is no assembly {k}: the mechanism has {n} assembl{'y' if n == 1 else 'ies'} at "
                         "the sketch's inputs (linkgen assemblies lists them)", *where)
    return found.listing[k - 1]


def moved(m: Mechanism, log: StepLog, a: AssemblyInfo) -> Mechanism:
    """The mechanism drawn in assembly ``a`` (of ``log``, its census log): every pair and point where
    the assembly has it, a prismatic pair's line turned with its guide; what the assembly leaves
    where the sketch has it (to SAME of the length scale: the fixed link, the input links) keeps
    the file's numbers.  Link lengths are the assembly's (the sketch's to its ``error``)."""
    v = dict(a.values)
    near = SAME * log.length_scale
    turn = {lk.name: math.remainder(v[f"{lk.name}.phi"] - lk.angle, 2 * math.pi) for lk in log.links}

    def spot(name: str, x: float, y: float) -> tuple[float, float]:
        nx, ny = v[f"{name}.x"], v[f"{name}.y"]
        return (x, y) if abs(nx - x) <= near and abs(ny - y) <= near else (nx, ny)

    def joint(j: Joint) -> Joint:
        x, y = spot(j.name, j.x, j.y)
        axis = j.axis
        if not j.revolute and abs(turn[m.prismatic_of(j.name).guide]) > SAME:
            axis += turn[m.prismatic_of(j.name).guide]
        return replace(j, x=x, y=y, axis=axis)

    def link(lk: Link) -> Link:
        points = tuple(replace(p, x=spot(p.name, p.x, p.y)[0], y=spot(p.name, p.x, p.y)[1]) for p in lk.points)
        return replace(lk, points=points)

    return replace(m, joints=tuple(joint(j) for j in m.joints), links=tuple(link(lk) for lk in m.links))


def census_of(log: StepLog) -> Census:
    """The step log's listing as a census (for the figures: linkgen.assemblies.render)."""
    assert log.assemblies is not None
    rec = log.assemblies
    out = Census(rec.inputs)
    out.assemblies = [Assembly(a.number, a.sketch, tuple(Choice(c.step, c.target, c.value, c.of, c.theta)
                                                         for c in a.choices), dict(a.values), a.error)
                      for a in rec.listing]
    return out

