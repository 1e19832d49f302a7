"""linkgen.extraction.index: the Solver's look-ups on the Whitworth quick-return (two prismatic pairs: S
guided by the lever, R by the frame), worked out by hand from its file, and the frontier that hands out
pairs in declaration order, each once until pushed again."""

from __future__ import annotations

from spelled import ROOT

from linkgen.extraction.index import Frontier, Index, copy
from linkgen.topology import analyse
from linkgen.validate import read_mechanism


def test_the_index_of_the_whitworth_quick_return():
    index = Index.of(analyse(read_mechanism(str(ROOT / "tests" / "mechanisms" / "whitworth.yaml"))))
    # joints: O1, A, O2, S (prismatic), C, D, R (prismatic); links: frame [O1, O2, R] (fixed), crank [O1, A],
    # lever [O2, S, C], block [A, S], rod [C, D], ram [D, R]
    assert index.joint_names == {"O1", "A", "O2", "S", "C", "D", "R"}
    assert dict(index.order) == {"O1": 0, "A": 1, "O2": 2, "S": 3, "C": 4, "D": 5, "R": 6}
    assert dict(index.link_order) == {"frame": 0, "crank": 1, "lever": 2, "block": 3, "rod": 4, "ram": 5}
    # S: no fixed link carries it and no input names a guide, so the first link listing it (lever) guides it;
    # R: the frame carries it, so the frame guides it
    assert dict(index.slider_of) == {"S": "block", "R": "ram"}
    assert dict(index.guided) == {"lever": ("S",), "frame": ("R",)}
    assert dict(index.slides) == {"lever": ("S",), "block": ("S",), "frame": ("R",), "ram": ("R",)}
    # a prismatic pair's own name is its slider's copy; the guide knows the reference point as S@guide
    assert dict(index.owners) == {"O1": ("frame", "crank"), "O2": ("frame", "lever"), "R@frame": ("frame",),
                                  "A": ("crank", "block"), "S@lever": ("lever",), "C": ("lever", "rod"),
                                  "S": ("block",), "D": ("rod", "ram"), "R": ("ram",)}


def test_a_links_copy_of_a_pair():
    slider_of = {"S": "block"}
    assert copy(slider_of, "S", "block") == "S"
    assert copy(slider_of, "S", "lever") == "S@lever"
    assert copy(slider_of, "A", "lever") == "A"  # a revolute pair is one point on every link


def test_the_frontier_hands_out_pairs_in_declaration_order_each_once_until_pushed_again():
    order = {"O1": 0, "A": 1, "B": 2, "C": 3}
    frontier = Frontier(order, ["C", "A"])
    frontier.push(["B", "A", "C"])  # A and C are queued already
    assert [frontier.pop(), frontier.pop()] == ["A", "B"]
    frontier.push(["O1", "A"])  # A was handed out: it may come again
    assert [frontier.pop(), frontier.pop(), frontier.pop(), frontier.pop()] == ["O1", "A", "C", None]
