"""linkgen.options: the settings' defaults are the policy's, the command line's replace the file's,
the policy follows the tolerance and cap asked for, and the files' first lines state them."""

from __future__ import annotations

import pytest

from linkgen.options import Options, describe, overridden, policy_for, reference, runtime_policy
from linkgen.policy import POLICY


def test_the_defaults_are_what_linkgen_builds_without_options():
    o = Options()
    assert (o.real, o.strategy, o.polish, o.predictor, o.checks, o.angles, o.units) == (
        "double", "newton", True, 2, True, "angle", "si")
    assert policy_for(o) == POLICY  # the step log of a file without options keeps the policy's numbers


def test_the_tolerance_and_cap_reach_the_policy_the_path_slack_in_proportion():
    p = policy_for(Options(tolerance=1e-6, iterations=30))
    assert (p.tolerance, p.max_iterations) == (1e-6, 30)
    assert p.path_slack == pytest.approx(POLICY.path_slack * 1e4, rel=1e-15)
    assert p.singular == POLICY.singular  # the real type's floor is the renderer's (policy.for_real)


def test_given_settings_replace_the_files_and_unknown_ones_are_refused():
    o = overridden(Options(strategy="closure", checks=False), {"checks": True, "predictor": 2})
    assert (o.strategy, o.checks, o.predictor) == ("closure", True, 2)
    with pytest.raises(ValueError, match="no such option: speed"):
        overridden(Options(), {"speed": 1})


def test_the_settings_as_the_first_lines_state_them():
    o = Options(strategy="fixed-point", tolerance=1e-8, polish=False, predictor=0, checks=False, angles="unit")
    assert describe(o, None) == "Settings: checks off, angles as unit vectors."
    assert describe(o, policy_for(o)) == ("Settings: resolver fixed-point (tolerance 1e-08, at most 8 iterations, "
                                          "polish off, predictor order 0), checks off, angles as unit vectors.")


def test_the_first_lines_state_the_files_units_only_where_asked():
    assert describe(Options(units="file"), None) == "Settings: checks on, angles as angles, units the file's."
    assert describe(Options(units="file", assembly=2), None) == (
        "Settings: checks on, angles as angles, units the file's, assembly 2.")


def test_the_runtime_reads_the_policys_numbers_and_the_resolvers_settings():
    o = Options(strategy="fixed-point", tolerance=1e-6, polish=False, predictor=2)
    p = runtime_policy(policy_for(o), o)
    assert (p.tolerance, p.max_iterations, p.path_share) == (1e-6, POLICY.max_iterations, POLICY.path_share)
    assert (p.strategy, p.polish, p.predictor) == ("fixed-point", False, 2)


def test_the_reference_is_the_default_iteration_with_every_check_and_the_other_settings_kept():
    o = Options(real="float", strategy="fixed-point", tolerance=1e-6, iterations=3, polish=False, predictor=0,
                checks=False, angles="unit")
    assert reference(o) == Options(real="float", tolerance=1e-6, iterations=3, angles="unit")
