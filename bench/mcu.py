"""The real-type knob where it is meant for: a microcontroller with a single-precision FPU.

    python bench/run.py mcu

On x86-64 a scalar float costs what a double does (docs/performance.md, Knobs), so the float build is
1.1-1.4x the double one there. Embedded users run the C on a Cortex-M4F, whose FPU computes in float
only: there every double operation is a call into the compiler's soft-float library. This group builds
each sample's C library in double and in float with arm-none-eabi-gcc -O2 for a Cortex-M4 with its FPU
(-mfpu=fpv4-sp-d16 -mfloat-abi=hard, newlib's libm), runs it on QEMU's mps2-an386 board (a Cortex-M4)
one instruction a translation block with every block logged, and counts the instructions NAME_solve and
what it calls execute per configuration: the driver sweeps the file's first ROWS rows (its spacing: warm
starts) once or twice, and the difference of the two runs' counts over ROWS is one sweep's, start-up and
printing cancelled. An instruction count on an emulator, not a time: on the M4 most instructions take a
cycle (vdiv.f32 and vsqrt.f32 14, a taken branch 2-4), in float code and in the soft-float library
alike, so the ratio of counts is the ratio of times to within those exceptions. The same drivers
compiled for x86-64 with gcc in double give the reference rows: each M4 build's sweep is checked against
them (double: 1e-12 of each quantity's scale, float: the float build's bound on x86-64, 32 eps of float)
before its count is reported.
Needs gcc-arm-none-eabi, libnewlib-arm-none-eabi and qemu-system-arm (apt); without them the group
says so and writes nothing.
"""

from __future__ import annotations

import math
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

from performance_doc import write_section

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from linkgen.pipeline import build_log  # noqa: E402
from linkgen.render import render_all  # noqa: E402
from linkgen.writer import write_all  # noqa: E402

HERE = Path(__file__).resolve().parent / "mcu"
SAMPLES = ("fourbar", "jansen_foot", "jansen", "sixbar_fig14")
ROWS = 10  # the file's first rows: a warm sweep at the file's spacing
TOOLS = ("arm-none-eabi-gcc", "qemu-system-arm")
M4 = ["-mcpu=cortex-m4", "-mthumb", "-mfpu=fpv4-sp-d16", "-mfloat-abi=hard"]
FLOAT_EPS = 2.0**-23
FLOAT_BOUND = 32  # eps of float of each quantity's scale (tests/test_real_type.py's bound, sigma 1 here)
DOUBLE_BOUND = 1e-12

DRIVER = r"""#include <stdio.h>
#include "@NAME@.h"

static const double start[] = @UP@_INPUT_START, stop[] = @UP@_INPUT_STOP, speed[] = @UP@_INPUT_SPEED;

/* REPEAT sweeps of the file's first ROWS rows, then one more that prints every row. */
int main(void)
{
    static @NAME@_state st;
    @NAME@_real in[ROWS][@UP@_N_INPUTS], din[@UP@_N_INPUTS], ddin[@UP@_N_INPUTS], col[@UP@_N_COLUMNS];
    int k, i, run, bad = 0;
    for (k = 0; k < ROWS; k++)
        for (i = 0; i < @UP@_N_INPUTS; i++)
            in[k][i] = (@NAME@_real)(start[i] + k * (stop[i] - start[i]) / (@UP@_SAMPLES - 1));
    for (i = 0; i < @UP@_N_INPUTS; i++) { din[i] = (@NAME@_real)speed[i]; ddin[i] = 0; }
    for (run = 0; run < REPEAT; run++) {
        @NAME@_init(&st);
        for (k = 0; k < ROWS; k++) bad += @NAME@_solve(in[k], din, ddin, &st) > 0;
    }
    @NAME@_init(&st);
    for (k = 0; k < ROWS; k++) {
        int status = @NAME@_solve(in[k], din, ddin, &st);
        @NAME@_columns(in[k], &st, col);
        for (i = 0; i < @UP@_N_COLUMNS; i++) printf("%.17g,", (double)col[i]);
        printf("%d\n", status);
    }
    return bad < 0;
}
"""


def _fill(text: str, name: str) -> str:
    return text.replace("@NAME@", name).replace("@UP@", name.upper())


def _m4(folder: Path, name: str, repeat: int) -> Path:
    exe = folder / f"m4_{repeat}.elf"
    subprocess.run(["arm-none-eabi-gcc", *M4, "-O2", "-std=c99", f"-DROWS={ROWS}", f"-DREPEAT={repeat}",
                    "-nostartfiles", "-T", str(HERE / "mps2.ld"), "--specs=rdimon.specs", str(HERE / "start.c"),
                    "driver.c", f"{name}.c", "-lm", "-o", str(exe)], cwd=folder, check=True)
    return exe


def _count(exe: Path, folder: Path) -> tuple[int, str]:
    """The instructions an M4 run executes (QEMU's log of single-instruction blocks, read through a
    pipe) and what it prints."""
    fifo = folder / "trace"
    if fifo.exists():
        fifo.unlink()
    os.mkfifo(fifo)
    counter = subprocess.Popen(["grep", "-c", "^Trace", str(fifo)], stdout=subprocess.PIPE, text=True)
    run = subprocess.run(["qemu-system-arm", "-M", "mps2-an386", "-nographic", "-semihosting", "-singlestep",
                          "-d", "exec,nochain", "-D", str(fifo), "-kernel", str(exe)],
                         capture_output=True, text=True, timeout=1800, check=True)
    out, _ = counter.communicate()
    return int(out), run.stdout


def _rows(text: str) -> list[list[float]]:
    return [[float(x) for x in line.split(",")] for line in text.strip().splitlines()]


def _worst(got: list[list[float]], want: list[list[float]], quantities: list[str]) -> float:
    """The largest difference of two sweeps over each column's quantity scale (angles at least 1)."""
    scale: dict[str, float] = {}
    for row in want:
        for q, x in zip(quantities, row):
            if math.isfinite(x):
                scale[q] = max(scale.get(q, 1.0 if q == "angle" else 0.0), abs(x))
    worst = 0.0
    for a, b in zip(got, want):
        assert a[-1] == b[-1], "another status"
        for q, x, y in zip(quantities, a, b):
            if not (math.isnan(x) and math.isnan(y)):
                worst = max(worst, abs(x - y) / max(scale[q], 1e-300))
    return worst


def measure(sample: str, real: str, folder: Path) -> tuple[float, float]:
    """Instructions per configuration on the M4 and the sweep's worst difference from x86-64's double."""
    log = build_log(str(ROOT / "samples" / sample / f"{sample}.yaml"), options={"real": real})
    write_all(render_all(log), str(folder))
    (folder / "driver.c").write_text(_fill(DRIVER, log.name))
    host = folder / "host"
    if not host.exists():  # the reference: the double library on this machine (the first build is double)
        subprocess.run(["gcc", "-O2", "-std=c99", f"-DROWS={ROWS}", "-DREPEAT=0", "driver.c", f"{log.name}.c", "-lm",
                        "-o", str(host)], cwd=folder, check=True)
    want = _rows(subprocess.run([str(host)], capture_output=True, text=True, check=True).stdout)
    (once, text), (twice, _) = (_count(_m4(folder, log.name, r), folder) for r in (1, 2))
    quantities = [c.quantity for c in log.columns] + ["status"]
    return (twice - once) / ROWS, _worst(_rows(text), want, quantities)


def bench_mcu() -> None:
    missing = [t for t in TOOLS if shutil.which(t) is None]
    if missing:
        print(f"mcu: {', '.join(missing)} missing (apt install gcc-arm-none-eabi libnewlib-arm-none-eabi "
              "qemu-system-arm): nothing measured")
        return
    lines = ["## Float on a microcontroller", "",
             "`make bench` (`bench/mcu.py`): each sample's C library built in double and in float for a Cortex-M4",
             "with its single-precision FPU (arm-none-eabi-gcc -O2, newlib), run on QEMU's mps2-an386 board, and",
             "the instructions NAME_solve executes per configuration counted (order 2, the file's outputs, a",
             f"sweep of the file's first {ROWS} rows, warm state kept).  On x86-64 a float costs what a double",
             "does (see Knobs); on the M4 a double operation is a call into the soft-float library.  Counts, not",
             "times: most M4 instructions take one cycle (vdiv.f32 and vsqrt.f32 14, a taken branch 2-4).  Each",
             "run's sweep is checked against the double library on x86-64: `error` is its worst difference over",
             "each quantity's scale.", "",
             "| sample | double: instructions | float: instructions | float's speed-up | double's error | "
             "float's error |",
             "| --- | ---: | ---: | ---: | ---: | ---: |"]
    for sample in SAMPLES:
        with tempfile.TemporaryDirectory() as tmp:
            (d, d_err), (f, f_err) = (measure(sample, real, Path(tmp)) for real in ("double", "float"))
        assert d_err <= DOUBLE_BOUND and f_err <= FLOAT_BOUND * FLOAT_EPS, (sample, d_err, f_err)
        lines.append(f"| {sample} | {d:.0f} | {f:.0f} | {d / f:.1f}x | {d_err:.1e} | {f_err:.1e} "
                     f"({f_err / FLOAT_EPS:.1f} eps of float) |")
    text = "\n".join(lines) + "\n"
    print(text)
    write_section("Float on a microcontroller", text)
