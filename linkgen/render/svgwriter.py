"""A small SVG writer with fixed-precision numbers, so a figure's bytes are the same on every run.

No dates, no ids drawn at random: the elements come out in the order they were added, each
attribute in the order given, every coordinate rounded to ``DIGITS`` decimals.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence

DIGITS = 1  # decimals of a page coordinate (0.1 px)


def num(x: float, digits: int = DIGITS) -> str:
    """x with at most ``digits`` decimals, trailing zeros dropped ("-0" is "0")."""
    text = f"{x:.{digits}f}".rstrip("0").rstrip(".") if digits else f"{x:.0f}"
    return "0" if text in ("-0", "") else text


def esc(text: str) -> str:
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;").replace('"', "&quot;")


def attrs(items: dict[str, object]) -> str:
    """' a="1" b="x"': numbers by num() (a data- attribute's, which a script computes with, to 10
    significant digits), text escaped, in the order given; None is left out."""
    out = []
    for key, value in items.items():
        if value is None:
            continue
        if isinstance(value, float):
            text = f"{value:.10g}" if key.startswith("data_") else num(value)
        else:
            text = esc(str(value))
        out.append(f' {key.rstrip("_").replace("_", "-")}="{text}"')
    return "".join(out)


def runs(points: Iterable[tuple[float, float]]) -> list[list[tuple[float, float]]]:
    """The stretches of points between non-finite ones (a failed row is a gap, never a line across)."""
    out: list[list[tuple[float, float]]] = [[]]
    for x, y in points:
        if math.isfinite(x) and math.isfinite(y):
            out[-1].append((x, y))
        elif out[-1]:
            out.append([])
    return [r for r in out if r]


def path_data(stretches: Sequence[Sequence[tuple[float, float]]]) -> str:
    """One path's d: M at the start of each stretch, L after (a single point is a dot: a zero-length line)."""
    parts = []
    for run in stretches:
        head = f"M{num(run[0][0])} {num(run[0][1])}"
        tail = "".join(f"L{num(x)} {num(y)}" for x, y in run[1:]) or f"L{num(run[0][0])} {num(run[0][1])}"
        parts.append(head + tail)
    return "".join(parts)


class Svg:
    """An SVG document built element by element."""

    def __init__(self, width: float, height: float, title: str, font: int = 11):
        self.width, self.height = width, height
        self.parts = [
            f'<svg xmlns="http://www.w3.org/2000/svg" width="{num(width)}" height="{num(height)}" '
            f'viewBox="0 0 {num(width)} {num(height)}" font-family="Helvetica, Arial, sans-serif" font-size="{font}">',
            f"<title>{esc(title)}</title>",
            '<rect width="100%" height="100%" fill="white"/>',
        ]

    def add(self, tag: str, *text: str, **items: object) -> None:
        """<tag .../> or <tag ...>text</tag>; attribute names with _ become - (a trailing _ is dropped)."""
        if not text:
            self.parts.append(f"<{tag}{attrs(items)}/>")
        else:
            self.parts.append(f"<{tag}{attrs(items)}>{esc(''.join(text))}</{tag}>")

    def open(self, tag: str, **items: object) -> None:
        self.parts.append(f"<{tag}{attrs(items)}>")

    def close(self, tag: str) -> None:
        self.parts.append(f"</{tag}>")

    def line(self, x1: float, y1: float, x2: float, y2: float, /, **items: object) -> None:
        self.add("line", **{"x1": float(x1), "y1": float(y1), "x2": float(x2), "y2": float(y2), **items})

    def text(self, x: float, y: float, text: str, /, **items: object) -> None:
        self.add("text", text, **{"x": float(x), "y": float(y), **items})

    def curve(self, points: Iterable[tuple[float, float]], **items: object) -> None:
        """A polyline with gaps where a point is not finite (nothing when no point is)."""
        stretches = runs(points)
        if stretches:
            self.add("path", d=path_data(stretches), fill="none", **items)

    def text_out(self) -> str:
        return "\n".join([*self.parts, "</svg>"]) + "\n"


def ticks(low: float, high: float, count: int = 5, steps: Sequence[float] = (1.0, 2.0, 2.5, 5.0)) -> list[float]:
    """Round values between low and high, about ``count`` of them: multiples of a step from
    ``steps`` times a power of ten (angles in degrees pass (1.5, 3, 4.5, 9) for 15, 30, 45, 90)."""
    if not (math.isfinite(low) and math.isfinite(high)) or high <= low:
        return [low] if math.isfinite(low) else []
    raw = (high - low) / max(count, 1)
    power = 10.0 ** math.floor(math.log10(raw))
    step = next((s * power for s in sorted(steps) if s * power >= raw), 10 * power * min(steps))
    first = math.ceil(low / step - 1e-9)
    out = []
    k = first
    while k * step <= high + 1e-9 * step:
        value = k * step
        out.append(0.0 if abs(value) < 1e-12 * step else value)
        k += 1
    return out


def label(value: float, step: float) -> str:
    """A tick label with as many decimals as the tick step needs."""
    if step <= 0 or not math.isfinite(step):
        return f"{value:g}"
    decimals = max(0, -math.floor(math.log10(step) + 1e-9))
    if step * 10 ** decimals % 1 > 1e-6:  # 2.5, 0.25: one decimal more
        decimals += 1
    text = f"{value:.{decimals}f}"
    return "0" if float(text) == 0 else text
