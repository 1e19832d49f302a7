"""linkgen.backends.py, the Python backend: NAME.py, run as a script, writes the sweep the in-process
evaluator computes (tests/programs.compare) for a mechanism of each kind; imported, its solve gives a row's
outputs; it imports only the math functions its code calls; text in its docstring cannot end it."""

from __future__ import annotations

import ast
import importlib.util
import re
import sys
from pathlib import Path

import pytest
from programs import build, compare, run_python
from spelled import ROOT

from linkgen.backends.py import BACKEND, python_text
from linkgen.evaluate import evaluate
from linkgen.rows import input_rows
from linkgen.table import csv

MECHANISMS = {"jansen_foot": "samples/jansen_foot/jansen_foot.yaml",  # order 1, many outputs
              "cylinder_triad": "tests/mechanisms/cylinder_triad.yaml",  # a resolver, a length input, a reach
              "parallelogram": "tests/mechanisms/parallelogram.yaml",  # change points
              "scotch_yoke": "samples/scotch_yoke/scotch_yoke.yaml"}


@pytest.mark.parametrize("name", sorted(MECHANISMS))
def test_the_program_writes_the_evaluators_sweep(name: str, tmp_path: Path):
    log = build(ROOT / MECHANISMS[name], tmp_path)
    assert BACKEND.files == ("NAME.py",) and (tmp_path / f"{name}.py").is_file()
    compare(log, run_python(log, tmp_path), csv(log, evaluate(log, *input_rows(log, log.samples))))


@pytest.mark.parametrize("name", sorted(MECHANISMS))
def test_it_imports_the_math_functions_its_code_calls_and_no_other(name: str, tmp_path: Path):
    build(ROOT / MECHANISMS[name], tmp_path)
    text = (tmp_path / f"{name}.py").read_text(encoding="utf-8")
    tree = ast.parse(text)
    imported = {a.name for node in ast.walk(tree) if isinstance(node, ast.ImportFrom) and node.module == "math"
                for a in node.names}
    called = {node.func.id for node in ast.walk(tree) if isinstance(node, ast.Call) and isinstance(node.func, ast.Name)}
    math_functions = {"atan2", "cos", "floor", "sin", "sqrt"}
    assert imported == called & math_functions


def test_solve_gives_a_rows_outputs(tmp_path: Path):
    log = build(ROOT / MECHANISMS["jansen_foot"], tmp_path)
    spec = importlib.util.spec_from_file_location("jansen_foot_generated", tmp_path / "jansen_foot.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    sys.modules.pop("jansen_foot_generated", None)
    values, rates, accs = input_rows(log, 5)
    want = evaluate(log, values, rates, accs)
    out = module.solve(list(values[2]), list(rates[2]), list(accs[2]))
    assert out["status"] == int(want.status[2]) == 0
    foot = next(c for c in log.columns if c.name.endswith(".x") and log.variable(c.variable).role == "point")
    x = want.values[foot.variable][0][2] + log.origin[0]
    assert out[foot.name] == pytest.approx(x, rel=1e-12, abs=1e-12 * log.length_scale)


def test_docstring_text_cannot_end_the_docstring():
    text = 'a "quoted" \\ title """'
    escaped = python_text(text)
    assert ast.literal_eval(f'"""{escaped}"""') == text
    assert re.search(r'(?<!\\)"""', escaped) is None
