"""A four-bar as mechanism-file text, to be renamed or edited line by line, and how the validator
(with the topology's checks after it) takes it: the tests of linkgen.validate share it.  Also a
six-bar whose resolver group holds a prismatic pair, which the closure strategy refuses."""

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

# Fig. 14 with its rocker1 (J1-J2) replaced by a block sliding on the frame: J2 is placed by a PRR chain.
SLIDER_TRIAD = """linkgen: 1
name: slider_triad
joints:
  J1: {type: prismatic, at: [0, 70], axis: 0}
  J2: [0, 70]
  J3: [100, 0]
  J4: [105, 65]
  J5: [60, 80]
  J6: [-60, 100]
  J7: [-60, 80]
links:
  block: [J1, J2]
  ternary: [J2, J4, J5]
  rocker2: [J3, J4]
  coupler: [J6, J5]
  crank: [J7, J6]
  frame: {joints: [J1, J3, J7], fixed: true}
inputs:
  - {joint: J7, link: crank, relative_to: frame, range: [0, 360]}
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
