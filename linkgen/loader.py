"""Stage 1: YAML text -> a tree of nodes that know their line and key path.

ruamel.yaml parses the text (it is a maintained YAML 1.2 parser and gives marks
for every node); scalars are then read by the YAML 1.2 core schema here, from
their raw text and quoting style, so that ``1e-6`` is a number, ``yes`` is a
name, a quoted ``"90"`` is a string and duplicate keys are reported with both
line numbers.
"""

from __future__ import annotations

import difflib
import math
import re
import warnings
from dataclasses import dataclass, field

from ruamel.yaml import YAML
from ruamel.yaml.error import MarkedYAMLError, ReusedAnchorWarning, YAMLError
from ruamel.yaml.events import (
    CollectionEndEvent,
    MappingStartEvent,
    NodeEvent,
    ScalarEvent,
    SequenceStartEvent,
)
from ruamel.yaml.nodes import MappingNode, ScalarNode, SequenceNode
from ruamel.yaml.nodes import Node as YAMLNode
from ruamel.yaml.reader import ReaderError

from .errors import InputError

_INT = re.compile(r"[-+]?[0-9]+|0o[0-7]+|0x[0-9a-fA-F]+")
_FLOAT = re.compile(r"[-+]?(\.[0-9]+|[0-9]+(\.[0-9]*)?)([eE][-+]?[0-9]+)?")
_NONFINITE = re.compile(r"[-+]?\.(inf|Inf|INF)|\.(nan|NaN|NAN)")
_BOOL = {"true": True, "True": True, "TRUE": True, "false": False, "False": False, "FALSE": False}
_NULL = {"", "~", "null", "Null", "NULL"}
IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")

# ruamel.yaml's description of a syntax error -> what to tell the user, and whether the
# start of the construct (the context mark) is the line to fix rather than where it was noticed
_SYNTAX = (
    ("expected ',' or ']'", "a list opened with [ is not closed with ]", True),
    ("expected ',' or '}'", "a mapping opened with { is not closed with }", True),
    ("found unexpected end of stream", "a quoted text is not closed with its quote", True),
    ("found character '\\t'", "a tab character; indent with spaces only", False),
    ("mapping values are not allowed here",
     "an unexpected ':' (put each key on its own line, and quote text that contains ': ')", False),
    ("could not find expected ':'", "a line that is neither 'key: value' nor a '- ' list item", True),
    ("but found ']'", "a ] that closes no list", False),
    ("but found '}'", "a } that closes no mapping", False),
    ("expected <block end>",
     "the indentation does not match the lines above (or '- ' items are mixed with 'key: value' lines)", False),
    ("found undefined alias", "an alias *NAME refers to no anchor &NAME given before it", False),
)


@dataclass
class Node:
    line: int
    key: str


@dataclass
class Scalar(Node):
    text: str
    quoted: bool

    def kind(self) -> str:
        """The YAML 1.2 core-schema type: str, int, float, nonfinite, bool or null."""
        if self.quoted:
            return "str"
        if self.text in _NULL:
            return "null"
        if self.text in _BOOL:
            return "bool"
        if _INT.fullmatch(self.text):
            return "int"
        if _FLOAT.fullmatch(self.text):
            return "float"
        if _NONFINITE.fullmatch(self.text):
            return "nonfinite"
        return "str"


@dataclass
class Mapping(Node):
    items: list[tuple[Scalar, Node]] = field(default_factory=list)

    def get(self, name: str) -> Node | None:
        for k, v in self.items:
            if k.text == name:
                return v
        return None

    def __getitem__(self, name: str) -> Node:
        """The value of a key that ``Reader.keys`` has required (KeyError where it is absent)."""
        node = self.get(name)
        if node is None:
            raise KeyError(name)
        return node


@dataclass
class Sequence(Node):
    items: list[Node] = field(default_factory=list)


def describe(node: Node) -> str:
    """What the user wrote, in words: 'a list', 'the number 12', 'the text 'abc'', ..."""
    if isinstance(node, Mapping):
        return "a mapping {key: value, ...}"
    if isinstance(node, Sequence):
        return "a list" if node.items else "an empty list"
    assert isinstance(node, Scalar)
    kind = node.kind()
    if kind == "str":
        return f"the text {_short(node.text)!r}"
    if kind == "null":
        return "nothing"
    if kind == "bool":
        return f"the boolean {node.text}"
    return f"the number {_short(node.text)}"


def _short(text: str) -> str:
    """The user's text, shortened for a one-line message."""
    return text if len(text) <= 30 else text[:27] + "..."


def _int(text: str) -> int:
    return int(text, 0) if text[:2] in ("0o", "0x") else int(text, 10)


class Reader:
    """Typed access to nodes; every failure is an InputError with file, line and key."""

    def __init__(self, path: str):
        self.path = path

    def error(self, node: Node, message: str) -> InputError:
        return InputError(message, self.path, node.line, node.key)

    def mapping(self, node: Node, what: str) -> Mapping:
        if not isinstance(node, Mapping):
            raise self.error(node, f"expected {what}, got {describe(node)}")
        return node

    def sequence(self, node: Node, what: str) -> Sequence:
        if not isinstance(node, Sequence):
            raise self.error(node, f"expected {what}, got {describe(node)}")
        return node

    def number(self, node: Node, what: str = "a number") -> float:
        if isinstance(node, Scalar):
            kind = node.kind()
            if kind in ("int", "float"):
                return self._finite(node, what)
            if kind == "nonfinite":
                raise self.error(node, f"expected {what}, got {node.text}, which is not a finite number")
            if node.quoted and (_INT.fullmatch(node.text) or _FLOAT.fullmatch(node.text)):
                raise self.error(node, f"expected {what}, got the quoted text {_short(node.text)!r}; "
                                 f"a number is written without quotes: {_short(node.text)}")
        raise self.error(node, f"expected {what}, got {describe(node)}")

    def _finite(self, node: Scalar, what: str) -> float:
        try:
            value = float(_int(node.text)) if node.kind() == "int" else float(node.text)
        except OverflowError:
            value = math.inf
        if not math.isfinite(value):
            raise self.error(node, f"expected {what}, got {_short(node.text)}, which is too large to compute with")
        return value

    def integer(self, node: Node, what: str = "a whole number") -> int:
        if isinstance(node, Scalar) and node.kind() == "int":
            return _int(node.text)
        if isinstance(node, Scalar) and node.kind() == "float" and float(node.text).is_integer():
            return int(float(node.text))
        raise self.error(node, f"expected {what}, got {describe(node)}")

    def boolean(self, node: Node, what: str) -> bool:
        if isinstance(node, Scalar) and node.kind() == "bool":
            return _BOOL[node.text]
        hint = ""
        if isinstance(node, Scalar) and node.text.lower() in ("yes", "no", "on", "off", "y", "n"):
            hint = " (YAML 1.2 reads yes, no, on and off as text)"
        raise self.error(node, f"expected {what}: true or false, got {describe(node)}{hint}")

    def name(self, node: Node, what: str = "a name") -> str:
        if not isinstance(node, Scalar) or node.kind() == "null":
            raise self.error(node, f"expected {what}, got {describe(node)}")
        if node.kind() == "bool":
            raise self.error(node, f"expected {what}, got the boolean {node.text}; "
                             f"write \"{node.text}\" in quotes to use it as a name")
        if not IDENTIFIER.fullmatch(node.text):
            raise self.error(node, f"expected {what}, got {_short(node.text)!r}, which is not a valid name: "
                             "use letters, digits and _, and do not start with a digit")
        return node.text

    def text(self, node: Node, what: str = "text") -> str:
        if isinstance(node, Scalar) and node.kind() != "null":
            return node.text
        raise self.error(node, f"expected {what}, got {describe(node)}")

    def keys(self, node: Mapping, required: tuple[str, ...], optional: tuple[str, ...], what: str) -> None:
        """Reject unknown keys and report missing required ones."""
        allowed = required + optional
        for k, _ in node.items:
            if k.text not in allowed:
                close = difflib.get_close_matches(k.text, allowed, n=1)
                hint = f" (did you mean {close[0]!r}?)" if close else ""
                raise InputError(f"unknown key {k.text!r} in {what}{hint}; the keys are: {', '.join(allowed)}",
                                 self.path, k.line, k.key)
        for name in required:
            if node.get(name) is None:
                raise InputError(f"{what} needs the key {name!r}", self.path, node.line, _join(node.key, name))


def _join(parent: str, key: str) -> str:
    return f"{parent}.{key}" if parent else key


def _convert(raw: YAMLNode, key: str, reader: Reader) -> Node:
    line = raw.start_mark.line + 1
    if raw.ctag.handle is not None:
        raise InputError(f"a YAML tag ({raw.ctag.handle}{raw.ctag.suffix}) is not used in a mechanism file; "
                         "write the value alone", reader.path, line, key)
    if isinstance(raw, ScalarNode):
        return Scalar(line, key, str(raw.value), raw.style is not None)
    if isinstance(raw, SequenceNode):
        return Sequence(line, key, [_convert(v, f"{key}[{i}]", reader) for i, v in enumerate(raw.value)])
    assert isinstance(raw, MappingNode)
    out = Mapping(line, key)
    seen: dict[str, int] = {}
    for rk, rv in raw.value:
        if not isinstance(rk, ScalarNode):
            raise InputError("a key must be a name, not a list or mapping", reader.path, rk.start_mark.line + 1, key)
        k = Scalar(rk.start_mark.line + 1, _join(key, str(rk.value)), str(rk.value), rk.style is not None)
        if k.text in seen:
            lines = "on this line" if seen[k.text] == k.line else f"at lines {seen[k.text]} and {k.line}"
            raise InputError(f"the key {k.text!r} is given twice, {lines}; each key may appear once",
                             reader.path, k.line, k.key)
        seen[k.text] = k.line
        value = _convert(rv, k.key, reader)
        if not isinstance(value, Scalar) or value.kind() == "null" and not value.text:
            value.line = k.line  # a block list or mapping starts below its key, an empty value nowhere
        out.items.append((k, value))
    return out


@dataclass
class _Open:
    """A collection open where an error is found: the index or key of its entry being written, and
    whether that entry's value has started."""

    mapping: bool
    index: int = -1
    key: str = "?"
    inside: bool = False


def _path_at(text: str) -> str:
    """The key path of the value being written where ``text`` (the file up to an error) ends."""
    frames: list[_Open] = []
    try:
        for event in YAML(typ="rt", pure=True).parse(text):
            if event.start_mark.index >= len(text):
                break
            if isinstance(event, CollectionEndEvent):
                frames.pop()
                if frames:
                    frames[-1].inside = False
                continue
            if not isinstance(event, NodeEvent):
                continue
            opens = isinstance(event, (MappingStartEvent, SequenceStartEvent))
            if frames:
                top = frames[-1]
                if not top.mapping:
                    top.index, top.inside = top.index + 1, opens
                elif not top.inside:
                    top.key, top.inside = str(event.value) if isinstance(event, ScalarEvent) else "?", True
                else:
                    top.inside = opens
            if opens:
                frames.append(_Open(isinstance(event, MappingStartEvent)))
    except YAMLError:
        pass
    path = ""
    for frame in frames:
        if not frame.inside:
            break
        path = _join(path, frame.key) if frame.mapping else f"{path}[{frame.index}]"
    return path


def _syntax_error(exc: MarkedYAMLError, text: str, path: str) -> InputError:
    problem = exc.problem or exc.context or "unreadable"
    mark = exc.problem_mark or exc.context_mark
    known = [(message, at_start) for pattern, message, at_start in _SYNTAX if pattern in problem]
    if known:
        message, at_start = known[0]
        if at_start and exc.context_mark is not None:
            mark = exc.context_mark
    else:
        message = problem + (f" ({exc.context})" if exc.context and exc.problem else "")
    if mark is None:
        return InputError(f"not valid YAML: {message}", path)
    return InputError(f"not valid YAML: {message}", path, mark.line + 1, _path_at(text[:mark.index]))


def parse(text: str, path: str) -> Mapping:
    """Parse one YAML document into a Mapping node tree."""
    reader = Reader(path)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ReusedAnchorWarning)  # YAML allows redefining an anchor
            docs = list(YAML(typ="rt", pure=True).compose_all(text))
    except MarkedYAMLError as exc:
        raise _syntax_error(exc, text, path) from None
    except ReaderError as exc:
        line = text.count("\n", 0, exc.position) + 1
        raise InputError(f"the file contains the control character U+{exc.character:04X}, which YAML text "
                         "may not contain", path, line) from None
    except YAMLError as exc:
        raise InputError(f"not valid YAML: {str(exc).splitlines()[0]}", path) from None
    if not docs:
        raise InputError("the file is empty: expected a mechanism (linkgen: 1, name: ..., joints: ...)", path, 1)
    if len(docs) > 1:
        raise InputError("a second YAML document starts here (after ---); a mechanism file holds one document",
                         path, docs[1].start_mark.line + 1)
    return reader.mapping(_convert(docs[0], "", reader),
                          "a mechanism: a mapping of keys such as linkgen: 1, name: ..., joints: ...")


def load(path: str) -> Mapping:
    try:
        with open(path, "rb") as fh:
            data = fh.read()
    except OSError as exc:
        raise InputError(f"cannot read the mechanism file: {exc.strerror}", path) from None
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        raise InputError(f"the file is not UTF-8 text: byte 0x{data[exc.start]:02X} cannot be read; "
                         "save the file as UTF-8", path, line) from None
    return parse(text, path)
