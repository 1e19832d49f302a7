"""The file's own keys: the format version, the name, title and units, the outputs, order, samples
and sweep."""

from __future__ import annotations

import math
import os

from ..instant.names import centre_problem, is_centre
from ..loader import Node, Scalar
from ..model import Where
from ..options import CHOICES, MAX_ITERATIONS, MAX_TOLERANCE, Options
from .naming import program_name
from .sheet import Sheet, did_you_mean, where

FORMAT_VERSION = 1
MAX_SAMPLES = 10_000_000
DEFAULT_SAMPLES = 361
DEFAULT_ORDER = 2
TOP_REQUIRED = ("linkgen", "name", "joints", "links", "inputs")
TOP_OPTIONAL = ("title", "units", "outputs", "order", "samples", "sweep", "options")
SWEEPS = ("together", "grid")  # every input along its range at once; every combination of the inputs' values


def file_label(path: str) -> str:
    """The file's base name as the generated files' banners and manual give it: printable ASCII;
    every other character, the backslash and the characters that end a comment or start markup
    in one of the generated languages (* < > & ` ") are written as Python's escapes \\xNN,
    \\uNNNN or \\UNNNNNNNN of their code point.  The same bytes on every machine (no Unicode
    tables are consulted), and valid in any file even for a name that is not UTF-8."""
    out = []
    for ch in os.path.basename(path):
        code = ord(ch)
        if 0x20 <= code < 0x7F and ch not in '\\*<>&`"':
            out.append(ch)
        elif code < 0x100:
            out.append(f"\\x{code:02x}")
        elif code < 0x10000:
            out.append(f"\\u{code:04x}")
        else:
            out.append(f"\\U{code:08x}")
    return "".join(out)


def header(sheet: Sheet) -> tuple[str, str, str, str]:
    """The name, title, length unit and angle unit; sets the sheet's units."""
    root = sheet.root
    sheet.keys(root, TOP_REQUIRED, TOP_OPTIONAL, "the mechanism file")
    node = root["linkgen"]
    version = sheet.integer(node, f"the format version {FORMAT_VERSION}")
    if version != FORMAT_VERSION:
        raise sheet.error(node, f"this file is format version {version}, "
                          f"but this linkgen reads format version {FORMAT_VERSION}")
    node = root["name"]
    name = sheet.name(node, "a name for the mechanism, such as fourbar")
    program_name(sheet, name, node)
    title_node = root.get("title")
    title = sheet.one_line(title_node, "a title (text)", "the title") if title_node is not None else name
    length_unit, angle_unit = "", "deg"
    units_node = root.get("units")
    if units_node is not None:
        units = sheet.mapping(units_node, "the units as {length: mm, angle: deg}")
        sheet.keys(units, (), ("length", "angle"), "units")
        length_node = units.get("length")
        if length_node is not None:
            length_unit = sheet.one_line(length_node, "a length unit label such as mm", "the length unit")
        angle_node = units.get("angle")
        if angle_node is not None:
            angle_unit = sheet.text(angle_node, "the angle unit deg or rad")
            if angle_unit not in ("deg", "rad"):
                raise sheet.error(angle_node, f"the angle unit is deg (degrees) or rad (radians), got {angle_unit!r}")
    sheet.angle_scale = math.pi / 180 if angle_unit == "deg" else 1.0
    sheet.length_unit = length_unit
    return name, title, length_unit, angle_unit


def outputs(sheet: Sheet, links: list[str]) -> tuple[tuple[str, ...], Where | None]:
    node = sheet.root.get("outputs")
    if node is None:
        return (), None
    seq = sheet.sequence(node, "the outputs as a list of pair, point and link names, such as [B, P, rocker]")
    names: list[str] = []
    for item in seq.items:
        text = item.text if isinstance(item, Scalar) else ""
        centre = is_centre(text)
        name = text if centre else sheet.name(item, "an output, a pair, point or link name")
        if centre:
            if problem := centre_problem(name, links, sheet.names):
                raise sheet.error(item, problem)
        elif name not in sheet.names:
            raise sheet.error(item, f"the output {name} is not a pair, point or link of this mechanism"
                              f"{did_you_mean(name, sheet.names)}")
        if name in names:
            raise sheet.error(item, f"the output {name} is listed twice")
        names.append(name)
    if not names:
        raise sheet.error(seq, "outputs is empty; leave the key out for the default outputs")
    return tuple(names), where(seq)


def scalars(sheet: Sheet) -> tuple[int, int]:
    """The order and the number of samples."""
    order, samples = DEFAULT_ORDER, DEFAULT_SAMPLES
    node = sheet.root.get("order")
    if node is not None:
        order = sheet.integer(node, "the order 0, 1 or 2")
        if order not in (0, 1, 2):
            raise sheet.error(node, f"the order is 0 (displacement), 1 (+ velocity) or 2 (+ acceleration), "
                              f"got {order}")
    node = sheet.root.get("samples")
    if node is not None:
        samples = sheet.integer(node, "the number of samples, a whole number")
        if samples < 2:
            raise sheet.error(node, f"a sweep needs at least 2 samples, got {samples}")
        if samples > MAX_SAMPLES:
            assert isinstance(node, Scalar)  # integer() reads scalars only
            raise sheet.error(node, f"a sweep has at most {MAX_SAMPLES} samples, got {node.text}")
    return order, samples


def sweep(sheet: Sheet, samples: int, inputs: int) -> str:
    """How the inputs move over the sweep (SWEEPS; together without the key); a grid's rows,
    samples to the power of the inputs, at most MAX_SAMPLES."""
    node = sheet.root.get("sweep")
    if node is None:
        return SWEEPS[0]
    kind = sheet.text(node, "the sweep: together or grid")
    if kind not in SWEEPS:
        raise sheet.error(node, f"the sweep is together (every input along its range at once) or grid "
                          f"(every combination of the inputs' samples), got {kind!r}")
    if kind == "grid" and samples ** inputs > MAX_SAMPLES:
        raise sheet.error(node, f"a grid over {inputs} inputs of {samples} samples each has {samples ** inputs} rows; "
                          f"at most {MAX_SAMPLES}")
    return kind


def options(sheet: Sheet) -> tuple[Options, dict[str, Where]]:
    """The options (linkgen.options.Options; each key optional, the defaults without it) and where
    the file gives each."""
    node = sheet.root.get("options")
    if node is None:
        return Options(), {}
    opts = sheet.mapping(node, "the options as {real: float, strategy: newton, ...}")
    sheet.keys(opts, (), tuple(Options.__dataclass_fields__), "options")
    given: dict[str, object] = {}
    for key, value in opts.items:
        given[key.text] = _option(sheet, key.text, value)
    return Options(**given), {key.text: where(value) for key, value in opts.items}  # type: ignore[arg-type]


def _option(sheet: Sheet, key: str, node: Node) -> object:
    """One option's value, checked against its choices or range."""
    if key in ("polish", "checks"):
        return sheet.boolean(node, f"options: {key}")
    if key == "tolerance":
        tol = sheet.number(node, "the resolver tolerance, a number relative to the length scale")
        if not 0.0 < tol <= MAX_TOLERANCE:
            raise sheet.error(node, f"the resolver tolerance is above 0 and at most {MAX_TOLERANCE:g}, got {tol:g}")
        return tol
    if key == "assembly":
        k = sheet.integer(node, "the assembly to follow, a whole number (linkgen assemblies numbers them)")
        if k < 1:
            raise sheet.error(node, f"options: assembly is a number from 1 (see linkgen assemblies), got {k}")
        return k
    if key == "iterations":
        cap = sheet.integer(node, "the resolver's iteration cap, a whole number")
        if not 1 <= cap <= MAX_ITERATIONS:
            raise sheet.error(node, f"the resolver's iteration cap is 1 to {MAX_ITERATIONS}, got {cap}")
        return cap
    choices = CHOICES[key]
    value: object = sheet.integer(node, f"options: {key}") if key == "predictor" else sheet.text(node, key)
    if value not in choices:
        words = ", ".join(str(c) for c in choices[:-1]) + f" or {choices[-1]}"
        raise sheet.error(node, f"options: {key} is {words}, got {value!r}")
    return value


def key_where(sheet: Sheet, key: str) -> Where:
    node = next(k for k, _ in sheet.root.items if k.text == key)
    return Where(node.line, key)
