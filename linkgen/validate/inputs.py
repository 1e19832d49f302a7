"""The inputs: section: revolute, prismatic and distance inputs with their ranges and speeds, and
which link of each prismatic pair is its guide."""

from __future__ import annotations

from ..errors import InputError, and_list
from ..loader import Mapping, Node
from ..model import Input, Joint, Link, Prismatic
from .sheet import Sheet, did_you_mean, where

INPUT_KEYS = ("joint", "link", "relative_to", "between", "speed")


def inputs(sheet: Sheet, joints: dict[str, Joint], links: tuple[Link, ...]) -> tuple[Input, ...]:
    """The inputs as given; a prismatic input's link and relative_to are the ones the file names (or ''),
    which ``resolve_prismatic`` replaces by the pair's slider and guide."""
    seq = sheet.sequence(sheet.root["inputs"],
                         "the inputs as a list, one '- {joint: ..., ...}' line per degree of freedom")
    if not seq.items:
        raise sheet.error(seq, "no inputs are given; give one input per degree of freedom")
    out: list[Input] = []
    driven: dict[str, Node] = {}
    by_name = {lk.name: lk for lk in links}
    for index, node in enumerate(seq.items):
        spec = sheet.mapping(node, "an input {joint: ..., link: ..., relative_to: ..., range: [from, to]}")
        sheet.keys(spec, ("range",), INPUT_KEYS, "an input")
        if spec.get("between") is not None:
            out.append(_distance_input(sheet, index, spec, joints, links, driven))
        elif spec.get("joint") is None:
            raise sheet.error(spec, "an input needs joint: (the driven pair) or between: [J1, J2] (an actuator)")
        else:
            out.append(_pair_input(sheet, index, spec, joints, by_name, driven))
    return tuple(out)


def _pair_input(sheet: Sheet, index: int, spec: Mapping, joints: dict[str, Joint], by_name: dict[str, Link],
                driven: dict[str, Node]) -> Input:
    jnode = spec["joint"]
    jname = sheet.pair_name(jnode, joints, "the driven pair")
    if jname in driven:
        raise sheet.error(jnode, f"the pair {jname} already carries an input (line {driven[jname].line}); "
                          "a pair carries at most one input")
    driven[jname] = jnode
    on = [name for name, lk in by_name.items() if jname in lk.joints]
    link_node, ref_node = spec.get("link"), spec.get("relative_to")
    if not joints[jname].revolute:
        link = "" if link_node is None else _input_link(sheet, link_node, jname, on, by_name)
        ref = "" if ref_node is None else _input_link(sheet, ref_node, jname, on, by_name)
        if ref_node is not None and link == ref:
            raise sheet.error(ref_node, "an input moves one link against another link, not against itself")
        start, stop, speed = _sweep(sheet, spec, False)
        return Input(index, "prismatic", jname, link, ref, (), start, stop, speed, where(spec))
    for key, what in (("link", "the driven link"), ("relative_to", "the link it turns against")):
        if spec.get(key) is None:
            raise InputError(f"a revolute input on {jname} needs {key}: {what}", sheet.path, spec.line,
                             f"{spec.key}.{key}")
    assert link_node is not None and ref_node is not None
    link = _input_link(sheet, link_node, jname, on, by_name)
    ref = _input_link(sheet, ref_node, jname, on, by_name)
    if by_name[link].fixed:
        raise sheet.error(link_node, f"the driven link {link} is the fixed link; drive the moving link "
                          f"and give the frame as relative_to (link: {ref}, relative_to: {link})")
    if link == ref:
        raise sheet.error(ref_node, f"an input turns link {link} against another link, not against itself")
    start, stop, speed = _sweep(sheet, spec, True)
    return Input(index, "revolute", jname, link, ref, (), start, stop, speed, where(spec))


def _input_link(sheet: Sheet, node: Node, joint: str, on: list[str], by_name: dict[str, Link]) -> str:
    name = sheet.name(node, "a link name")
    if name not in by_name:
        raise sheet.error(node, f"{name} is not a link{did_you_mean(name, by_name)}")
    if name not in on:
        raise sheet.error(node, f"link {name} does not carry the pair {joint}, so the input on {joint} "
                          f"cannot move it; {joint} joins {and_list(on)}")
    return name


def _sweep(sheet: Sheet, spec: Mapping, angular: bool) -> tuple[float, float, float]:
    """The input's range and speed, in radians or length units."""
    rng = sheet.sequence(spec["range"], "the input range as [from, to]")
    if len(rng.items) != 2:
        raise sheet.error(rng, f"expected the input range as [from, to], two numbers, got {len(rng.items)}")
    unit = ("degrees" if sheet.angle_scale != 1.0 else "radians") if angular else ""
    start = sheet.magnitude(rng.items[0], "the start of the range", unit)
    stop = sheet.magnitude(rng.items[1], "the end of the range", unit)
    speed_node = spec.get("speed")
    per_second = f"{unit or sheet.length_unit or 'length units'} per second"
    speed = sheet.magnitude(speed_node, "the input speed", per_second) if speed_node is not None else 1.0
    scale = sheet.angle_scale if angular else 1.0
    return start * scale, stop * scale, speed * scale


def _distance_input(sheet: Sheet, index: int, spec: Mapping, joints: dict[str, Joint], links: tuple[Link, ...],
                    driven: dict[str, Node]) -> Input:
    for key in ("joint", "link", "relative_to"):
        node = spec.get(key)
        if node is not None:
            raise sheet.error(node, f"an actuator (between: [J1, J2]) takes no {key}:")
    bnode = sheet.sequence(spec["between"], "the two pairs of the actuator as [J1, J2]")
    if len(bnode.items) != 2:
        raise sheet.error(bnode, f"an actuator acts between exactly two pairs [J1, J2], got {len(bnode.items)}")
    pair = [sheet.pair_name(item, joints, "the actuator's end") for item in bnode.items]
    for item, jname in zip(bnode.items, pair):
        if not joints[jname].revolute:
            raise sheet.error(item, f"an actuator acts between revolute pairs; {jname} is prismatic")
    if pair[0] == pair[1]:
        raise sheet.error(bnode, "an actuator acts between two different pairs")
    shared = [lk.name for lk in links if pair[0] in lk.joints and pair[1] in lk.joints]
    if shared:
        raise sheet.error(bnode, f"{pair[0]} and {pair[1]} are both on link {shared[0]}, so their distance "
                          "cannot change; an actuator acts between pairs that share no link")
    a, b = joints[pair[0]], joints[pair[1]]
    if (a.x, a.y) == (b.x, b.y):
        raise sheet.error(bnode, f"{pair[0]} and {pair[1]} are at the same position in the sketch, so the "
                          "actuator has no length and no direction")
    key = "+".join(sorted(pair))
    if key in driven:
        raise sheet.error(bnode, f"an actuator between {pair[0]} and {pair[1]} is already given "
                          f"(line {driven[key].line})")
    driven[key] = bnode
    start, stop, speed = _sweep(sheet, spec, False)
    return Input(index, "distance", "", "", "", tuple(pair), start, stop, speed, where(spec))


def input_columns(sheet: Sheet, inputs: tuple[Input, ...]) -> None:
    """Input columns (theta_J, s_J, d_J1_J2) name the CSV's first columns: they must differ."""
    seen: dict[str, Input] = {}
    for i in inputs:
        if i.column in seen:
            first = seen[i.column]
            raise sheet.error_at(i.where, f"this input's CSV column would be {i.column}, as is the column of the "
                                 f"input on line {first.where.line}; rename one of the pairs")
        seen[i.column] = i


def prismatic(joints: tuple[Joint, ...], links: tuple[Link, ...], inputs: tuple[Input, ...]) -> tuple[Prismatic, ...]:
    """The guide of each prismatic pair: the fixed link if it carries the pair, else the relative_to link of a
    prismatic input on the pair, else the first link that lists the pair; the slider is the other link."""
    out = []
    for j in joints:
        if j.revolute:
            continue
        on = [lk for lk in links if j.name in lk.joints]
        ref = next((i.relative_to for i in inputs if i.kind == "prismatic" and i.joint == j.name), "")
        if any(lk.fixed for lk in on):
            guide = next(lk.name for lk in on if lk.fixed)
        elif ref:
            guide = ref
        else:
            guide = on[0].name
        out.append(Prismatic(j.name, guide, next(lk.name for lk in on if lk.name != guide)))
    return tuple(out)


def resolve_prismatic(inputs: tuple[Input, ...], prismatic: tuple[Prismatic, ...]) -> tuple[Input, ...]:
    """The inputs with each prismatic input's link and relative_to its pair's slider and guide."""
    out = []
    for i in inputs:
        if i.kind == "prismatic":
            p = next(p for p in prismatic if p.joint == i.joint)
            i = Input(i.index, i.kind, i.joint, p.slider, p.guide, (), i.start, i.stop, i.speed, i.where)
        out.append(i)
    return tuple(out)
