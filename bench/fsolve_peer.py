"""scipy's fsolve as the generic baseline: the loop-closure equations of a sample solved row by row.

The model is the pose formulation of tests/reference.py (three coordinates per moving link, each
revolute pair two equations, the crank's angle one), read from its parsed mechanism, here in numpy
with its Jacobian written out: ``fsolve(f, q_last, fprime=jacobian)`` at scipy's default tolerance,
started from the last row (the first row is reached from the sketch in a few steps).  Velocities
and accelerations then take one linear solve each with the same Jacobian.  Revolute pairs and a
revolute input only (the three mechanisms it is run on).
"""

from __future__ import annotations

import statistics
import sys
import time
import warnings
from math import cos, sin
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

from reference import Reference  # noqa: E402

RUNS = 3
LEAD_IN = 10  # steps from the sketch's input value to the first row


class Loops:
    """f(q, theta) = 0 for the poses q of the moving links, its Jacobian, the rates and the outputs."""

    def __init__(self, path: str):
        self.ref = ref = Reference(path)
        m = ref.m
        if any(j.kind != "revolute" for j in m.joints) or len(m.inputs) != 1 or m.inputs[0].kind != "revolute":
            raise ValueError(f"{m.name}: the baseline takes revolute pairs and one revolute input only")
        slot = {name: i for i, name in enumerate(ref.moving)}
        n = len(ref.moving)  # index n: the fixed links' pose (the identity)
        a, b, xy = [], [], []
        for j in m.joints:
            on = ref.on[j.name]
            for other in on[1:]:
                a.append(slot.get(on[0], n))
                b.append(slot.get(other, n))
                xy.append((j.x, j.y))
        self.a, self.b, self.xy = np.array(a), np.array(b), np.array(xy, dtype=float)
        self.pairs = [(3 * i, 3 * k, p) for i, k, p in zip(a, b, xy)]  # offsets into the poses
        inp = m.inputs[0]
        self.driven, self.frame = 3 * slot[inp.link] + 2, 3 * slot.get(inp.relative_to, n) + 2
        self.offset = float(ref.offsets[False][0])
        self.n = n
        spots = [(j.name, ref.on[j.name][0], j.x, j.y) for j in m.joints] + [(p.name, p.link, p.x, p.y)
                                                                            for p in m.points]
        self.names = [s[0] for s in spots]
        self.at_link = np.array([slot.get(s[1], n) for s in spots])
        self.at_xy = np.array([(s[2], s[3]) for s in spots], dtype=float)

    def _poses(self, q: np.ndarray) -> np.ndarray:
        return np.vstack([q.reshape(-1, 3), np.zeros(3)])

    @staticmethod
    def _turn(r: np.ndarray, xy: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """R(r) (x, y) and its derivative by r, rows of two."""
        c, s = np.cos(r)[:, None], np.sin(r)[:, None]
        x, y = xy[:, :1], xy[:, 1:]
        return np.hstack([c * x - s * y, s * x + c * y]), np.hstack([-s * x - c * y, c * x - s * y])

    def f(self, q: np.ndarray, theta: float) -> list[float]:
        """The residuals, in plain floats (numpy's per-call cost dominates systems this small)."""
        v = [*q.tolist(), 0.0, 0.0, 0.0]
        out = []
        for a, b, (x, y) in self.pairs:
            ca, sa, cb, sb = cos(v[a + 2]), sin(v[a + 2]), cos(v[b + 2]), sin(v[b + 2])
            out.append(v[a] + ca * x - sa * y - v[b] - cb * x + sb * y)
            out.append(v[a + 1] + sa * x + ca * y - v[b + 1] - sb * x - cb * y)
        out.append(v[self.driven] - v[self.frame] + self.offset - theta)
        return out

    def jacobian(self, q: np.ndarray, theta: float = 0.0) -> np.ndarray:
        v = [*q.tolist(), 0.0, 0.0, 0.0]
        size = 3 * self.n + 3
        rows = []
        for a, b, (x, y) in self.pairs:
            rx, ry = [0.0] * size, [0.0] * size
            for k, sign in ((a, 1.0), (b, -1.0)):
                c, s = cos(v[k + 2]), sin(v[k + 2])
                rx[k] += sign
                ry[k + 1] += sign
                rx[k + 2] += sign * (-s * x - c * y)
                ry[k + 2] += sign * (c * x - s * y)
            rows += [rx, ry]
        last = [0.0] * size
        last[self.driven] += 1.0
        last[self.frame] -= 1.0
        rows.append(last)
        return np.array(rows)[:, : 3 * self.n]

    def rates(self, q: np.ndarray, speed: float) -> tuple[np.ndarray, np.ndarray]:
        """q' and q'' at the input's speed (no input acceleration)."""
        jac = self.jacobian(q)
        drive = np.zeros(len(jac))
        drive[-1] = speed
        dq = np.linalg.solve(jac, drive)
        p, dp = self._poses(q), self._poses(dq)
        ra, _ = self._turn(p[self.a, 2], self.xy)
        rb, _ = self._turn(p[self.b, 2], self.xy)
        gamma = -(dp[self.a, 2:] ** 2) * ra + dp[self.b, 2:] ** 2 * rb
        return dq, np.linalg.solve(jac, -np.append(gamma.ravel(), 0.0))

    def outputs(self, q: np.ndarray, dq: np.ndarray, ddq: np.ndarray) -> dict[str, float]:
        """Position, velocity and acceleration of every pair and point, by column name."""
        p, dp, ddp = (self._poses(v)[self.at_link] for v in (q, dq, ddq))
        r, d = self._turn(p[:, 2], self.at_xy)
        pos, vel = p[:, :2] + r, dp[:, :2] + dp[:, 2:] * d
        acc = ddp[:, :2] + ddp[:, 2:] * d - dp[:, 2:] ** 2 * r
        out = {}
        for k, name in enumerate(self.names):
            for key, rec in (("x", pos), ("vx", vel), ("ax", acc)):
                out[f"{name}.{key}"], out[f"{name}.{key[:-1]}y"] = float(rec[k, 0]), float(rec[k, 1])
        return out


def sweep(loops: Loops, values: np.ndarray, speed: float, full: bool) -> tuple[float, list[dict[str, float]], int]:
    """Seconds per row of the sweep over ``values`` (median of RUNS), with the rates where ``full``;
    the rows' outputs (rates too where full), and the rows where fsolve reported no convergence."""
    from scipy.optimize import fsolve

    start = float(loops.ref.sketch_inputs()[0])
    q0 = np.zeros(3 * loops.n)
    for theta in np.linspace(start, values[0], LEAD_IN):
        q0 = fsolve(loops.f, q0, args=(theta,), fprime=loops.jacobian)

    def run() -> tuple[float, list[tuple], int]:
        q, rows, missed = q0, [], 0
        t = time.perf_counter()
        for theta in values:
            q, _, done, _ = fsolve(loops.f, q, args=(theta,), fprime=loops.jacobian, full_output=True)
            missed += done != 1
            if full:
                rows.append((q, *loops.rates(q, speed)))
        return (time.perf_counter() - t) / len(values), rows, missed

    with warnings.catch_warnings():  # fsolve warns where it stops short of its tolerance: counted instead
        warnings.simplefilter("ignore", RuntimeWarning)
        _, solved, missed = run()
        seconds = statistics.median(run()[0] for _ in range(RUNS))
    return seconds, [loops.outputs(*r) for r in solved], missed
