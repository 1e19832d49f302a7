"""linkgen.instant.steps: one instant_centre step per centre after the procedure's last step, reading
the pair two links share for a first centre, the fallback blocks moved up past them."""

from __future__ import annotations

from pathlib import Path

from linkgen.instant.steps import centre_records, record_name, with_centres
from linkgen.pipeline import analyse_file

SAMPLES = Path(__file__).resolve().parents[2] / "samples"


def procedure(name: str):
    m, _, proc = analyse_file(str(SAMPLES / name / f"{name}.yaml"))
    return m, proc


def test_steps_after_the_last_with_the_shared_pair():
    m, proc = procedure("fourbar")
    last = max(s.number for s in proc.steps)
    records = centre_records(proc, ("ic:coupler:rocker", "ic:frame:coupler"))
    assert records == {"ic:coupler:rocker": "ic_coupler_rocker", "ic:frame:coupler": "ic_frame_coupler"}
    out = with_centres(proc, m, records)
    added = [s for s in out.steps if s.function == "instant_centre"]
    assert [s.number for s in added] == [last + 1, last + 2]
    shared = added[0]
    assert shared.args[0].var == shared.args[2].var == proc.positions["B"]  # the pair both links carry
    assert (shared.args[1].var, shared.args[3].var) == (proc.angles["coupler"], proc.angles["rocker"])
    assert added[1].pairs == ("O1", "A")  # the frame's first pair, the coupler's first pair
    assert out.variable("ic_frame_coupler").kind == "CENTRE"


def test_fallback_blocks_move_up():
    m, proc = procedure("sixbar_fig14")
    variants = [s.number for s in proc.steps if s.variant]
    assert variants
    out = with_centres(proc, m, centre_records(proc, ("ic:frame:coupler",)))
    assert [s.number for s in out.steps if s.variant] == [n + 1 for n in variants]
    assert [s.function for s in out.steps if not s.variant][-1] == "instant_centre"


def test_record_names_do_not_clash():
    assert record_name("ic:a:b", {"ic_a_b"}) == "ic_a_b_"
    assert with_centres(procedure("fourbar")[1], procedure("fourbar")[0], {}) is not None
