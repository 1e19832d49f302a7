"""Stage 1: YAML text -> a tree of nodes that know their line and key path.

ruamel.yaml parses the text (it is a maintained YAML 1.2 parser and gives marks
for every node); scalars are then read by the YAML 1.2 core schema here, from
their raw text and quoting style, so that ``1e-6`` is a number, ``yes`` is a
name, a quoted ``"90"`` is a string and duplicate keys are reported with both
line numbers.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field

from ruamel.yaml import YAML
from ruamel.yaml.error import MarkedYAMLError, YAMLError
from ruamel.yaml.nodes import MappingNode, ScalarNode, SequenceNode

from .errors import InputError

_INT = re.compile(r"[-+]?[0-9]+|0o[0-7]+|0x[0-9a-fA-F]+")
_FLOAT = re.compile(r"[-+]?(\.[0-9]+|[0-9]+(\.[0-9]*)?)([eE][-+]?[0-9]+)?")
_NONFINITE = re.compile(r"[-+]?\.(inf|Inf|INF)|\.(nan|NaN|NAN)")
_BOOL = {"true": True, "True": True, "TRUE": True, "false": False, "False": False, "FALSE": False}
_NULL = {"", "~", "null", "Null", "NULL"}
IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


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


@dataclass
class Sequence(Node):
    items: list[Node] = field(default_factory=list)


def _describe(node: Node) -> str:
    if isinstance(node, Mapping):
        return "a mapping"
    if isinstance(node, Sequence):
        return "a list"
    assert isinstance(node, Scalar)
    kind = node.kind()
    if kind == "str":
        return f"the text {node.text!r}" if node.quoted or node.text else "nothing"
    return {"null": "nothing", "bool": f"the boolean {node.text}"}.get(kind, f"the number {node.text}")


class Reader:
    """Typed access to nodes; every failure is an InputError with file, line and key."""

    def __init__(self, path: str):
        self.path = path

    def error(self, node: Node, message: str) -> InputError:
        return InputError(message, self.path, node.line, node.key)

    def mapping(self, node: Node, what: str) -> Mapping:
        if not isinstance(node, Mapping):
            raise self.error(node, f"expected {what} (a mapping), got {_describe(node)}")
        return node

    def sequence(self, node: Node, what: str) -> Sequence:
        if not isinstance(node, Sequence):
            raise self.error(node, f"expected {what} (a list), got {_describe(node)}")
        return node

    def number(self, node: Node, what: str = "a number") -> float:
        if isinstance(node, Scalar):
            kind = node.kind()
            if kind == "int":
                return float(int(node.text, 0) if node.text[:2] in ("0o", "0x") else int(node.text, 10))
            if kind == "float":
                value = float(node.text)
                if math.isfinite(value):
                    return value
                raise self.error(node, f"{node.text} is too large: expected {what}")
            if kind == "nonfinite":
                raise self.error(node, f"expected {what}, got {node.text}, which is not a finite number")
            if node.quoted and (_INT.fullmatch(node.text) or _FLOAT.fullmatch(node.text)):
                raise self.error(node, f"expected {what}, got the quoted text {node.text!r}; write it without quotes")
        raise self.error(node, f"expected {what}, got {_describe(node)}")

    def integer(self, node: Node, what: str = "a whole number") -> int:
        if isinstance(node, Scalar) and node.kind() == "int":
            return int(node.text, 0) if node.text[:2] in ("0o", "0x") else int(node.text, 10)
        if isinstance(node, Scalar) and node.kind() == "float":
            value = float(node.text)
            if value.is_integer():
                return int(value)
        raise self.error(node, f"expected {what}, got {_describe(node)}")

    def boolean(self, node: Node) -> bool:
        if isinstance(node, Scalar) and node.kind() == "bool":
            return _BOOL[node.text]
        raise self.error(node, f"expected true or false, got {_describe(node)}")

    def name(self, node: Node, what: str = "a name") -> str:
        if isinstance(node, Scalar) and node.kind() == "str" and IDENTIFIER.fullmatch(node.text):
            return node.text
        if isinstance(node, Scalar) and node.kind() == "str" and node.text:
            raise self.error(
                node, f"{node.text!r} is not a valid name: use letters, digits and _, not starting with a digit"
            )
        raise self.error(node, f"expected {what}, got {_describe(node)}")

    def text(self, node: Node, what: str = "text") -> str:
        if isinstance(node, Scalar) and node.kind() != "null":
            return node.text
        raise self.error(node, f"expected {what}, got {_describe(node)}")

    def keys(self, node: Mapping, required: tuple[str, ...], optional: tuple[str, ...], what: str) -> None:
        """Reject unknown keys and report missing required ones."""
        allowed = required + optional
        for k, _ in node.items:
            if k.text not in allowed:
                raise InputError(
                    f"unknown key {k.text!r} in {what}; allowed: {', '.join(allowed)}",
                    self.path, k.line, _join(node.key, k.text),
                )
        for name in required:
            if node.get(name) is None:
                raise self.error(node, f"{what} needs the key {name!r}")


def _join(parent: str, key: str) -> str:
    return f"{parent}.{key}" if parent else key


def _convert(raw, key: str, reader: Reader) -> Node:
    line = raw.start_mark.line + 1
    if isinstance(raw, ScalarNode):
        return Scalar(line, key, str(raw.value), raw.style is not None)
    if isinstance(raw, SequenceNode):
        return Sequence(line, key, [_convert(v, f"{key}[{i}]", reader) for i, v in enumerate(raw.value)])
    if isinstance(raw, MappingNode):
        out = Mapping(line, key)
        seen: dict[str, int] = {}
        for rk, rv in raw.value:
            if not isinstance(rk, ScalarNode):
                raise InputError("a key must be a plain name", reader.path, rk.start_mark.line + 1, key)
            k = Scalar(rk.start_mark.line + 1, _join(key, str(rk.value)), str(rk.value), rk.style is not None)
            if k.text in seen:
                raise InputError(
                    f"duplicate key {k.text!r} (first given at line {seen[k.text]})",
                    reader.path, k.line, _join(key, k.text),
                )
            seen[k.text] = k.line
            out.items.append((k, _convert(rv, _join(key, k.text), reader)))
        return out
    raise InputError("unsupported YAML node", reader.path, line, key)


def parse(text: str, path: str) -> Mapping:
    """Parse one YAML document into a Mapping node tree."""
    reader = Reader(path)
    try:
        docs = list(YAML(typ="rt", pure=True).compose_all(text))
    except MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        line = mark.line + 1 if mark is not None else 0
        raise InputError(f"not valid YAML: {exc.problem or exc.context}", path, line) from None
    except YAMLError as exc:
        raise InputError(f"not valid YAML: {exc}", path) from None
    docs = [d for d in docs if d is not None]
    if not docs:
        raise InputError("the file is empty: expected a mechanism", path, 1)
    if len(docs) > 1:
        raise InputError("the file holds more than one YAML document", path, docs[1].start_mark.line + 1)
    return reader.mapping(_convert(docs[0], "", reader), "a mechanism")


def load(path: str) -> Mapping:
    try:
        with open(path, encoding="utf-8") as fh:
            text = fh.read()
    except OSError as exc:
        raise InputError(f"cannot read the file: {exc.strerror}", path) from None
    except UnicodeDecodeError:
        raise InputError("the file is not UTF-8 text", path) from None
    return parse(text, path)
