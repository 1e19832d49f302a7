"""The summary in words (linkgen.summary.text): what each line says, from records written by hand."""

from __future__ import annotations

import json

from linkgen.summary.records import Failure, FourBar, InputRange, Position, Summary, Transmission, Travel
from linkgen.summary.text import lines, markdown, one_line, to_json

INPUT = InputRange("theta", "revolute", "deg", 0.0, 360.0, 30.0, -120.5, 120.5, True)
LIMIT = Transmission(3, "B", "RRR", ("coupler", "rocker"), 0.0, (120.5,), 89.5, True)
FAILS = Failure(31, 3, "step 3 (B): the chain cannot close", 119, tuple((float(k), float(k) + 0.5) for k in range(8)))


def _summary(**changes: object) -> Summary:
    base = dict(name="m", title="t", length_unit="mm", angle_unit="deg", grubler=1, mobility=1, redundant=0,
                inputs=(INPUT,), four_bars=(FourBar(("O1", "A", "B", "O2"), ("frame", "crank", "coupler", "rocker"),
                                                     (60.0, 40.0, 50.0, 41.0), "non-Grashof", "triple-rocker",
                                                     "theta"),),
                positions=(Position(3, "B", "limit", (120.5,)),), transmission=(LIMIT,),
                travels=(Travel("S.s", "slide", "mm", -2.0, 8.0, (180.0,), (0.0,), 10.0, False, 1.25),),
                rows=361, near=0, singular=2, failed=119, failures=(FAILS,))
    base.update(changes)
    return Summary(**base)  # type: ignore[arg-type]


def test_lines_say_each_fact_in_the_files_units():
    text = lines(_summary())
    assert text[2] == "input theta: sweep 0 to 360 deg, sketch 30; assembles from -120.5 to 120.5 deg"
    assert text[3].startswith("four-bar O1-A-B-O2 driven by theta: frame 60, crank 40, coupler 50, rocker 41: "
                              "non-Grashof (s + l > p + q), triple-rocker")
    assert text[4] == "limit of step 3 (B) at theta = 120.5 deg"
    assert text[5] == ("transmission angle (sigma is its sine) at step 3 (B, RRR chain of coupler and rocker): "
                       "least 0 at the limit position theta = 120.5 deg; greatest 89.5 deg")
    assert text[6] == "S.s stroke 10 mm: from -2 at theta = 180 deg to 8 at theta = 0 deg; time ratio 1.25"
    assert text[7] == "361 rows: 240 assemble, 0 near a singular position, 2 singular, 119 fail"
    assert text[8].endswith("theta 0 to 0.5, 1 to 1.5, 2 to 2.5, 3 to 3.5, 4 to 4.5, 5 to 5.5 and 2 more runs deg")


def test_one_line_gives_the_rows_their_runs_and_the_worst_transmission_angle():
    line = one_line(_summary(failures=(Failure(31, 3, "x", 119, ((130.0, 229.0),)),)))
    assert line == ("361 rows: 240 assemble, 0 near a singular position, 2 singular, 119 fail (at theta 130 to "
                    "229 deg); least transmission angle 0 deg (step 3, B) at the limit position theta = 120.5 deg")
    flat = Transmission(3, "P", "PPR", ("yoke", "block"), 90.0, (359.0,), 90.0, False)
    assert one_line(_summary(transmission=(flat,), failures=(), failed=0)).endswith("90 deg (step 3, P) at every row")


def test_markdown_escapes_each_line_and_json_holds_every_record():
    assert markdown(_summary(), lambda t: t.replace("_", "\\_")).splitlines()[0] == "- mobility 1 (Gruebler 1)"
    data = json.loads(to_json(_summary()))
    assert data["failures"][0]["ranges"][7] == [7.0, 7.5] and data["inputs"][0]["low"] == -120.5
