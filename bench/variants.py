"""Hand-edited copies of a speed target's generated C, timed against it: whether an edit buys time before
the generators are changed to make it.

    python bench/variants.py fourbar_P                  # the generated NAME.c alone
    python bench/variants.py fourbar_P a.c b.c          # and edited copies of it

Each program (the generated NAME.c, then each copy in the order given) gets a folder of its own with the
target's build: its instructions per configuration (bench/speed.py's callgrind run, exact), its ns per
configuration as the minimum over ROUNDS rounds that run every program once in turn (a shared machine's
load and clock drift hit all of them alike; a single run's median moves by 1-2 ns on a 40 ns target), and
whether its NAME_main.c sweep writes the generated program's CSV byte for byte ("same bits") or not.
"""

from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "bench"))

import languages as lang  # noqa: E402
import speed  # noqa: E402

from linkgen.pipeline import build_log  # noqa: E402
from linkgen.render import render_all  # noqa: E402
from linkgen.writer import write_all  # noqa: E402

ROUNDS = 9


def compare(target: str, edits: list[Path]) -> str:
    """One line per program: instructions, best ns and same bits or not (see the module's docstring)."""
    sample, outputs, _, options = speed.TARGETS[target]
    log = build_log(str(ROOT / "samples" / sample / f"{sample}.yaml"), outputs, options=options)
    with tempfile.TemporaryDirectory() as tmp:
        folders = []
        for k, edit in enumerate([None, *edits]):
            folder = Path(tmp) / f"p{k}"
            write_all(render_all(log), str(folder))
            if edit is not None:
                shutil.copy(edit, folder / f"{log.name}.c")
            lang.C_ROWS, lang.C_RUNS = speed.C_ROWS, 5
            folders.append((str(edit or f"{log.name}.c (generated)"), folder, lang.time_c(log, folder)[1]))
        best = {name: float("inf") for name, _, _ in folders}
        for _ in range(ROUNDS):
            for name, folder, _ in folders:
                out = subprocess.run(["./bench_c"], cwd=folder, check=True, capture_output=True, text=True).stdout
                best[name] = min(best[name], float(out.split()[0]))
        sweep = folders[0][2]
        return "\n".join(f"{name}: {speed.instructions(log, folder):.0f} instructions, {best[name] * 1e9:.1f} ns, "
                         f"{'same bits' if csv == sweep else 'OTHER BITS'}" for name, folder, csv in folders)


if __name__ == "__main__":
    print(compare(sys.argv[1], [Path(a).resolve() for a in sys.argv[2:]]))
