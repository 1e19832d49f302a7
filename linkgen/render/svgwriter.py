"""A small SVG writer with fixed-precision numbers, so a figure's bytes are the same on every run.

No dates, no ids drawn at random: the elements come out in the order they were added, each
attribute in the order given, every coordinate rounded to ``DIGITS`` decimals.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

DIGITS = 1  # decimals of a page coordinate (0.1 px)


def num(x: float, digits: int = DIGITS) -> str:
    """x with at most ``digits`` decimals, trailing zeros dropped ("-0" is "0")."""
    text = f"{x:.{digits}f}".rstrip("0").rstrip(".") if digits else f"{x:.0f}"
    return "0" if text in ("-0", "") else text


def esc(text: str) -> str:
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;").replace('"', "&quot;")


class _Names(dict[str, str]):
    """An attribute's name from its keyword (class_ -> class, stroke_width -> stroke-width), each made once."""

    def __missing__(self, key: str) -> str:
        name = self[key] = key.rstrip("_").replace("_", "-")
        return name


NAMES = _Names()


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
        out.append(f' {NAMES[key]}="{text}"')
    return "".join(out)


def _tenths(k: int) -> str:
    """An integer count of tenths as num() writes it: 12 -> "1.2", -30 -> "-3", 0 -> "0"."""
    whole, tenth = divmod(abs(k), 10)
    return ("-" if k < 0 else "") + (f"{whole}.{tenth}" if tenth else str(whole))


def fit(text: str, width: float, size: float, bold: bool = False) -> str:
    """Text cut with an ellipsis to about ``width`` px at a font of ``size`` px (an average glyph
    is taken as 0.55 of the size, 0.62 in bold: the figure's bytes cannot ask a font)."""
    room = int(width / ((0.62 if bold else 0.55) * size))
    return text if len(text) <= room else text[:max(room - 1, 1)].rstrip() + "…"


class _Tenths(dict[int, str]):
    """_tenths of every count asked for, each written once (a figure's curves share their xs and
    most of their ys: a 1000-dyad chain's plots ask for four million)."""

    def __missing__(self, k: int) -> str:
        if len(self) > 1 << 20:
            self.clear()
        text = self[k] = _tenths(k)
        return text


TENTHS = _Tenths()


def path_data(xs: np.ndarray, ys: np.ndarray) -> str:
    """One path's d through the points (xs, ys) to 0.1: M at the start of each stretch of finite
    points, L after (a point alone is a dot: a zero-length line); a point that is not finite is a gap
    (a failed row is never a line across)."""
    ok = np.isfinite(xs) & np.isfinite(ys)
    where = np.flatnonzero(ok)
    if not where.size:
        return ""
    tx = [TENTHS[k] for k in np.rint(np.where(ok, xs, 0.0) * 10).astype(np.int64).tolist()]
    ty = [TENTHS[k] for k in np.rint(np.where(ok, ys, 0.0) * 10).astype(np.int64).tolist()]
    parts = []
    for run in np.split(where, np.flatnonzero(np.diff(where) > 1) + 1):
        first, last = int(run[0]), int(run[-1]) + 1  # a stretch: consecutive rows
        parts.append(f"M{tx[first]} {ty[first]}" + ("".join([f"L{x} {y}" for x, y in zip(tx[first + 1:last],
                                                                                      ty[first + 1:last])])
                                                      if last > first + 1 else f"L{tx[first]} {ty[first]}"))
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

    def curve(self, xs: np.ndarray, ys: np.ndarray, **items: object) -> None:
        """A polyline through (xs, ys) with gaps where a point is not finite (nothing when no point is)."""
        d = path_data(xs, ys)
        if d:
            self.add("path", d=d, fill="none", **items)

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
    """A tick label with as many decimals as the tick step needs; in powers of ten ("-5e6", "2.5e-5")
    where the step is 1e5 or more or below 1e-3."""
    if step <= 0 or not math.isfinite(step):
        return f"{value:g}"
    if value and (step >= 1e5 or step < 1e-3):
        text = f"{value:.3g}"
        return text.replace("e+0", "e").replace("e+", "e").replace("e-0", "e-")
    decimals = max(0, -math.floor(math.log10(step) + 1e-9))
    if step * 10 ** decimals % 1 > 1e-6:  # 2.5, 0.25: one decimal more
        decimals += 1
    text = f"{value:.{decimals}f}"
    return "0" if float(text) == 0 else text
