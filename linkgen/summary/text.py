"""The summary in words: lines for the terminal (``linkgen check``), a Markdown block for the
manual and JSON (``linkgen check --json``)."""

from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import asdict

from ..errors import and_list
from .records import Failure, FourBar, Summary, Transmission, Travel

RUNS = 6  # runs of failing rows listed; the others counted
PLACE = 7  # significant digits of an extreme's place
LAW = {"Grashof": "<", "non-Grashof": ">", "change point": "="}  # s + l against p + q
GRASHOF = {
    "crank-rocker": "the link at {o1} turns fully, the link at {o2} rocks",
    "rocker-crank": "the link at {o2} turns fully, the link at {o1} rocks",
    "double-crank": "both links at the frame turn fully (a drag link)",
    "double-rocker": "the coupler turns fully relative to the others, both links at the frame rock",
    "triple-rocker": "no link turns fully: every link at the frame rocks between limit positions",
}


def num(x: float) -> str:
    """A value to 12 significant digits (closed forms are checked to 1e-9)."""
    text = "%.12g" % x
    return "0" if text == "-0" else text


def _unit(unit: str) -> str:
    return {"deg": " deg", "rad": " rad", "": ""}.get(unit, f" {unit}")


def _at(s: Summary, values: tuple[float, ...], digits: int = 12) -> str:
    """Input values; an extreme's place (digits 7) is found to about the square root of the
    rounding, its value to rounding."""
    return ", ".join(f"{i.column} = {'%.*g' % (digits, x) if x else '0'}{_unit(i.unit)}"
                     for i, x in zip(s.inputs, values))


def _four_bar(f: FourBar) -> str:
    o1, a, b, o2 = f.pairs
    d, la, lb, lc = (num(x) for x in f.lengths)
    driven = f" driven by {f.driven}" if f.driven else " (a loop of the mechanism that no input drives directly)"
    return (f"four-bar {o1}-{a}-{b}-{o2}{driven}: frame {d}, {f.links[1]} {la}, {f.links[2]} {lb}, "
            f"{f.links[3]} {lc}: {f.grashof} (s + l {LAW[f.grashof]} p + q), "
            f"{f.kind}: {GRASHOF[f.kind].format(o1=o1, o2=o2)}")


def _constant(t: Transmission) -> bool:
    """Whether a chain's transmission angle is the same at every row (a slider on a slider at a fixed angle)."""
    return not t.at_limit and t.maximum - t.minimum <= 1e-9 * t.maximum


def _transmission(s: Summary, t: Transmission) -> str:
    if _constant(t):
        return (f"step {t.step} ({t.target}, {t.chain} chain of {' and '.join(t.links)}): "
                f"{num(t.minimum)}{_unit(s.angle_unit)} at every row")
    where = (f"0 at the limit position {_at(s, t.at)}" if t.at_limit
             else f"{num(t.minimum)}{_unit(s.angle_unit)} at {_at(s, t.at, PLACE)}")
    return (f"step {t.step} ({t.target}, {t.chain} chain of {' and '.join(t.links)}): least {where}; "
            f"greatest {num(t.maximum)}{_unit(s.angle_unit)}")


def _travel(s: Summary, t: Travel) -> str:
    if t.turns:
        return f"{t.name} turns fully ({num(t.travel)}{_unit(t.unit)} over the sweep)"
    word = "stroke" if t.quantity == "slide" else "swing"
    ratio = f"; time ratio {'%.*g' % (PLACE, t.time_ratio)}" if t.time_ratio is not None else ""  # from the places
    return (f"{t.name} {word} {num(t.travel)}{_unit(t.unit)}: from {num(t.low)} at {_at(s, t.at_low, PLACE)} "
            f"to {num(t.high)} at {_at(s, t.at_high, PLACE)}{ratio}")


def _rows(s: Summary) -> str:
    ok = s.rows - s.failed - s.near - s.singular
    return (f"{s.rows} rows: {ok} assemble, {s.near} near a singular position, {s.singular} singular, "
            f"{s.failed} fail")


def lines(s: Summary) -> list[str]:
    """The summary as lines of text, one fact each."""
    out = [f"{s.name}: {s.title}",
           f"mobility {s.mobility} (Gruebler {s.grubler}{f', {s.redundant} redundant' if s.redundant else ''})"]
    for i in s.inputs:
        span = f"input {i.column}: sweep {num(i.start)} to {num(i.stop)}{_unit(i.unit)}, sketch {num(i.sketch)}"
        if not i.known:
            out.append(span + "; the assembling range is searched with one input only")
        elif i.low is None and i.high is None:
            out.append(span + "; assembles over every value")
        else:
            low = "no limit" if i.low is None else num(i.low)
            high = "no limit" if i.high is None else num(i.high)
            out.append(span + f"; assembles from {low} to {high}{_unit(i.unit)}")
    out += [_four_bar(f) for f in s.four_bars]
    out += [f"{p.kind} of step {p.step} ({p.target}) at {_at(s, p.inputs)}" for p in s.positions]
    out += [f"transmission angle (sigma is its sine) at {_transmission(s, t)}" for t in s.transmission]
    out += [_travel(s, t) for t in s.travels]
    out.append(_rows(s))
    out += [f"  {f.rows} rows fail with status {f.code}, {f.meaning}: {_runs(s, f)}" for f in s.failures]
    return out


def _runs(s: Summary, f: Failure) -> str:
    """The runs of the first input's values where rows fail with f's status."""
    shown = [f"{num(a)} to {num(b)}" if a != b else num(a) for a, b in f.ranges[:RUNS]]
    if len(f.ranges) > RUNS:
        shown.append(f"{len(f.ranges) - RUNS} more runs")
    return f"{s.inputs[0].column} {and_list(shown)}{_unit(s.inputs[0].unit)}"


def text(s: Summary) -> str:
    return "\n".join(lines(s)) + "\n"


def markdown(s: Summary, escape: Callable[[str], str]) -> str:
    """The summary as a Markdown list (the manual's first section), each line's text escaped."""
    return "".join(f"- {escape(line.strip())}\n" for line in lines(s)[1:])


def to_json(s: Summary) -> str:
    return json.dumps(asdict(s), indent=2, allow_nan=False, ensure_ascii=False) + "\n"


def one_line(s: Summary) -> str:
    """``build``'s one line: the rows and the worst transmission angle."""
    out = _rows(s)
    if s.failures:
        out += f" (at {'; '.join(_runs(s, f) for f in s.failures)})"
    worst = min(s.transmission, key=lambda t: (t.minimum, t.step), default=None)
    if worst is not None:
        where = (f"at the limit position {_at(s, worst.at)}" if worst.at_limit else "at every row"
                 if _constant(worst) else f"at {_at(s, worst.at, PLACE)}")
        out += (f"; least transmission angle {num(worst.minimum)}{_unit(s.angle_unit)} "
                f"(step {worst.step}, {worst.target}) {where}")
    return out
