"""linkgen.status, the one encoding of a row's status: code, reason and step read each other back over
every step and reason, on ints and numpy arrays alike, and each language's runtime reason_of (run as C,
Python and Octave) classifies every code as linkgen.status does."""

from __future__ import annotations

import subprocess
from importlib import resources
from pathlib import Path

import numpy as np
import pytest
from programs import CFLAGS, need

from linkgen import status

REASONS = (status.CANNOT_CLOSE, status.NOT_CONVERGED, status.SINGULAR, status.NEAR_SINGULAR, status.BAD_INPUT,
           status.NOT_CONTRACTING)
STEPS = range(0, 131)  # three-digit steps too
CODES = sorted({0} | {status.code(s, r) for s in STEPS for r in REASONS})


def test_the_reasons_are_the_digits_one_to_six():
    assert REASONS == (1, 2, 3, 4, 5, 6)
    assert status.FAILED == (status.CANNOT_CLOSE, status.NOT_CONVERGED, status.NOT_CONTRACTING)


def test_only_a_fixed_point_resolver_fails_to_contract():
    assert status.failures("fixed-point") == status.FAILED
    for strategy in ("newton", "closure", None):
        assert status.failures(strategy) == (status.CANNOT_CLOSE, status.NOT_CONVERGED)


@pytest.mark.parametrize("step, reason, code", [
    (3, 1, 31), (3, 2, 32), (3, 3, 33), (3, 4, -34), (0, 5, 5), (12, 1, 121), (12, 4, -124), (104, 3, 1043),
])
def test_code_by_hand(step: int, reason: int, code: int):
    assert status.code(step, reason) == code
    assert (status.step(code), status.reason(code)) == (step, reason)


def test_code_reason_and_step_round_trip_over_every_step_and_reason():
    for s in STEPS:
        for r in REASONS:
            c = status.code(s, r)
            assert (status.step(c), status.reason(c)) == (s, r)
            assert (c < 0) == (r == status.NEAR_SINGULAR)
            assert abs(c) == 10 * s + r
    assert len(CODES) == 1 + len(STEPS) * len(REASONS)  # no two (step, reason) share a code
    assert (status.step(0), status.reason(0)) == (0, 0)


def test_failed_and_singular_by_reason_and_sign():
    for c in CODES:
        r = abs(c) % 10
        assert bool(status.failed(c)) == (c > 0 and r in (1, 2, 6)), c
        assert bool(status.singular(c)) == (c > 0 and r == 3), c


def test_the_functions_work_on_numpy_arrays_as_on_ints():
    steps = np.repeat(np.array(STEPS), len(REASONS))
    reasons = np.tile(np.array(REASONS), len(STEPS))
    codes = status.code(steps, reasons)
    assert codes.tolist() == [status.code(int(s), int(r)) for s, r in zip(steps, reasons)]
    assert np.array_equal(status.step(codes), steps) and np.array_equal(status.reason(codes), reasons)
    assert status.failed(codes).tolist() == [bool(status.failed(int(c))) for c in codes]
    assert status.singular(codes).tolist() == [bool(status.singular(int(c))) for c in codes]


# -- each language's reason_of --------------------------------------------------------------------

def runtime(lang: str) -> str:
    return resources.files("linkgen.backends").joinpath(lang, "runtime", f"status.{lang}").read_text(encoding="utf-8")


def python_reasons() -> list[int]:
    space: dict[str, object] = {}
    exec(runtime("py"), space)
    reason_of = space["reason_of"]
    return [reason_of(c) for c in CODES]  # type: ignore[operator]


def c_reasons(tmp_path: Path) -> list[int]:
    codes = ", ".join(map(str, CODES))
    main = (f"#include <stdio.h>\n{runtime('c')}\nstatic const int codes[] = {{{codes}}};\n"
            "int main(void)\n{\n    unsigned k;\n    for (k = 0; k < sizeof codes / sizeof codes[0]; k++) "
            "printf(\"%d\\n\", reason_of(codes[k]));\n    return 0;\n}\n")
    (tmp_path / "status.c").write_text(main, encoding="utf-8")
    subprocess.run([need("gcc"), *CFLAGS, "status.c", "-o", "status"], cwd=tmp_path, check=True)
    return [int(x) for x in subprocess.run([str(tmp_path / "status")], capture_output=True, text=True,
                                           check=True).stdout.split()]


def octave_reasons(tmp_path: Path) -> list[int]:
    script = f"1;\n{runtime('m')}\nfor c = [{' '.join(map(str, CODES))}]\n    printf('%d\\n', reason_of(c));\nend\n"
    (tmp_path / "reasons.m").write_text(script, encoding="utf-8")
    done = subprocess.run([need("octave-cli"), "--no-gui", "--no-init-file", "--quiet", "reasons.m"], cwd=tmp_path,
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return [int(x) for x in done.stdout.split()]


@pytest.mark.parametrize("lang", ["py", "c", "m"])
def test_each_runtime_reason_of_classifies_every_code_as_linkgen_status(lang: str, tmp_path: Path):
    got = {"py": python_reasons, "c": lambda: c_reasons(tmp_path), "m": lambda: octave_reasons(tmp_path)}[lang]()
    assert len(got) == len(CODES)
    for c, r in zip(CODES, got):
        # a program reads a positive code's reason, and takes a negative one (near singular) as no failure
        assert r == (status.reason(c) if c > 0 else 0), c
        assert (r in status.FAILED) == bool(status.failed(c)), c
        assert (r == status.SINGULAR) == bool(status.singular(c)), c
