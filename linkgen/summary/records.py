"""The engineering summary as plain records: what a designer judges a linkage by.

Every value is in the file's units: angles in degrees where the file gives them in
degrees (``angle_unit``), lengths in its length unit.  Input values are tuples with
one entry per input (all inputs move together along the sweep).
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class InputRange:
    """An input's sweep and the part of it that assembles from the sketch (one input only)."""

    column: str
    kind: str  # revolute | prismatic (an angle or a length)
    unit: str  # deg | rad | the length unit
    start: float
    stop: float
    sketch: float
    low: float | None  # the assembling range around the sketch: None where it has no limit that side
    high: float | None
    known: bool  # whether the range was searched (one input only)


@dataclass(frozen=True)
class FourBar:
    """A four-bar loop of revolute pairs O1-A-B-O2 with the frame, and its Grashof class."""

    pairs: tuple[str, str, str, str]  # O1, A, B, O2
    links: tuple[str, str, str, str]  # frame, the link at O1, coupler, the link at O2
    lengths: tuple[float, float, float, float]  # frame d, a, coupler b, c
    grashof: str  # Grashof | non-Grashof | change point (s + l = p + q)
    kind: str  # crank-rocker | rocker-crank | double-crank | double-rocker | triple-rocker
    driven: str  # the input column turning the link at O1 ("" when no input drives it)


@dataclass(frozen=True)
class Position:
    """A limit position (the chain cannot close beyond it), a change point (two branches cross)
    or a single value where a chain cannot close."""

    step: int
    target: str
    kind: str  # limit | change point | cannot close
    inputs: tuple[float, ...]


@dataclass(frozen=True)
class Transmission:
    """A chain's transmission angle over the sweep: the angle whose sine is the chain's
    conditioning sigma (at a 3R chain the angle between its two links at the middle pair; with
    a slider, between the link and the normal to the slide), folded to 0..90 degrees."""

    step: int
    target: str
    chain: str
    links: tuple[str, ...]
    minimum: float  # in the file's angle unit
    at: tuple[float, ...]  # the inputs where it is least
    maximum: float
    at_limit: bool  # the minimum is 0 at a limit position of the chain


@dataclass(frozen=True)
class Travel:
    """An output's stroke (a slide) or swing (a link angle) over the rows that assemble, or a
    link that turns fully; with a time ratio where one input turns fully and the output
    oscillates (the slower stroke's input angle over the faster's)."""

    name: str  # the output's column
    quantity: str  # angle | slide
    unit: str
    low: float
    high: float
    at_low: tuple[float, ...]
    at_high: tuple[float, ...]
    travel: float  # high - low; a full turn for a link that turns fully
    turns: bool
    time_ratio: float | None


@dataclass(frozen=True)
class Failure:
    """Rows of the sweep that fail for one reason (a status code)."""

    code: int
    step: int
    meaning: str
    rows: int
    ranges: tuple[tuple[float, float], ...]  # runs of failing rows, the first input's values


@dataclass(frozen=True)
class Summary:
    """The engineering summary of a mechanism over its sweep."""

    name: str
    title: str
    length_unit: str
    angle_unit: str  # deg | rad: the unit of every angle below
    grubler: int
    mobility: int
    redundant: int
    inputs: tuple[InputRange, ...]
    four_bars: tuple[FourBar, ...]
    positions: tuple[Position, ...]
    transmission: tuple[Transmission, ...]
    travels: tuple[Travel, ...]
    rows: int
    near: int  # rows computed near a singular position
    singular: int  # rows at a singular position (rates nan)
    failed: int
    failures: tuple[Failure, ...]
