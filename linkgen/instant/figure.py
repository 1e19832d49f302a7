"""NAME_centres.svg: the sketch with every finite instant centre marked and labelled (the
manual's figure), the Aronhold-Kennedy lines that place or carry them drawn faintly.

Links are numbered in the file's order (I13: the centre of links 1 and 3, as the paper writes
them); the legend names them.  The view is the sketch's box widened by its size on every side:
a centre beyond it is listed at the foot, not drawn; centres on one spot (a crank along the frame
puts two pairs of them together) get their labels one under the other.  Every number is rounded to 0.01 of the
drawing unit, so the bytes are the same on every machine.
"""

from __future__ import annotations

import math

from ..render.svg import _f, _line
from ..render.svgwriter import esc
from ..steplog import CentreAt, StepLog

WIDTH = 640.0
MARGIN = 30.0
LABEL_GAP = 13.0  # px: centres closer than this share a spot, their labels stacked one line apart

Point = tuple[float, float]


def label(log: StepLog, c: CentreAt) -> str:
    """I13, or I1,12 where a link's number has two digits."""
    order = [lk.name for lk in log.links]
    a, b = (order.index(x) + 1 for x in c.links)
    return f"I{a}{b}" if len(order) < 10 else f"I{a},{b}"


def _clip(p: Point, d: Point, box: tuple[float, float, float, float]) -> tuple[Point, Point] | None:
    """The part of the line through p with direction d inside box (x0, y0, x1, y1); None if it misses."""
    lo, hi = -1e300, 1e300
    for k in range(2):
        if d[k] == 0:
            if not box[k] <= p[k] <= box[k + 2]:
                return None
            continue
        t0, t1 = sorted(((box[k] - p[k]) / d[k], (box[k + 2] - p[k]) / d[k]))
        lo, hi = max(lo, t0), min(hi, t1)
    if lo >= hi:
        return None
    return (p[0] + lo * d[0], p[1] + lo * d[1]), (p[0] + hi * d[0], p[1] + hi * d[1])


def kennedy_line(by: dict[frozenset[str], CentreAt], a: str, k: str, b: str) -> tuple[Point, Point] | None:
    """A point and the direction of the line through the centres (a, k) and (k, b), where it is known."""
    one, two = by[frozenset((a, k))], by[frozenset((k, b))]
    finite = [(c.x, c.y) for c in (one, two) if c.status != 1 and c.x is not None and c.y is not None]
    far = [(c.ux, c.uy) for c in (one, two) if c.status == 1 and c.ux is not None and c.uy is not None]
    if len(finite) == 2 and finite[0] != finite[1]:
        (x0, y0), (x1, y1) = finite
        return (x0, y0), (x1 - x0, y1 - y0)
    if len(finite) == 1 and len(far) == 1:
        return finite[0], far[0]
    return None


def render_centres_svg(log: StepLog) -> str:
    spots = {p.name: (p.x, p.y) for p in log.pairs}
    spots.update({v.entity: (v.sketch[0], v.sketch[1]) for v in log.variables if v.role == "point" and v.sketch})
    xs, ys = [x for x, _ in spots.values()], [y for _, y in spots.values()]
    span = max(max(xs) - min(xs), max(ys) - min(ys), log.length_scale * 1e-3)
    box = (min(xs) - span, min(ys) - span, max(xs) + span, max(ys) + span)
    scale = (WIDTH - 2 * MARGIN) / (box[2] - box[0])
    height = (box[3] - box[1]) * scale + 2 * MARGIN + 16 * 3

    def at(p: Point) -> Point:
        return MARGIN + (p[0] - box[0]) * scale, MARGIN + (box[3] - p[1]) * scale

    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{_f(WIDTH)}" height="{_f(height)}" '
           f'viewBox="0 0 {_f(WIDTH)} {_f(height)}" font-family="sans-serif" font-size="11">',
           f"<title>{esc(log.title)}: instant centres at the sketch, the inputs at their speeds</title>",
           '<rect width="100%" height="100%" fill="white"/>']
    by = {frozenset(c.links): c for c in log.centres}
    drawn: set[tuple[str, ...]] = set()
    for c in log.centres:
        for k in c.lines:
            key = tuple(sorted((c.links[0], k))) + tuple(sorted((k, c.links[1])))
            line = kennedy_line(by, c.links[0], k, c.links[1])
            if line is None or key in drawn:
                continue
            drawn.add(key)
            seg = _clip(line[0], line[1], box)
            if seg is not None:
                out.append(_line(at(seg[0]), at(seg[1]), 'stroke="#9467bd" stroke-width="0.8" stroke-opacity="0.35"'))
    for lk in log.links:
        pts = [at(spots[n]) for n in (*lk.pairs, *lk.points)]
        for p, q in zip(pts, pts[1:] + pts[:1] if len(pts) > 2 else pts[1:]):
            out.append(_line(p, q, 'stroke="#555555" stroke-width="2" stroke-opacity="0.6"'))
    for pair in log.pairs:
        x, y = at((pair.x, pair.y))
        out.append(f'<circle cx="{_f(x)}" cy="{_f(y)}" r="3" fill="white" stroke="#555555"/>')
    off: list[str] = []
    placed: list[Point] = []  # centres drawn so far: a centre drawn on one stacks its label under theirs
    for c in log.centres:
        name = label(log, c)
        if c.x is None or c.y is None or not (box[0] <= c.x <= box[2] and box[1] <= c.y <= box[3]):
            off.append(f"{name} at infinity" if c.status == 1 else f"{name} beyond the view")
            continue
        x, y = at((c.x, c.y))
        colour = {"first": "#1f77b4", "secondary": "#2ca02c", "third A": "#d62728"}.get(c.kind, "#ff7f0e")
        below = sum(1 for p in placed if math.dist(p, (x, y)) < LABEL_GAP)
        placed.append((x, y))
        out.append(f'<circle cx="{_f(x)}" cy="{_f(y)}" r="4" fill="{colour}"/>')
        out.append(f'<text x="{_f(x + 5)}" y="{_f(y - 5 + LABEL_GAP * below)}" fill="{colour}">{esc(name)}</text>')
    legend = ", ".join(f"{k + 1} {lk.name}" for k, lk in enumerate(log.links))
    foot = [f"links: {legend}",
            "blue first, green secondary, red third A, orange third B; faint: the Aronhold-Kennedy lines",
            ("not drawn: " + ", ".join(off)) if off else "every centre is drawn"]
    for row, text in enumerate(foot):
        out.append(f'<text x="{_f(MARGIN / 2)}" y="{_f(height - 10 - 16 * (2 - row))}" fill="#555555">'
                   f"{esc(text)}</text>")
    out.append("</svg>")
    return "\n".join(out) + "\n"
