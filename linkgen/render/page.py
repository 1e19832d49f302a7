"""NAME.html: one self-contained page that animates the mechanism over its sweep.

The page holds everything inline: its style and script (templates/html/page.css and page.js,
pasted in), the sweep as JSON (every pair's and point's position per row, each number to
``DIGITS`` significant digits, null where a row failed), the plot figures (linkgen.render.plots)
and the engineering summary (linkgen.summary).  No network, no external script, and the
same bytes on every run.
"""

from __future__ import annotations

import json
import math
from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from ..steplog import PairInfo, StepLog
from ..summary.text import facts as summary_facts
from .plots import figures, input_axis

if TYPE_CHECKING:
    from ..sweepdata import Sweep

DIGITS = 9  # significant digits of a position in the page's data (the drawing needs far fewer)
SPEEDS = (0.25, 0.5, 1, 2)  # the play speeds offered, in sweeps per SWEEP_SECONDS (page.js)


def _num(x: float) -> str:
    return f"{x:.{DIGITS}g}" if math.isfinite(x) else "null"


def _array(values: Sequence[float] | np.ndarray) -> str:
    """The values as a JSON array, each as _num writes it (a 1000-dyad chain's page has two million)."""
    xs = np.asarray(values, dtype=float)
    text = [f"{x:.{DIGITS}g}" for x in xs.tolist()]
    for k in np.flatnonzero(~np.isfinite(xs)).tolist():
        text[k] = "null"
    return "[" + ",".join(text) + "]"


def _shown(log: StepLog, kind: str) -> tuple[str, float]:
    """An input's unit on the page and the factor from its column (SI radians) to it."""
    if kind == "revolute":
        return ("deg", 180 / math.pi) if log.angle_unit == "deg" else ("rad", 1.0)
    return log.length_unit or "length", 1.0


def _slider(log: StepLog, pair: PairInfo, places: dict[str, tuple[np.ndarray, np.ndarray]]) -> str:
    """A sliding pair for the page: its slide axis in the sketch, whether its guide is fixed, and
    two places fixed in a moving guide (the axis turns with them) with their direction in the sketch."""
    guide = next(lk for lk in log.links if lk.name == pair.guide)
    sketch = {p.name: (p.x, p.y) for p in log.pairs if p.kind != "prismatic"}
    sketch.update({v.entity: (v.sketch[0], v.sketch[1]) for v in log.variables if v.role == "point" and v.sketch})
    ends = [n for n in (*guide.pairs, *guide.points) if n in sketch and n in places][:2]
    turn = 0.0
    if len(ends) == 2:
        (ax, ay), (bx, by) = sketch[ends[0]], sketch[ends[1]]
        turn = math.atan2(by - ay, bx - ax)
    return '{"name":%s,"axis":%s,"fixed":%s,"guide":%s,"turn":%s}' % (
        json.dumps(pair.name), _num(pair.axis), json.dumps(guide.fixed), json.dumps(ends), _num(turn))


def sweep_json(log: StepLog, sweep: Sweep) -> str:
    """The page's data, one key a line: rows, each row's number in the file's sweep (index), inputs
    (shown in the file's units), status, the places per row, the links to draw between them, the
    fixed pivots, the sliding pairs (_slider), the plots' x values."""
    places = sweep.places
    inputs = []
    for k, i in enumerate(log.inputs):
        unit, factor = _shown(log, i.kind)
        inputs.append('{"column":%s,"unit":%s,"values":%s}' % (json.dumps(i.column), json.dumps(unit),
                                                               _array(sweep.data[:, k] * factor)))
    revolute = {p.name for p in log.pairs if p.kind != "prismatic"}
    links = []
    for link in log.links:  # a fixed link is drawn between its pivots (its sliding pairs move along its guides)
        members = [n for n in (*link.pairs, *link.points) if n in places and (n in revolute or not link.fixed)]
        links.append('{"name":%s,"fixed":%s,"members":%s}' % (json.dumps(link.name), json.dumps(link.fixed),
                                                            json.dumps(members)))
    axis = input_axis(log)
    xs = sweep.data[:, axis.index] * axis.factor if axis.index >= 0 else sweep.index.astype(float)
    finite = [v for x, y in places.values() for v in (x, y)]
    box = [float(np.nanmin(np.concatenate(finite[0::2]))), float(np.nanmin(np.concatenate(finite[1::2]))),
           float(np.nanmax(np.concatenate(finite[0::2]))), float(np.nanmax(np.concatenate(finite[1::2])))] \
        if finite else [-1.0, -1.0, 1.0, 1.0]
    pivots = sorted({n for lk in log.links if lk.fixed for n in lk.pairs if n in places and n in revolute})
    sliders = [_slider(log, p, places) for p in log.pairs if p.kind == "prismatic" and p.name in places]
    points = [v.entity for v in log.variables if v.role == "point" and v.entity in places]
    lines = [
        f'"rows":{sweep.rows}',
        f'"index":[{",".join(str(int(k)) for k in sweep.index)}]',
        f'"unit":{json.dumps(log.length_unit or "")}',
        f'"axis":{json.dumps(axis.name)}',
        f'"x":{_array(xs)}',
        f'"inputs":[{",".join(inputs)}]',
        f'"status":[{",".join(str(int(s)) for s in sweep.status)}]',
        f'"box":{_array(box)}',
        f'"links":[{",".join(links)}]',
        f'"pivots":{json.dumps(pivots)}',
        f'"sliders":[{",".join(sliders)}]',
        f'"points":{json.dumps(points)}',
        '"places":{' + ",\n".join(f'{json.dumps(n)}:[{_array(x)},{_array(y)}]' for n, (x, y) in places.items())
        + "}",
    ]
    return ("{" + ",\n".join(lines) + "}").replace("</", "<\\/")


def render_page(log: StepLog, sweep: Sweep, plots: dict[str, str]) -> str:
    """The page: templates/html/NAME.html.j2 with the style, the script, the data, the figures and
    the engineering summary (the log's: linkgen.summary, the same lines as the manual's and
    ``linkgen check``'s; none for a log built without the sweep, as in the manual)."""
    from . import make_env, template_dir

    folder = template_dir() / "html"
    return make_env().get_template("html/NAME.html.j2").render(
        title=log.title, name=log.name, source=log.source, data=sweep_json(log, sweep),
        facts=[(what, line.strip()) for what, line in summary_facts(log.summary)] if log.summary else [],
        figures=[(fig, plots[fig.file]) for fig in figures(log)],
        style=(folder / "page.css").read_text(encoding="utf-8"),
        script=(folder / "page.js").read_text(encoding="utf-8"),
        points=[v.entity for v in log.variables if v.role == "point" and v.entity in sweep.places],
        places=list(sweep.places), rows=sweep.rows, samples=log.samples, axis=input_axis(log).name, speeds=SPEEDS,
        encoding="utf-8")
