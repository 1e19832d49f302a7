"""linkgen.instant.classify: first, secondary and third (A, B) centres from the links and pairs alone,
worked by hand on the samples (the paper's tables are checked in tests/test_instant_centres.py)."""

from __future__ import annotations

from pathlib import Path

from linkgen.instant.classify import FIRST, SECONDARY, THIRD_A, THIRD_B, classify
from linkgen.validate import read_mechanism

SAMPLES = Path(__file__).resolve().parents[2] / "samples"


def centres(name: str):
    return {c.name: c for c in classify(read_mechanism(str(SAMPLES / name / f"{name}.yaml")))}


def test_four_bar():
    """Four revolute pairs are the first centres; frame-coupler and crank-rocker each on two lines of them."""
    c = centres("fourbar")
    assert list(c) == ["ic:frame:crank", "ic:frame:coupler", "ic:frame:rocker", "ic:crank:coupler",
                       "ic:crank:rocker", "ic:coupler:rocker"]  # the links' pairs in the file's order
    assert {n for n, x in c.items() if x.kind == FIRST} == {"ic:frame:crank", "ic:frame:rocker",
                                                             "ic:crank:coupler", "ic:coupler:rocker"}
    assert c["ic:frame:crank"].pair == "O1" and c["ic:coupler:rocker"].pair == "B"
    assert c["ic:frame:coupler"].kind == SECONDARY and c["ic:frame:coupler"].lines == ("crank", "rocker")
    assert c["ic:crank:rocker"].kind == SECONDARY and c["ic:crank:rocker"].lines == ("frame", "coupler")
    assert all(x.placed for x in c.values())


def test_prismatic_pair_is_known_and_counted_third_a():
    """The slider-crank: frame-block is the pair S's centre (at infinity), third A as the paper counts it;
    frame-rod and crank-block are placed through it, so they are third A too, placed."""
    c = centres("slider_crank")
    assert c["ic:frame:block"].kind == THIRD_A and c["ic:frame:block"].pair == "S" and c["ic:frame:block"].placed
    assert c["ic:frame:rod"].kind == THIRD_A and c["ic:frame:rod"].placed
    assert c["ic:frame:rod"].lines == ("crank", "block")


def test_two_degrees_of_freedom_leave_third_centres_on_one_line():
    """The five-bar: no secondary centre; each third one on the one line of its neighbours, not placed."""
    c = centres("fivebar")
    thirds = [x for x in c.values() if x.kind != FIRST]
    assert len(thirds) == 5 and all(x.kind == THIRD_A and not x.placed and len(x.lines) == 1 for x in thirds)
    assert c["ic:frame:link1"].lines == ("crank1",)
    assert not any(x.kind == THIRD_B for x in c.values())
