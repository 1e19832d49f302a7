"""The census as a table (stdout) and as JSON: in the file's units, angles as the file writes them."""

from __future__ import annotations

import json
import math
from typing import Any

from ..steplog import StepLog
from .enumerate import Assembly, Census

METHOD = ("characteristic polynomial has its real roots isolated from its exact rational coefficients (arb's "
          "certified complex_roots on each irreducible factor, python-flint) and counted again by Sturm's theorem, "
          "each root polished by Newton's method at 50 digits")

METHOD_IV = ("class-IV group's eliminant (resultants of its closure equations in tangent half-angles, python-flint) "
             "has its real roots isolated from its exact integer coefficients (arb's certified complex_roots on each "
             "irreducible factor; for two links on their own pivots, counted again by Sturm's theorem), each root "
             "back-substituted and polished by Newton's method at 50 digits, the spurious ones rejected")

MANUAL_METHOD = ("every resolver group's characteristic polynomial\nhas its real roots isolated from its exact "
                 "coefficients (arb's certified\nball arithmetic) and counted by Sturm's theorem, each polished at 50 "
                 "digits")
MANUAL_METHOD_IV = ("every resolver group's polynomial (a class-IV group's eliminant\nby resultants) has its real "
                    "roots isolated from its exact coefficients (arb's certified ball\narithmetic; counted again by "
                    "Sturm's theorem for two links on their own pivots), each\nback-substituted and polished at 50 "
                    "digits")


def _g(x: float) -> str:
    """A number for the table: 6 significant digits, no negative zero."""
    text = f"{x:.6g}"
    return "0" if text == "-0" else text


def _angle(log: StepLog, radians: float) -> float:
    return math.degrees(radians) if log.angle_unit == "deg" else radians


def _unit(log: StepLog, kind: str) -> str:
    return log.angle_unit if kind == "revolute" else log.length_unit


def given(log: StepLog, census: Census) -> tuple[float, ...]:
    """The input values in the file's units: as given, else from the census's radians."""
    return census.at or tuple(_angle(log, v) if i.kind == "revolute" else v for i, v in zip(log.inputs, census.inputs))


def inputs_text(log: StepLog, census: Census) -> str:
    """theta_J7 = 90 deg, ..."""
    values = given(log, census)
    return ", ".join(f"{i.column} = {_g(v)} {_unit(log, i.kind)}".rstrip() for i, v in zip(log.inputs, values))


def _choice_columns(census: Census) -> list[tuple[int, str]]:
    """(step, header) of every chain and group some assembly passes, in the procedure's order."""
    seen: dict[int, str] = {}
    for a in census.assemblies:
        for c in a.choices:
            seen.setdefault(c.step, c.target if c.target.startswith("group") else f"{c.target} (step {c.step})")
    return sorted(seen.items())


def _choice_text(log: StepLog, a: Assembly, step: int) -> str:
    for c in a.choices:
        if c.step == step:
            if c.target.startswith("group"):
                return f"root {c.value} of {c.of} ({_g(_angle(log, c.theta))} {log.angle_unit})"
            return f"{c.value:+d}" + (" (toggle)" if c.of == 1 else "")
    return ""


def notes(log: StepLog, census: Census) -> list[str]:
    """What the walk met besides the assemblies: groups, chains that cannot close, toggles, the sketch."""
    out = []
    for g in census.solves:
        pi = ", and theta = pi is a root too" if g.at_pi else ""
        if g.factors:
            pi = ", and one assembly has theta = pi" if g.at_pi else ""
            out.append(f"group {g.group} ({g.triad}, class IV): eliminant of degree {g.degree} in t = tan(theta/2), "
                       f"theta the first link's turn from the sketch (irreducible factors of degree "
                       f"{', '.join(map(str, g.factors))}); {g.real_roots} real roots, {g.real_roots - g.rejected} of "
                       f"them assemblies, {g.rejected} rejected by back-substitution{pi}")
            continue
        out.append(f"group {g.group} ({g.triad}): characteristic polynomial of degree {g.degree} in "
                   f"t = tan(theta/2), theta the ternary's turn from the sketch; {g.real_roots} real roots{pi}")
        for theta, k in g.multiple:
            out.append(f"group {g.group}: the root at theta = {_g(_angle(log, theta))} {log.angle_unit} has "
                       f"multiplicity {k}: {k} assemblies meet there (a singular position), counted once")
    steps = {s.number: s for s in log.steps}
    for step, ends in census.cannot_close.items():
        out.append(f"step {step} ({steps[step].target}) cannot close: {ends} branch{'es' if ends > 1 else ''} "
                   "of the walk end there")
    for step in census.toggles:
        out.append(f"step {step} ({steps[step].target}) is at a toggle: its two branches are one assembly")
    for link, error in census.broken:
        out.append(f"dropped: a walk that breaks link {link} (by {error:.3g} of the length scale; a redundant "
                   "constraint the procedure does not use)")
    if census.sketch_note:
        out.append(census.sketch_note)
    return out


def _methods(census: Census) -> list[str]:
    """How the census's groups were counted: triads, class-IV groups (each named once)."""
    out = []
    if any(not g.factors for g in census.solves):
        out.append(METHOD)
    if any(g.factors for g in census.solves):
        out.append(METHOD_IV)
    return out


def table(log: StepLog, census: Census) -> str:
    """The census as text: a heading, the notes, one row per assembly (pair positions as x, y)."""
    n = len(census.assemblies)
    lines = [f"{log.name} at {inputs_text(log, census)}: {n} assembl{'y' if n == 1 else 'ies'}"]
    lines.append("The count is exact: both branches of every two-link chain are tried"
                 + "".join("; every " + (m if m is METHOD_IV else "group's " + m) for m in _methods(census)) + ".")
    lines += notes(log, census)
    if not n:
        return "\n".join(lines) + "\n"
    choices = _choice_columns(census)
    header = ["#", "sketch"] + [h for _, h in choices] + [p.name for p in log.pairs]
    rows = [[str(a.number), "*" if a.sketch else ""] + [_choice_text(log, a, s) for s, _ in choices]
            + [f"{_g(a.values[p.name + '.x'])}, {_g(a.values[p.name + '.y'])}" for p in log.pairs]
            for a in census.assemblies]
    widths = [max(len(r[k]) for r in [header, *rows]) for k in range(len(header))]
    lines.append("")
    for r in [header, *rows]:
        lines.append("  ".join(cell.ljust(w) for cell, w in zip(r, widths)).rstrip())
    if any(a.sketch for a in census.assemblies):
        lines.append("* the sketch's assembly: the one the programs follow from the sketch")
    return "\n".join(lines) + "\n"


def _assembly(log: StepLog, a: Assembly) -> dict[str, Any]:
    v = a.values
    chains = [{"step": c.step, "pair": c.target, "branch": c.value, "toggle": c.of == 1}
              for c in a.choices if not c.target.startswith("group")]
    groups = [{"group": int(c.target.split()[1]), "root": c.value, "of": c.of, "theta": _angle(log, c.theta)}
              for c in a.choices if c.target.startswith("group")]
    points = [p.name for p in log.pairs] + [q for lk in log.links for q in lk.points]
    return {
        "number": a.number, "sketch": a.sketch, "chains": chains, "groups": groups,
        "positions": {name: [v[f"{name}.x"], v[f"{name}.y"]] for name in points},
        "angles": {lk.name: _angle(log, v[f"{lk.name}.phi"]) for lk in log.links},
        "slides": {p.name: v[f"{p.name}.s"] for p in log.pairs if p.kind == "prismatic"},
        "length_error": a.error,
    }


def to_json(log: StepLog, census: Census) -> str:
    """The census as JSON (positions in length units, angles in the file's angle unit)."""
    marked = [a.number for a in census.assemblies if a.sketch]
    steps = {s.number: s for s in log.steps}
    doc = {
        "mechanism": log.name,
        "units": {"length": log.length_unit, "angle": log.angle_unit},
        "inputs": {i.column: v for i, v in zip(log.inputs, given(log, census))},
        "count": len(census.assemblies),
        "sketch": marked[0] if marked else None,
        "sketch_note": census.sketch_note,
        "method": "; ".join(_methods(census)),
        "groups": [{"group": g.group, "triad": g.triad, "degree": g.degree, "real_roots": g.real_roots,
                    "theta_pi_root": g.at_pi, "thetas": [_angle(log, t) for t in g.thetas],
                    "multiple": [{"theta": _angle(log, t), "multiplicity": k} for t, k in g.multiple],
                    "coefficients": list(g.coefficients),
                    **({"class": "IV", "factors": list(g.factors), "rejected": g.rejected} if g.factors else {})}
                   for g in census.solves],
        "cannot_close": [{"step": s, "pair": steps[s].target, "ends": k} for s, k in census.cannot_close.items()],
        "toggles": list(census.toggles),
        "dropped": [{"link": link, "length_error": e} for link, e in census.broken],
        "assemblies": [_assembly(log, a) for a in census.assemblies],
    }
    return json.dumps(doc, indent=2, allow_nan=False, ensure_ascii=False) + "\n"


def manual(log: StepLog) -> dict[str, Any] | None:
    """The manual's listing of the step log's assemblies: the inputs, the notes, the table's
    header and rows (pair positions as x, y), the figures' names; None where none was looked for."""
    rec = log.assemblies
    if rec is None:
        return None
    from .follow import census_of

    census = census_of(log)
    n = len(census.assemblies)
    choices = _choice_columns(census)
    header = ["#", "sketch", "programs"] + [h for _, h in choices] + [p.name for p in log.pairs]
    rows = [[str(a.number), "*" if a.sketch else "", "follow" if a.number == rec.follows else ""]
            + [_choice_text(log, a, s) for s, _ in choices]
            + [f"{_g(a.values[p.name + '.x'])}, {_g(a.values[p.name + '.y'])}" for p in log.pairs]
            for a in census.assemblies]
    sketch = next((a.number for a in census.assemblies if a.sketch), 0)
    return {"inputs": inputs_text(log, census), "counted": rec.counted, "notes": list(rec.notes),
            "count": n, "follows": rec.follows, "sketch": sketch, "chosen": log.options.assembly,
            "header": header, "rows": rows,
            "method": MANUAL_METHOD_IV if any(", class IV)" in n for n in rec.notes) else
            MANUAL_METHOD if any(n.startswith("group") for n in rec.notes) else "",
            "prismatic": any(p.kind == "prismatic" for p in log.pairs),
            "figures": " ".join(f"![assembly {a.number} of {n}]({log.name}_assembly_{a.number}.svg)"
                                for a in census.assemblies)}
