"""linkgen.instant.names: the output names ic:LINK1:LINK2, their fields in the programs, the errors."""

from __future__ import annotations

import pytest

from linkgen.instant.names import centre_name, centre_problem, field_name, is_centre, links_of

LINKS = ["frame", "crank", "coupler", "rocker"]


def test_names_round_trip():
    assert is_centre("ic:crank:rocker") and not is_centre("crank") and not is_centre("icon")
    assert links_of("ic:crank:rocker") == ("crank", "rocker")
    assert centre_name("crank", "rocker") == "ic:crank:rocker"
    assert field_name("ic:crank:rocker") == "ic_crank_rocker"


@pytest.mark.parametrize(("name", "problem"), [
    ("ic:crank:rocker", ""), ("ic:crank", "ic:LINK1:LINK2"), ("ic::rocker", "ic:LINK1:LINK2"),
    ("ic:a:b:c", "ic:LINK1:LINK2"), ("ic:crank:wheel", "wheel in ic:crank:wheel is not a link"),
    ("ic:rocker:rocker", "names one link twice")])
def test_problems(name, problem):
    got = centre_problem(name, LINKS)
    assert (problem in got) if problem else got == ""


def test_the_field_is_no_other_name():
    assert "the field ic_crank_rocker" in centre_problem("ic:crank:rocker", LINKS, {"ic_crank_rocker", "B"})
