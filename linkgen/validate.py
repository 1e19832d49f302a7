"""Stage 2: node tree -> validated Mechanism (format version 1).

Checks everything that can be checked on the file alone: keys, names, numbers,
which pairs each link carries, the fixed link, the inputs.  Mobility and whether
the inputs determine the sketch are checked by ``topology``.
"""

from __future__ import annotations

import difflib
import math
import os
import unicodedata

from .errors import InputError, and_list
from .loader import IDENTIFIER, Mapping, Node, Reader, Sequence, describe, load
from .model import Input, Joint, Link, Mechanism, Point, Prismatic, Where
from .names import entity_name_problem, mechanism_name_problem, spellings
from .policy import MAX_MAGNITUDE

FORMAT_VERSION = 1
MAX_SAMPLES = 10_000_000
# Bidirectional-text controls: no title or unit label may hold them (nor a control character or line break),
# which would make a line of a generated file read other than it compiles.
_BIDI = frozenset("\u061c\u200e\u200f\u202a\u202b\u202c\u202d\u202e\u2066\u2067\u2068\u2069")
DEFAULT_SAMPLES = 361
DEFAULT_ORDER = 2
_TOP_REQUIRED = ("linkgen", "name", "joints", "links", "inputs")
_TOP_OPTIONAL = ("title", "units", "outputs", "order", "samples")
_INPUT_KEYS = ("joint", "link", "relative_to", "between", "speed")


def _where(node: Node) -> Where:
    return Where(node.line, node.key)


def _did_you_mean(name: str, known) -> str:
    close = difflib.get_close_matches(name, list(known), n=1)
    return f" (did you mean {close[0]}?)" if close else ""


def _bad_character(text: str) -> str:
    """The first character of a text that a line of a generated file cannot carry ('' when none)."""
    for ch in text:
        if unicodedata.category(ch) in ("Cc", "Cs", "Zl", "Zp") or ch in _BIDI:
            return ch
    return ""


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


class _Validator:
    def __init__(self, root: Mapping, path: str):
        self.root = root
        self.path = path
        self.r = Reader(path)
        self.names: dict[str, Node] = {}  # pairs, points and links share one namespace
        self.angle_scale = math.pi / 180
        self.length_unit = ""

    # -- helpers -------------------------------------------------------------
    def error(self, message: str, where: Where) -> InputError:
        return InputError(message, self.path, where.line, where.key)

    def claim(self, name: str, node: Node, what: str) -> None:
        if name in self.names:
            first = self.names[name]
            raise self.r.error(node, f"the name {name} is already used at line {first.line} ({first.key}); "
                               f"pairs, points and links share one set of names, so this {what} needs another")
        self.names[name] = node

    def xy(self, node: Node, what: str) -> tuple[float, float]:
        seq = self.r.sequence(node, f"the position of {what} as [x, y]")
        if len(seq.items) != 2:
            raise self.r.error(node, f"expected the position of {what} as [x, y], two numbers, "
                               f"got {len(seq.items)} value{'' if len(seq.items) == 1 else 's'}")
        x = self.magnitude(seq.items[0], f"the x coordinate of {what}")
        y = self.magnitude(seq.items[1], f"the y coordinate of {what}")
        return x, y

    def magnitude(self, node: Node, what: str, unit: str = "") -> float:
        """A number of at most MAX_MAGNITUDE in size (file units)."""
        value = self.r.number(node, f"{what}, a number")
        if abs(value) > MAX_MAGNITUDE:
            unit = unit or self.length_unit or "the file's length unit"
            raise self.r.error(node, f"{what} is {node.text}, outside the range linkgen supports: at most "
                               f"1e30 in size (in {unit})")
        return value

    def one_line(self, node: Node, what: str, label: str) -> str:
        """A text the generated files carry in comments and headings: one line, no control character."""
        text = self.r.text(node, what)
        bad = _bad_character(text)
        if bad:
            kind = "line break" if bad in "\n\r\x85\u2028\u2029" else "control character"
            raise self.r.error(node, f"{label} holds the {kind} U+{ord(bad):04X}, which the generated files cannot "
                               "carry in their comments and headings; write it as one line of plain text")
        return text

    def angle(self, node: Node, what: str) -> float:
        return self.r.number(node, what) * self.angle_scale

    def pair_name(self, node: Node, joints: dict[str, Joint], what: str) -> str:
        name = self.r.name(node, f"{what}, a pair name")
        if name not in joints:
            raise self.r.error(node, f"{name} is not a pair in joints{_did_you_mean(name, joints)}")
        return name

    # -- sections ------------------------------------------------------------
    def header(self) -> tuple[str, str, str, str]:
        root = self.root
        self.r.keys(root, _TOP_REQUIRED, _TOP_OPTIONAL, "the mechanism file")
        node = root.get("linkgen")
        version = self.r.integer(node, f"the format version {FORMAT_VERSION}")
        if version != FORMAT_VERSION:
            raise self.r.error(node, f"this file is format version {version}, "
                               f"but this linkgen reads format version {FORMAT_VERSION}")
        node = root.get("name")
        name = self.r.name(node, "a name for the mechanism, such as fourbar")
        self.program_name(name, node)
        title_node = root.get("title")
        title = self.one_line(title_node, "a title (text)", "the title") if title_node is not None else name
        length_unit, angle_unit = "", "deg"
        units = root.get("units")
        if units is not None:
            units = self.r.mapping(units, "the units as {length: mm, angle: deg}")
            self.r.keys(units, (), ("length", "angle"), "units")
            if units.get("length") is not None:
                length_unit = self.one_line(units.get("length"), "a length unit label such as mm", "the length unit")
            node = units.get("angle")
            if node is not None:
                angle_unit = self.r.text(node, "the angle unit deg or rad")
                if angle_unit not in ("deg", "rad"):
                    raise self.r.error(node, f"the angle unit is deg (degrees) or rad (radians), got {angle_unit!r}")
        self.angle_scale = math.pi / 180 if angle_unit == "deg" else 1.0
        self.length_unit = length_unit
        return name, title, length_unit, angle_unit

    def joints(self) -> tuple[Joint, ...]:
        section = self.r.mapping(self.root.get("joints"),
                                 "the pairs as NAME: [x, y] or NAME: {type: prismatic, at: [x, y], axis: ANGLE}")
        if not section.items:
            raise self.r.error(section, "no pairs are given; list every pair at its position in the sketch")
        out = []
        for index, (key, node) in enumerate(section.items):
            name = self.r.name(key, "a pair name")
            self.claim(name, key, "pair")
            if isinstance(node, Sequence):
                x, y = self.xy(node, f"pair {name}")
                out.append(Joint(name, index, "revolute", x, y, 0.0, _where(key)))
                continue
            spec = self.r.mapping(node, f"pair {name} as [x, y] or {{type: prismatic, at: [x, y], axis: ANGLE}}")
            kind_node = spec.get("type")
            kind = self.r.text(kind_node, "the pair type") if kind_node is not None else "revolute"
            if kind not in ("revolute", "prismatic"):
                raise self.r.error(kind_node, f"a pair is revolute (a hinge) or prismatic (a slider), got {kind!r}")
            axis = 0.0
            if kind == "revolute":
                self.r.keys(spec, ("at",), ("type",), f"revolute pair {name}")
            else:
                self.r.keys(spec, ("at", "axis"), ("type",), f"prismatic pair {name}")
                axis = self.angle(spec.get("axis"), f"the slide axis angle of pair {name}, a number")
            x, y = self.xy(spec.get("at"), f"pair {name}")
            out.append(Joint(name, index, kind, x, y, axis, _where(key)))
        return tuple(out)

    def links(self, joints: dict[str, Joint]) -> tuple[Link, ...]:
        section = self.r.mapping(self.root.get("links"), "the links as NAME: [PAIR, PAIR, ...]")
        out = []
        point_index = 0
        for index, (key, node) in enumerate(section.items):
            name = self.r.name(key, "a link name")
            self.claim(name, key, "link")
            fixed = False
            points: list[Point] = []
            jnode = node
            if isinstance(node, Mapping):
                self.r.keys(node, ("joints",), ("fixed", "points"), f"link {name}")
                jnode = node.get("joints")
                if node.get("fixed") is not None:
                    fixed = self.r.boolean(node.get("fixed"), f"whether link {name} is fixed")
                if node.get("points") is not None:
                    points = self.points(name, node.get("points"), point_index)
                    point_index += len(points)
            elif not isinstance(node, Sequence):
                raise self.r.error(node, f"expected link {name} as [PAIR, PAIR, ...] or "
                                   f"{{joints: [...], fixed: true, points: {{NAME: [x, y]}}}}, got {describe(node)}")
            names = self.link_pairs(name, jnode, joints)
            self.link_geometry(name, names, points, joints, jnode)
            out.append(Link(name, index, tuple(names), fixed, tuple(points), _where(key)))
        self.one_fixed(out, section)
        return tuple(out)

    def points(self, link: str, node: Node, first_index: int) -> list[Point]:
        section = self.r.mapping(node, f"the points of link {link} as {{NAME: [x, y], ...}}")
        out = []
        for pkey, pval in section.items:
            pname = self.r.name(pkey, "a point name")
            self.claim(pname, pkey, "point")
            x, y = self.xy(pval, f"point {pname}")
            out.append(Point(pname, first_index + len(out), link, x, y, _where(pkey)))
        return out

    def link_pairs(self, link: str, node: Node, joints: dict[str, Joint]) -> list[str]:
        seq = self.r.sequence(node, f"the pairs link {link} carries, as [PAIR, PAIR, ...]")
        names: list[str] = []
        for item in seq.items:
            jname = self.pair_name(item, joints, f"a pair of link {link}")
            if jname in names:
                raise self.r.error(item, f"link {link} lists the pair {jname} twice")
            names.append(jname)
        if not names:
            raise self.r.error(seq, f"link {link} carries no pair")
        return names

    def link_geometry(self, name: str, names: list[str], points: list[Point], joints: dict[str, Joint],
                      node: Node) -> None:
        revolute = [joints[j] for j in names if joints[j].revolute]
        for i, a in enumerate(revolute):
            for b in revolute[i + 1:]:
                if (a.x, a.y) == (b.x, b.y):
                    raise self.r.error(node, f"link {name} carries the revolute pairs {a.name} and {b.name} at the "
                                       f"same position ({a.x:g}, {a.y:g}); a link cannot be hinged twice at one point")
        spots = {(joints[j].x, joints[j].y) for j in names} | {(p.x, p.y) for p in points}
        if len(names) + len(points) > 1 and len(spots) == 1 and all(joints[j].revolute for j in names):
            raise self.r.error(node, f"all pairs and points of link {name} lie at one position, so the link has no "
                               "direction; give a pair or point of the link elsewhere, at its place in the sketch")

    def one_fixed(self, links: list[Link], section: Mapping) -> None:
        fixed = [lk for lk in links if lk.fixed]
        if not fixed:
            raise self.r.error(section, "no link is fixed; mark the frame with {joints: [...], fixed: true}")
        if len(fixed) > 1:
            raise self.error(f"links {fixed[0].name} and {fixed[1].name} are both fixed; exactly one link is "
                             "the frame (pairs on the frame are all listed by that one link)", fixed[1].where)

    def pair_usage(self, joints: tuple[Joint, ...], links: tuple[Link, ...]) -> None:
        for j in joints:
            on = [lk.name for lk in links if j.name in lk.joints]
            if not on:
                raise self.error(f"the pair {j.name} is on no link; list it in the two links it joins", j.where)
            if len(on) == 1:
                raise self.error(f"the pair {j.name} is only on link {on[0]}, but a pair joins two links; list it "
                                 f"in the other link too, or make it a point of {on[0]} (points: {{{j.name}: [x, y]}})",
                                 j.where)
            if not j.revolute and len(on) != 2:
                raise self.error(f"the prismatic pair {j.name} is on {len(on)} links ({and_list(on)}); a prismatic "
                                 "pair joins exactly two links, the guide and the slider", j.where)

    def inputs(self, joints: dict[str, Joint], links: tuple[Link, ...]) -> tuple[Input, ...]:
        seq = self.r.sequence(self.root.get("inputs"),
                              "the inputs as a list, one '- {joint: ..., ...}' line per degree of freedom")
        if not seq.items:
            raise self.r.error(seq, "no inputs are given; give one input per degree of freedom")
        out: list[Input] = []
        driven: dict[str, Node] = {}
        by_name = {lk.name: lk for lk in links}
        for index, node in enumerate(seq.items):
            spec = self.r.mapping(node, "an input {joint: ..., link: ..., relative_to: ..., range: [from, to]}")
            self.r.keys(spec, ("range",), _INPUT_KEYS, "an input")
            if spec.get("between") is not None:
                out.append(self.distance_input(index, spec, joints, links, driven))
            elif spec.get("joint") is None:
                raise self.r.error(spec, "an input needs joint: (the driven pair) or between: [J1, J2] (an actuator)")
            else:
                out.append(self.pair_input(index, spec, joints, by_name, driven))
        return tuple(out)

    def pair_input(self, index: int, spec: Mapping, joints: dict[str, Joint], by_name: dict[str, Link],
                   driven: dict[str, Node]) -> Input:
        jnode = spec.get("joint")
        jname = self.pair_name(jnode, joints, "the driven pair")
        if jname in driven:
            raise self.r.error(jnode, f"the pair {jname} already carries an input (line {driven[jname].line}); "
                               "a pair carries at most one input")
        driven[jname] = jnode
        on = [name for name, lk in by_name.items() if jname in lk.joints]
        if not joints[jname].revolute:
            for key in ("link", "relative_to"):
                if spec.get(key) is not None:
                    self.input_link(spec.get(key), jname, on, by_name)
            both = spec.get("link") is not None and spec.get("relative_to") is not None
            if both and self.r.name(spec.get("link")) == self.r.name(spec.get("relative_to")):
                raise self.r.error(spec.get("relative_to"), "an input moves one link against another link, "
                                       "not against itself")
            start, stop, speed = self.sweep(spec, False)
            return Input(index, "prismatic", jname, "", "", (), start, stop, speed, _where(spec))
        for key, what in (("link", "the driven link"), ("relative_to", "the link it turns against")):
            if spec.get(key) is None:
                raise InputError(f"a revolute input on {jname} needs {key}: {what}", self.path, spec.line,
                                 f"{spec.key}.{key}")
        link = self.input_link(spec.get("link"), jname, on, by_name)
        ref = self.input_link(spec.get("relative_to"), jname, on, by_name)
        if by_name[link].fixed:
            raise self.r.error(spec.get("link"), f"the driven link {link} is the fixed link; drive the moving link "
                               f"and give the frame as relative_to (link: {ref}, relative_to: {link})")
        if link == ref:
            raise self.r.error(spec.get("relative_to"), f"an input turns link {link} against another link, "
                               "not against itself")
        start, stop, speed = self.sweep(spec, True)
        return Input(index, "revolute", jname, link, ref, (), start, stop, speed, _where(spec))

    def input_link(self, node: Node, joint: str, on: list[str], by_name: dict[str, Link]) -> str:
        name = self.r.name(node, "a link name")
        if name not in by_name:
            raise self.r.error(node, f"{name} is not a link{_did_you_mean(name, by_name)}")
        if name not in on:
            raise self.r.error(node, f"link {name} does not carry the pair {joint}, so the input on {joint} "
                               f"cannot move it; {joint} joins {and_list(on)}")
        return name

    def sweep(self, spec: Mapping, angular: bool) -> tuple[float, float, float]:
        """The input's range and speed, in radians or length units."""
        rng = self.r.sequence(spec.get("range"), "the input range as [from, to]")
        if len(rng.items) != 2:
            raise self.r.error(rng, f"expected the input range as [from, to], two numbers, got {len(rng.items)}")
        unit = ("degrees" if self.angle_scale != 1.0 else "radians") if angular else ""
        start = self.magnitude(rng.items[0], "the start of the range", unit)
        stop = self.magnitude(rng.items[1], "the end of the range", unit)
        speed_node = spec.get("speed")
        per_second = f"{unit or self.length_unit or 'length units'} per second"
        speed = self.magnitude(speed_node, "the input speed", per_second) if speed_node is not None else 1.0
        scale = self.angle_scale if angular else 1.0
        return start * scale, stop * scale, speed * scale

    def distance_input(self, index: int, spec: Mapping, joints: dict[str, Joint], links: tuple[Link, ...],
                       driven: dict[str, Node]) -> Input:
        for key in ("joint", "link", "relative_to"):
            if spec.get(key) is not None:
                raise self.r.error(spec.get(key), f"an actuator (between: [J1, J2]) takes no {key}:")
        bnode = self.r.sequence(spec.get("between"), "the two pairs of the actuator as [J1, J2]")
        if len(bnode.items) != 2:
            raise self.r.error(bnode, f"an actuator acts between exactly two pairs [J1, J2], got {len(bnode.items)}")
        pair = [self.pair_name(item, joints, "the actuator's end") for item in bnode.items]
        for item, jname in zip(bnode.items, pair):
            if not joints[jname].revolute:
                raise self.r.error(item, f"an actuator acts between revolute pairs; {jname} is prismatic")
        if pair[0] == pair[1]:
            raise self.r.error(bnode, "an actuator acts between two different pairs")
        shared = [lk.name for lk in links if pair[0] in lk.joints and pair[1] in lk.joints]
        if shared:
            raise self.r.error(bnode, f"{pair[0]} and {pair[1]} are both on link {shared[0]}, so their distance "
                               "cannot change; an actuator acts between pairs that share no link")
        a, b = joints[pair[0]], joints[pair[1]]
        if (a.x, a.y) == (b.x, b.y):
            raise self.r.error(bnode, f"{pair[0]} and {pair[1]} are at the same position in the sketch, so the "
                               "actuator has no length and no direction")
        key = "+".join(sorted(pair))
        if key in driven:
            raise self.r.error(bnode, f"an actuator between {pair[0]} and {pair[1]} is already given "
                               f"(line {driven[key].line})")
        driven[key] = bnode
        start, stop, speed = self.sweep(spec, False)
        return Input(index, "distance", "", "", "", tuple(pair), start, stop, speed, _where(spec))

    def single_pair_links(self, links: tuple[Link, ...], inputs: tuple[Input, ...]) -> None:
        driven = {i.link for i in inputs if i.kind == "revolute"}
        for lk in links:
            if len(lk.joints) < 2 and not (lk.points and lk.name in driven):
                raise self.error(f"link {lk.name} carries only the pair {lk.joints[0]}; a link needs two pairs "
                                 "(one pair and a point only when it is the driven link of a revolute input)",
                                 lk.where)

    def connected(self, links: tuple[Link, ...]) -> None:
        frame = next(lk for lk in links if lk.fixed)
        reach = {frame.name}
        changed = True
        while changed:
            changed = False
            for lk in links:
                if lk.name not in reach and any(set(lk.joints) & set(o.joints) for o in links if o.name in reach):
                    reach.add(lk.name)
                    changed = True
        apart = [lk for lk in links if lk.name not in reach]
        if apart:
            raise self.error(f"the mechanism falls apart: link{'s' if len(apart) > 1 else ''} "
                             f"{and_list(lk.name for lk in apart)} share{'' if len(apart) > 1 else 's'} no pair with "
                             f"the fixed link {frame.name} or the links joined to it", apart[0].where)

    def prismatic(self, joints: tuple[Joint, ...], links: tuple[Link, ...],
                  inputs: tuple[Input, ...]) -> tuple[Prismatic, ...]:
        out = []
        for j in joints:
            if j.revolute:
                continue
            on = [lk for lk in links if j.name in lk.joints]
            given = next((i for i in inputs if i.kind == "prismatic" and i.joint == j.name), None)
            ref = self.input_reference(given) if given is not None else ""
            if any(lk.fixed for lk in on):
                guide = next(lk.name for lk in on if lk.fixed)
            elif ref:
                guide = ref
            else:
                guide = on[0].name
            out.append(Prismatic(j.name, guide, next(lk.name for lk in on if lk.name != guide)))
        return tuple(out)

    def input_reference(self, given: Input) -> str:
        spec = self.root.get("inputs").items[given.index]
        node = spec.get("relative_to")
        return self.r.name(node) if node is not None else ""

    def resolve_prismatic_inputs(self, inputs: tuple[Input, ...],
                                 prismatic: tuple[Prismatic, ...]) -> tuple[Input, ...]:
        out = []
        for i in inputs:
            if i.kind == "prismatic":
                p = next(p for p in prismatic if p.joint == i.joint)
                i = Input(i.index, i.kind, i.joint, p.slider, p.guide, (), i.start, i.stop, i.speed, i.where)
            out.append(i)
        return tuple(out)

    def outputs(self) -> tuple[tuple[str, ...], Where | None]:
        node = self.root.get("outputs")
        if node is None:
            return (), None
        seq = self.r.sequence(node, "the outputs as a list of pair, point and link names, such as [B, P, rocker]")
        names: list[str] = []
        for item in seq.items:
            name = self.r.name(item, "an output, a pair, point or link name")
            if name not in self.names:
                raise self.r.error(item, f"the output {name} is not a pair, point or link of this mechanism"
                                   f"{_did_you_mean(name, self.names)}")
            if name in names:
                raise self.r.error(item, f"the output {name} is listed twice")
            names.append(name)
        if not names:
            raise self.r.error(seq, "outputs is empty; leave the key out for the default outputs")
        return tuple(names), _where(seq)

    def program_name(self, name: str, node: Node) -> None:
        """The mechanism's name names files, a module, a script and functions (linkgen.names)."""
        problem = mechanism_name_problem(name)
        if problem:
            better = next((n for n in (name.lstrip("_"), f"{name}_linkage", f"{name[:40]}_linkage")
                           if n and n != name and IDENTIFIER.fullmatch(n) and not mechanism_name_problem(n)), "")
            raise self.r.error(node, f"{name} {problem}; choose another name for the mechanism"
                               + (f", such as {better}" if better else ""))

    def entity_names(self, joints: tuple[Joint, ...], links: tuple[Link, ...], mechanism: str) -> None:
        """Pairs, points and links are fields of the programs' outputs (linkgen.names), whether outputs
        lists them or not: a name a program cannot carry is refused, and so are two names a program
        would write alike (end and end_ in MATLAB, where the keyword end is written end_)."""
        entities = [(j.name, j.where, "pair") for j in joints] + [(lk.name, lk.where, "link") for lk in links]
        entities += [(p.name, p.where, "point") for lk in links for p in lk.points]
        written: dict[tuple[str, str], str] = {}
        for name, where, what in sorted(entities, key=lambda e: e[1].line):
            problem = entity_name_problem(name, mechanism)
            for lang, spelling, why in spellings(name):
                other = written.setdefault((lang, spelling), name)
                if other != name and not problem:
                    word, why = (name, why) if why else (other, next(w for g, _, w in spellings(other) if g == lang))
                    problem = (f"is written {spelling} in the generated {lang} program, as is {other} (line "
                               f"{self.names[other].line}), because {word} is {why} and gets a trailing _ there")
            if problem:
                base = "_".join(filter(None, name.split("_")))
                better = next((n for n in (base, f"{base}_{what}", f"{what}_{base}")
                               if IDENTIFIER.fullmatch(n) and n not in self.names
                               and not entity_name_problem(n, mechanism)), "")
                advice = f"call the {what} {better} or similar" if better else f"choose another name for the {what}"
                raise self.error(f"{name} {problem}; {advice}", where)

    def input_columns(self, inputs: tuple[Input, ...]) -> None:
        """Input columns (theta_J, s_J, d_J1_J2) name the CSV's first columns: they must differ."""
        seen: dict[str, Input] = {}
        for i in inputs:
            if i.column in seen:
                first = seen[i.column]
                raise self.error(f"this input's CSV column would be {i.column}, as is the column of the input on "
                                 f"line {first.where.line}; rename one of the pairs", i.where)
            seen[i.column] = i

    def key_where(self, key: str) -> Where:
        node = next(k for k, _ in self.root.items if k.text == key)
        return Where(node.line, key)

    def scalars(self) -> tuple[int, int]:
        order, samples = DEFAULT_ORDER, DEFAULT_SAMPLES
        node = self.root.get("order")
        if node is not None:
            order = self.r.integer(node, "the order 0, 1 or 2")
            if order not in (0, 1, 2):
                raise self.r.error(node, f"the order is 0 (displacement), 1 (+ velocity) or 2 (+ acceleration), "
                                   f"got {order}")
        node = self.root.get("samples")
        if node is not None:
            samples = self.r.integer(node, "the number of samples, a whole number")
            if samples < 2:
                raise self.r.error(node, f"a sweep needs at least 2 samples, got {samples}")
            if samples > MAX_SAMPLES:
                raise self.r.error(node, f"a sweep has at most {MAX_SAMPLES} samples, got {node.text}")
        return order, samples

    def run(self) -> Mechanism:
        name, title, length_unit, angle_unit = self.header()
        joints = self.joints()
        by_name = {j.name: j for j in joints}
        links = self.links(by_name)
        self.entity_names(joints, links, name)
        self.pair_usage(joints, links)
        inputs = self.inputs(by_name, links)
        self.input_columns(inputs)
        self.single_pair_links(links, inputs)
        self.connected(links)
        prismatic = self.prismatic(joints, links, inputs)
        inputs = self.resolve_prismatic_inputs(inputs, prismatic)
        outputs, outputs_where = self.outputs()
        order, samples = self.scalars()
        return Mechanism(
            name, title, file_label(self.path), self.path, length_unit, angle_unit, joints, links,
            inputs, prismatic, outputs, outputs_where, order, samples, Where(1, ""), self.key_where("inputs"),
        )


def validate(root: Mapping, path: str) -> Mechanism:
    """Check a parsed file against format version 1 and build the Mechanism."""
    return _Validator(root, path).run()


def read_mechanism(path: str) -> Mechanism:
    return validate(load(path), path)
