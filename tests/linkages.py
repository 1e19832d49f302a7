"""Four-bar files of chosen lengths, and their limit positions in closed form (law of cosines).

A four-bar O1-A-B-O2: the ground O1-O2 (length d) at an angle, the crank O1-A (a) driven
relative to the ground, the coupler A-B (b) and the rocker O2-B (c).  With the crank at
theta from the ground line, |A O2|^2 = a^2 + d^2 - 2 a d cos(theta), and the chain A-B-O2
closes while b - c <= |A O2| <= b + c (in absolute value): its toggles lie where |A O2|
is b + c or |b - c|.
"""

from __future__ import annotations

import math
from pathlib import Path

import mpmath

MP = mpmath.mp.clone()
MP.dps = 40


def four_bar(folder: Path, name: str, a: float, b: float, c: float, d: float, crank: float, *, ground: float = 0.0,
             side: int = 1, samples: int = 73) -> Path:
    """A four-bar file with the crank drawn at ``crank`` degrees from the ground line (itself at
    ``ground`` degrees), B on the ``side`` of A -> O2; coordinates to 40 digits, then rounded."""
    g, t = MP.radians(ground), MP.radians(ground + crank)
    o2 = (d * MP.cos(g), d * MP.sin(g))
    pa = (a * MP.cos(t), a * MP.sin(t))
    dx, dy = o2[0] - pa[0], o2[1] - pa[1]
    q = MP.sqrt(dx * dx + dy * dy)
    along = (b * b - c * c + q * q) / (2 * q)
    h = MP.sqrt(b * b - along * along)
    pb = (pa[0] + (along * dx - side * h * dy) / q, pa[1] + (along * dy + side * h * dx) / q)

    def xy(p: tuple) -> str:
        return f"[{float(p[0])!r}, {float(p[1])!r}]"

    path = folder / f"{name}.yaml"
    path.write_text(f"""linkgen: 1
name: {name}
title: Four-bar a={a}, b={b}, c={c}, d={d}
joints:
  O1: [0, 0]
  A: {xy(pa)}
  B: {xy(pb)}
  O2: {xy(o2)}
links:
  frame: {{joints: [O1, O2], fixed: true}}
  crank: [O1, A]
  coupler: [A, B]
  rocker: [O2, B]
inputs:
  - {{joint: O1, link: crank, relative_to: frame, range: [0, 360]}}
samples: {samples}
""")
    return path


def toggle(a: float, b: float, c: float, d: float, far: bool) -> float:
    """The crank angle in [0, pi] from the ground line where the chain A-B-O2 is stretched
    (far: |A O2| = b + c) or folded (|A O2| = |b - c|)."""
    reach = b + c if far else abs(b - c)
    return float(MP.acos((a * a + d * d - MP.mpf(reach) ** 2) / (2 * a * d)))


def sigma(a: float, b: float, c: float, d: float, theta: float) -> float:
    """The chain A-B-O2's conditioning with the crank at theta: |sin| of the angle at B between
    coupler and rocker (twice the triangle's area over b c)."""
    q2 = a * a + d * d - 2 * a * d * math.cos(theta)
    cos_b = (b * b + c * c - q2) / (2 * b * c)
    return math.sqrt(max(0.0, 1.0 - cos_b * cos_b))
