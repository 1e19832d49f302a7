"""The class-IV group of two links on their own pivots tied by a link and a slot (tests/regressions/
class4_slot.yaml: left on O1, right on the crank tip O2, tied by upper and a block on C in a slot of
right) against a 50-digit multistart Newton search of its two equations written here from the file's
coordinates (tests/reference.py's model), not from the step log:

    |O1 + R(a) (B - O1) - O2' - R(b) (E - O2)|^2 = |B - E|^2,
    R(b) n . (O1 + R(a) (C - O1) - O2' - R(b) (S - O2)) = 0,   n = (-sin 30 deg, cos 30 deg),

a and b the two links' turns from the sketch, O2' the crank tip at the input.  The search starts
from a 12 x 12 grid of (a, b) over the whole torus (damped Newton's method; measured: a 24 x 24
grid finds the same poses at 0, 90, 140, 150, 180 and 300 deg).
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from assembly_oracle import MP
from reference import Reference
from test_assemblies import _matches, _valid_and_distinct

from linkgen.assemblies import assemblies, whole_log

ROOT = Path(__file__).resolve().parents[1]
SLOT = str(ROOT / "tests" / "regressions" / "class4_slot.yaml")  # one file: not in every suite's glob
GRID = 12  # starts per angle
AXIS = 30  # the slot's axis in the sketch, degrees


def _rot(t, v):
    c, s = MP.cos(t), MP.sin(t)
    return c * v[0] - s * v[1], s * v[0] + c * v[1]


LEFT, RIGHT = ("B", "C"), ("E", "F", "S")  # the pairs of left (on O1) and right (on O2) in both files
SLOT_TIES = ((("B", "E"),), (("C", "S", AXIS),))  # class4_slot: upper B-E; C in right's slot through S
LINK_TIES = ((("B", "E"), ("C", "F")), ())  # class4: upper B-E, lower C-F


def search(deg: float, grid: int = GRID, path: str = "", ties=SLOT_TIES) -> list[dict[str, tuple[float, float]]]:
    """Every pose of left and right at the crank angle ``deg`` (file degrees), as pair -> position;
    ``ties``: (links (a on left, b on right)), (slots (a on left, s on right, axis in degrees))."""
    ref = Reference(path or SLOT)
    p = {k: (MP.mpf(x), MP.mpf(y)) for k, (x, y) in ref.m.positions.items()}
    turn = MP.radians(MP.mpf(deg)) - ref.sketch_inputs(exact=True)[0]
    tip = _rot(turn, (p["O2"][0] - p["J7"][0], p["O2"][1] - p["J7"][1]))
    o2 = (p["J7"][0] + tip[0], p["J7"][1] + tip[1])

    def off(a, b):
        return p[a][0] - p[b][0], p[a][1] - p[b][1]

    links, slots = ties

    def pose(z):
        return {**{a: _add(p["O1"], _rot(z[0], off(a, "O1"))) for a in LEFT if a in p},
                **{b: _add(o2, _rot(z[1], off(b, "O2"))) for b in RIGHT if b in p}}

    def _f(z):
        q, out = pose(z), []
        for a, b in links:
            v = (q[a][0] - q[b][0], q[a][1] - q[b][1])
            out.append((v[0] ** 2 + v[1] ** 2 - sum(x * x for x in off(a, b))) / 100)
        for a, b, axis in slots:  # a on the line through b's place on right, at axis turned with right
            w = (q[a][0] - q[b][0], q[a][1] - q[b][1])
            nn = _rot(z[1], (-MP.sin(MP.radians(axis)), MP.cos(MP.radians(axis))))
            out.append(nn[0] * w[0] + nn[1] * w[1])
        return out

    def system(z):  # the residuals and their Jacobian by a forward difference of 1e-30 (50 digits)
        h = MP.mpf(10) ** -30
        f0 = _f(z)
        cols = [[(a - b) / h for a, b in zip(_f([z[0] + h * (k == 0), z[1] + h * (k == 1)]), f0)] for k in (0, 1)]
        return f0, [[cols[0][i], cols[1][i]] for i in (0, 1)]

    found: list = []
    for i in range(grid):
        for j in range(grid):
            z = [MP.pi * (2 * MP.mpf(i) / grid - 1), MP.pi * (2 * MP.mpf(j) / grid - 1)]
            for _ in range(60):
                f, jac = system(z)
                try:
                    step = MP.lu_solve(MP.matrix(jac), MP.matrix(f))
                except ZeroDivisionError:
                    break
                lam, norm = 1.0, sum(x * x for x in f)
                while sum(x * x for x in _f([z[0] - lam * step[0], z[1] - lam * step[1]])) >= norm:
                    lam /= 2
                    if lam < 1e-3:
                        break
                if lam < 1e-3:
                    break  # no descent: a start that leads nowhere
                z = [z[0] - lam * step[0], z[1] - lam * step[1]]
                if max(abs(step[0]), abs(step[1])) < MP.mpf(10) ** -35:
                    z = [MP.atan2(MP.sin(x), MP.cos(x)) for x in z]
                    if max(abs(x) for x in _f(z)) < MP.mpf(10) ** -30 and not any(
                            max(abs(MP.sin((x - y) / 2)) for x, y in zip(z, u)) < MP.mpf(10) ** -20 for u in found):
                        found.append(z)
                    break
    out = []
    for z in sorted(found):
        q = pose(z)
        out.append({k: (float(x), float(y)) for k, (x, y) in q.items() if k != "S"})  # S: the slot's place
    return out


def _add(a, b):
    return a[0] + b[0], a[1] + b[1]


INPUTS = [pytest.param(90.0), pytest.param(180.0, marks=pytest.mark.long), pytest.param(140.0, marks=pytest.mark.long)]


@pytest.mark.parametrize("deg", INPUTS)
def test_class4_slots_count_is_the_multistart_searchs(deg):
    """At the sketch (90 deg: 2 assemblies) and where it has 6 (180) or 4 (140): the resultant's
    assemblies are the search's poses, pose for pose, every one keeps every constraint of the
    reference model to 1e-12 L, the sketch's is marked."""
    log = whole_log(SLOT)
    census = assemblies(SLOT, log, [deg])
    poses = search(deg)
    (solve,) = census.solves
    assert solve.degree == 6 and solve.real_roots - solve.rejected == len(poses)
    assert len(census.assemblies) == len(poses) >= 2
    assert _matches(census, poses, log.length_scale) == [1] * len(poses)
    _valid_and_distinct(SLOT, log, _block_turned(log, census))


def _block_turned(log, census):
    """The census with each block's angle taken the whole turn that keeps its slot's angle constraint
    (block.phi - right.phi, which the reference model does not wrap) nearest the sketch's."""
    angle = {lk.name: lk.angle for lk in log.links}
    sketch = angle["block"] - angle["right"]
    for a in census.assemblies:
        d = a.values["block.phi"] - a.values["right.phi"]
        a.values["block.phi"] -= 2 * math.pi * round((d - sketch) / (2 * math.pi))
    return census


def test_the_slot_count_states_its_eliminant():
    """The table names the group, the eliminant's degree and its real roots (class IV)."""
    from linkgen.assemblies.report import table

    log = whole_log(SLOT)
    text = table(log, assemblies(SLOT, log))
    assert "left (on O1) and right (on O2) tied by upper and the slot of block, class IV" in text
    assert "eliminant of degree 6" in text and "2 real roots" in text and math.isfinite(log.length_scale)


@pytest.mark.long
@pytest.mark.parametrize("deg", [90.0, 200.0])
def test_class4s_count_is_the_multistart_searchs(deg):
    """tests/assemblies/class4.yaml (the same two ternaries tied by two links, upper and lower): its
    resultant's assemblies are the search's poses (2 at both inputs)."""
    path = str(ROOT / "tests" / "assemblies" / "class4.yaml")
    log = whole_log(path)
    census = assemblies(path, log, [deg])
    poses = search(deg, path=path, ties=LINK_TIES)
    (solve,) = census.solves
    assert solve.degree == 6 and solve.real_roots - solve.rejected == len(poses) == len(census.assemblies) >= 2
    assert _matches(census, poses, log.length_scale) == [1] * len(poses)
    _valid_and_distinct(path, log, census)
