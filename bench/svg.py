"""A small SVG writer for the bench's plots: axes (linear or log10), lines, labelled marks.

Deterministic: the same data give the same bytes (no dates, no random ids, numbers rounded to
0.1 px).  Used for docs/performance-pareto.svg and docs/performance-addlinks.svg.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from html import escape

COLOURS = ("#1f6fb4", "#d2452b", "#2a9d4b", "#8e44ad", "#e08a00", "#16a2b8", "#7f7f7f", "#b8860b", "#c2185b",
           "#2e4053")


@dataclass
class Axis:
    """One axis: its label, its range (in data units, log10 of them when log) and its ticks."""

    label: str
    lo: float
    hi: float
    log: bool = False

    def unit(self, value: float) -> float:
        """value's place on the axis, 0 at lo and 1 at hi (clipped)."""
        v = math.log10(value) if self.log else value
        return min(max((v - self.lo) / (self.hi - self.lo), 0.0), 1.0)

    def ticks(self) -> list[tuple[float, str]]:
        """(place, text): every decade of a log axis, about six round steps of a linear one."""
        if self.log:
            return [(k, f"1e{k}") for k in range(math.ceil(self.lo), math.floor(self.hi) + 1)]
        step = 10 ** math.floor(math.log10((self.hi - self.lo) / 5))
        first = math.ceil(self.lo / step)
        return [(k * step, f"{k * step:g}") for k in range(first, math.floor(self.hi / step) + 1)]


def log_axis(label: str, values: list[float]) -> Axis:
    """A log axis spanning the positive values with a quarter decade to spare, in whole decades."""
    logs = [math.log10(v) for v in values if v > 0 and math.isfinite(v)]
    lo, hi = (math.floor(min(logs) - 0.25), math.ceil(max(logs) + 0.25)) if logs else (0, 1)
    return Axis(label, lo, hi if hi > lo else lo + 1, log=True)


@dataclass
class Panel:
    """A plot: axes, polylines (label, colour, points) and marks (label, colour, shape, x, y)."""

    title: str
    x: Axis
    y: Axis
    lines: list[tuple[str, str, list[tuple[float, float]]]] = field(default_factory=list)
    marks: list[tuple[str, str, str, float, float]] = field(default_factory=list)


def _mark(shape: str, x: float, y: float, colour: str) -> str:
    if shape == "square":
        return f'<rect x="{x - 4:.1f}" y="{y - 4:.1f}" width="8" height="8" fill="{colour}"/>'
    if shape == "triangle":
        corners = f"{x:.1f},{y - 5:.1f} {x - 5:.1f},{y + 4:.1f} {x + 5:.1f},{y + 4:.1f}"
        return f'<polygon points="{corners}" fill="{colour}"/>'
    return f'<circle cx="{x:.1f}" cy="{y:.1f}" r="4" fill="{colour}"/>'


def _panel(p: Panel, left: float, top: float, width: float, height: float) -> list[str]:
    def px(v: float) -> float:
        return left + p.x.unit(v) * width

    def py(v: float) -> float:
        return top + (1 - p.y.unit(v)) * height

    out = [f'<text x="{left + width / 2:.1f}" y="{top - 10:.1f}" text-anchor="middle" font-size="13">'
           f"{escape(p.title)}</text>"]
    for value, text in p.x.ticks():
        x = px(10**value if p.x.log else value)
        out.append(f'<line x1="{x:.1f}" y1="{top:.1f}" x2="{x:.1f}" y2="{top + height:.1f}" stroke="#e4e4e4"/>')
        out.append(f'<text x="{x:.1f}" y="{top + height + 15:.1f}" text-anchor="middle">{text}</text>')
    for value, text in p.y.ticks():
        y = py(10**value if p.y.log else value)
        out.append(f'<line x1="{left:.1f}" y1="{y:.1f}" x2="{left + width:.1f}" y2="{y:.1f}" stroke="#e4e4e4"/>')
        out.append(f'<text x="{left - 5:.1f}" y="{y + 4:.1f}" text-anchor="end">{text}</text>')
    out.append(f'<rect x="{left:.1f}" y="{top:.1f}" width="{width:.1f}" height="{height:.1f}" fill="none" '
               'stroke="#333"/>')
    out.append(f'<text x="{left + width / 2:.1f}" y="{top + height + 32:.1f}" text-anchor="middle">'
               f"{escape(p.x.label)}</text>")
    out.append(f'<text transform="translate({left - 48:.1f} {top + height / 2:.1f}) rotate(-90)" '
               f'text-anchor="middle">{escape(p.y.label)}</text>')
    for k, (label, colour, points) in enumerate(p.lines):  # a legend in the right margin
        d = " ".join(f"{px(x):.1f},{py(y):.1f}" for x, y in points)
        out.append(f'<polyline points="{d}" fill="none" stroke="{colour}" stroke-width="1.5"/>')
        y = top + 8 + 16 * k
        out.append(f'<line x1="{left + width + 10:.1f}" y1="{y:.1f}" x2="{left + width + 30:.1f}" y2="{y:.1f}" '
                   f'stroke="{colour}" stroke-width="2"/>')
        out.append(f'<text x="{left + width + 34:.1f}" y="{y + 4:.1f}" font-size="10">{escape(label)}</text>')
    placed: list[tuple[float, float, float, float]] = []
    for label, colour, shape, x, y in p.marks:
        out.append(_mark(shape, px(x), py(y), colour))
        out.append(_label(label, px(x), py(y), placed))
    return out


def _label(text: str, x: float, y: float, placed: list[tuple[float, float, float, float]]) -> str:
    """A mark's label beside it: above right, below right, above left or below left, the first place
    whose box meets no label placed before (else above right)."""
    width, height = 5.0 * len(text), 10.0
    tries = [(x + 6, y - 5, "start"), (x + 6, y + 13, "start"), (x - 6, y - 5, "end"), (x - 6, y + 13, "end")]
    for tx, ty, anchor in tries:
        box = (tx if anchor == "start" else tx - width, ty - height, width, height)
        if not any(box[0] < b[0] + b[2] and b[0] < box[0] + box[2] and box[1] < b[1] + b[3] and b[1] < box[1] + box[3]
                   for b in placed):
            break
    else:
        tx, ty, anchor = tries[0]
        box = (tx, ty - height, width, height)
    placed.append(box)
    return f'<text x="{tx:.1f}" y="{ty:.1f}" font-size="9" text-anchor="{anchor}">{escape(text)}</text>'


def write(path, panels: list[Panel], note: str, width: int = 640, height: int = 420) -> None:
    """Panels stacked top to bottom, each width x height, and a note under them."""
    left, right, top, bottom = 80, 160, 40, 50
    total = height * len(panels) + 30
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{total}" '
           f'viewBox="0 0 {width} {total}" font-family="sans-serif" font-size="11">',
           f'<rect width="{width}" height="{total}" fill="white"/>']
    for k, p in enumerate(panels):
        out += _panel(p, left, k * height + top, width - left - right, height - top - bottom)
    out.append(f'<text x="10" y="{total - 10}" font-size="10" fill="#555">{escape(note)}</text>')
    out.append("</svg>")
    path.write_text("\n".join(out) + "\n", encoding="utf-8")
