"""The C program's conditioning per step (NAME_state.sigma, which the CSV does not carry) is the Python
program's on every row of the sweep, bit for bit, with the same status: rows that are computed, near
singular, singular and failed.  The C steps write their conditioning straight into the public state and
failed() resets the steps after the failing one; Python keeps a list it publishes whole (the independent
route: another language's program).  make test runs the Stephenson six-bar (its failed rows reset the
chains after the failing one); the long tier the rest."""

from __future__ import annotations

import importlib.util
import math
import subprocess
from pathlib import Path

import pytest
from programs import CFLAGS, ROOT, build, need

DRIVER = r"""
#include <stdio.h>
#include "@NAME@.h"

int main(void)
{
    static const double start[] = @UP@_INPUT_START, stop[] = @UP@_INPUT_STOP, speed[] = @UP@_INPUT_SPEED;
    @NAME@_state st;
    double in[@UP@_N_INPUTS], din[@UP@_N_INPUTS], ddin[@UP@_N_INPUTS];
    int k, i;
    @NAME@_init(&st);
    for (k = 0; k < @UP@_SAMPLES; k++) {
        for (i = 0; i < @UP@_N_INPUTS; i++) {
            in[i] = start[i] + (double)k * (stop[i] - start[i]) / (double)(@UP@_SAMPLES - 1);
            din[i] = speed[i];
            ddin[i] = 0;
        }
        @NAME@_solve(in, din, ddin, &st);
        printf("%d", st.status);
        for (i = 0; i <= @UP@_N_STEPS; i++) printf(" %a", st.sigma[i]);
        printf("\n");
    }
    return 0;
}
"""

# mechanism -> whether its sweep has rows of a non-zero status
MECHANISMS = {"tests/mechanisms/nongrashof_near_change.yaml": True,  # near-singular rows and failed ones
              "tests/mechanisms/parallelogram.yaml": True,  # singular rows
              "tests/mechanisms/stephenson_circuit.yaml": True,  # rows failed at step 3 of 10, chains after it
              "samples/jansen_foot/jansen_foot.yaml": False}  # chains in a row, every row computed


def _c_rows(name: str, folder: Path) -> list[tuple[int, list[float]]]:
    (folder / "sigma_driver.c").write_text(DRIVER.replace("@NAME@", name).replace("@UP@", name.upper()),
                                           encoding="utf-8")
    done = subprocess.run([need("gcc"), *CFLAGS, f"{name}.c", "sigma_driver.c", "-lm", "-o", "sigma_c"], cwd=folder,
                          capture_output=True, text=True)
    assert done.returncode == 0 and not done.stderr, done.stderr
    out = subprocess.run([str(folder / "sigma_c")], check=True, capture_output=True, text=True).stdout
    return [(int(line.split()[0]), [float.fromhex(x) for x in line.split()[1:]]) for line in out.splitlines()]


def _python_rows(name: str, folder: Path) -> list[tuple[int, list[float]]]:
    spec = importlib.util.spec_from_file_location(f"sigma_{name}", folder / f"{name}.py")
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    rows = []
    for k in range(mod.SAMPLES):
        values = [start + k * (stop - start) / (mod.SAMPLES - 1) for start, stop, _ in mod.INPUTS]
        out = mod.solve(values, [speed for _, _, speed in mod.INPUTS], [0.0] * len(values))
        rows.append((out["status"], list(out["sigma"])))
    return rows


def _same(x: float, y: float) -> bool:
    return (math.isnan(x) and math.isnan(y)) or (x == y and math.copysign(1, x) == math.copysign(1, y))


@pytest.mark.parametrize("mechanism", [pytest.param(m, marks=() if "stephenson" in m else pytest.mark.long)
                                       for m in MECHANISMS], ids=lambda m: Path(m).stem)
def test_the_c_state_has_the_python_programs_conditioning_on_every_row(mechanism: str, tmp_path: Path):
    log = build(ROOT / mechanism, tmp_path)
    c, py = _c_rows(log.name, tmp_path), _python_rows(log.name, tmp_path)
    assert len(c) == len(py) == log.samples
    for k, ((st_c, sig_c), (st_py, sig_py)) in enumerate(zip(c, py)):
        assert st_c == st_py, (k, st_c, st_py)
        assert len(sig_c) == len(sig_py) and all(_same(x, y) for x, y in zip(sig_c, sig_py)), (k, sig_c, sig_py)
    assert ({st for st, _ in c} != {0}) == MECHANISMS[mechanism]  # the rows whose bookkeeping differs reached
