"""NAME.svg: the sketch with pairs and links labelled and the order of the steps.

Coordinates are data, so the figure is drawn here in Python, not in a template.
Every number is rounded to 0.01 of the drawing unit, so the bytes are the same
on every machine.
"""

from __future__ import annotations

import math

from ..steplog import StepLog

WIDTH = 640.0
MARGIN = 60.0
COLOURS = ("#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#8c564b", "#e377c2", "#17becf", "#bcbd22", "#ff7f0e")


def _f(x: float) -> str:
    text = f"{x:.2f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def _esc(text: str) -> str:
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def _line(a: tuple[float, float], b: tuple[float, float], style: str) -> str:
    return f'<line x1="{_f(a[0])}" y1="{_f(a[1])}" x2="{_f(b[0])}" y2="{_f(b[1])}" {style}/>'


def render_svg(log: StepLog) -> str:
    spots = {p.name: (p.x, p.y) for p in log.pairs}
    for v in log.variables:
        if v.role == "point" and v.sketch:
            spots[v.entity] = (v.sketch[0], v.sketch[1])
    xs = [x for x, _ in spots.values()]
    ys = [y for _, y in spots.values()]
    span = max(max(xs) - min(xs), max(ys) - min(ys), log.length_scale * 1e-3)
    scale = (WIDTH - 2 * MARGIN) / span
    height = (max(ys) - min(ys)) * scale + 2 * MARGIN
    x0, y1 = min(xs), max(ys)

    def at(name: str) -> tuple[float, float]:
        x, y = spots[name]
        return MARGIN + (x - x0) * scale, MARGIN + (y1 - y) * scale

    step_of = {p: s.number for s in log.steps for p in s.determines}
    for s in log.steps:
        if s.action == "point" and s.target in spots and s.target not in step_of:
            step_of[s.target] = s.number
    out = [
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{_f(WIDTH)}" height="{_f(height)}" '
        f'viewBox="0 0 {_f(WIDTH)} {_f(height)}" font-family="sans-serif" font-size="12">',
        f"<title>{_esc(log.title)}: sketch, pairs and links, with the step that finds each pair</title>",
        '<rect width="100%" height="100%" fill="white"/>',
    ]
    for k, link in enumerate(log.links):
        colour = "#555555" if link.fixed else COLOURS[k % len(COLOURS)]
        names = list(link.pairs) + list(link.points)
        pts = [at(n) for n in names]
        dash = ' stroke-dasharray="6 3"' if link.fixed else ""
        if len(pts) >= 3:
            poly = " ".join(f"{_f(x)},{_f(y)}" for x, y in pts)
            out.append(f'<polygon points="{poly}" fill="{colour}" fill-opacity="0.12" stroke="{colour}" '
                       f'stroke-width="3"{dash}/>')
        elif len(pts) == 2:
            out.append(_line(pts[0], pts[1], f'stroke="{colour}" stroke-width="3"{dash}'))
        cx = sum(x for x, _ in pts) / len(pts)
        cy = sum(y for _, y in pts) / len(pts)
        out.append(f'<text x="{_f(cx + 6)}" y="{_f(cy - 6)}" fill="{colour}" font-style="italic">'
                   f"{_esc(link.name)}</text>")
    for add in log.add_links:
        (xa, ya), (xb, yb) = at(add.pairs[0]), at(add.pairs[1])
        out.append(_line((xa, ya), (xb, yb), 'stroke="#2ca02c" stroke-width="2" stroke-dasharray="2 4"'))
        out.append(f'<text x="{_f((xa + xb) / 2)}" y="{_f((ya + yb) / 2 + 14)}" fill="#2ca02c">'
                   f"Add-link {_esc(add.name)}</text>")
    pivots = {name for lk in log.links if lk.fixed for name in lk.pairs}
    for p in log.pairs:
        x, y = at(p.name)
        fixed = p.name in pivots
        if p.kind == "prismatic":
            ux, uy = math.cos(p.axis), -math.sin(p.axis)  # the axis on the page (y points down)
            out.append(_line((x - 40 * ux, y - 40 * uy), (x + 40 * ux, y + 40 * uy),
                             'stroke="black" stroke-width="1" stroke-dasharray="4 2"'))
            out.append(f'<rect x="{_f(x - 7)}" y="{_f(y - 5)}" width="14" height="10" fill="white" stroke="black" '
                       f'transform="rotate({_f(-math.degrees(p.axis))} {_f(x)} {_f(y)})"/>')
        else:
            fill = "#555555" if fixed else "white"
            out.append(f'<circle cx="{_f(x)}" cy="{_f(y)}" r="5" fill="{fill}" stroke="black" stroke-width="1.5"/>')
        label = p.name + (f" ({step_of[p.name]})" if p.name in step_of else "")
        out.append(f'<text x="{_f(x + 8)}" y="{_f(y + 16)}">{_esc(label)}</text>')
    pairs = {p.name for p in log.pairs}
    for name in spots:
        if name in pairs:
            continue
        x, y = at(name)
        out.append(f'<circle cx="{_f(x)}" cy="{_f(y)}" r="3" fill="black"/>')
        label = name + (f" ({step_of[name]})" if name in step_of else "")
        out.append(f'<text x="{_f(x + 6)}" y="{_f(y - 6)}">{_esc(label)}</text>')
    out.append(f'<text x="{_f(MARGIN / 3)}" y="{_f(height - 10)}" fill="#555555">'
               "(k): the step that finds the pair; filled: fixed pivots; dashed outline: the fixed link; "
               "dotted: Add-links</text>")
    out.append("</svg>")
    return "\n".join(out) + "\n"
