"""The census as a table and as JSON: the count, the groups' polynomials, one row per assembly in the
file's units, the sketch's marked."""

from __future__ import annotations

import json
import math
from pathlib import Path

from linkgen.assemblies import assemblies, whole_log
from linkgen.assemblies.report import inputs_text, table, to_json

ROOT = Path(__file__).resolve().parents[2]
FIG14 = str(ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml")
JANSEN = str(ROOT / "samples" / "jansen" / "jansen.yaml")


def test_the_table_states_the_count_the_polynomial_and_each_assembly():
    log = whole_log(FIG14)
    c = assemblies(FIG14, log, [90.0])
    text = table(log, c)
    lines = text.splitlines()
    assert lines[0] == "sixbar_fig14 at theta_J7 = 90 deg: 4 assemblies"
    assert "characteristic polynomial of degree 6" in text and "4 real roots" in text and "Sturm" in text
    header = next(k for k, line in enumerate(lines) if line.startswith("#"))
    rows = lines[header + 1: header + 5]
    assert [r.split()[0] for r in rows] == ["1", "2", "3", "4"]
    (marked,) = [r for r in rows if r.split()[1] == "*"]
    assert "root 2 of 4 (0 deg)" in marked and "0, 70" in marked and "105, 65" in marked
    assert lines[-1].startswith("* the sketch's assembly")


def test_the_table_says_where_chains_cannot_close():
    log = whole_log(JANSEN)
    text = table(log, assemblies(JANSEN, log, [180.0]))
    assert "6 assemblies" in text.splitlines()[0]
    assert "step 6 (F) cannot close: 2 branches of the walk end there" in text
    assert "F (step 6)" in text


def test_the_json_holds_every_assembly_in_file_units():
    log = whole_log(FIG14)
    c = assemblies(FIG14, log, [90.0])
    doc = json.loads(to_json(log, c))
    assert doc["count"] == 4 and doc["sketch"] == 2 and doc["inputs"] == {"theta_J7": 90.0}
    (g,) = doc["groups"]
    assert (g["degree"], g["real_roots"], g["theta_pi_root"]) == (6, 4, False)
    assert g["thetas"] == [math.degrees(t) for t in c.solves[0].thetas]
    a = doc["assemblies"][1]
    assert a["sketch"] and a["groups"] == [{"group": 1, "root": 2, "of": 4, "theta": 0.0}]
    assert a["positions"]["J4"] == [105.0, 65.0]
    assert abs(a["angles"]["crank"] - 90.0) < 1e-12  # degrees, as the file writes angles
    assert len(g["coefficients"]) == 7 and max(abs(x) for x in g["coefficients"]) == 1.0


def test_inputs_in_the_files_units():
    log = whole_log(str(ROOT / "samples" / "actuator" / "actuator.yaml"))
    c = assemblies(str(ROOT / "samples" / "actuator" / "actuator.yaml"), log, [1900.0])
    assert inputs_text(log, c) == "d_S0_K = 1900 mm"


def test_a_multiple_root_is_said_to_be_a_singular_position():
    from linkgen.assemblies.enumerate import Census, GroupCount

    log = whole_log(FIG14)
    census = Census((math.pi / 2,), solves=[GroupCount(1, "the ternary ternary", 6, 3, False, (-1.0, 0.5, 1.0),
                                                        (1.0,) * 7, ((0.5, 2),))])
    lines = [line for line in table(log, census).splitlines() if "multiplicity" in line]
    assert lines == [f"group 1: the root at theta = {math.degrees(0.5):.6g} deg has multiplicity 2: 2 assemblies "
                     "meet there (a singular position), counted once"]
    assert json.loads(to_json(log, census))["groups"][0]["multiple"] == [{"theta": math.degrees(0.5),
                                                                           "multiplicity": 2}]


def test_the_manual_names_a_class_iv_groups_method():
    """class4_slot's build (two links on their own pivots, counted at every build): the manual's method
    names the class-IV eliminant; the Fig. 14 six-bar's keeps the triads' wording."""
    from linkgen.assemblies.report import manual
    from linkgen.pipeline import build_log

    slot = manual(build_log(str(ROOT / "tests" / "regressions" / "class4_slot.yaml"), sweep=False))
    fig14 = manual(build_log(str(ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"), sweep=False))
    assert slot is not None and fig14 is not None and slot["count"] == 2 and fig14["count"] == 4
    assert "class-IV group's eliminant" in slot["method"] and "class-IV" not in fig14["method"]
    assert "Sturm's theorem" in fig14["method"]
