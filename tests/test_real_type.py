"""The C programs in float and long double (options: real, linkgen build --real): every sample compiles
without a diagnostic under gcc and clang -O2 with the strict flags (float also with -Wdouble-promotion:
no real is silently computed in double), and its sweep has the double program's status on every row
and its values to the type's bound.

The bound of a column is BOUND_EPS eps of the type, divided by the worst conditioning sigma of any
step over the sweep (the manual's lowest, at least near_singular; 1e-3 on near-singular rows),
relative to the larger of the value and its quantity's scale S (tests/programs.scales; angles
compared modulo 2 pi).  Measured (gcc 12 -O2): float within 10.2 eps_float / sigma of double on
every sample (fivebar; 3.1 to 10.2), long double within 7.3 eps_double / sigma (double's own
rounding: the long double program is the more accurate one); the bound is 32."""

from __future__ import annotations

import math
import subprocess
from pathlib import Path

import pytest
from programs import CXXFLAGS, SAMPLES, STRICT, compile_step, need, parse, scales

from linkgen.backends.c.real import retype
from linkgen.pipeline import build_log
from linkgen.policy import EPSILON
from linkgen.render import render_all
from linkgen.steplog import StepLog
from linkgen.writer import write_all

BOUND_EPS = 32


def _sweep(mechanism: Path, real: str, outdir: Path) -> tuple[StepLog, str]:
    """Build in ``real``, compile under gcc and clang -O2 with no diagnostic, return gcc's CSV."""
    log = build_log(str(mechanism), options={"real": real})
    write_all(render_all(log), str(outdir))
    flags = [*STRICT, "-O2", *(["-Wdouble-promotion"] if real == "float" else [])]
    for cc in ("gcc", "clang"):
        done = subprocess.run([need(cc), *flags, f"{log.name}.c", f"{log.name}_main.c", "-lm", "-o", f"sweep_{cc}"],
                              cwd=outdir, capture_output=True, text=True)
        assert done.returncode == 0 and not done.stderr and not done.stdout, f"{cc}: {done.stderr}"
    return log, subprocess.run([str(outdir / "sweep_gcc")], check=True, capture_output=True, text=True).stdout


def _worst_eps(log: StepLog, exact: str, rounded: str, eps: float) -> float:
    """The worst difference in eps times the bound's conditioning factor; asserts equal statuses."""
    head, ref, st_ref = parse(exact)
    head2, got, st_got = parse(rounded)
    assert head == head2 and st_ref == st_got, [k for k, (a, b) in enumerate(zip(st_ref, st_got)) if a != b][:5]
    sigma = max(min([c.low for c in log.conditioning] + [1.0]), log.policy.near_singular)
    scale = [max(x, y) for x, y in zip(scales(log, ref), scales(log, got))]
    worst = 0.0
    for row_ref, row_got, status in zip(ref, got, st_ref):
        if status > 0:
            continue
        for j, (c, x, y) in enumerate(zip(log.columns, row_ref, row_got)):
            if math.isnan(x) or math.isnan(y):
                assert math.isnan(x) and math.isnan(y), (c.name, x, y)
                continue
            diff = abs(math.remainder(x - y, 2 * math.pi)) if c.quantity == "angle" else abs(x - y)
            factor = 1 / (sigma if status == 0 else log.policy.near_singular)
            worst = max(worst, diff / max(abs(x), abs(y), scale[j]) / (eps * factor))
    return worst


FAST = ("fourbar", "jansen")  # make test; the other samples (the resolver's sixbar_fig14: 12 s) in the long tier
CASES = [pytest.param(p, id=p.stem, marks=() if p.stem in FAST else pytest.mark.long) for p in SAMPLES]


@pytest.mark.parametrize("mechanism", CASES)
def test_float_and_long_double_agree_with_double_to_their_bound(mechanism: Path, tmp_path: Path):
    runs: dict[str, tuple[StepLog, str]] = {}
    for real in ("double", "float", "long double"):
        (tmp_path / real.replace(" ", "_")).mkdir()
        runs[real] = _sweep(mechanism, real, tmp_path / real.replace(" ", "_"))
    log, double = runs["double"]
    worst = (_worst_eps(log, double, runs["float"][1], EPSILON["float"]),
             _worst_eps(log, runs["long double"][1], double, EPSILON["double"]))
    print(f"{log.name}: float {worst[0]:.3g}, long double {worst[1]:.3g} (eps / sigma)")
    assert max(worst) <= BOUND_EPS
    assert runs["float"][1] != double  # computed in float indeed: not double's bits


@pytest.mark.parametrize("real", ["float", "long double"])
def test_the_library_compiled_as_cpp_writes_the_same_sweep(real: str, tmp_path: Path):
    """NAME.c as C++ (g++ -std=c++11 -pedantic -Werror: the same named float and long double functions of math.h),
    linked with the C sweep program: the same CSV as the C library's."""
    log, csv = _sweep(SAMPLES[0].parent.parent / "sixbar_fig14" / "sixbar_fig14.yaml", real, tmp_path)
    compile_step([need("g++"), "-x", "c++", *CXXFLAGS, "-O2", "-c", f"{log.name}.c", "-o", "lib.o"], tmp_path)
    compile_step([need("gcc"), *STRICT, "-O2", "-c", f"{log.name}_main.c", "-o", "main.o"], tmp_path)
    compile_step([need("g++"), "lib.o", "main.o", "-lm", "-o", "sweep_cxx"], tmp_path)
    assert subprocess.run([str(tmp_path / "sweep_cxx")], check=True, capture_output=True, text=True).stdout == csv


def test_float_program_states_its_type_and_thresholds(tmp_path: Path):
    log, _ = _sweep(SAMPLES[0].parent.parent / "sixbar_fig14" / "sixbar_fig14.yaml", "float", tmp_path)
    header = (tmp_path / f"{log.name}.h").read_text()
    assert "Real type: float. Settings: resolver newton (tolerance 7.62939e-06," in header.splitlines()[0]
    assert f"typedef float {log.name}_real;" in header
    assert "double" not in header and "double" not in (tmp_path / f"{log.name}.c").read_text().replace(
        "double program", "")


ATAN2_CHECK = r"""
#include <stdio.h>
#include <stdlib.h>
int main(void)
{
    static const float special[] = { 0.0f, -0.0f, 1.0f, -1.0f, NAN };
    double worst = 0.0;
    long i;
    int j, k, odd = 0;
    srand(7);
    for (i = 0; i < 400000; i++) {
        const float x = (float)(rand() / (double)RAND_MAX * 2 - 1) * (float)pow(10.0, rand() % 7 - 3);
        const float y = (float)(rand() / (double)RAND_MAX * 2 - 1) * (float)pow(10.0, rand() % 7 - 3);
        const double exact = atan2((double)y, (double)x);
        const double ulp = (double)nextafterf(fabsf((float)exact), INFINITY) - (double)fabsf((float)exact);
        const double err = fabs((double)g(y, x) - exact) / ulp;
        if (err > worst) worst = err;
    }
    for (j = 0; j < 5; j++)
        for (k = 0; k < 5; k++) {
            const float a = g(special[j], special[k]), b = atan2f(special[j], special[k]);
            if (!(isnan(a) && isnan(b)) && !(a == b && !signbit(a) == !signbit(b))) odd++;
        }
    printf("%.3f %d\n", worst, odd);
    return 0;
}
"""


def test_float_atan2_within_its_ulps_of_the_double_one(tmp_path: Path):
    """The float programs' own atan2 (linkgen/backends/c/real.py) against glibc's double atan2 on random pairs
    over six decades (worst 2.3 float ulps of the exact angle), and atan2f's values at signed zeros, the axes, the
    diagonals and nan."""
    text = "typedef float m_real;\n" + retype("#include <math.h>\nstatic double g(double y, double x) "
                                              "{ return atan2(y, x); }\n", "float", "m") + ATAN2_CHECK
    (tmp_path / "check.c").write_text(text)
    compile_step([need("gcc"), "-std=c99", "-O2", "-Wall", "-Wextra", "-c", "check.c"], tmp_path)
    compile_step([need("gcc"), "check.o", "-lm", "-o", "check"], tmp_path)
    worst, odd = subprocess.run([str(tmp_path / "check")], check=True, capture_output=True, text=True).stdout.split()
    assert float(worst) <= 2.5 and odd == "0"
