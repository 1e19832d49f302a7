"""The joints: and links: sections: every pair at its place, every link with the pairs and points it
carries, one fixed link, and a mechanism in one piece."""

from __future__ import annotations

from ..errors import and_list
from ..loader import Mapping, Node, Sequence, describe
from ..model import Input, Joint, Link, Point
from .sheet import Sheet, where


def joints(sheet: Sheet) -> tuple[Joint, ...]:
    section = sheet.mapping(sheet.root["joints"],
                            "the pairs as NAME: [x, y] or NAME: {type: prismatic, at: [x, y], axis: ANGLE}")
    if not section.items:
        raise sheet.error(section, "no pairs are given; list every pair at its position in the sketch")
    out = []
    for index, (key, node) in enumerate(section.items):
        name = sheet.name(key, "a pair name")
        sheet.claim(name, key, "pair")
        if isinstance(node, Sequence):
            x, y = sheet.xy(node, f"pair {name}")
            out.append(Joint(name, index, "revolute", x, y, 0.0, where(key)))
            continue
        spec = sheet.mapping(node, f"pair {name} as [x, y] or {{type: prismatic, at: [x, y], axis: ANGLE}}")
        kind_node = spec.get("type")
        kind = sheet.text(kind_node, "the pair type") if kind_node is not None else "revolute"
        if kind not in ("revolute", "prismatic"):
            assert kind_node is not None
            raise sheet.error(kind_node, f"a pair is revolute (a hinge) or prismatic (a slider), got {kind!r}")
        axis = 0.0
        if kind == "revolute":
            sheet.keys(spec, ("at",), ("type",), f"revolute pair {name}")
        else:
            sheet.keys(spec, ("at", "axis"), ("type",), f"prismatic pair {name}")
            axis = sheet.angle(spec["axis"], f"the slide axis angle of pair {name}, a number")
        x, y = sheet.xy(spec["at"], f"pair {name}")
        out.append(Joint(name, index, kind, x, y, axis, where(key)))
    return tuple(out)


def links(sheet: Sheet, joints: dict[str, Joint]) -> tuple[Link, ...]:
    section = sheet.mapping(sheet.root["links"], "the links as NAME: [PAIR, PAIR, ...]")
    out = []
    point_index = 0
    for index, (key, node) in enumerate(section.items):
        name = sheet.name(key, "a link name")
        sheet.claim(name, key, "link")
        fixed = False
        points: list[Point] = []
        jnode = node
        if isinstance(node, Mapping):
            sheet.keys(node, ("joints",), ("fixed", "points"), f"link {name}")
            jnode = node["joints"]
            fixed_node, points_node = node.get("fixed"), node.get("points")
            if fixed_node is not None:
                fixed = sheet.boolean(fixed_node, f"whether link {name} is fixed")
            if points_node is not None:
                points = _points(sheet, name, points_node, point_index)
                point_index += len(points)
        elif not isinstance(node, Sequence):
            raise sheet.error(node, f"expected link {name} as [PAIR, PAIR, ...] or "
                              f"{{joints: [...], fixed: true, points: {{NAME: [x, y]}}}}, got {describe(node)}")
        names = _link_pairs(sheet, name, jnode, joints)
        _link_geometry(sheet, name, names, points, joints, jnode)
        out.append(Link(name, index, tuple(names), fixed, tuple(points), where(key)))
    _one_fixed(sheet, out, section)
    return tuple(out)


def _points(sheet: Sheet, link: str, node: Node, first_index: int) -> list[Point]:
    section = sheet.mapping(node, f"the points of link {link} as {{NAME: [x, y], ...}}")
    out: list[Point] = []
    for pkey, pval in section.items:
        pname = sheet.name(pkey, "a point name")
        sheet.claim(pname, pkey, "point")
        x, y = sheet.xy(pval, f"point {pname}")
        out.append(Point(pname, first_index + len(out), link, x, y, where(pkey)))
    return out


def _link_pairs(sheet: Sheet, link: str, node: Node, joints: dict[str, Joint]) -> list[str]:
    seq = sheet.sequence(node, f"the pairs link {link} carries, as [PAIR, PAIR, ...]")
    names: list[str] = []
    for item in seq.items:
        jname = sheet.pair_name(item, joints, f"a pair of link {link}")
        if jname in names:
            raise sheet.error(item, f"link {link} lists the pair {jname} twice")
        names.append(jname)
    if not names:
        raise sheet.error(seq, f"link {link} carries no pair")
    return names


def _link_geometry(sheet: Sheet, name: str, names: list[str], points: list[Point], joints: dict[str, Joint],
                   node: Node) -> None:
    revolute = [joints[j] for j in names if joints[j].revolute]
    for i, a in enumerate(revolute):
        for b in revolute[i + 1:]:
            if (a.x, a.y) == (b.x, b.y):
                raise sheet.error(node, f"link {name} carries the revolute pairs {a.name} and {b.name} at the "
                                  f"same position ({a.x:g}, {a.y:g}); a link cannot be hinged twice at one point")
    spots = {(joints[j].x, joints[j].y) for j in names} | {(p.x, p.y) for p in points}
    if len(names) + len(points) > 1 and len(spots) == 1 and all(joints[j].revolute for j in names):
        raise sheet.error(node, f"all pairs and points of link {name} lie at one position, so the link has no "
                          "direction; give a pair or point of the link elsewhere, at its place in the sketch")


def _one_fixed(sheet: Sheet, links: list[Link], section: Mapping) -> None:
    fixed = [lk for lk in links if lk.fixed]
    if not fixed:
        raise sheet.error(section, "no link is fixed; mark the frame with {joints: [...], fixed: true}")
    if len(fixed) > 1:
        raise sheet.error_at(fixed[1].where, f"links {fixed[0].name} and {fixed[1].name} are both fixed; exactly "
                             "one link is the frame (pairs on the frame are all listed by that one link)")


def pair_usage(sheet: Sheet, joints: tuple[Joint, ...], links: tuple[Link, ...]) -> None:
    """Every revolute pair joins two links or more, every prismatic pair exactly two."""
    carriers: dict[str, list[str]] = {j.name: [] for j in joints}
    for lk in links:
        for name in dict.fromkeys(lk.joints):
            carriers.get(name, []).append(lk.name)
    for j in joints:
        on = carriers[j.name]
        if not on:
            raise sheet.error_at(j.where, f"the pair {j.name} is on no link; list it in the two links it joins")
        if len(on) == 1:
            raise sheet.error_at(j.where, f"the pair {j.name} is only on link {on[0]}, but a pair joins two links; "
                                 f"list it in the other link too, or make it a point of {on[0]} "
                                 f"(points: {{{j.name}: [x, y]}})")
        if not j.revolute and len(on) != 2:
            raise sheet.error_at(j.where, f"the prismatic pair {j.name} is on {len(on)} links ({and_list(on)}); "
                                 "a prismatic pair joins exactly two links, the guide and the slider")


def single_pair_links(sheet: Sheet, links: tuple[Link, ...], inputs: tuple[Input, ...]) -> None:
    """A link with one pair is the driven link of a revolute input, with a point to give it a direction."""
    driven = {i.link for i in inputs if i.kind == "revolute"}
    for lk in links:
        if len(lk.joints) < 2 and not (lk.points and lk.name in driven):
            raise sheet.error_at(lk.where, f"link {lk.name} carries only the pair {lk.joints[0]}; a link needs two "
                                 "pairs (one pair and a point only when it is the driven link of a revolute input)")


def connected(sheet: Sheet, links: tuple[Link, ...]) -> None:
    """Every link is joined to the fixed link through pairs."""
    frame = next(lk for lk in links if lk.fixed)
    by_pair: dict[str, list[Link]] = {}
    for lk in links:
        for name in lk.joints:
            by_pair.setdefault(name, []).append(lk)
    reach, walk = {frame.name}, [frame]
    while walk:  # depth first through the pairs
        for name in walk.pop().joints:
            for lk in by_pair.pop(name, []):
                if lk.name not in reach:
                    reach.add(lk.name)
                    walk.append(lk)
    apart = [lk for lk in links if lk.name not in reach]
    if apart:
        raise sheet.error_at(apart[0].where, f"the mechanism falls apart: link{'s' if len(apart) > 1 else ''} "
                             f"{and_list(lk.name for lk in apart)} share{'' if len(apart) > 1 else 's'} no pair "
                             f"with the fixed link {frame.name} or the links joined to it")
