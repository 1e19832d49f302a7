"""The loop strategy beside Newton (issue 20): per-row time of the C and Python programs, resolver iterations
per row, and the worst position error against the 50-digit reference, for the class-III samples.

Run: .venv/bin/python bench/loops.py (a minute or two; docs/loops.md quotes its output)."""

from __future__ import annotations

import importlib.util
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import settings  # noqa: E402
from knobs import OUT, Sample  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
SAMPLES = [ROOT / "samples" / name / f"{name}.yaml" for name in ("sixbar_fig14", "double_triad")]
STRATEGIES = [{}, {"strategy": "loop"}, {"strategy": "loop", "tolerance": 1e-13}]


def iterations(folder: Path, name: str, samples: int) -> tuple[float, dict[str, int]]:
    """The Python program's resolver iterations per row over its sweep, and which blocks solved the rows."""
    spec = importlib.util.spec_from_file_location(f"loops_{name}_{folder.name}", folder / f"{name}.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    state: dict = {}
    total, used = 0, {}
    for k in range(samples):
        row = module.solve([math.radians(360.0 * k / (samples - 1))], [1.0], [0.0], state=state)
        total += sum(row["iterations"])
        blocks = "/".join(str(b) for b in state["warm"][4]) if state.get("warm") else "failed"
        used[blocks] = used.get(blocks, 0) + 1
    return total / samples, used


def main() -> None:
    print("| sample | strategy | C per row | Python per row | iterations per row | blocks that solved the rows "
          "(index: count) | worst position error (C, L) |")
    print("| --- | --- | ---: | ---: | ---: | --- | ---: |")
    for path in SAMPLES:
        sample = Sample(path)
        for index, setting in enumerate(STRATEGIES):
            m = sample.measure(setting, index)
            folder = OUT / sample.name / str(index)
            per_row, used = iterations(folder, sample.name, 361)
            err = m.errors["C"].points if "C" in m.errors else math.nan
            print(f"| {sample.name} | {settings.label(setting)} | {m.c * 1e9:.0f} ns | "
                  f"{m.python * 1e6:.1f} us | {per_row:.2f} | {used} | {err:.2g} |")


if __name__ == "__main__":
    main()
