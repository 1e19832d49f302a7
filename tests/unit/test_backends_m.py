"""linkgen.backends.m, the MATLAB/Octave backend: NAME.m, run by octave-cli, writes the sweep the in-process
evaluator computes (tests/programs.compare) for a mechanism of each kind; NAME_solve returns the row's status
and a struct with a field per output, the conditioning and the CSV row."""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest
from programs import build, compare, need, run_octave
from spelled import ROOT

from linkgen.backends.m import BACKEND
from linkgen.evaluate import evaluate
from linkgen.rows import input_rows
from linkgen.table import csv

MECHANISMS = {"jansen_foot": "samples/jansen_foot/jansen_foot.yaml",  # order 1, many outputs
              "cylinder_triad": "tests/mechanisms/cylinder_triad.yaml",  # a resolver, a length input, a reach
              "parallelogram": "tests/mechanisms/parallelogram.yaml"}  # change points


@pytest.mark.parametrize("name", sorted(MECHANISMS))
def test_the_script_writes_the_evaluators_sweep(name: str, tmp_path: Path):
    log = build(ROOT / MECHANISMS[name], tmp_path)
    assert sorted(p.name for p in tmp_path.glob("*.m")) == sorted(f.replace("NAME", name) for f in BACKEND.files)
    compare(log, run_octave(log, tmp_path), csv(log, evaluate(log, *input_rows(log, log.samples))))


def test_solve_returns_each_output_as_a_struct_of_its_public_fields(tmp_path: Path):
    log = build(ROOT / MECHANISMS["cylinder_triad"], tmp_path)
    values, rates, accs = input_rows(log, 5)
    row = ", ".join(repr(float(x)) for x in values[2])
    script = (f"[out, status] = cylinder_triad_solve([{row}], [{float(rates[2][0])!r}], [0]);\n"
              "printf('%d\\n', status);\nnames = fieldnames(out);\nprintf('%s\\n', names{:});\n")
    done = subprocess.run([need("octave-cli"), "--no-gui", "--no-init-file", "--quiet", "--eval", script],
                          cwd=tmp_path, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    status, *fields = done.stdout.split()
    assert int(status) == int(evaluate(log, values, rates, accs).status[2])
    owners = list(dict.fromkeys(c.name.split(".")[0] for c in log.columns[len(log.inputs):]))
    assert set(owners) <= set(fields) and {"sigma", "columns"} <= set(fields)
