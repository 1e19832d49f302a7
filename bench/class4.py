"""The class-IV counts of ``linkgen assemblies`` (docs/assemblies.md), timed: the census at the sketch's
inputs of each class-IV test mechanism (median of runs), and with ``--resultant`` the class-IV
eliminant's last resultant both ways (FLINT's multivariate resultant, then evaluation and
interpolation: linkgen.assemblies.interpolate), checked equal.

    python bench/class4.py [--resultant]
"""

from __future__ import annotations

import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from linkgen.assemblies import assemblies, whole_log  # noqa: E402

MECHANISMS = {"class4_slot": ("tests/regressions/class4_slot.yaml", 5), "class4": ("tests/assemblies/class4.yaml", 5),
              "quaternary_fold": ("tests/mechanisms/quaternary_fold.yaml", 1),
              "quaternary_slide": ("tests/regressions/quaternary_slide.yaml", 1)}


def bench_counts() -> None:
    print("| mechanism | assemblies | degree | real roots | rejected | census, median (s) |")
    print("| --- | --- | --- | --- | --- | --- |")
    for name, (path, repeat) in MECHANISMS.items():
        log = whole_log(str(ROOT / path))
        times = []
        for _ in range(repeat):
            t = time.perf_counter()
            census = assemblies(str(ROOT / path), log)
            times.append(time.perf_counter() - t)
        (g,) = census.solves
        print(f"| {name} | {len(census.assemblies)} | {g.degree} | {g.real_roots} | {g.rejected} | "
              f"{statistics.median(times):.3g} |")


def bench_resultant() -> None:
    import flint

    from linkgen.assemblies import resultant
    from linkgen.assemblies.enumerate import _Walk, shape_of
    from linkgen.assemblies.interpolate import resultant as interpolated
    from linkgen.assemblies.triad import grid, snap

    log = whole_log(str(ROOT / MECHANISMS["quaternary_fold"][0]))
    shape = shape_of(log, log.groups[0])
    walk = _Walk(log, tuple(i.sketch for i in log.inputs), True)
    env = dict(walk.start)
    for s in walk.steps[:next(k for k, s in enumerate(walk.steps) if s.action == "resolve")]:
        env.update(zip(s.outputs, walk.call(s, env)[2]))
    unit = grid(log.length_scale)
    names = [n for b in shape.bodies for n in (b.base, b.base if b.line else b.other_base)]
    bases = [(snap(env[walk.pos[n]][0], unit), snap(env[walk.pos[n]][1], unit)) for n in names]
    ctx = flint.fmpz_mpoly_ctx.get(resultant.NAMES, "lex")
    polys = [resultant.polynomial(ctx, *e) for e in resultant.equations(shape, bases, unit)]
    s1, s2, _ = resultant.eliminate(*polys, ctx)
    t = time.perf_counter()
    a = interpolated(s1, s2, 3, 1)
    mid = time.perf_counter()
    b = resultant.univariate(s1.resultant(s2, "tR"), 1)
    end = time.perf_counter()
    print(f"quaternary_fold's last resultant (degree {a.degree()}): interpolated {mid - t:.3g} s, "
          f"FLINT's fmpz_mpoly.resultant {end - mid:.3g} s, equal: {a == b}")


if __name__ == "__main__":
    bench_counts()
    if "--resultant" in sys.argv:
        bench_resultant()
