"""linkgen.backends.c, the C99 backend: the three files it renders, compiled with gcc -Werror and run,
write the sweep the in-process evaluator computes (tests/programs.compare: same statuses, values within the
spec's tolerance) for a mechanism of each kind; the header's public fields follow the order; comment text
cannot close a comment."""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import pytest
from programs import build, compare, need, run_c
from spelled import ROOT

from linkgen.backends.c import BACKEND
from linkgen.evaluate import evaluate
from linkgen.pipeline import build_log
from linkgen.render import render_all
from linkgen.rows import input_rows
from linkgen.table import csv

MECHANISMS = {"jansen_foot": "samples/jansen_foot/jansen_foot.yaml",  # order 1, many outputs
              "cylinder_triad": "tests/mechanisms/cylinder_triad.yaml",  # a resolver, a length input, a reach
              "parallelogram": "tests/mechanisms/parallelogram.yaml"}  # change points


def evaluated(log) -> str:
    return csv(log, evaluate(log, *input_rows(log, log.samples)))


@pytest.mark.parametrize("name", sorted(MECHANISMS))
def test_the_compiled_program_writes_the_evaluators_sweep(name: str, tmp_path: Path):
    log = build(ROOT / MECHANISMS[name], tmp_path)
    assert sorted(p.name for p in tmp_path.glob(f"{name}*.[ch]")) == sorted(
        f.replace("NAME", name) for f in BACKEND.files)
    compare(log, run_c(log, tmp_path), evaluated(log))


@pytest.mark.parametrize("name, fields", [
    ("jansen_foot", ("x, y, vx, vy", "phi, omega", "s, ds")),
    ("cylinder_triad", ("x, y, vx, vy, ax, ay", "phi, omega, alpha", "s, ds, dds")),
])
def test_the_public_records_have_the_fields_of_the_order(name: str, fields: tuple[str, str, str], tmp_path: Path):
    log = build(ROOT / MECHANISMS[name], tmp_path)
    header = (tmp_path / f"{name}.h").read_text(encoding="utf-8")
    point, angle, slide = fields
    assert f"typedef struct {{ double {point}; }} {name}_point;" in header
    assert f"typedef struct {{ double {angle}; }} {name}_angle;" in header
    assert f"typedef struct {{ double {point}, {slide}; }} {name}_prismatic;" in header
    n_columns = re.search(rf"#define {name.upper()}_N_COLUMNS (\d+)", header)
    assert n_columns is not None and int(n_columns[1]) == len(log.columns)


def test_comment_text_cannot_close_the_comment(tmp_path: Path):
    text = "a */ b"
    escaped = BACKEND.filters["cbody"](text)
    assert escaped == "a * / b"
    (tmp_path / "c.c").write_text(f"/* {escaped} */\nint main(void) {{ return 0; }}\n", encoding="utf-8")
    assert subprocess.run([need("gcc"), "-std=c99", "-fsyntax-only", "c.c"], cwd=tmp_path).returncode == 0


def test_a_direction_record_is_declared_only_where_an_output_is_a_direction(tmp_path: Path):
    """angles: unit: the links' public records are NAME_direction {ux, uy, dux, duy, ddux, dduy}; the
    angle build's header declares no NAME_direction."""
    log = build_log(str(ROOT / MECHANISMS["jansen_foot"]), sweep=False, options={"angles": "unit"})
    header = render_all(log)["jansen_foot.h"].decode()
    assert "typedef struct { double ux, uy, dux, duy; } jansen_foot_direction;" in header  # order 1
    assert "    jansen_foot_direction crank;" in header
    assert "_direction" not in (ROOT / "samples" / "jansen_foot" / "expected" / "jansen_foot.h").read_text()
