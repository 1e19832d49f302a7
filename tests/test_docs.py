"""The README and docs/generated-programs.md give the generated programs' signatures exactly.

The signatures are read from the generated files of every sample (Python and numpy through their
syntax trees, C from NAME.h, MATLAB/Octave from the function line of NAME_solve.m), written with NAME
for the mechanism's name, and looked up among the code spans of both documents.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SAMPLES = sorted(p for p in (ROOT / "samples").iterdir() if (p / "expected").is_dir())
DOCS = {"README.md": ROOT / "README.md", "generated-programs.md": ROOT / "docs" / "generated-programs.md"}


def _spans(path: Path) -> set[str]:
    """Every `code span` of a Markdown file (outside fenced blocks), with its line breaks and runs
    of spaces joined."""
    text = re.sub(r"^```.*?^```", "", path.read_text(encoding="utf-8"), flags=re.M | re.S)
    return {" ".join(span.split()) for span in re.findall(r"`([^`]+)`", text)}


def _generic(text: str, name: str) -> str:
    return re.sub(rf"\b{name.upper()}_", "NAME_", re.sub(rf"\b{name}(?=[_.(])", "NAME", text))


def _python(sample: Path, name: str, module: str = "NAME") -> str:
    """solve() of NAME.py (module NAME) or NAME_np.py (module NAME_np)."""
    path = sample / "expected" / f"{module.replace('NAME', name)}.py"
    tree = ast.parse(path.read_text(encoding="utf-8"))
    fn = next(n for n in tree.body if isinstance(n, ast.FunctionDef) and n.name == "solve")
    args = fn.args.args
    defaults = [None] * (len(args) - len(fn.args.defaults)) + fn.args.defaults
    parts = [a.arg if d is None else f"{a.arg}={ast.unparse(d)}" for a, d in zip(args, defaults)]
    return f"{module}.solve({', '.join(parts)}) -> dict"


def _c(sample: Path, name: str) -> list[str]:
    header = (sample / "expected" / f"{name}.h").read_text(encoding="utf-8")
    found = re.findall(rf"^(?:int|void) {name}_(?:solve|init|columns)\([^;]*\);", header, re.M)
    assert len(found) == 3, found
    return [_generic(" ".join(f.split()), name) for f in found]


def _matlab(sample: Path, name: str) -> str:
    first = (sample / "expected" / f"{name}_solve.m").read_text(encoding="utf-8").splitlines()[0]
    assert first.startswith("function "), first
    return _generic(first.removeprefix("function "), name)


@pytest.mark.parametrize("sample", SAMPLES, ids=lambda p: p.name)
@pytest.mark.parametrize("doc", sorted(DOCS))
def test_documents_give_the_generated_signatures(sample: Path, doc: str):
    spans = _spans(DOCS[doc])
    name = sample.name
    wanted = [_python(sample, name), _python(sample, name, "NAME_np"), *_c(sample, name), _matlab(sample, name)]
    missing = [w for w in wanted if w not in spans]
    assert not missing, f"{doc} does not give {missing}"


def test_the_signatures_are_read_as_generated():
    """The readers above see what the files say (so the comparison cannot pass on empty text)."""
    sample = ROOT / "samples" / "fourbar"
    assert _python(sample, "fourbar") == "NAME.solve(inputs, d_inputs, dd_inputs, order=ORDER, state=None) -> dict"
    assert _python(sample, "fourbar", "NAME_np") == \
        "NAME_np.solve(inputs, d_inputs, dd_inputs, order=ORDER, params=None, out=None) -> dict"
    assert _matlab(sample, "fourbar") == "[out, status, warm] = NAME_solve(in, din, ddin, warm)"
    assert "int NAME_solve(const double in[], const double din[], const double ddin[], NAME_state *out);" in \
        _c(sample, "fourbar")


@pytest.mark.parametrize("name", ["sixbar_fig14", "double_triad"])
def test_linkgen_run_gives_the_python_programs_bits_with_add_links(name: str, tmp_path: Path):
    """The README's promise for mechanisms with Add-links: `linkgen run` prints the very CSV of
    `python NAME.py` (the closed-form ones agree within the spec's rule: tests/test_programs.py)."""
    from programs import build, run_python

    from linkgen.evaluate import evaluate
    from linkgen.rows import input_rows
    from linkgen.table import csv

    log = build(ROOT / "samples" / name / f"{name}.yaml", tmp_path)
    assert log.groups
    assert csv(log, evaluate(log, *input_rows(log, log.samples))) == run_python(log, tmp_path)
