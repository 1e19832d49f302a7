"""Templates lay text out: they hold no threshold, tolerance or limit of their own.

Every number a program or the manual uses comes from the step log (its policy, its steps)
or from linkgen/status.py, so a change of policy is a change in one place.  What is left
in the templates are the structural numbers of code (zero, one, an index, the three input
arrays) and, in the manual's prose, the paper's citation and the status-code formula.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
TEMPLATES = sorted((ROOT / "templates").glob("*/*.j2"))
NUMBER = re.compile(r"(?<![\w.])(\d+\.\d+|\d+(?:\.\d+)?[eE][-+]?\d+|\d+)(?![\w.])")
STRUCTURAL = {"0", "1", "2", "3", "4", "0.0", "1.0"}  # zeros, ones, indexes; 3 arrays; warm[4]; nargin < 4
PROSE = {"6", "8", "41", "2020", "11", "4463", "2021"}  # the manual: Machines 8(3) 41, 2020, its section 6;
# the instant-centre paper: Appl. Sci. 11 4463, 2021


def _numbers(path: Path) -> set[str]:
    text = re.sub(r"\{#.*?#\}", "", path.read_text(encoding="utf-8"), flags=re.S)
    return set(NUMBER.findall(text))


@pytest.mark.parametrize("path", TEMPLATES, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_templates_hold_no_number_of_their_own(path: Path):
    allowed = STRUCTURAL | (PROSE if path.parent.name == "md" else set())
    assert _numbers(path) <= allowed, sorted(_numbers(path) - allowed)


def test_the_check_sees_a_threshold(tmp_path: Path):
    planted = tmp_path / "x.j2"
    planted.write_text("{# 0.5 in a comment is fine #}if (sigma < 1e-07) return 52;\n")
    assert _numbers(planted) == {"1e-07", "52"}


def test_the_c_macros_names_may_not_take_are_the_ones_name_c_defines():
    """linkgen.backends.c.words.SOURCE_MACROS (names refused for a mechanism's parts) is exactly
    what NAME.c.j2 and the C runtime it pastes in #define."""
    from linkgen.backends.c.words import SOURCE_MACROS

    runtime = sorted((ROOT / "linkgen" / "backends" / "c" / "runtime").glob("*.c"))
    sources = [ROOT / "templates" / "c" / "NAME.c.j2", *runtime]
    defined = {m for path in sources for m in re.findall(r"^#define (\w+)", path.read_text(), flags=re.M)}
    assert defined == SOURCE_MACROS
