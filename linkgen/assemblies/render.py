"""One SVG per assembly (NAME_assembly_K.svg): the links at the assembly's positions.

Every assembly of a census is drawn on the same scale and page, so the figures can be laid
side by side.  Numbers are rounded to 0.01 of the drawing unit: the bytes are the same on
every machine (the house style of NAME.svg, linkgen/render/svg.py).
"""

from __future__ import annotations

import math

from ..render.svg import _f
from ..render.svgwriter import esc
from ..steplog import StepLog
from .enumerate import Assembly, Census
from .report import inputs_text

WIDTH = 480.0
MARGIN = 40.0
CAPTION = 36.0  # room under the drawing for the caption
COLOURS = ("#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#8c564b", "#e377c2", "#17becf", "#bcbd22", "#ff7f0e")
FIXED = "#555555"

Page = tuple[float, float, float, float]  # x0, y1 (the drawing's top left in sketch units), scale, height


def _spots(log: StepLog, a: Assembly) -> dict[str, tuple[float, float]]:
    names = [p.name for p in log.pairs] + [q for lk in log.links for q in lk.points]
    return {n: (a.values[f"{n}.x"], a.values[f"{n}.y"]) for n in names}


def page(log: StepLog, census: Census) -> Page:
    """One page for every assembly: the bounding box of all their pairs and points."""
    xs = [x for a in census.assemblies for x, _ in _spots(log, a).values()]
    ys = [y for a in census.assemblies for _, y in _spots(log, a).values()]
    span = max(max(xs) - min(xs), max(ys) - min(ys), log.length_scale * 1e-3)
    scale = (WIDTH - 2 * MARGIN) / span
    return min(xs), max(ys), scale, (max(ys) - min(ys)) * scale + 2 * MARGIN + CAPTION


def caption(log: StepLog, census: Census, a: Assembly) -> str:
    """assembly 2 of 4 at theta_J7 = 90 deg (the sketch's); group 1: root 2 of 4"""
    text = f"assembly {a.number} of {len(census.assemblies)} at {inputs_text(log, census)}"
    text += " (the sketch's)" if a.sketch else ""
    groups = [f"{c.target}: root {c.value} of {c.of}" for c in a.choices if c.target.startswith("group")]
    return "; ".join([text, *groups])


def render_assembly(log: StepLog, census: Census, a: Assembly, where: Page) -> str:
    """The SVG of one assembly on the page ``where``."""
    x0, y1, scale, height = where
    spots = _spots(log, a)

    def at(name: str) -> tuple[float, float]:
        x, y = spots[name]
        return MARGIN + (x - x0) * scale, MARGIN + (y1 - y) * scale

    title = caption(log, census, a)
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{_f(WIDTH)}" height="{_f(height)}" '
           f'viewBox="0 0 {_f(WIDTH)} {_f(height)}" font-family="sans-serif" font-size="11">',
           f"<title>{esc(log.title or log.name)}: {esc(title)}</title>",
           '<rect width="100%" height="100%" fill="white"/>']
    guides = {p.name: p.guide for p in log.pairs if p.kind == "prismatic"}
    for k, link in enumerate(log.links):
        colour = FIXED if link.fixed else COLOURS[k % len(COLOURS)]
        pts = [at(n) for n in (*link.pairs, *link.points) if guides.get(n) != link.name]
        dash = ' stroke-dasharray="6 3"' if link.fixed else ""
        if len(pts) >= 3:
            poly = " ".join(f"{_f(x)},{_f(y)}" for x, y in pts)
            out.append(f'<polygon points="{poly}" fill="{colour}" fill-opacity="0.12" stroke="{colour}" '
                       f'stroke-width="3"{dash}/>')
        elif len(pts) == 2:
            (xa, ya), (xb, yb) = pts
            out.append(f'<line x1="{_f(xa)}" y1="{_f(ya)}" x2="{_f(xb)}" y2="{_f(yb)}" stroke="{colour}" '
                       f'stroke-width="3"{dash}/>')
    links = {lk.name: lk for lk in log.links}
    pivots = {p for lk in log.links if lk.fixed for p in lk.pairs}
    for p in log.pairs:
        x, y = at(p.name)
        if p.kind == "prismatic":
            guide = links[p.guide]
            axis = p.axis + a.values[f"{guide.name}.phi"] - guide.angle
            out.append(f'<rect x="{_f(x - 7)}" y="{_f(y - 5)}" width="14" height="10" fill="white" stroke="black" '
                       f'transform="rotate({_f(-math.degrees(axis))} {_f(x)} {_f(y)})"/>')
        else:
            fill = FIXED if p.name in pivots else "white"
            out.append(f'<circle cx="{_f(x)}" cy="{_f(y)}" r="4" fill="{fill}" stroke="black" stroke-width="1.5"/>')
        out.append(f'<text x="{_f(x + 7)}" y="{_f(y + 14)}">{esc(p.name)}</text>')
    for name in (q for lk in log.links for q in lk.points):
        x, y = at(name)
        out.append(f'<circle cx="{_f(x)}" cy="{_f(y)}" r="2.5" fill="black"/>')
        out.append(f'<text x="{_f(x + 5)}" y="{_f(y - 5)}">{esc(name)}</text>')
    out.append(f'<text x="{_f(MARGIN / 2)}" y="{_f(height - CAPTION / 2)}" fill="{FIXED}">{esc(title)}</text>')
    out.append("</svg>")
    return "\n".join(out) + "\n"


def render_all(log: StepLog, census: Census) -> dict[str, bytes]:
    """NAME_assembly_K.svg of every assembly, on one page size."""
    if not census.assemblies:
        return {}
    where = page(log, census)
    return {f"{log.name}_assembly_{a.number}.svg": render_assembly(log, census, a, where).encode()
            for a in census.assemblies}


def figures(log: StepLog) -> dict[str, bytes]:
    """The figures of the step log's assemblies (the manual's), NAME_assembly_K.svg."""
    if log.assemblies is None:
        return {}
    from .follow import census_of

    return render_all(log, census_of(log))
