"""The six-bar with its Add-link in every language: the same Newton steps, exact rates.

Each program is driven row by row over the sweep; its Newton iteration counts
agree within one with the other languages', and its velocities and accelerations
agree with central differences of its own positions (and rates).
"""

from __future__ import annotations

import subprocess
import sys

import pytest
from programs import CFLAGS, ROOT, build, need

FIG14 = ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"
ROWS = 24
H = 1e-6  # input step of the central differences (radians)

C_DRIVER = r"""
#include <stdio.h>
#include "sixbar_fig14.h"

int main(void)
{
    sixbar_fig14_state st;
    double in[1], din[1] = {1.0}, ddin[1] = {0.0};
    int k, j;
    sixbar_fig14_init(&st);
    for (k = 0; k < @ROWS@; k++) {
        for (j = -1; j <= 1; j++) {
            in[0] = @START@ + k * @STEP@ + j * @H@;
            sixbar_fig14_solve(in, din, ddin, &st);
            printf("%d %d %.17g %.17g %.17g %.17g %.17g %.17g\n", st.status, st.iterations[0], st.J5.x, st.J5.y,
                   st.J5.vx, st.J5.vy, st.J5.ax, st.J5.ay);
        }
    }
    return 0;
}
"""

PY_DRIVER = r"""
import sys
sys.path.insert(0, ".")
import sixbar_fig14 as m
state = {}
for k in range(@ROWS@):
    for j in (-1, 0, 1):
        out = m.solve([@START@ + k * @STEP@ + j * @H@], [1.0], [0.0], 2, state)
        print(out["status"], out["iterations"][0], *("%.17g" % out[c] for c in ("J5.x", "J5.y", "J5.vx", "J5.vy",
                                                                                  "J5.ax", "J5.ay")))
"""

M_DRIVER = r"""
warm = [];
for k = 0:@ROWS@ - 1
    for j = -1:1
        [out, status, warm] = sixbar_fig14_solve(@START@ + k * @STEP@ + j * @H@, 1, 0, warm);
        fprintf('%d %d %.17g %.17g %.17g %.17g %.17g %.17g\n', status, out.iterations(1), out.J5.x, out.J5.y, ...
                out.J5.vx, out.J5.vy, out.J5.ax, out.J5.ay);
    end
end
"""


def _fill(text: str, log) -> str:
    inp = log.inputs[0]
    values = {"ROWS": str(ROWS), "START": repr(inp.start), "STEP": repr((inp.stop - inp.start) / ROWS), "H": repr(H)}
    for key, value in values.items():
        text = text.replace(f"@{key}@", value)
    assert "@" not in text
    return text


def _rows(text: str) -> list[tuple[int, int, list[float]]]:
    out = []
    for line in text.split("\n"):
        if line.strip():
            parts = line.split()
            out.append((int(parts[0]), int(parts[1]), [float(x) for x in parts[2:]]))
    return out


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    folder = tmp_path_factory.mktemp("fig14")
    log = build(FIG14, folder)
    (folder / "driver.c").write_text(_fill(C_DRIVER, log))
    subprocess.run([need("gcc"), *CFLAGS, "sixbar_fig14.c", "driver.c", "-lm", "-o", "driver"], cwd=folder,
                   check=True, capture_output=True)
    c = subprocess.run(["./driver"], cwd=folder, check=True, capture_output=True, text=True).stdout
    py = subprocess.run([sys.executable, "-I", "-c", _fill(PY_DRIVER, log)], cwd=folder, check=True,
                        capture_output=True, text=True).stdout
    (folder / "driver_m.m").write_text(_fill(M_DRIVER, log))
    m = subprocess.run([need("octave-cli"), "--no-gui", "--no-init-file", "--quiet", "driver_m.m"], cwd=folder,
                       capture_output=True, text=True)
    assert m.returncode == 0, m.stderr
    return {"C": _rows(c), "Python": _rows(py), "Octave": _rows(m.stdout)}


def test_same_newton_iterations_in_every_language(runs):
    c = runs["C"]
    assert len(c) == 3 * ROWS and sum(st == 0 for st, _, _ in c) >= ROWS  # the sweep is mostly assembled
    for name in ("Python", "Octave"):
        other = runs[name]
        assert [st for st, _, _ in other] == [st for st, _, _ in c], name
        for (st, its_c, _), (_, its_o, _) in zip(c, other):
            if st <= 0:
                assert abs(its_c - its_o) <= 1, name


@pytest.mark.parametrize("lang", ["C", "Python", "Octave"])
def test_rates_agree_with_central_differences(runs, lang):
    rows = runs[lang]
    checked = 0
    for k in range(0, len(rows), 3):
        (s0, _, lo), (s1, _, mid), (s2, _, hi) = rows[k:k + 3]
        if s0 != 0 or s1 != 0 or s2 != 0:
            continue
        scale_v = max(abs(mid[2]), abs(mid[3]), 1.0)
        scale_a = max(abs(mid[4]), abs(mid[5]), 1.0)
        for i in (0, 1):
            assert (hi[i] - lo[i]) / (2 * H) == pytest.approx(mid[2 + i], abs=1e-6 * scale_v)
            assert (hi[2 + i] - lo[2 + i]) / (2 * H) == pytest.approx(mid[4 + i], abs=1e-5 * scale_a)
        checked += 1
    assert checked >= ROWS // 2
