"""Step log types: every assembly of the mechanism at the sketch's inputs, as the step log
records them (``linkgen assemblies``' census, made by linkgen.assemblies.follow), and the
one the programs follow."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class AssemblyChoice:
    """How an assembly passes one step: a two-link chain's branch or a resolver group's root."""

    step: int
    target: str  # the chain's pair, or "group N"
    value: int  # chain: the branch (+1 / -1); group: the root's number (1 = smallest turn)
    of: int  # chain: 2 (1 at a toggle); group: its real roots
    theta: float = 0.0  # group: the ternary's turn from the sketch (radians)


@dataclass(frozen=True)
class AssemblyInfo:
    """One assembly of the mechanism at the sketch's inputs (linkgen assemblies' census)."""

    number: int
    sketch: bool  # the sketch's own assembly
    choices: tuple[AssemblyChoice, ...]
    values: tuple[tuple[str, float], ...]  # the CSV's columns at order 0 (points as drawn), by name
    error: float  # the worst link length error, over the length scale


@dataclass(frozen=True)
class Assemblies:
    """Every assembly at the sketch's inputs and the one the programs follow."""

    inputs: tuple[float, ...]  # the sketch's inputs (radians, length units)
    counted: bool  # False: linkgen cannot count them (``notes`` says why), ``listing`` is empty
    follows: int  # the assembly the programs follow (options.assembly, else the sketch's; 0: none found)
    notes: tuple[str, ...]  # what the census met (groups, chains that cannot close, ...), or why no count
    listing: tuple[AssemblyInfo, ...]
