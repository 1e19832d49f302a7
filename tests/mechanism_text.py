"""A four-bar as mechanism-file text, to be renamed or edited line by line, and how the validator
(with the topology's checks after it) takes it: the tests of linkgen.validate share it."""

from __future__ import annotations

import re

import pytest

from linkgen.errors import InputError
from linkgen.loader import parse
from linkgen.topology import Topology, analyse
from linkgen.validate import validate

PATH = "m.yaml"
FOURBAR = """linkgen: 1
name: fourbar
title: Test linkage
units: {length: mm, angle: deg}
joints:
  O1: [0, 0]
  A: [20, 0]
  B: [80, 50]
  O2: [90, 0]
links:
  frame: {joints: [O1, O2], fixed: true}
  crank: [O1, A]
  coupler: {joints: [A, B], points: {P: [60, 70]}}
  rocker: [O2, B]
inputs:
  - {joint: O1, link: crank, relative_to: frame, range: [0, 360], speed: 360}
"""


def fourbar(**renamed: str) -> str:
    """The four-bar with names replaced (whole words: O1=..., fourbar=..., ...)."""
    text = FOURBAR
    for old, new in renamed.items():
        text = re.sub(rf"\b{old}\b", new, text)
    return text


def check(text: str) -> Topology:
    return analyse(validate(parse(text, PATH), PATH))


def refused(text: str) -> InputError:
    with pytest.raises(InputError) as info:
        check(text)
    return info.value
