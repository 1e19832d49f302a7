"""What the step log keeps of an instant centre: its class and its place at the sketch."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class CentreAt:
    """An instant centre at the sketch, moving at the inputs' speeds (the manual's table and figure;
    linkgen.instant): its class from the topology and its place (x, y None at infinity)."""

    name: str  # ic:LINK1:LINK2
    links: tuple[str, str]
    kind: str  # first | secondary | third A | third B
    pair: str  # the pair that joins the links ("" for none)
    lines: tuple[str, ...]  # the third links of the Kennedy lines it lies on (those that place it)
    placed: bool  # the theorem places it (first, secondary, and the third centres it reaches)
    x: float | None
    y: float | None
    ux: float | None
    uy: float | None
    status: int  # 0 finite, 1 at infinity, 2 the links move alike (x, y their pair)
    sigma: float
