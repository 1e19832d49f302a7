"""The resolver's iterations themselves (runtime resolver.{c,py,m}) on closed-form groups: Newton and the
fixed-point iteration, polish on and off, in C, Python and Octave alike.

A group is f(a) = a^2 - c (one Add-link, root sqrt(c)) or f(a) = (a0 a1 - 2, a0 - a1 - 1) (two, root (2, 1)).
The expected verdicts, steps and roots are worked here by hand: the fixed-point iteration is
a <- a - f(a) / f'(a0), so from a0 = 0.9 with c = 1 it contracts by |1 - 2 a / 1.8| (about 0.11 at the
root), while from a0 = 0.1, next to the fold at a = 0, its first step lands at 0.1 + 0.99 / 0.2 = 5.05
where f = 23.5025 > 0.99: it does not contract (verdict -1).  Newton converges from both.
"""

from __future__ import annotations

import math
import subprocess
from importlib import resources
from pathlib import Path

import pytest
from programs import CFLAGS, need

TOL = 1e-12
CAP = 16  # the fixed-point iteration from 0.9 needs 12 steps (it contracts by about 0.11), Newton from 0.1 needs 9
HALVINGS = 3
REACH = 10.0
# (name, group, start): the groups as the three languages write them below
CASES = [("near", "square", (0.9,)), ("fold", "square", (0.1,)), ("pair", "pair", (1.8, 0.9))]
SETTINGS = [(s, p) for s in ("newton", "fixed-point") for p in (True, False)]


def _runtime(lang: str, name: str) -> str:
    suffix = {"py": "py", "c": "c", "m": "m"}[lang]
    return resources.files("linkgen.backends").joinpath(lang, "runtime", f"{name}.{suffix}").read_text("utf-8")


def _group(name: str, a: list[float]) -> list[float]:
    return [a[0] * a[0] - 1.0] if name == "square" else [a[0] * a[1] - 2.0, a[0] - a[1] - 1.0]


def _hand_fixed_point(start: tuple[float, ...], polish: bool) -> tuple[int, int]:
    """The scalar fixed-point iteration worked by hand: (verdict, steps)."""
    a, slope, steps = start[0], 2.0 * start[0], 0
    f = a * a - 1.0
    while abs(f) > TOL:
        if steps == CAP - polish:
            return 0, steps
        steps += 1
        a -= f / slope
        if abs(a * a - 1.0) >= abs(f):
            return -1, steps
        f = a * a - 1.0
    return 1, steps + polish


def _hand_newton(start: tuple[float, ...], polish: bool) -> tuple[int, int]:
    """The scalar Newton iteration worked by hand: (verdict, steps)."""
    a = start[0]
    for step in range(1, CAP + 1):
        done = abs(a * a - 1.0) <= TOL
        if done and not polish:
            return 1, step - 1
        a -= (a * a - 1.0) / (2.0 * a)
        if done:
            return 1, step
    return int(not polish and abs(a * a - 1.0) <= TOL), CAP


PY_GROUPS = """
def square(a, da, dda, live):
    return 0, [(a[0] * a[0] - 1.0, 2.0 * a[0] * da[0], 2.0 * da[0] * da[0] + 2.0 * a[0] * dda[0])]

def pair(a, da, dda, live):
    return 0, [(a[0] * a[1] - 2.0, da[0] * a[1] + a[0] * da[1], 0.0), (a[0] - a[1] - 1.0, da[0] - da[1], 0.0)]
"""

C_HARNESS = r"""
#include <math.h>
#include <stdio.h>
#define LINKGEN_NMAX 3
#define LINKGEN_NSENS 1
#define LINKGEN_NADD 2
@RESOLVER@
static int square(void *ctx, const double a[], const double da[], const double dda[], int live, double f[],
                  double df[], double ddf[])
{
    (void)ctx; (void)live;
    f[0] = a[0] * a[0] - 1.0; df[0] = 2.0 * a[0] * da[0];
    if (ddf) ddf[0] = 2.0 * da[0] * da[0] + 2.0 * a[0] * dda[0];  /* null: no accelerations asked for */
    return 0;
}
static int pair(void *ctx, const double a[], const double da[], const double dda[], int live, double f[],
                double df[], double ddf[])
{
    (void)ctx; (void)live; (void)dda;
    f[0] = a[0] * a[1] - 2.0; df[0] = da[0] * a[1] + a[0] * da[1];
    f[1] = a[0] - a[1] - 1.0; df[1] = da[0] - da[1];
    if (ddf) ddf[0] = ddf[1] = 0.0;
    return 0;
}
static void one(group_fn g, int n, double a0, double a1, int strategy, int polish)
{
    resolver_policy p = { @TOL@, @CAP@, @HALVINGS@, @REACH@, 0.0, 0, 0.0, 0.0, 0.0, 0, 0, 0, 1 };
    double a[LINKGEN_NMAX] = { 0.0 }, jac[LINKGEN_NMAX][LINKGEN_NMAX];
    int its, ok;
    a[0] = a0; a[1] = a1;
    p.strategy = strategy; p.polish = polish;
    ok = solve_block(g, 0, n, a, &p, 1.0, jac, NULL, NULL, &its);
    printf("%d %d %.17g %.17g\n", ok, its, a[0], n > 1 ? a[1] : 0.0);
}
int main(void)
{
@CALLS@
    return 0;
}
"""


def _python(tmp_path: Path) -> list[str]:
    space: dict[str, object] = {"sqrt": math.sqrt, "NAN": math.nan}
    exec(_runtime("py", "resolver") + PY_GROUPS, space)
    out = []
    for _, group, start in CASES:
        for strategy, polish in SETTINGS:
            p = type("P", (), dict(tolerance=TOL, max_iterations=CAP, newton_halvings=HALVINGS, max_move=REACH,
                                   strategy=strategy, polish=polish))
            ok, a, its, _ = space["solve_block"](space[group], list(start), p, 1.0)  # type: ignore[operator]
            out.append(f"{ok} {its} {a[0]:.17g} {(a[1] if len(a) > 1 else 0.0):.17g}")
    return out


def _c(tmp_path: Path) -> list[str]:
    calls = [f"    one({group}, {len(start)}, {start[0]!r}, {(start + (0.0,))[1]!r}, "
             f"{'RESOLVER_FIXED_POINT' if s == 'fixed-point' else 'RESOLVER_NEWTON'}, {int(p)});"
             for _, group, start in CASES for s, p in SETTINGS]
    text = C_HARNESS
    for key, value in {"RESOLVER": _runtime("c", "resolver"), "CALLS": "\n".join(calls), "TOL": repr(TOL),
                       "CAP": str(CAP), "HALVINGS": str(HALVINGS), "REACH": repr(REACH)}.items():
        text = text.replace(f"@{key}@", value)
    (tmp_path / "iterations.c").write_text(text, encoding="utf-8")
    subprocess.run([need("gcc"), *CFLAGS, "-Wno-unused-function", "iterations.c", "-lm", "-o", "iterations"],
                   cwd=tmp_path, check=True)
    done = subprocess.run([str(tmp_path / "iterations")], capture_output=True, text=True, check=True)
    return done.stdout.splitlines()


M_GROUPS = """
function [st, res, w] = square(w, a, da, dda, live)
    st = 0;
    res = [a(1) ^ 2 - 1, 2 * a(1) * da(1), 2 * da(1) ^ 2 + 2 * a(1) * dda(1)];
end

function [st, res, w] = pair(w, a, da, dda, live)
    st = 0;
    res = [a(1) * a(2) - 2, da(1) * a(2) + a(1) * da(2), 0; a(1) - a(2) - 1, da(1) - da(2), 0];
end
"""


def _octave(tmp_path: Path) -> list[str]:
    lines = ["1;", _runtime("m", "resolver"), M_GROUPS]
    for _, group, start in CASES:
        for strategy, polish in SETTINGS:
            a = "; ".join(repr(x) for x in start)
            lines.append(f"p = struct('tolerance', {TOL!r}, 'max_iterations', {CAP}, 'newton_halvings', {HALVINGS}, "
                         f"'max_move', {REACH!r}, 'strategy', '{strategy}', 'polish', {int(polish)});")
            lines.append(f"[ok, a, its] = resolver_solve_block(@{group}, struct(), [{a}], p, 1);")
            lines.append("a(end + 1) = 0; printf('%d %d %.17g %.17g\\n', ok, its, a(1), a(2));")
    (tmp_path / "iterations.m").write_text("\n".join(lines) + "\n", encoding="utf-8")
    done = subprocess.run([need("octave-cli"), "--no-gui", "--no-init-file", "--quiet", "iterations.m"],
                          cwd=tmp_path, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return done.stdout.splitlines()


@pytest.fixture(scope="module")
def runs(tmp_path_factory) -> dict[str, list[tuple[int, int, list[float]]]]:
    out = {}
    for lang, run in (("Python", _python), ("C", _c), ("Octave", _octave)):
        lines = run(tmp_path_factory.mktemp(lang))
        out[lang] = [(int(x.split()[0]), int(x.split()[1]), [float(v) for v in x.split()[2:]]) for x in lines]
    return out


def _row(runs, lang: str, case: str, strategy: str, polish: bool):
    k = [c[0] for c in CASES].index(case) * len(SETTINGS) + SETTINGS.index((strategy, polish))
    return runs[lang][k]


def test_the_three_languages_iterate_alike(runs):
    assert runs["C"] == runs["Python"] == runs["Octave"]


@pytest.mark.parametrize("strategy, polish", SETTINGS)
@pytest.mark.parametrize("case", ["near", "fold"])
def test_the_scalar_iterations_take_the_steps_worked_by_hand(runs, case, strategy, polish):
    start = dict((c[0], c[2]) for c in CASES)[case]
    hand = (_hand_fixed_point if strategy == "fixed-point" else _hand_newton)(start, polish)
    ok, steps, a = _row(runs, "Python", case, strategy, polish)
    assert (ok, steps) == hand
    if ok == 1:  # the root is 1: |f| = |a^2 - 1| <= TOL; Newton's polishing step leaves rounding only
        assert abs(a[0] * a[0] - 1.0) <= (4 * 2.0 ** -52 if polish and strategy == "newton" else TOL)


def test_fixed_point_stops_at_the_first_step_that_does_not_contract_next_to_the_fold(runs):
    """From 0.1 the first fixed-point step lands at 5.05 (f = 23.5025 > 0.99): verdict -1 after one
    step, the lengths left where they were; Newton from the same start finds the root."""
    ok, steps, a = _row(runs, "Python", "fold", "fixed-point", True)
    assert (ok, steps, a[0]) == (-1, 1, 0.1)
    assert _row(runs, "Python", "fold", "newton", True)[0] == 1


def test_polish_off_stops_at_the_tolerance_one_step_earlier(runs):
    for case, _, _ in CASES:
        for strategy in ("newton", "fixed-point"):
            on, off = _row(runs, "Python", case, strategy, True), _row(runs, "Python", case, strategy, False)
            if on[0] == 1:
                assert off[0] == 1 and off[1] == on[1] - 1, (case, strategy)


def test_both_strategies_solve_the_two_add_link_group(runs):
    """The pair's root is (2, 1); both iterations reach it (the fixed-point one with J0 at (1.8, 0.9))."""
    for strategy, polish in SETTINGS:
        ok, _, a = _row(runs, "Python", "pair", strategy, polish)
        assert ok == 1
        assert max(abs(f) for f in _group("pair", a)) <= TOL, (strategy, polish)
        assert a == pytest.approx([2.0, 1.0], abs=1e-11)
