"""Accuracy of linkgen's evaluator, checked against the format spec and the 50-digit reference.

Every sample and test mechanism (globbed at collection) is evaluated once with every
output at order 2.  The checks: rigidity and slides in float over the whole sweep (a),
the driving constraints as the spec defines the input values, agreement with the
reference on a subsample of rows (b), the sketch row (c), no jumps between rows (d), and
the branch followed continuously from the sketch by an independent float continuation.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest
import sketches as sk
from programs import noise_floors
from reference import Reference, wrap

from linkgen.evaluate import evaluate
from linkgen.pipeline import build_log
from linkgen.rows import input_rows
from linkgen.table import columns

ROOT = Path(__file__).resolve().parent.parent
MECHANISMS = sorted(ROOT.glob("samples/*/*.yaml")) + sorted((ROOT / "tests" / "mechanisms").glob("*.yaml"))
IDS = [p.stem for p in MECHANISMS]

POSITION_TOL = 1e-12  # times the length scale (radians for angles)
CONDITIONED = 2.0  # near a singular position: eps L times this over the reference's conditioning, if larger
RATE_TOL = 1e-8  # relative, with the spec's near-zero rule
NEAR_RATE_TOL = 1e-6  # on near-singular rows (status < 0), as the spec allows between languages
REFERENCE_ROWS = 12  # rows per mechanism compared with the 50-digit reference
JUMP_FACTOR = 50  # a step this many times the median step of its column is a jump

CLASS = {"x": "position", "y": "position", "s": "position", "vx": "velocity", "vy": "velocity", "ds": "velocity",
         "ax": "acceleration", "ay": "acceleration", "dds": "acceleration", "phi": "angle",
         "omega": "angular_velocity", "alpha": "angular_acceleration"}


def quantity(name: str) -> str:
    """The spec's quantity class of a CSV column."""
    if "." in name:
        return CLASS[name.rsplit(".", 1)[1]]
    return "angle" if name.startswith("theta_") else "position"


def np_wrap(x: np.ndarray) -> np.ndarray:
    return x - 2 * np.pi * np.ceil((x - np.pi) / (2 * np.pi))


@dataclass
class Sweep:
    """linkgen's whole sweep of one mechanism, every output at order 2."""

    ref: Reference
    log: object
    names: list
    data: np.ndarray
    status: np.ndarray
    rates: np.ndarray

    @property
    def length(self) -> float:
        return self.log.length_scale

    def col(self, name: str) -> np.ndarray:
        return self.data[:, self.names.index(name)]

    def row(self, k: int) -> dict:
        return dict(zip(self.names, (float(x) for x in self.data[k])))

    @functools.cached_property
    def scales(self) -> dict:
        """S per quantity class: the largest magnitude in the CSV's solved rows, with the floors of
        programs.noise_floors."""
        ok = self.status <= 0
        largest = {}
        for k, name in enumerate(self.names):
            vals = self.data[ok, k]
            vals = vals[np.isfinite(vals)]
            if vals.size:
                largest[quantity(name)] = max(largest.get(quantity(name), 0.0), float(np.max(np.abs(vals))))
        return noise_floors(largest, self.length)


@functools.cache
def sweep(path: Path) -> Sweep:
    log = build_log(str(path), outputs=(), order=2, sweep=False)
    values, rates, accs = input_rows(log, log.samples)
    result = evaluate(log, values, rates, accs)
    names, data = columns(log, result)
    return Sweep(Reference(str(path)), log, names, data, result.status, rates)


def mismatches(sw: Sweep, got: dict, want: dict, near: bool, cond: float = 1.0) -> list[tuple]:
    """(column, linkgen, reference, error, tolerance) for every column out of tolerance.

    Positions are held to POSITION_TOL, or where the reference's conditioning cond is so low
    that the sketch's own rounding moves them more, to CONDITIONED eps L / cond."""
    out = []
    pos_tol = max(POSITION_TOL, CONDITIONED * sk.EPS / cond)
    for name, b in want.items():
        a, b = got[name], float(b)
        q = quantity(name)
        if q == "angle":
            err, tol = abs(float(wrap(a - b))), pos_tol
        elif q == "position":
            err, tol = abs(a - b), pos_tol * sw.length
        else:
            err = abs(a - b)
            tol = (NEAR_RATE_TOL if near else RATE_TOL) * max(abs(a), abs(b), sw.scales[q])
        if not err <= tol:
            out.append((name, a, b, err, tol))
    return out


def describe(path: Path, what: str, bad: list[tuple]) -> str:
    lines = [f"{path.name}: {what}"]
    lines += [f"  {r}" for r in bad[:12]]
    if len(bad) > 12:
        lines.append(f"  ... and {len(bad) - 12} more")
    return "\n".join(lines)


@pytest.mark.parametrize("path", MECHANISMS, ids=IDS)
def test_columns_follow_spec(path):
    """The header is the spec's default set, and the input columns follow the spec's row formula."""
    sw = sweep(path)
    assert sw.names == sw.ref.column_names()
    m = sw.ref.m
    k = np.arange(m.samples, dtype=float)
    for i, inp in enumerate(m.inputs):
        want = inp.start + k * (inp.stop - inp.start) / (m.samples - 1)
        np.testing.assert_allclose(sw.data[:, i], want, rtol=0, atol=1e-15 * max(abs(inp.start), abs(inp.stop)))


@pytest.mark.parametrize("path", MECHANISMS, ids=IDS)
def test_links_rigid_and_slides_hold(path):
    """(a) Every link keeps its sketch lengths (and turns as its phi says); every slide holds; all rows."""
    sw, ref = sweep(path), sweep(path).ref
    ok = np.flatnonzero(sw.status <= 0)
    assert ok.size, "no row of the sweep assembles"
    tol = POSITION_TOL * sw.length
    bad = []
    for k in ok.tolist():
        row = sw.row(k)
        for lk in ref.m.links:
            rot = row[f"{lk.name}.phi"] - ref.directions[False][lk.name]
            c, s = math.cos(rot), math.sin(rot)
            spots = ref.anchors(lk.name, row, with_guides=False)
            if lk.fixed:
                bad += [(k, lk.name, "moved", (x, y), (sx, sy)) for sx, sy, x, y in spots
                        if math.hypot(x - sx, y - sy) > tol]
            for i, (sx, sy, x, y) in enumerate(spots):
                for tx, ty, u, v in spots[i + 1:]:
                    drawn = math.hypot(tx - sx, ty - sy)
                    now = math.hypot(u - x, v - y)
                    if abs(now - drawn) > tol:
                        bad.append((k, lk.name, "length", now, drawn))
                    ex = c * (tx - sx) - s * (ty - sy) - (u - x)
                    ey = s * (tx - sx) + c * (ty - sy) - (v - y)
                    if math.hypot(ex, ey) > tol:
                        bad.append((k, lk.name, "turn vs phi", math.hypot(ex, ey)))
        for name, guide in ref.guide.items():
            j, slider = ref.joints[name], ref.slider[name]
            turn = wrap(row[f"{slider}.phi"] - row[f"{guide}.phi"]
                        - ref.directions[False][slider] + ref.directions[False][guide])
            if abs(turn) > POSITION_TOL:
                bad.append((k, name, "slider turns on its guide", turn))
            spots = ref.anchors(guide, row, with_guides=False)
            if not spots:
                continue
            rot = row[f"{guide}.phi"] - ref.directions[False][guide]
            c, s = math.cos(rot), math.sin(rot)
            sx, sy, x, y = spots[0]
            gx, gy = x + c * (j.x - sx) - s * (j.y - sy), y + s * (j.x - sx) + c * (j.y - sy)
            ux, uy = math.cos(j.axis + rot), math.sin(j.axis + rot)
            dx, dy = row[f"{name}.x"] - gx, row[f"{name}.y"] - gy
            if abs(ux * dy - uy * dx) > tol:
                bad.append((k, name, "off the guide's line", ux * dy - uy * dx))
            if abs(ux * dx + uy * dy - row[f"{name}.s"]) > tol:
                bad.append((k, name, "s", row[f"{name}.s"], ux * dx + uy * dy))
    assert not bad, describe(path, "(row, link or pair, what, values)", bad)


@pytest.mark.parametrize("path", MECHANISMS, ids=IDS)
def test_inputs_hold(path):
    """The input columns mean what the spec says: theta = phi_L - phi_F (phi_F = 0 for the frame), s, |J1 - J2|."""
    sw, ref = sweep(path), sweep(path).ref
    ok = np.flatnonzero(sw.status <= 0)
    bad = []
    for k in ok.tolist():
        row = sw.row(k)
        for i, inp in enumerate(ref.m.inputs):
            value = float(sw.data[k, i])
            if inp.kind == "revolute":
                turn = {name: row[f"{name}.phi"] - ref.directions[False][name] for name in ref.links}
                now = turn[inp.link] - turn[inp.relative_to] + ref.offsets[False][i]
                err = abs(wrap(now - value))
                if err > POSITION_TOL:
                    bad.append((k, sw.names[i], value, "linkgen's links give", wrap(now)))
            elif inp.kind == "prismatic":
                if abs(row[f"{inp.joint}.s"] - value) > POSITION_TOL * sw.length:
                    bad.append((k, sw.names[i], value, "s column", row[f"{inp.joint}.s"]))
            else:
                a, b = inp.between
                d = math.hypot(row[f"{a}.x"] - row[f"{b}.x"], row[f"{a}.y"] - row[f"{b}.y"])
                if abs(d - value) > POSITION_TOL * sw.length:
                    bad.append((k, sw.names[i], value, "distance", d))
    assert not bad, describe(path, "(row, input column, value, what linkgen's positions give)", bad)


@pytest.mark.parametrize("path", MECHANISMS, ids=IDS)
def test_sketch_input_value(path):
    """The step log's sketch input value is the spec's (modulo whole turns)."""
    sw = sweep(path)
    for inp, want in zip(sw.log.inputs, sw.ref.sketch_inputs()):
        err = wrap(inp.sketch - want) if inp.kind == "revolute" else inp.sketch - want
        assert abs(err) <= POSITION_TOL * (1 if inp.kind == "revolute" else sw.length), (
            f"{path.name}: input {inp.column}: linkgen's sketch value {inp.sketch!r}, the spec's {want!r}")


def reference_rows(sw: Sweep) -> np.ndarray:
    """About REFERENCE_ROWS rows spread over the rows that assemble."""
    ok = np.flatnonzero(sw.status <= 0)
    if ok.size == 0:
        return ok
    pick = np.unique(np.linspace(0, ok.size - 1, min(REFERENCE_ROWS, ok.size)).round().astype(int))
    return ok[pick]


@pytest.mark.parametrize("path", MECHANISMS, ids=IDS)
def test_matches_reference(path):
    """(b) Positions to 1e-12 L (angles 1e-12 rad), rates to 1e-8 relative, against 50 digits."""
    sw = sweep(path)
    rows = reference_rows(sw)
    assert rows.size, "no row of the sweep assembles"
    bad, compared = [], 0
    for k in rows.tolist():
        row = sw.row(k)
        values = [row[n] for n in sw.names[: len(sw.ref.m.inputs)]]
        try:
            sol = sw.ref.solve(values, sw.rates[k], sw.ref.guess(row))
        except (ArithmeticError, ZeroDivisionError) as exc:
            bad.append((k, "the reference finds no assembly near linkgen's row", str(exc)[:80]))
            continue
        if sol.cond < 1e-9:
            continue  # a change point: the reference has no unique motion here
        compared += 1
        bad += [(k, *b) for b in mismatches(sw, row, sol.columns, sw.status[k] < 0, sol.cond)]
    assert not bad, describe(path, "(row, column, linkgen, reference, error, tolerance)", bad)
    assert compared, "every sampled row is at a change point"


@pytest.mark.parametrize("path", MECHANISMS, ids=IDS)
def test_sketch_row(path):
    """(c) At the spec's sketch input values linkgen reproduces the sketch (the branch choice).

    The rates there are compared with the reference solved from the sketch pose alone.
    """
    sw = sweep(path)
    ref = sw.ref
    values = np.array([ref.sketch_inputs()], dtype=float)
    rates = sw.rates[:1]
    result = evaluate(sw.log, values, rates, np.zeros_like(values))
    assert result.status[0] <= 0, (f"{path.name}: the sketch row (inputs {values[0].tolist()}) fails with "
                                   f"status {result.status[0]}")
    names, data = columns(sw.log, result)
    row = dict(zip(names, (float(x) for x in data[0])))
    sol = ref.solve(values[0], rates[0], ref.sketch_pose())
    drawn = {}
    for j in ref.m.joints:
        drawn[f"{j.name}.x"], drawn[f"{j.name}.y"] = j.x, j.y
        if j.kind == "prismatic":
            drawn[f"{j.name}.s"] = 0.0
    for p in ref.m.points:
        drawn[f"{p.name}.x"], drawn[f"{p.name}.y"] = p.x, p.y
    for lk in ref.m.links:
        drawn[f"{lk.name}.phi"] = wrap(ref.directions[True][lk.name])
    bad = mismatches(sw, row, drawn, False, sol.cond)
    assert not bad, describe(path, "sketch positions (column, linkgen, sketch, error, tolerance)", bad)
    bad = mismatches(sw, row, sol.columns, result.status[0] < 0, sol.cond)
    assert not bad, describe(path, "sketch row against the reference (column, linkgen, reference, error, tol)", bad)


def _steps(sw: Sweep, name: str) -> tuple[np.ndarray, np.ndarray]:
    """Rows k (with k + 1) where both rows assemble, and |column(k + 1) - column(k)|."""
    x = sw.col(name)
    ok = (sw.status[:-1] <= 0) & (sw.status[1:] <= 0) & np.isfinite(x[:-1]) & np.isfinite(x[1:])
    d = np.diff(x)
    if quantity(name) == "angle":
        d = np_wrap(d)
    return np.flatnonzero(ok), np.abs(d[ok])


SLOW = {"nongrashof_near_change", "triad_far", "quaternary_fold"}  # 10-22 s each: cases in the long tier only


def _tiered(paths):
    return [pytest.param(p, marks=pytest.mark.long) if p.stem in SLOW else p for p in paths]


@pytest.mark.parametrize("path", _tiered(MECHANISMS), ids=IDS)
def test_no_jumps(path):
    """(d) No position, angle or slide column jumps between consecutive rows (a branch switch)."""
    sw = sweep(path)
    bad = []
    for name in sw.names[len(sw.ref.m.inputs):]:
        q = quantity(name)
        if q not in ("position", "angle"):
            continue
        rows, steps = _steps(sw, name)
        if steps.size < 3:
            continue
        floor = 1e-9 * (1.0 if q == "angle" else sw.length)
        limit = JUMP_FACTOR * float(np.median(steps)) + floor
        x = sw.col(name)
        bad += [(int(k), name, float(x[k]), float(x[k + 1]), float(s), limit)
                for k, s in zip(rows, steps) if s > limit and not _followed(sw, int(k))]
    assert not bad, describe(path, "(row k, column, value at k, at k + 1, step, limit)", bad)


@functools.cache
def _follow_cache() -> dict:
    return {}


def _followed(sw: Sweep, k: int) -> bool:
    """Whether the reference, started at row k's pose and turned in small steps to row k + 1's
    inputs, arrives at row k + 1 (a large step near a limit position is motion, not a jump)."""
    key = (sw.log.name, k)
    cache = _follow_cache()
    if key not in cache:
        n_in = len(sw.ref.m.inputs)
        q = sw.ref.guess(sw.row(k))
        q = sk.walk(sw.ref, q, float(sw.data[k, 0]), float(sw.data[k + 1, 0]), step=math.radians(0.01)) \
            if n_in == 1 else None
        if q is None:
            cache[key] = False
        else:
            got, want = sw.row(k + 1), sw.ref.outputs(q)
            cache[key] = all(abs(got[c] - float(v)) <= 1e-6 * sw.length
                             for c, v in want.items() if quantity(c) == "position")
    return cache[key]


@pytest.mark.parametrize("path", MECHANISMS, ids=IDS)
def test_failed_row_alone(path):
    """A row that fails, evaluated on its own, fails there too and gives the spec's nan columns."""
    sw = sweep(path)
    n_in = len(sw.ref.m.inputs)
    failed = np.flatnonzero((sw.status > 0) & np.isin(sw.status % 10, (1, 2)))
    if not failed.size:
        pytest.skip("every row of the sweep assembles")
    k = int(failed[failed.size // 2])
    values = sw.data[k:k + 1, :n_in].copy()
    result = evaluate(sw.log, values, sw.rates[k:k + 1], np.zeros_like(values))
    assert result.status[0] > 0, f"{path.name}: row {k} fails in the sweep but not alone"
    names, data = columns(sw.log, result)
    assert names == sw.names
    assert np.array_equal(data[0, :n_in], values[0])
    assert np.isnan(data[0, n_in:]).all()


SPANS = (math.radians(1), 1 / 100)  # largest continuation step: angle inputs, length inputs (times L)


def _walk(ref: Reference, q: list, start: list, stop: list) -> list | None:
    """Follow the assembly in float from inputs ``start`` to ``stop`` in small steps: at most one
    span, and no longer than the scale-free conditioning c allows (c radians, down to 1e-4 of a
    span), since where two branches pass within c L of each other a longer step can land on the
    other one.

    None where it cannot: Newton fails, the pose jumps, or the path comes near a singular
    position (there the branch is no longer defined by continuation).
    """
    spans = [SPANS[0] if i.kind == "revolute" else SPANS[1] * ref.length_scale for i in ref.m.inputs]
    length = max([abs(b - a) / s for a, b, s in zip(start, stop, spans)] + [1e-300])  # in spans
    scale = [ref.length_scale, ref.length_scale, 1.0] * len(ref.moving)
    t, h = 0.0, 1e-4 / length
    while t < 1.0:
        t = min(1.0, t + h)
        u = [a + (b - a) * t for a, b in zip(start, stop)] if t < 1.0 else list(stop)
        try:
            try:
                new, jac, _ = ref.newton(q, ref.turned_inputs(q, u), exact=False, max_iter=10)
            except ArithmeticError:  # float Newton stalls where the conditioning is 1e-4: 50 digits
                new, jac, _ = ref.newton(q, ref.turned_inputs(q, u), exact=True, max_iter=30)
                new = [float(x) for x in new]
        except (ArithmeticError, np.linalg.LinAlgError, ZeroDivisionError):
            return None
        if ref.cond(jac) < 1e-6 or max(abs(a - b) / s for a, b, s in zip(new, q, scale)) > 0.5:
            return None
        q, h = new, min(1.0, max(sk.conditioning(ref, jac) / SPANS[0], 1e-4)) / length
    return q


def _from_sketch(ref: Reference, target: list) -> list | None:
    """The sketch's assembly at ``target``, walked from the sketch (either way round for one angle input)."""
    start = ref.sketch_inputs()
    ends = [list(target)]
    if len(target) == 1 and ref.m.inputs[0].kind == "revolute":
        short = start[0] + wrap(target[0] - start[0])
        ends = [[short], [short - math.copysign(2 * math.pi, short - start[0])]]
    for end in ends:
        q = _walk(ref, ref.sketch_pose(), start, end)
        if q is not None:
            return q
    return None


@pytest.mark.parametrize("path", _tiered(MECHANISMS), ids=IDS)
def test_branch_followed_from_sketch(path):
    """The sweep is on the sketch's branch: an independent float continuation from the sketch agrees.

    Each assembled row is reached from the previous one (or, where that path is cut, from
    the sketch) and compared to 1e-7 L; a row linkgen fails right after an assembled row must
    not be reachable from it along a well-conditioned path.
    """
    bad, checked = _off_branch(path)
    assert not bad, describe(path, "(row, column, linkgen, followed from the sketch)", bad)
    if not checked:
        pytest.skip("no assembled row is reachable from the sketch by continuation")


def _off_branch(path: Path) -> tuple[list, int]:
    """Rows off the branch an independent float continuation follows from the sketch, and the
    number of rows checked (see test_branch_followed_from_sketch)."""
    sw = sweep(path)
    ref = sw.ref
    n_in = len(ref.m.inputs)
    state, tries, checked, bad = None, 3, 0, []
    for k in range(sw.data.shape[0]):
        target = [float(x) for x in sw.data[k, :n_in]]
        if sw.status[k] > 0 and sw.status[k] % 10 in (1, 2):
            if state is not None and state[2] == k - 1 and _walk(ref, state[1], state[0], target) is not None:
                bad.append((k, f"status {sw.status[k]}", "but the sketch's branch reaches it from row", state[2]))
            continue
        q = _walk(ref, state[1], state[0], target) if state is not None else None
        if q is None and tries:
            tries -= 1
            q = _from_sketch(ref, target)
        if q is None:
            state = None
            continue
        state = (target, q, k)
        row = sw.row(k)
        for name, want in ref.outputs(q).items():
            angle = name.endswith(".phi")
            err = abs(wrap(row[name] - want)) if angle else abs(row[name] - want)
            if err > 1e-7 * (1.0 if angle else sw.length):
                bad.append((k, name, row[name], float(want)))
        checked += 1
        if len(bad) > 12:
            break
    return bad, checked


# -- change points: zero wrong-branch rows at any sampling -------------------------------------------

BRANCH_SAMPLES = (36, 37, 360, 361)  # with 37 and 361 rows fall on the change points (0 and 180 degrees)
PARALLELOGRAM = """linkgen: 1
name: {name}
joints:
  O1: [0, 0]
  A: [20, 20]
  B: [80, 20]
  O2: [{o2}, 0]
links:
  frame: {{joints: [O1, O2], fixed: true}}
  crank: [O1, A]
  coupler: [A, B]
  rocker: [O2, B]
inputs:
  - {{joint: O1, link: crank, relative_to: frame, range: [0, 360]}}
samples: {samples}
"""


def _parallelogram(folder: Path, o2: str, samples: int) -> Path:
    path = folder / f"parallelogram_{samples}.yaml"
    path.write_text(PARALLELOGRAM.format(name=f"parallelogram_{samples}", o2=o2, samples=samples))
    return path


@pytest.mark.parametrize("samples", BRANCH_SAMPLES)
def test_parallelogram_stays_a_parallelogram(tmp_path, samples):
    """The exact parallelogram passes its change points (all four pivots in line, both branches
    meet) on its own branch: on every row the coupler is the frame moved, B - A = O2 - O1 (the closed
    form), never the anti-parallelogram."""
    sw = sweep(_parallelogram(tmp_path, "60", samples))
    assert all(s <= 0 or s % 10 == 3 for s in sw.status), list(sw.status)
    dx, dy = sw.col("B.x") - sw.col("A.x"), sw.col("B.y") - sw.col("A.y")
    bad = [(k, float(dx[k]), float(dy[k])) for k in range(samples)
           if not (abs(dx[k] - 60.0) <= 1e-12 * sw.length and abs(dy[k]) <= 1e-12 * sw.length)]
    assert not bad, f"rows off the parallelogram (row, B.x - A.x, B.y - A.y): {bad[:8]}"


def _fine_walk(ref: Reference, q: list, start: float, stop: float) -> list | None:
    """Follow the assembly at q (one angle input at ``start``) to ``stop`` in steps of a fifth of
    the conditioning (radians, 3e-5 to 1 degree): fine enough where two branches pass within
    1e-3 of each other.  None where Newton fails (past a limit position)."""
    t, step, h = start, math.copysign(1.0, stop - start), 3e-5
    while t != stop:
        t = stop if abs(stop - t) <= h else t + step * h
        try:
            try:
                q, jac, _ = ref.newton(q, ref.turned_inputs(q, [t]), exact=False, max_iter=10)
            except ArithmeticError:  # float Newton stalls where the conditioning is 1e-4: 50 digits
                q, jac, _ = ref.newton(q, ref.turned_inputs(q, [t]), exact=True, max_iter=30)
        except (ArithmeticError, ZeroDivisionError, np.linalg.LinAlgError):
            return None
        h = min(max(float(ref.cond(jac)), 3e-5), SPANS[0])
    return q


@pytest.mark.parametrize("samples", BRANCH_SAMPLES)
@pytest.mark.parametrize("o2", ["59.99994", "60.00006"], ids=["grashof", "non-grashof"])
def test_perturbed_grashof_equality_keeps_its_branch(tmp_path, samples, o2):
    """The parallelogram with its frame 1e-6 shorter (s + l - p - q = -1.8e-5: a crank that passes
    within conditioning 2e-4 of the change point twice a turn, where its motion turns from the
    parallelogram's to the anti-parallelogram's) or longer (+1.8e-5: limit positions near 0 and 180
    degrees).  Neither has a change point.  Every row is on the branch a fine float continuation
    follows from the sketch (a 1-degree one jumps between the branches there), and every row that
    continuation reaches is solved."""
    path = _parallelogram(tmp_path, o2, samples)
    sw = sweep(path)
    ref = sw.ref
    assert not any(s.change_points for s in sw.log.steps), "a near change point taken for a change point"
    t0 = ref.sketch_inputs()[0]
    bad, checked, q, last = [], 0, None, None
    for k in range(samples):
        target = float(sw.data[k, 0])
        q = _fine_walk(ref, q, last, target) if q is not None else None
        if q is None:  # from the sketch, either way round
            for end in (target, target - math.copysign(2 * math.pi, target - t0)):
                q = _fine_walk(ref, ref.sketch_pose(), t0, end)
                if q is not None:
                    break
        last = target
        if q is None:
            continue
        if sw.status[k] > 0 and sw.status[k] % 10 != 3:
            bad.append((k, f"status {sw.status[k]}", "but the continuation reaches it"))
            continue
        row = sw.row(k)
        for name, want in ref.outputs(q).items():
            err = abs(wrap(row[name] - want)) if name.endswith(".phi") else abs(row[name] - want) / sw.length
            if err > 1e-7:
                bad.append((k, name, row[name], float(want)))
        checked += 1
    assert not bad, describe(path, "(row, column, linkgen, followed from the sketch)", bad)
    assert checked >= samples // 3
