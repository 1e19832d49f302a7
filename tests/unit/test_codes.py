"""codes: what each status of a step log's programs means."""

from __future__ import annotations

from pathlib import Path

from linkgen.pipeline import build_log

ROOT = Path(__file__).resolve().parents[2]
FIG14 = ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"


def test_each_failing_step_has_its_reasons():
    """The six-bar of Fig. 14: a chain fails (1), is singular (3) or near it (4); the resolver
    does not converge (2) or its Jacobian is (near) singular; a residual's pairs coincide (3); a
    link angle's points coincide (1), and so do the pairs a link_point places from (1); and an input out of
    range is step 0's 5."""
    log = build_log(str(FIG14), sweep=False)
    reasons: dict[int, set[int]] = {}
    for c in log.status_codes:
        reasons.setdefault(c.step, set()).add(abs(c.code) % 10)
    want = {"resolve": {2, 3, 4}, "residual": {3}, "link_angle": {1}, "link_point": {1}, "RRR_links": {1, 3, 4}}
    for s in log.steps:
        kind = s.action if s.action in ("resolve", "residual") else s.function
        if s.fails and kind in want:
            assert reasons.pop(s.number) == want[kind], s
    assert reasons == {0: {5}}
    assert [c.step for c in log.status_codes] == sorted(c.step for c in log.status_codes)
    assert all(c.meaning.startswith(f"step {c.step}") for c in log.status_codes)


def test_a_point_placed_linearly_fails_where_its_two_pairs_coincide():
    """The four-bar's P is placed by pair_point (step 4) from B and A: its one failure is reason 1."""
    log = build_log(str(ROOT / "samples" / "fourbar" / "fourbar.yaml"), sweep=False)
    assert log.step(4).function == "pair_point"
    assert [(c.code, c.meaning) for c in log.status_codes if c.step == 4] == [
        (41, "step 4 (P): the two pairs P is placed from coincide")]


def test_a_resolver_limit_position_has_a_code_of_its_own():
    """Rows past sixbar_partial's limit positions fail at the resolve step (8) with reason 1."""
    log = build_log(str(ROOT / "tests" / "mechanisms" / "sixbar_partial.yaml"), sweep=False)
    (code,) = [c for c in log.status_codes if c.code == 81]
    assert log.step(8).action == "resolve" and code.meaning == "step 8 (group1): cannot assemble past a limit position"


def test_a_links_direction_fails_where_its_two_points_coincide():
    log = build_log(str(FIG14), sweep=False, options={"angles": "unit"})
    meaning = {c.code: c.meaning for c in log.status_codes}
    assert log.step(10).function == "link_direction"
    assert meaning[101] == "step 10 (ternary): the two points of ternary coincide"


def test_a_fixed_point_resolver_reports_when_it_does_not_contract():
    """Built with the fixed-point strategy, the resolve step (8: frame, input, Add-link, two chains,
    link_point, residual, resolve) of the Fig. 14 six-bar has reason 6 besides Newton's; the other
    steps' reasons are the same."""
    newton = build_log(str(FIG14), sweep=False)
    fixed = build_log(str(FIG14), sweep=False, options={"strategy": "fixed-point"})
    (stuck,) = set(fixed.status_codes) - set(newton.status_codes)
    assert (stuck.code, stuck.meaning) == (86,
                                           "step 8 (group1): the resolver's fixed-point iteration does not contract")
    assert set(newton.status_codes) < set(fixed.status_codes)
