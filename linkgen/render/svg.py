"""NAME.svg: the sketch with pairs and links labelled and the order of the steps.

Coordinates are data, so the figure is drawn here in Python, not in a template.
Every number is rounded to 0.01 of the drawing unit, so the bytes are the same
on every machine.
"""

from __future__ import annotations

import math
from typing import Generic, TypeVar

from ..steplog import PairInfo, StepLog
from .svgwriter import esc, num

WIDTH = 640.0
MARGIN = 60.0
SPOT_SPACE = 40.0  # the least width per pair and point of the figure (wider than WIDTH beyond 16 of them)
COLOURS = ("#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#8c564b", "#e377c2", "#17becf", "#bcbd22", "#ff7f0e")


def _f(x: float) -> str:
    """A drawing coordinate to 0.01 of the drawing unit."""
    return num(x, 2)


def _line(a: tuple[float, float], b: tuple[float, float], style: str) -> str:
    return f'<line x1="{_f(a[0])}" y1="{_f(a[1])}" x2="{_f(b[0])}" y2="{_f(b[1])}" {style}/>'


Box = tuple[float, float, float, float]  # left, top, right, bottom on the page
Segment = tuple[tuple[float, float], tuple[float, float]]
CHAR = 7.0  # the width of a character of the 12-pixel font, generously
TEXT_HEIGHT = 12.0
# where a label may go around its anchor, tried in this order: (dx, dy) of the text's start on its baseline
PLACES = ((8, 16), (8, -8), (-8, 16), (-8, -8), (10, 5), (-10, 5), (0, 22), (0, -14), (14, 26), (14, -18),
          (-14, 26), (-14, -18), (24, 5), (-24, 5), (0, 34), (0, -26), (30, 30), (30, -22), (-30, 30), (-30, -22),
          (0, 46), (0, -38), (40, 5), (-40, 5), (0, 58), (0, -50), (40, 40), (40, -32), (-40, 40), (-40, -32))


def first_steps(log: StepLog) -> dict[str, int]:
    """The step that first finds each pair or point, in the main procedure (a fallback block
    finds them again: it is tried only where the block before cannot solve a row)."""
    found: dict[str, int] = {}
    for s in sorted(log.steps, key=lambda s: s.number):
        if s.variant:
            continue
        for p in s.determines:
            found.setdefault(p, s.number)
        if s.action == "point":
            found.setdefault(s.target, s.number)
    return found


def _box(x: float, y: float, text: str, anchor_end: bool) -> Box:
    width = CHAR * len(text)
    left = x - width if anchor_end else x
    return left, y - TEXT_HEIGHT, left + width, y + 3


def _overlaps(a: Box, b: Box) -> bool:
    return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]


SLACK = 1e-6  # a segment's bounds widened by this on the page: its sampled points' rounding stays inside


def _crosses(box: Box, seg: Segment) -> bool:
    """Whether a segment passes through a box (sampled finely enough for a 12-pixel label)."""
    (x1, y1), (x2, y2) = seg
    if max(x1, x2) + SLACK <= box[0] or min(x1, x2) - SLACK >= box[2] or max(y1, y2) + SLACK <= box[1] \
            or min(y1, y2) - SLACK >= box[3]:  # no sampled point can be inside
        return False
    n = max(2, int(math.hypot(x2 - x1, y2 - y1) / 3))
    return any(box[0] < x1 + (x2 - x1) * k / n < box[2] and box[1] < y1 + (y2 - y1) * k / n < box[3]
               for k in range(n + 1))


T = TypeVar("T")
CELL = 64.0  # the side of a cell of the labels' index, on the page


class _Cells(Generic[T]):
    """Boxes or segments by the cells of the page their bounds touch: what may meet a box is
    found among those sharing a cell with it, not among all (a figure of thousands of pairs)."""

    def __init__(self) -> None:
        self.items: list[T] = []
        self.cells: dict[tuple[int, int], list[int]] = {}

    def add(self, item: T, bounds: Box) -> None:
        for cell in _cells(bounds):
            self.cells.setdefault(cell, []).append(len(self.items))
        self.items.append(item)

    def near(self, box: Box) -> list[T]:
        """The items whose bounds share a cell with the box, each once (in no particular order:
        they are counted)."""
        return [self.items[k] for k in {k for cell in _cells(box) for k in self.cells.get(cell, ())}]


def _cells(b: Box) -> list[tuple[int, int]]:
    """The cells a box's closed bounds touch."""
    i0, j0, i1, j1 = (math.floor(v / CELL) for v in b)
    return [(i, j) for i in range(i0, i1 + 1) for j in range(j0, j1 + 1)]


class _Labels:
    """Labels placed one by one where they cover no label, marker or line placed before them;
    where every place is taken, the one covering least (first of the equals): deterministic."""

    def __init__(self, width: float, height: float) -> None:
        self.boxes: _Cells[Box] = _Cells()  # markers
        self.labels: _Cells[Box] = _Cells()
        self.segments: _Cells[Segment] = _Cells()
        self.width, self.height = width, height
        self.out: list[str] = []

    def mark(self, x: float, y: float, r: float) -> None:
        box = (x - r, y - r, x + r, y + r)
        self.boxes.add(box, box)

    def line(self, a: tuple[float, float], b: tuple[float, float]) -> None:
        self.segments.add((a, b), (min(a[0], b[0]) - SLACK, min(a[1], b[1]) - SLACK,
                                   max(a[0], b[0]) + SLACK, max(a[1], b[1]) + SLACK))

    def put(self, x: float, y: float, text: str, attrs: str = "", places: tuple[tuple[int, int], ...] = PLACES) -> None:
        best: tuple[int, float, float, bool] | None = None
        for dx, dy in places:
            end = dx < 0
            box = _box(x + dx, y + dy, text, end)
            cost = (100 * sum(_overlaps(box, b) for b in self.labels.near(box))
                    + 20 * sum(_overlaps(box, b) for b in self.boxes.near(box))
                    + 5 * sum(_crosses(box, s) for s in self.segments.near(box))
                    + 50 * (box[0] < 0 or box[2] > self.width or box[1] < 0 or box[3] > self.height))
            if best is None or cost < best[0]:
                best = (cost, x + dx, y + dy, end)
            if cost == 0:
                break
        assert best is not None
        _, tx, ty, end = best
        placed = _box(tx, ty, text, end)
        self.labels.add(placed, placed)
        anchor = ' text-anchor="end"' if end else ""
        self.out.append(f'<text x="{_f(tx)}" y="{_f(ty)}"{anchor}{attrs}>{esc(text)}</text>')


def _foot(p: tuple[float, float], on: tuple[float, float], u: tuple[float, float]) -> tuple[float, float]:
    """The foot of the perpendicular from p to the line through ``on`` along the unit vector u."""
    t = (p[0] - on[0]) * u[0] + (p[1] - on[1]) * u[1]
    return on[0] + t * u[0], on[1] + t * u[1]


def render_svg(log: StepLog) -> str:
    spots = {p.name: (p.x, p.y) for p in log.pairs}
    for v in log.variables:
        if v.role == "point" and v.sketch:
            spots[v.entity] = (v.sketch[0], v.sketch[1])
    xs = [x for x, _ in spots.values()]
    ys = [y for _, y in spots.values()]
    width, scale = _page(log)
    height = (max(ys) - min(ys)) * scale + 2 * MARGIN
    x0, y1 = min(xs), max(ys)

    def at(name: str) -> tuple[float, float]:
        x, y = spots[name]
        return MARGIN + (x - x0) * scale, MARGIN + (y1 - y) * scale

    step_of = first_steps(log)
    labels = _Labels(width, height)
    out = [
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{_f(width)}" height="{_f(height)}" '
        f'viewBox="0 0 {_f(width)} {_f(height)}" font-family="sans-serif" font-size="12">',
        f"<title>{esc(log.title)}: sketch, pairs and links, with the step that finds each pair</title>",
        '<rect width="100%" height="100%" fill="white"/>',
    ]
    guided = {p.name: p for p in log.pairs if p.kind == "prismatic" and any(lk.fixed and lk.name == p.guide
                                                                            for lk in log.links)}
    link_labels: list[tuple[float, float, str, str]] = []
    for k, link in enumerate(log.links):
        colour = "#555555" if link.fixed else COLOURS[k % len(COLOURS)]
        # the frame's slide lines are drawn with its prismatic pairs, not as edges of it
        names = [n for n in link.pairs if not (link.fixed and n in guided)] + list(link.points)
        pts = [at(n) for n in names]
        dash = ' stroke-dasharray="6 3"' if link.fixed else ""
        if len(pts) >= 3:
            poly = " ".join(f"{_f(x)},{_f(y)}" for x, y in pts)
            out.append(f'<polygon points="{poly}" fill="{colour}" fill-opacity="0.12" stroke="{colour}" '
                       f'stroke-width="3"{dash}/>')
        elif len(pts) == 2:
            out.append(_line(pts[0], pts[1], f'stroke="{colour}" stroke-width="3"{dash}'))
        for a, b in zip(pts, pts[1:] + pts[:1] if len(pts) >= 3 else pts[1:]):
            labels.line(a, b)
        if link.fixed:
            for name in link.pairs:
                if name in guided:
                    out += _slide_line(log, guided[name], at(name), [at(n) for n in names], labels)
            if not pts:
                continue
        else:
            pts = pts or [at(n) for n in link.pairs]
        cx = sum(x for x, _ in pts) / len(pts)
        cy = sum(y for _, y in pts) / len(pts)
        link_labels.append((cx, cy, link.name, f' fill="{colour}" font-style="italic"'))
    add_labels = []
    for add in log.add_links:
        (xa, ya), (xb, yb) = at(add.pairs[0]), at(add.pairs[1])
        out.append(_line((xa, ya), (xb, yb), 'stroke="#2ca02c" stroke-width="2" stroke-dasharray="2 4"'))
        labels.line((xa, ya), (xb, yb))
        add_labels.append(((xa + xb) / 2, (ya + yb) / 2, f"Add-link {add.name}", ' fill="#2ca02c"'))
    pivots = {name for lk in log.links if lk.fixed for name in lk.pairs}
    pair_labels = []
    for p in log.pairs:
        x, y = at(p.name)
        fixed = p.name in pivots
        if p.kind == "prismatic":
            ux, uy = math.cos(p.axis), -math.sin(p.axis)  # the axis on the page (y points down)
            if p.name not in guided:
                out.append(_line((x - 40 * ux, y - 40 * uy), (x + 40 * ux, y + 40 * uy),
                                 'stroke="black" stroke-width="1" stroke-dasharray="4 2"'))
            out.append(f'<rect x="{_f(x - 7)}" y="{_f(y - 5)}" width="14" height="10" fill="white" stroke="black" '
                       f'transform="rotate({_f(-math.degrees(p.axis))} {_f(x)} {_f(y)})"/>')
            labels.mark(x, y, 8)
        else:
            fill = "#555555" if fixed else "white"
            out.append(f'<circle cx="{_f(x)}" cy="{_f(y)}" r="5" fill="{fill}" stroke="black" stroke-width="1.5"/>')
            labels.mark(x, y, 6)
        pair_labels.append((x, y, p.name + (f" ({step_of[p.name]})" if p.name in step_of else ""), ""))
    pairs = {p.name for p in log.pairs}
    for name in spots:
        if name in pairs:
            continue
        x, y = at(name)
        out.append(f'<circle cx="{_f(x)}" cy="{_f(y)}" r="3" fill="black"/>')
        labels.mark(x, y, 4)
        pair_labels.append((x, y, name + (f" ({step_of[name]})" if name in step_of else ""), ""))
    for x, y, text, attrs in pair_labels + link_labels + add_labels:
        labels.put(x, y, text, attrs)
    out += labels.out
    out.append(f'<text x="{_f(MARGIN / 3)}" y="{_f(height - 10)}" fill="#555555">'
               "(k): the step that finds the pair; filled: fixed pivots; dashed outline: the fixed link; "
               "dotted: Add-links</text>")
    out.append("</svg>")
    return "\n".join(out) + "\n"


def _slide_line(log: StepLog, p: PairInfo, spot: tuple[float, float], pivots: list[tuple[float, float]],
                labels: _Labels) -> list[str]:
    """A slide line of the frame: the line itself across the figure, and the perpendicular from
    each of the frame's other pivots to it, with its length (the offset)."""
    u = (math.cos(p.axis), -math.sin(p.axis))
    reach = max([120.0] + [abs((q[0] - spot[0]) * u[0] + (q[1] - spot[1]) * u[1]) + 60 for q in pivots])
    a = (spot[0] - reach * u[0], spot[1] - reach * u[1])
    b = (spot[0] + reach * u[0], spot[1] + reach * u[1])
    out = [_line(a, b, 'stroke="#555555" stroke-width="2"')]
    labels.line(a, b)
    scale = _page(log)[1]
    for q in pivots:
        foot = _foot(q, spot, u)
        offset = math.dist(q, foot) / scale
        if offset <= 1e-9 * log.length_scale:
            continue
        out.append(_line(q, foot, 'stroke="#555555" stroke-width="1" stroke-dasharray="3 3"'))
        labels.line(q, foot)
        labels.put((q[0] + foot[0]) / 2, (q[1] + foot[1]) / 2, f"offset {offset:.4g}", ' fill="#555555"')
    return out


def _page(log: StepLog) -> tuple[float, float]:
    """(the figure's width, its scale): the sketch's extent fills WIDTH, or SPOT_SPACE per pair
    and point where that is wider (a large mechanism's labels get room: a chain of 1000
    dyads is drawn 120,000 units wide, not 640)."""
    spots = [(p.x, p.y) for p in log.pairs] + [(v.sketch[0], v.sketch[1]) for v in log.variables
                                              if v.role == "point" and v.sketch]
    xs = [x for x, _ in spots]
    ys = [y for _, y in spots]
    width = max(WIDTH, SPOT_SPACE * len(spots))
    return width, (width - 2 * MARGIN) / max(max(xs) - min(xs), max(ys) - min(ys), log.length_scale * 1e-3)
