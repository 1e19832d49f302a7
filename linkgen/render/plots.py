"""The plots of the manual and the page: every output against the input, the conditioning of each
step with its singular positions marked, and the paths of all points on the sketch.

Figures (``figures``): NAME_points.svg (positions, velocities and accelerations of the pairs and
points that move, one row of panels per output), NAME_angles.svg (the angles of the links that turn
and their rates), NAME_conditioning.svg (each measured step's sigma) and NAME_paths.svg.  Which
figures a mechanism has follows from its step log alone, so the manual can name them.  A failed row
is a gap in every curve; an angle's wrap from +180 to -180 degrees is a gap too.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..numeric import percentiles
from ..steplog import Column, StepLog
from .svgwriter import Svg, fit, label, ticks

if TYPE_CHECKING:  # the sweep is evaluated outside render (linkgen.sweepdata)
    from ..sweepdata import Sweep

PANEL_W, PANEL_H = 250.0, 110.0  # plot area of one panel
LEFT, RIGHT, TOP, BOTTOM = 62.0, 14.0, 30.0, 34.0  # around a panel's plot area
HEAD = 44.0  # the figure's heading: the title, then what it shows
SERIES = ("#1f77b4", "#d62728", "#2ca02c", "#9467bd")
MARK = "#8c564b"  # singular positions
PATHS = ("#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#8c564b", "#e377c2", "#17becf", "#bcbd22", "#ff7f0e")
SIGMA = (0.0, 1.05)  # the conditioning panels' vertical range (sigma is 0 to 1)
MOTION = ("position", "velocity", "acceleration")
TURNING = ("angle", "angular_velocity", "angular_acceleration")


@dataclass(frozen=True)
class Figure:
    file: str  # NAME_points.svg, ...
    caption: str


def _moving(log: StepLog, quantities: Sequence[str]) -> list[str]:
    """Outputs with a computed column of these quantities, in column order."""
    out: list[str] = []
    for c in log.columns[len(log.inputs):]:
        owner = c.name.split(".")[0]
        if c.quantity in quantities and log.drawn(c) is None and owner not in out:
            out.append(owner)
    return out


def figures(log: StepLog) -> list[Figure]:
    """The plot files of a mechanism, decided by its step log alone."""
    axis = input_axis(log)
    out = []
    if _moving(log, MOTION):
        out.append(Figure(f"{log.name}_points.svg", f"Positions, velocities and accelerations against {axis.name}"))
    if _moving(log, TURNING):
        out.append(Figure(f"{log.name}_angles.svg", f"Link angles and their rates against {axis.name}"))
    if log.conditioning:
        out.append(Figure(f"{log.name}_conditioning.svg", f"Conditioning sigma of each step against {axis.name}, "
                                                          "limit positions and change points marked"))
    out.append(Figure(f"{log.name}_paths.svg", "Paths of all points over the sweep on the sketch"))
    return out


@dataclass(frozen=True)
class Axis:
    """The plots' horizontal axis: an input's column shown in the file's unit."""

    index: int  # the input's column (-1: the row number, where no input moves)
    name: str  # as a label: "theta_O1 (deg)"
    factor: float  # display value per value of the column
    turn: bool  # an angle: its ticks at 15, 30, 45, 90 degrees
    column: str = "row"
    unit: str = ""


def input_axis(log: StepLog) -> Axis:
    """The first input whose range is not one value; a revolute one in degrees where the file's
    angles are in degrees."""
    for k, i in enumerate(log.inputs):
        if i.start != i.stop:
            if i.kind == "revolute":
                deg = log.angle_unit == "deg"
                unit = "deg" if deg else "rad"
                return Axis(k, f"{i.column} ({unit})", 180 / math.pi if deg else 1.0, deg, i.column, unit)
            unit = log.length_unit or "length"
            return Axis(k, f"{i.column} ({unit})", 1.0, False, i.column, unit)
    return Axis(-1, "row", 1.0, False)


def _unit(log: StepLog, quantity: str) -> tuple[str, float]:
    """A quantity's unit as shown and the factor from the CSV's (SI radians) to it."""
    deg = log.angle_unit == "deg"
    angle, factor = ("deg", 180 / math.pi) if deg else ("rad", 1.0)
    length = log.length_unit or "length"
    return {
        "position": (length, 1.0), "velocity": (f"{length}/s", 1.0), "acceleration": (f"{length}/s²", 1.0),
        "angle": (angle, factor), "angular_velocity": (f"{angle}/s", factor),
        "angular_acceleration": (f"{angle}/s²", factor),
    }[quantity]


def _xs(log: StepLog, sweep: Sweep, axis: Axis) -> np.ndarray:
    if axis.index < 0:
        return sweep.index.astype(float)
    out: np.ndarray = sweep.data[:, axis.index] * axis.factor
    return out


def _xlim(xs: np.ndarray) -> tuple[float, float]:
    """The horizontal range: the input's values (one value: a unit either side)."""
    low, high = float(np.nanmin(xs)), float(np.nanmax(xs))
    return (low, high) if high > low else (low - 1, high + 1)


def singular_inputs(log: StepLog, axis: Axis) -> list[tuple[int, float, str]]:
    """(step, input value as shown, kind) of every limit position and change point found, moved
    into the sweep's range by whole turns for an angle."""
    if axis.index < 0:
        return []
    i = log.inputs[axis.index]
    lo, hi = sorted((i.start, i.stop))
    out = []
    for c in log.conditioning:
        for s in c.singular:
            if s.kind == "minimum":
                continue
            x = s.inputs[axis.index]
            if i.kind == "revolute":
                x = lo + math.fmod(x - lo, 2 * math.pi) + (2 * math.pi if x < lo else 0.0)
            if lo - 1e-12 <= x <= hi + 1e-12:
                out.append((c.step, x * axis.factor, s.kind))
    return sorted(out, key=lambda m: m[1])


class _Panel:
    """One plot area: x and y ranges mapped to the page, its frame, ticks and curves clipped to it."""

    def __init__(self, svg: Svg, left: float, top: float, xlim: tuple[float, float], ylim: tuple[float, float],
                 turn: bool):
        self.svg, self.left, self.top, self.xlim, self.ylim, self.turn = svg, left, top, xlim, ylim, turn

    def x(self, u: float) -> float:
        a, b = self.xlim
        return self.left + (u - a) / (b - a) * PANEL_W

    def y(self, v: float) -> float:
        a, b = self.ylim
        return self.top + PANEL_H - (v - a) / (b - a) * PANEL_H

    def frame(self, clip: str, title: str, xname: str, yname: str) -> None:
        svg, (a, b), (c, d) = self.svg, self.xlim, self.ylim
        svg.add("rect", x=self.left, y=self.top, width=PANEL_W, height=PANEL_H, fill="#fbfbfb", stroke="#999999",
                stroke_width="0.8")
        xt = ticks(a, b, 6, (1.5, 3.0, 4.5, 9.0) if self.turn else (1.0, 2.0, 2.5, 5.0))
        for u in xt:
            px = self.x(u)
            svg.line(px, self.top, px, self.top + PANEL_H, stroke="#e4e4e4", stroke_width="0.6")
            svg.text(px, self.top + PANEL_H + 12, label(u, xt[1] - xt[0] if len(xt) > 1 else 0.0),
                     text_anchor="middle", fill="#444444", font_size="9")
        yt = ticks(c, d, 4)
        for v in yt:
            py = self.y(v)
            svg.line(self.left, py, self.left + PANEL_W, py, stroke="#e4e4e4", stroke_width="0.6")
            svg.text(self.left - 4, py + 3, label(v, yt[1] - yt[0] if len(yt) > 1 else 0.0), text_anchor="end",
                     fill="#444444", font_size="9")
        if c < 0 < d:
            svg.line(self.left, self.y(0.0), self.left + PANEL_W, self.y(0.0), stroke="#b0b0b0", stroke_width="0.8")
        svg.open("clipPath", id=clip)
        svg.add("rect", x=self.left, y=self.top, width=PANEL_W, height=PANEL_H)
        svg.close("clipPath")
        svg.text(self.left, self.top - 8, title, font_weight="bold")
        svg.text(self.left + PANEL_W / 2, self.top + PANEL_H + 26, xname, text_anchor="middle", fill="#444444",
                 font_size="9")
        svg.text(self.left - 46, self.top + PANEL_H / 2, yname, text_anchor="middle", fill="#444444", font_size="9",
                 transform=f"rotate(-90 {self.left - 46:.1f} {self.top + PANEL_H / 2:.1f})")

    def marks(self, marks: list[tuple[int, float, str]], named: bool) -> None:
        for step, u, kind in marks:
            px = self.x(u)
            self.svg.line(px, self.top, px, self.top + PANEL_H, stroke=MARK, stroke_width="1",
                          stroke_dasharray="4 3")
            if named:
                self.svg.text(px + 3, self.top + 10, f"{kind} (step {step})", fill=MARK, font_size="9")

    def curve(self, xs: np.ndarray, ys: np.ndarray, colour: str, clip: str, column: str) -> None:
        (a, b), (c, d) = self.xlim, self.ylim
        px = self.left + (xs - a) / (b - a) * PANEL_W
        py = self.top + PANEL_H - (ys - c) / (d - c) * PANEL_H
        self.svg.curve(px, py, stroke=colour,
                       stroke_width="1.4", stroke_linejoin="round", clip_path=f"url(#{clip})", data_column=column)


def _range(values: list[np.ndarray], ref: float) -> tuple[tuple[float, float], bool]:
    """The y range of the finite values, padded; where a few rows (near a singular position) run far
    beyond the rest, the range of the central 98 % and True (those rows are clipped).  ``ref`` is the
    quantity's scale (``_scale``): a spread below 1e-9 of it is rounding, and the values are shown as
    one constant (a crank's angular acceleration is 0 to a few 1e-15)."""
    finite = np.concatenate([v[np.isfinite(v)] for v in values]) if values else np.array([])
    if finite.size == 0:
        return (-1.0, 1.0), False
    lo, hi = float(finite.min()), float(finite.max())
    clipped = False
    q1, q99 = percentiles(finite, (1.0, 99.0))
    if q99 > q1 and hi - lo > 20 * (q99 - q1):
        lo, hi, clipped = q1, q99, True
    span = hi - lo
    if span <= 1e-9 * max(abs(lo), abs(hi), ref):
        mid = (lo + hi) / 2 if abs(lo + hi) > 2e-9 * ref else 0.0
        pad = max(0.1 * abs(mid), 0.05 * ref) or 1.0
        return (mid - pad, mid + pad), clipped
    return (lo - 0.06 * span, hi + 0.06 * span), clipped


def _scale(log: StepLog, quantity: str) -> float:
    """The magnitude a quantity's rounding errors are relative to (SI radians): the length scale L
    and the fastest input's rate w (an angle's speed, or a length's over L) make L, L w, L w^2, 1 rad,
    w and w^2."""
    rate = max([abs(i.speed) if i.kind == "revolute" else abs(i.speed) / log.length_scale for i in log.inputs]
               or [0.0]) or 1.0
    length = log.length_scale
    return {"position": length, "velocity": length * rate, "acceleration": length * rate * rate, "angle": 1.0,
            "angular_velocity": rate, "angular_acceleration": rate * rate}[quantity]


def _heading(svg: Svg, left: float, title: str, what: str) -> None:
    svg.text(left, 18, fit(title, svg.width - left - 10, 13, bold=True), font_size="13", font_weight="bold")
    svg.text(left, 34, fit(what, svg.width - left - 10, 11), font_size="11", fill="#444444")


def _wraps(ys: np.ndarray, quantity: str, factor: float) -> np.ndarray:
    """An angle's values with nan put where it wraps by a turn between two rows (a gap, not a line across)."""
    if quantity != "angle" or ys.size < 2:
        return ys
    out: np.ndarray = ys.copy()
    jump = np.abs(np.diff(ys)) > math.pi * factor
    out[1:][jump] = np.nan
    return out


def _grid(log: StepLog, sweep: Sweep, kind: str, quantities: Sequence[str], heading: str) -> str:
    """Panels of the moving outputs (rows) by quantity (columns: the value, its rate, its acceleration)."""
    axis = input_axis(log)
    xs = _xs(log, sweep, axis)
    xlim = _xlim(xs)
    marks = singular_inputs(log, axis)
    owners = _moving(log, quantities)
    used = [q for q in quantities if any(c.quantity == q for c in log.columns)]
    width = len(used) * (LEFT + PANEL_W + RIGHT)
    height = HEAD + len(owners) * (TOP + PANEL_H + BOTTOM)
    svg = Svg(width, height, f"{log.title}: {heading}")
    _heading(svg, LEFT, log.title, heading)
    panels: dict[tuple[str, str], list[Column]] = {}  # (owner, quantity) -> its columns, in the log's order
    for c in log.columns[len(log.inputs):]:
        panels.setdefault((c.name.split(".")[0], c.quantity), []).append(c)
    for r, owner in enumerate(owners):
        for q, quantity in enumerate(used):
            cols = panels.get((owner, quantity), [])
            unit, factor = _unit(log, quantity)
            series = [_wraps(sweep.column(c.name) * factor, quantity, factor) for c in cols]
            ylim, clipped = _range(series, _scale(log, quantity) * factor)
            left = q * (LEFT + PANEL_W + RIGHT) + LEFT
            top = HEAD + r * (TOP + PANEL_H + BOTTOM) + TOP
            panel = _Panel(svg, left, top, xlim, ylim, axis.turn)
            clip = f"{kind}-{r}-{q}"
            title = f"{owner} {quantity.replace('_', ' ')}" + (" (clipped)" if clipped else "")
            svg.open("g", class_="panel", data_x0=xlim[0], data_x1=xlim[1], data_y0=ylim[0], data_y1=ylim[1],
                     data_left=left, data_top=top, data_width=PANEL_W, data_height=PANEL_H)
            panel.frame(clip, title, axis.name, unit)
            panel.marks(marks, False)
            for k, (c, ys) in enumerate(zip(cols, series)):
                colour = SERIES[k % len(SERIES)]
                panel.curve(xs, ys, colour, clip, c.name)
                field = c.name.split(".", 1)[1]
                lx = left + PANEL_W - 44 * (len(cols) - k)
                svg.line(lx, top - 12, lx + 12, top - 12, stroke=colour, stroke_width="2")
                svg.text(lx + 14, top - 8, field, fill=colour, font_size="10")
            svg.close("g")
    return svg.text_out()


def _conditioning(log: StepLog, sweep: Sweep) -> str:
    """One panel per step of the manual's conditioning table: sigma per row, 0 to 1, the step's limit
    positions and change points marked and named."""
    axis = input_axis(log)
    xs = _xs(log, sweep, axis)
    xlim = _xlim(xs)
    marks = singular_inputs(log, axis)
    steps = [c.step for c in log.conditioning]
    per_row = 2
    rows = (len(steps) + per_row - 1) // per_row
    width = per_row * (LEFT + PANEL_W + RIGHT)
    height = HEAD + rows * (TOP + PANEL_H + BOTTOM)
    heading = f"sigma of each step against {axis.name}"
    svg = Svg(width, height, f"{log.title}: {heading}")
    _heading(svg, LEFT, log.title, f"{heading}; dashed: limits and change points")
    for k, step in enumerate(steps):
        left = (k % per_row) * (LEFT + PANEL_W + RIGHT) + LEFT
        top = HEAD + (k // per_row) * (TOP + PANEL_H + BOTTOM) + TOP
        panel = _Panel(svg, left, top, xlim, SIGMA, axis.turn)
        target = log.step(step).target
        sigma = sweep.sigma.get(step)
        svg.open("g", class_="panel", data_x0=xlim[0], data_x1=xlim[1], data_y0=SIGMA[0], data_y1=SIGMA[1],
                 data_left=left, data_top=top, data_width=PANEL_W, data_height=PANEL_H)
        panel.frame(f"sigma-{k}", f"step {step}" + (f": {target}" if target else ""), axis.name, "sigma")
        panel.marks([m for m in marks if m[0] == step], True)
        if sigma is None or not np.isfinite(sigma).any():
            svg.text(left + PANEL_W / 2, top + PANEL_H / 2, "not measured (built without checks)",
                     text_anchor="middle", fill="#777777")
        else:
            panel.curve(xs, sigma, SERIES[0], f"sigma-{k}", f"sigma {step}")
        svg.close("g")
    return svg.text_out()


PATH_W, PATH_MARGIN = 640.0, 50.0


def _paths(log: StepLog, sweep: Sweep) -> str:
    """The sketch (links and pairs as drawn) with the path of every moving pair and point over the sweep."""
    sketch = {p.name: (p.x, p.y) for p in log.pairs}
    for v in log.variables:
        if v.role == "point" and v.sketch:
            sketch[v.entity] = (v.sketch[0], v.sketch[1])
    moving = [n for n, (x, y) in sweep.places.items() if np.nanmax(x) - np.nanmin(x) > 0 or
              np.nanmax(y) - np.nanmin(y) > 0] if sweep.places else []
    xs = np.concatenate([[x for x, _ in sketch.values()], *(sweep.places[n][0] for n in moving)])
    ys = np.concatenate([[y for _, y in sketch.values()], *(sweep.places[n][1] for n in moving)])
    x0, x1, y0, y1 = (float(f(v)) for f, v in ((np.nanmin, xs), (np.nanmax, xs), (np.nanmin, ys), (np.nanmax, ys)))
    span = max(x1 - x0, y1 - y0, log.length_scale * 1e-3)
    scale = (PATH_W - 2 * PATH_MARGIN) / span
    height = (y1 - y0) * scale + 2 * PATH_MARGIN + HEAD

    def at(x: float, y: float) -> tuple[float, float]:
        return PATH_MARGIN + (x - x0) * scale, PATH_MARGIN + HEAD + (y1 - y) * scale

    heading = f"paths of the points over the sweep ({log.samples} rows), on the sketch"
    svg = Svg(PATH_W, height, f"{log.title}: {heading}")
    _heading(svg, PATH_MARGIN / 2, log.title, heading)
    for link in log.links:
        pts = [at(*sketch[n]) for n in (*link.pairs, *link.points) if n in sketch]
        style: dict[str, object] = dict(stroke="#9a9a9a", stroke_width="2")
        if link.fixed:
            style["stroke_dasharray"] = "6 3"
        if len(pts) >= 3:
            svg.add("polygon", points=" ".join(f"{x:.1f},{y:.1f}" for x, y in pts), fill="#9a9a9a",
                    fill_opacity="0.08", **style)
        elif len(pts) == 2:
            svg.line(*pts[0], *pts[1], **style)
    for k, name in enumerate(moving):
        colour = PATHS[k % len(PATHS)]
        px, py = sweep.places[name]
        svg.curve(PATH_MARGIN + (px - x0) * scale, PATH_MARGIN + HEAD + (y1 - py) * scale, stroke=colour,
                  stroke_width="1.5",
                  stroke_linejoin="round", data_name=name)
        first = next(((float(u), float(v)) for u, v in zip(px, py) if math.isfinite(u) and math.isfinite(v)), None)
        if first is not None:
            fx, fy = at(*first)
            svg.add("circle", cx=fx, cy=fy, r="3", fill=colour)
    pivots = {n for lk in log.links if lk.fixed for n in lk.pairs}
    pivots -= {p.name for p in log.pairs if p.kind == "prismatic"}
    for name, (x, y) in sketch.items():
        sx, sy = at(x, y)
        colour = PATHS[moving.index(name) % len(PATHS)] if name in moving else "#333333"
        svg.add("circle", cx=sx, cy=sy, r="4", fill="#555555" if name in pivots else "white", stroke="black",
                stroke_width="1.2")
        svg.text(sx + 7, sy - 6, name, fill=colour, font_weight="bold")
    svg.text(PATH_MARGIN / 2, height - 10, "grey: the links in the sketch; coloured: each point's path, "
             "a dot at row 0; gaps: rows that fail", fill="#555555")
    return svg.text_out()


def render_plots(log: StepLog, sweep: Sweep) -> dict[str, str]:
    """{file: SVG text} of every figure of ``figures(log)``, in that order."""
    out: dict[str, str] = {}
    for fig in figures(log):
        kind = fig.file[len(log.name) + 1:-4]
        if kind == "points":
            out[fig.file] = _grid(log, sweep, "points", MOTION,
                                  f"positions, velocities and accelerations against {input_axis(log).name}")
        elif kind == "angles":
            out[fig.file] = _grid(log, sweep, "angles", TURNING,
                                  f"link angles and their rates against {input_axis(log).name}")
        elif kind == "conditioning":
            out[fig.file] = _conditioning(log, sweep)
        else:
            out[fig.file] = _paths(log, sweep)
    return out
