"""linkgen.policy, every number that steers the resolver, the continuation and the status rules: the
step log records POLICY whole, each generated program takes the resolver's numbers from its log (a log
given other numbers gives programs with those), and the chains' status thresholds are the ones the
runtime primitives apply (checked on the 3R chain at conditionings worked out by hand)."""

from __future__ import annotations

import dataclasses
import json
import math
import re
import sys
from functools import cache
from pathlib import Path

import pytest

from linkgen import policy
from linkgen.pipeline import build_log
from linkgen.policy import POLICY, Policy
from linkgen.primitives import python_backend
from linkgen.render import render_all
from linkgen.steplog import StepLog

ROOT = Path(__file__).resolve().parents[2]
CYLINDER = ROOT / "tests" / "mechanisms" / "cylinder_triad.yaml"  # a resolver, and a length input
RESOLVER_FIELDS = ("tolerance", "max_iterations", "newton_halvings", "max_move", "min_chain_sigma", "max_halvings",
                   "path_slack", "path_share", "turn_share", "walk_passes")
# Numbers no other part of a program holds, so that finding one is finding the policy.
OTHER = Policy(tolerance=2.5e-11, max_iterations=7, max_halvings=19, max_move=0.125, min_chain_sigma=0.0625,
               step_angle=0.09375, step_length=0.046875, path_slack=3.5e-8, near_singular=1.5e-3, singular=2.5e-7,
               toggle_slack=6.0, good_lever=0.3125, max_input=5e29, newton_halvings=5, walk_passes=999,
               path_share=0.1875, turn_share=0.015625)


@cache
def cylinder() -> StepLog:
    return build_log(str(CYLINDER), None, None, sweep=False)


@cache
def files_with(p: Policy) -> dict[str, str]:
    """The files of the cylinder's log given the policy ``p``, by their names with NAME for the mechanism's."""
    log = dataclasses.replace(cylinder(), policy=p)
    return {name.replace(log.name, "NAME"): text.decode("utf-8") for name, text in render_all(log).items()}


def test_the_numbers_derived_from_others():
    assert POLICY.path_slack == 1e3 * POLICY.tolerance == pytest.approx(1e-7, rel=1e-15)
    assert math.radians(5) == policy.PROBE_ANGLE == 5 * math.pi / 180
    assert policy.LENGTH_SCALES == (1e-30, 1e30) and policy.LENGTH_SCALES[1] == policy.MAX_MAGNITUDE
    assert POLICY.max_input == policy.MAX_MAGNITUDE
    # a singular position is nearer than a near-singular one; a turned block's path is the narrower
    assert 0 < POLICY.singular < POLICY.near_singular < POLICY.min_chain_sigma < 1
    assert 0 < POLICY.turn_share < POLICY.path_share < 1


def test_policy_holds_every_field_as_the_module_defines_it():
    """Each field is one of the module's named numbers, each named number used at most once."""
    named = {k: v for k, v in vars(policy).items() if k.isupper() and isinstance(v, (int, float))}
    values = dataclasses.astuple(POLICY)
    assert len(values) == len(dataclasses.fields(Policy)) == 17
    for f in dataclasses.fields(Policy):
        value = getattr(POLICY, f.name)
        assert any(type(v) is type(value) and v == value for v in named.values()), f.name


def test_the_step_log_records_the_policy_whole():
    log = cylinder()
    assert log.policy == POLICY
    assert json.loads(log.to_json())["policy"] == dataclasses.asdict(POLICY)


def _python_policy(text: str) -> dict[str, float]:
    block = re.search(r"^POLICY = SimpleNamespace\(.*?\n((?:    \w+=.*\n)+)\)", text, re.M)
    assert block is not None
    return {k: float(v) for k, v in re.findall(r"^    (\w+)=(.*),$", block[1], re.M)}


def _octave_policy(text: str) -> dict[str, float]:
    return {k: float(v) for k, v in re.findall(r"^    p\.(\w+) = (.*);$", text, re.M)}


def _c_policy(text: str) -> dict[str, float]:
    block = re.search(r"static const resolver_policy POLICY = \{(.*?)\};", text, re.S)
    struct = re.search(r"typedef struct \{([^{}]*)\} resolver_policy;", text)
    assert block is not None and struct is not None
    names = re.findall(r"^\s*(?:double|int) (\w+);", struct[1], re.M)
    values = [v.strip() for v in block[1].split(",")]
    return {name: float(v) for name, v in zip(names, values) if name in RESOLVER_FIELDS}


@pytest.mark.parametrize("p", [POLICY, OTHER], ids=["POLICY", "other"])
@pytest.mark.parametrize("file, read", [("NAME.py", _python_policy), ("NAME_solve.m", _octave_policy),
                                        ("NAME.c", _c_policy)], ids=["py", "m", "c"])
def test_each_program_takes_the_resolvers_numbers_from_its_log(file, read, p: Policy):
    got = read(files_with(p)[file])
    assert got == {name: float(getattr(p, name)) for name in RESOLVER_FIELDS}


@pytest.mark.parametrize("p", [POLICY, OTHER], ids=["POLICY", "other"])
def test_the_limits_the_input_check_and_the_resolvers_status_follow_the_log(p: Policy):
    files = files_with(p)
    c, py, m = files["NAME.c"], files["NAME.py"], files["NAME_solve.m"]
    log = cylinder()
    limit = repr(p.step_length * log.length_scale)  # a length input: a share of the length scale
    assert f"static const double LIMITS[LINKGEN_NINPUTS] = {{ {limit} }};" in c
    assert f"limits=({limit},)," in py
    assert f"m.limits = [{limit}];" in m
    bound = repr(p.max_input)
    assert f"if (!(fabs(in[i]) <= {bound}) || !(fabs(din[i]) <= {bound}) || !(fabs(ddin[i]) <= {bound}))" in c
    assert f"if not abs(x) <= {bound}:" in py
    assert f"all(abs(in) <= {bound})" in m
    # the resolver's step reports its conditioning against the log's thresholds
    step = log.groups[0].step
    c_note = re.search(rf"note\(w, w->sigma\[{step}\] < (\S+) \? 3 : w->sigma\[{step}\] < (\S+) \? 4 : 0", c)
    py_note = re.search(rf"w\.note\(3 if w\.sigma\[{step}\] < (\S+) else 4 if w\.sigma\[{step}\] < (\S+) else 0", py)
    m_note = re.search(rf"if w\.sigma\({step}\) < (\S+)\n.*\n\s*elseif w\.sigma\({step}\) < (\S+)\n", m)
    for found in (c_note, py_note, m_note):
        assert found is not None and (float(found[1]), float(found[2])) == (p.singular, p.near_singular)


def test_the_manual_states_the_resolvers_numbers():
    md = files_with(OTHER)["NAME.md"]
    for text in ("at most 2.5e-11 of the length scale", "at most 7 steps", "(at most 5 times)", "0.1875 of the",
                 "within 0.015625 of it", "at most 19 times in a row", "at most 999 passes",
                 "conditioning at least 0.0625", "conditioning below 0.0015"):
        assert text in md.replace("\n", " "), text


# -- the chains' thresholds, as the runtime applies them ---------------------------------------------

def rrr_status(height: float) -> tuple[int, float]:
    """The 3R chain over the base (0, 0)-(2, 0) with jb at (1, h): its status and conditioning."""
    record = (math.hypot(1.0, height), 0.0, 0.0)
    st, sigma, _ = python_backend(2)["RRR_links"]((0.0, 0.0, 0.0, 0.0, 0.0, 0.0), (2.0, 0.0, 0.0, 0.0, 0.0, 0.0),
                                                  record, record, 1)
    return st, sigma


@pytest.mark.parametrize("threshold, below, above", [(POLICY.singular, 3, 4), (POLICY.near_singular, 4, 0)])
def test_a_chain_is_singular_or_near_singular_below_the_policys_conditioning(threshold: float, below: int,
                                                                              above: int):
    """sigma is the sine of the angle at jb, 2 h / (1 + h^2): about s for jb far up at h = 2 / s (a thin
    triangle, well conditioned in its sides)."""
    for factor, want in ((0.9, below), (1.1, above)):
        h = 2 / (factor * threshold)
        st, sigma = rrr_status(h)
        assert sigma == pytest.approx(2 * h / (1 + h * h), rel=1e-9)
        assert st == want, (factor, sigma)


@pytest.mark.parametrize("ulps", [1, 16, 24, 40])
def test_a_chain_short_by_less_than_the_toggle_slack_is_a_toggle(ulps: int):
    """Sides 2 and 3 - d over a base of 5: short by d, which is a toggle (status 3) while d is at most
    toggle_slack eps times the longest side, else the chain cannot close (status 1)."""
    l2 = 3.0
    for _ in range(ulps):
        l2 = math.nextafter(l2, 0.0)
    short = 3.0 - l2  # exact (Sterbenz)
    st, _, _ = python_backend(2)["RRR_links"]((0.0, 0.0, 0.0, 0.0, 0.0, 0.0), (5.0, 0.0, 0.0, 0.0, 0.0, 0.0),
                                              (2.0, 0.0, 0.0), (l2, 0.0, 0.0), 1)
    slack = POLICY.toggle_slack * sys.float_info.epsilon * 5.0
    assert st == (3 if short <= slack else 1), (short, slack)
    assert (short <= slack) == (ulps <= 20)  # ulp(3) = eps * 2: 20 ulps is 8 eps * 5


def test_the_policy_of_each_real_type_follows_its_epsilon():
    """float: the tolerance 1e-10 is below float's rounding (64 eps_float = 7.6e-6 is not), and
    so is the singular threshold 1e-7 (8 eps_float = 9.5e-7); double and long double keep POLICY."""
    from linkgen.policy import EPSILON, POLICY, for_real
    assert for_real(POLICY, "double") == POLICY == for_real(POLICY, "long double")
    single = for_real(POLICY, "float")
    assert single.tolerance == 64 * 2.0**-23 == 64 * EPSILON["float"]
    assert single.path_slack == pytest.approx(1e3 * single.tolerance, rel=1e-15)
    assert single.singular == 8 * 2.0**-23 and single.near_singular == POLICY.near_singular
    assert (single.max_iterations, single.max_move) == (POLICY.max_iterations, POLICY.max_move)
