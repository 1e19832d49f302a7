"""Stage 2: node tree -> validated Mechanism (format version 1).

Checks everything that can be checked on the file alone: keys, names, numbers,
which pairs each link carries, the fixed link, the inputs.  Mobility and whether
the inputs determine the sketch are checked by ``topology``.
"""

from __future__ import annotations

import math
import os

from .errors import InputError
from .loader import Mapping, Node, Reader, Sequence, load
from .model import Input, Joint, Link, Mechanism, Point, Prismatic, Where

FORMAT_VERSION = 1
DEFAULT_SAMPLES = 361
DEFAULT_ORDER = 2
_TOP_REQUIRED = ("linkgen", "name", "joints", "links", "inputs")
_TOP_OPTIONAL = ("title", "units", "outputs", "order", "samples")


def _where(node: Node) -> Where:
    return Where(node.line, node.key)


class _Validator:
    def __init__(self, root: Mapping, path: str):
        self.root = root
        self.path = path
        self.r = Reader(path)
        self.names: dict[str, Node] = {}  # pairs, points and links share one namespace
        self.angle_scale = math.pi / 180

    # -- helpers -------------------------------------------------------------
    def claim(self, name: str, node: Node, what: str) -> None:
        if name in self.names:
            first = self.names[name]
            raise self.r.error(node, f"the name {name!r} is used twice (first at line {first.line}, {first.key}); "
                               f"pairs, points and links share one set of names, so each {what} needs its own")
        self.names[name] = node

    def xy(self, node: Node, what: str) -> tuple[float, float]:
        seq = self.r.sequence(node, f"{what} as [x, y]")
        if len(seq.items) != 2:
            raise self.r.error(node, f"expected {what} as [x, y], got {len(seq.items)} numbers")
        return self.r.number(seq.items[0], "an x coordinate"), self.r.number(seq.items[1], "a y coordinate")

    def angle(self, node: Node, what: str) -> float:
        return self.r.number(node, what) * self.angle_scale

    # -- sections ------------------------------------------------------------
    def header(self) -> tuple[str, str, str, str]:
        root = self.root
        self.r.keys(root, _TOP_REQUIRED, _TOP_OPTIONAL, "the mechanism file")
        version = root.get("linkgen")
        if self.r.integer(version, "the format version 1") != FORMAT_VERSION:
            raise self.r.error(version, f"this linkgen reads format version {FORMAT_VERSION}")
        name = self.r.name(root.get("name"), "an identifier for the mechanism")
        title_node = root.get("title")
        title = self.r.text(title_node, "a title") if title_node is not None else name
        length_unit, angle_unit = "", "deg"
        units = root.get("units")
        if units is not None:
            units = self.r.mapping(units, "units")
            self.r.keys(units, (), ("length", "angle"), "units")
            if units.get("length") is not None:
                length_unit = self.r.text(units.get("length"), "a length unit label")
            if units.get("angle") is not None:
                node = units.get("angle")
                angle_unit = self.r.text(node, "deg or rad")
                if angle_unit not in ("deg", "rad"):
                    raise self.r.error(node, f"angle unit must be deg or rad, got {angle_unit!r}")
        self.angle_scale = math.pi / 180 if angle_unit == "deg" else 1.0
        return name, title, length_unit, angle_unit

    def joints(self) -> tuple[Joint, ...]:
        section = self.r.mapping(self.root.get("joints"), "the pairs (joints)")
        if not section.items:
            raise self.r.error(section, "no pairs are given")
        out = []
        for index, (key, node) in enumerate(section.items):
            name = self.r.name(key, "a pair name")
            self.claim(name, key, "pair")
            if isinstance(node, Sequence):
                x, y = self.xy(node, "the pair's position")
                out.append(Joint(name, index, "revolute", x, y, 0.0, _where(key)))
                continue
            spec = self.r.mapping(node, "a pair: [x, y] or {at: [x, y], type: ..., axis: ...}")
            kind_node = spec.get("type")
            kind = self.r.text(kind_node, "revolute or prismatic") if kind_node is not None else "revolute"
            if kind not in ("revolute", "prismatic"):
                raise self.r.error(kind_node, f"a pair type is revolute or prismatic, got {kind!r}")
            if kind == "revolute":
                self.r.keys(spec, ("at",), ("type",), f"revolute pair {name}")
                axis = 0.0
            else:
                self.r.keys(spec, ("at", "axis"), ("type",), f"prismatic pair {name}")
                axis = self.angle(spec.get("axis"), "the slide axis angle")
            x, y = self.xy(spec.get("at"), "the pair's position")
            out.append(Joint(name, index, kind, x, y, axis, _where(key)))
        return tuple(out)

    def links(self, joints: dict[str, Joint]) -> tuple[Link, ...]:
        section = self.r.mapping(self.root.get("links"), "the links")
        out = []
        point_index = 0
        for index, (key, node) in enumerate(section.items):
            name = self.r.name(key, "a link name")
            self.claim(name, key, "link")
            fixed = False
            points: list[Point] = []
            if isinstance(node, Mapping):
                self.r.keys(node, ("joints",), ("fixed", "points"), f"link {name}")
                jnode = node.get("joints")
                if node.get("fixed") is not None:
                    fixed = self.r.boolean(node.get("fixed"))
                if node.get("points") is not None:
                    pnode = self.r.mapping(node.get("points"), "the link's points {NAME: [x, y]}")
                    for pkey, pval in pnode.items:
                        pname = self.r.name(pkey, "a point name")
                        self.claim(pname, pkey, "point")
                        x, y = self.xy(pval, "the point's position")
                        points.append(Point(pname, point_index, name, x, y, _where(pkey)))
                        point_index += 1
            else:
                jnode = node
            seq = self.r.sequence(jnode, f"the pairs link {name} carries")
            names: list[str] = []
            for item in seq.items:
                jname = self.r.name(item, "a pair name")
                if jname not in joints:
                    raise self.r.error(item, f"link {name} carries {jname!r}, which is not a pair in joints")
                if jname in names:
                    raise self.r.error(item, f"link {name} lists the pair {jname} twice")
                names.append(jname)
            if not names:
                raise self.r.error(seq, f"link {name} carries no pair")
            self.link_geometry(name, names, points, joints, seq)
            out.append(Link(name, index, tuple(names), fixed, tuple(points), _where(key)))
        fixed_links = [lk for lk in out if lk.fixed]
        if not fixed_links:
            raise self.r.error(section, "no link is fixed: mark the frame with fixed: true")
        if len(fixed_links) > 1:
            second = fixed_links[1]
            raise InputError(
                f"two links are fixed ({fixed_links[0].name} and {second.name}); exactly one link is the frame",
                self.path, second.where.line, second.where.key,
            )
        return tuple(out)

    def link_geometry(self, name: str, names: list[str], points: list[Point], joints: dict[str, Joint],
                      node: Node) -> None:
        revolute = [joints[j] for j in names if joints[j].revolute]
        for i, a in enumerate(revolute):
            for b in revolute[i + 1:]:
                if (a.x, a.y) == (b.x, b.y):
                    raise self.r.error(node, f"link {name} carries the revolute pairs {a.name} and {b.name} "
                                       f"at the same position ({a.x:g}, {a.y:g}); a link cannot be pinned twice at one point")
        spots = {(joints[j].x, joints[j].y) for j in names} | {(p.x, p.y) for p in points}
        if len(spots) == 1 and not any(not joints[j].revolute for j in names):
            raise self.r.error(node, f"all pairs and points of link {name} lie at one position, so its direction "
                               "is undefined; give a second pair or point elsewhere on the link")

    def inputs(self, joints: dict[str, Joint], links: tuple[Link, ...]) -> tuple[Input, ...]:
        seq = self.r.sequence(self.root.get("inputs"), "the inputs, one per degree of freedom")
        out: list[Input] = []
        driven: dict[str, Node] = {}
        by_name = {lk.name: lk for lk in links}
        for index, node in enumerate(seq.items):
            spec = self.r.mapping(node, "an input {joint: ..., ...} or {between: [J1, J2], ...}")
            self.r.keys(spec, ("range",), ("joint", "link", "relative_to", "between", "speed"), "an input")
            rng = self.r.sequence(spec.get("range"), "the input range [from, to]")
            if len(rng.items) != 2:
                raise self.r.error(rng, "expected the input range as [from, to]")
            speed_node = spec.get("speed")
            if spec.get("between") is not None:
                out.append(self.distance_input(index, spec, joints, links, rng, speed_node, driven))
                continue
            if spec.get("joint") is None:
                raise self.r.error(spec, "an input needs joint: (a driven pair) or between: [J1, J2] (an actuator)")
            jnode = spec.get("joint")
            jname = self.r.name(jnode, "the driven pair")
            if jname not in joints:
                raise self.r.error(jnode, f"{jname!r} is not a pair in joints")
            if jname in driven:
                raise self.r.error(jnode, f"the pair {jname} already carries an input (line {driven[jname].line}); "
                                   "a pair carries at most one input")
            driven[jname] = jnode
            on = [lk.name for lk in links if jname in lk.joints]
            joint = joints[jname]
            if joint.revolute:
                kind, scale = "revolute", self.angle_scale
                for key in ("link", "relative_to"):
                    if spec.get(key) is None:
                        raise self.r.error(spec, f"a revolute input on {jname} needs {key}: the "
                                           f"{'driven link' if key == 'link' else 'link it turns against'}")
                link = self.input_link(spec.get("link"), jname, on, by_name)
                ref = self.input_link(spec.get("relative_to"), jname, on, by_name)
                if by_name[link].fixed:
                    raise self.r.error(spec.get("link"), f"the driven link {link} is the fixed link; drive the moving "
                                       "link and give the frame as relative_to")
                if link == ref:
                    raise self.r.error(spec.get("relative_to"), f"an input turns {link} against another link, not itself")
            else:
                kind, scale = "prismatic", 1.0
                if len(on) != 2:
                    raise self.r.error(jnode, f"the prismatic pair {jname} must join exactly two links")
                link, ref = "", ""
                for key in ("link", "relative_to"):
                    if spec.get(key) is not None:
                        self.input_link(spec.get(key), jname, on, by_name)
                if spec.get("link") is not None and spec.get("relative_to") is not None:
                    if self.r.name(spec.get("link")) == self.r.name(spec.get("relative_to")):
                        raise self.r.error(spec.get("relative_to"), "an input moves one link against another link")
            start = self.r.number(rng.items[0], "the start of the range") * scale
            stop = self.r.number(rng.items[1], "the end of the range") * scale
            speed = self.r.number(speed_node, "a speed") * scale if speed_node is not None else scale
            out.append(Input(index, kind, jname, link, ref, (), start, stop, speed, _where(node)))
        return tuple(out)

    def input_link(self, node: Node, joint: str, on: list[str], by_name: dict[str, Link]) -> str:
        name = self.r.name(node, "a link name")
        if name not in by_name:
            raise self.r.error(node, f"{name!r} is not a link")
        if name not in on:
            raise self.r.error(node, f"the input pair {joint} does not join link {name} "
                               f"({joint} is on {', '.join(on) if on else 'no link'})")
        return name

    def distance_input(self, index: int, spec: Mapping, joints: dict[str, Joint], links: tuple[Link, ...],
                       rng: Sequence, speed_node: Node | None, driven: dict[str, Node]) -> Input:
        for key in ("joint", "link", "relative_to"):
            if spec.get(key) is not None:
                raise self.r.error(spec.get(key), f"a distance input (between:) takes no {key}:")
        bnode = self.r.sequence(spec.get("between"), "the two pairs [J1, J2] of the actuator")
        if len(bnode.items) != 2:
            raise self.r.error(bnode, "an actuator acts between exactly two pairs [J1, J2]")
        pair = []
        for item in bnode.items:
            jname = self.r.name(item, "a pair name")
            if jname not in joints:
                raise self.r.error(item, f"{jname!r} is not a pair in joints")
            if not joints[jname].revolute:
                raise self.r.error(item, f"an actuator acts between revolute pairs; {jname} is prismatic")
            pair.append(jname)
        if pair[0] == pair[1]:
            raise self.r.error(bnode, "an actuator needs two different pairs")
        shared = [lk.name for lk in links if pair[0] in lk.joints and pair[1] in lk.joints]
        if shared:
            raise self.r.error(bnode, f"{pair[0]} and {pair[1]} are both on link {shared[0]}, so their distance "
                               "cannot change; an actuator acts between pairs that share no link")
        key = "+".join(sorted(pair))
        if key in driven:
            raise self.r.error(bnode, f"an actuator between {pair[0]} and {pair[1]} is already given")
        driven[key] = bnode
        start = self.r.number(rng.items[0], "the start of the range")
        stop = self.r.number(rng.items[1], "the end of the range")
        speed = self.r.number(speed_node, "a speed") if speed_node is not None else 1.0
        a, b = joints[pair[0]], joints[pair[1]]
        if math.hypot(a.x - b.x, a.y - b.y) == 0:
            raise self.r.error(bnode, f"{pair[0]} and {pair[1]} coincide in the sketch; an actuator needs a length")
        return Input(index, "distance", "", "", "", tuple(pair), start, stop, speed, _where(spec))

    def pair_usage(self, joints: tuple[Joint, ...], links: tuple[Link, ...], inputs: tuple[Input, ...]) -> None:
        driven_single = {i.link for i in inputs if i.kind == "revolute"}
        for lk in links:
            if len(lk.joints) < 2 and not (lk.points and lk.name in driven_single):
                raise InputError(
                    f"link {lk.name} carries only one pair; a link needs two pairs, or one pair and a point "
                    "when it is the driven link of a revolute input", self.path, lk.where.line, lk.where.key)
        for j in joints:
            on = [lk.name for lk in links if j.name in lk.joints]
            if not on:
                raise InputError(f"the pair {j.name} is on no link; list it in the links it joins",
                                 self.path, j.where.line, j.where.key)
            if len(on) == 1:
                raise InputError(f"the pair {j.name} is only on link {on[0]}; a pair joins two links",
                                 self.path, j.where.line, j.where.key)
            if not j.revolute and len(on) != 2:
                raise InputError(f"the prismatic pair {j.name} is on {len(on)} links ({', '.join(on)}); "
                                 "a prismatic pair joins exactly two links", self.path, j.where.line, j.where.key)

    def connected(self, links: tuple[Link, ...]) -> None:
        reach = {links[0].name}
        changed = True
        while changed:
            changed = False
            for lk in links:
                if lk.name not in reach and any(set(lk.joints) & set(o.joints) for o in links if o.name in reach):
                    reach.add(lk.name)
                    changed = True
        apart = [lk for lk in links if lk.name not in reach]
        if apart:
            node = self.root.get("links")
            raise self.r.error(node, "the mechanism is not connected: " + ", ".join(lk.name for lk in apart)
                               + f" share no pair with {links[0].name} and the links joined to it")

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

    def resolve_prismatic_inputs(self, inputs: tuple[Input, ...], prismatic: tuple[Prismatic, ...]) -> tuple[Input, ...]:
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
        seq = self.r.sequence(node, "the outputs, a list of pair, point and link names")
        names: list[str] = []
        for item in seq.items:
            name = self.r.name(item, "an output name")
            if name not in self.names:
                raise self.r.error(item, f"{name!r} is not a pair, point or link of this mechanism")
            if name in names:
                raise self.r.error(item, f"{name} is listed twice in outputs")
            names.append(name)
        if not names:
            raise self.r.error(seq, "outputs is empty; leave it out for the default outputs")
        return tuple(names), _where(seq)

    def scalars(self) -> tuple[int, int]:
        order, samples = DEFAULT_ORDER, DEFAULT_SAMPLES
        if self.root.get("order") is not None:
            node = self.root.get("order")
            order = self.r.integer(node, "0, 1 or 2")
            if order not in (0, 1, 2):
                raise self.r.error(node, f"order is 0 (displacement), 1 (+ velocity) or 2 (+ acceleration), got {order}")
        if self.root.get("samples") is not None:
            node = self.root.get("samples")
            samples = self.r.integer(node, "a number of samples")
            if samples < 2:
                raise self.r.error(node, f"a sweep needs at least 2 samples, got {samples}")
        return order, samples

    def run(self) -> Mechanism:
        name, title, length_unit, angle_unit = self.header()
        joints = self.joints()
        by_name = {j.name: j for j in joints}
        links = self.links(by_name)
        inputs = self.inputs(by_name, links)
        self.pair_usage(joints, links, inputs)
        self.connected(links)
        prismatic = self.prismatic(joints, links, inputs)
        inputs = self.resolve_prismatic_inputs(inputs, prismatic)
        outputs, outputs_where = self.outputs()
        order, samples = self.scalars()
        return Mechanism(
            name, title, os.path.basename(self.path), self.path, length_unit, angle_unit, joints, links,
            inputs, prismatic, outputs, outputs_where, order, samples, Where(1, ""),
        )


def validate(root: Mapping, path: str) -> Mechanism:
    """Check a parsed file against format version 1 and build the Mechanism."""
    return _Validator(root, path).run()


def read_mechanism(path: str) -> Mechanism:
    return validate(load(path), path)
