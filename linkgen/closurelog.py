"""The loop-closure equations of a resolver group, as the step log records them (options:
strategy closure): plain records that extraction writes and the templates read."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Distance:
    """A closure equation: |points[1] - points[0]| = length (one row)."""

    points: tuple[str, str]  # position variables
    length: float  # in the sketch
    step: int  # the step whose chain or residual holds it
    link: str
    variable: str = ""  # the VARIABLE record holding the length where it changes with the inputs (an actuator's)


@dataclass(frozen=True)
class Frame:
    """A closure equation: a point fixed in the frame of its link, point = origin + w (b - a)
    with w a complex number (two rows, x and y): (gsi + i eta) e^(i off) / |b - a| for
    coupler_point, (c - a) / (b - a) of the sketch for link_point (whose origin is a)."""

    point: str
    origin: str
    base: tuple[str, str]  # (a, b): the link's points its angle is measured on
    w: tuple[float, float]  # real and imaginary part
    step: int
    link: str


@dataclass(frozen=True)
class Closure:
    """The loop-closure equations of a resolver group (options: strategy closure): every rigid-link
    constraint inside the group, in the positions the group places (x and y of each)."""

    unknowns: tuple[str, ...]  # POINT variables; unknowns 2i and 2i + 1 are the x and y of the i-th
    distances: tuple[Distance, ...]  # rows 0 .. len - 1
    frames: tuple[Frame, ...]  # then two rows each
