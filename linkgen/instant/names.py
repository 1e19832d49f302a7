"""The names of instant centres as outputs: ``ic:LINK1:LINK2`` (an unordered pair of links)."""

from __future__ import annotations

from collections.abc import Collection

PREFIX = "ic:"
# the quantity classes of a centre's columns (x, y; ux, uy; status; sigma), every one of order 1
CENTRE_QUANTITIES = ("centre", "centre_direction", "centre_status", "centre_sigma")


def is_centre(name: str) -> bool:
    """Whether an output name asks for an instant centre."""
    return name.startswith(PREFIX)


def links_of(name: str) -> tuple[str, str]:
    """The two links of a centre's output name (as written)."""
    a, _, b = name[len(PREFIX):].partition(":")
    return a, b


def centre_name(a: str, b: str) -> str:
    """The output name of the centre of links a and b."""
    return f"{PREFIX}{a}:{b}"


def field_name(name: str) -> str:
    """The centre as a field of the programs' outputs (``out->ic_crank_rocker``): colons are no identifier."""
    return name.replace(":", "_")


def centre_problem(name: str, links: list[str], taken: Collection[str] = ()) -> str:
    """Why an output name that starts with ic: names no centre ('' when it does); ``taken``: the names
    of the pairs, points and links, which its field in the programs must not be."""
    a, b = links_of(name)
    if name.count(":") != 2 or not a or not b:
        return f"an instant centre is written ic:LINK1:LINK2, two link names, not {name}"
    for x in (a, b):
        if x not in links:
            return f"{x} in {name} is not a link of this mechanism (the links are {', '.join(links)})"
    if a == b:
        return f"{name} names one link twice: a centre belongs to two links"
    if field_name(name) in taken:
        return f"{name} is the field {field_name(name)} of the programs' outputs, the name of a pair, point or link"
    return ""
