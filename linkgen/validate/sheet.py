"""The mechanism file being validated: typed reading (loader.Reader), the file's units, and the
one namespace its pairs, points and links share."""

from __future__ import annotations

import difflib
import math
import unicodedata
from collections.abc import Iterable

from ..errors import InputError
from ..loader import Mapping, Node, Reader, Scalar
from ..model import Joint, Where
from ..policy import MAX_MAGNITUDE

# Bidirectional-text controls: no title or unit label may hold them (nor a control character or line break),
# which would make a line of a generated file read other than it compiles.
_BIDI = frozenset("\u061c\u200e\u200f\u202a\u202b\u202c\u202d\u202e\u2066\u2067\u2068\u2069")


def where(node: Node) -> Where:
    return Where(node.line, node.key)


def did_you_mean(name: str, known: Iterable[str]) -> str:
    close = difflib.get_close_matches(name, list(known), n=1)
    return f" (did you mean {close[0]}?)" if close else ""


def bad_character(text: str) -> str:
    """The first character of a text that a line of a generated file cannot carry ('' when none)."""
    for ch in text:
        if unicodedata.category(ch) in ("Cc", "Cs", "Zl", "Zp") or ch in _BIDI:
            return ch
    return ""


class Sheet(Reader):
    """Reads the file's nodes in its units; ``header.header`` sets the units once it has read them."""

    def __init__(self, root: Mapping, path: str):
        super().__init__(path)
        self.root = root
        self.names: dict[str, Node] = {}  # pairs, points and links share one namespace
        self.angle_scale = math.pi / 180
        self.length_unit = ""

    def error_at(self, where: Where, message: str) -> InputError:
        """An error at an entity already read (a pair, link or input)."""
        return InputError(message, self.path, where.line, where.key)

    def claim(self, name: str, node: Node, what: str) -> None:
        if name in self.names:
            first = self.names[name]
            raise self.error(node, f"the name {name} is already used at line {first.line} ({first.key}); "
                             f"pairs, points and links share one set of names, so this {what} needs another")
        self.names[name] = node

    def xy(self, node: Node, what: str) -> tuple[float, float]:
        seq = self.sequence(node, f"the position of {what} as [x, y]")
        if len(seq.items) != 2:
            raise self.error(node, f"expected the position of {what} as [x, y], two numbers, "
                             f"got {len(seq.items)} value{'' if len(seq.items) == 1 else 's'}")
        x = self.magnitude(seq.items[0], f"the x coordinate of {what}")
        y = self.magnitude(seq.items[1], f"the y coordinate of {what}")
        return x, y

    def magnitude(self, node: Node, what: str, unit: str = "") -> float:
        """A number of at most MAX_MAGNITUDE in size (file units)."""
        value = self.number(node, f"{what}, a number")
        assert isinstance(node, Scalar)  # number() reads scalars only
        if abs(value) > MAX_MAGNITUDE:
            unit = unit or self.length_unit or "the file's length unit"
            raise self.error(node, f"{what} is {node.text}, outside the range linkgen supports: at most "
                             f"1e30 in size (in {unit})")
        return value

    def one_line(self, node: Node, what: str, label: str) -> str:
        """A text the generated files carry in comments and headings: one line, no control character."""
        text = self.text(node, what)
        bad = bad_character(text)
        if bad:
            kind = "line break" if bad in "\n\r\x85\u2028\u2029" else "control character"
            raise self.error(node, f"{label} holds the {kind} U+{ord(bad):04X}, which the generated files cannot "
                             "carry in their comments and headings; write it as one line of plain text")
        return text

    def angle(self, node: Node, what: str) -> float:
        return self.number(node, what) * self.angle_scale

    def pair_name(self, node: Node, joints: dict[str, Joint], what: str) -> str:
        name = self.name(node, f"{what}, a pair name")
        if name not in joints:
            raise self.error(node, f"{name} is not a pair in joints{did_you_mean(name, joints)}")
        return name
