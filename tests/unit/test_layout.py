"""The package's shape: modules and classes small enough to read whole, and one unit-test module per
module of linkgen (tests/unit/test_<dotted path with _>.py; a package's __init__ is the package's own)."""

from __future__ import annotations

import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PACKAGE = ROOT / "linkgen"
UNIT = ROOT / "tests" / "unit"
MAX_MODULE_LINES = 400
MAX_CLASS_LINES = 200

# Modules without a mirror here, on purpose.
UNMIRRORED = {
    "linkgen": "the version and an environment default only",
    "linkgen.__main__": "`python -m linkgen` calls cli.main: tests/test_cli.py runs it",
    "linkgen.cli": "the command line is tested end to end by tests/test_cli.py and tests/test_errors.py",
    "linkgen.closurelog": "records only: tests/unit/test_extraction_closure.py makes them, "
                          "test_render_closure.py reads them",
}
# Runtime sources (backends/<lang>/runtime/) are pasted into the generated programs and run by the
# evaluator, never imported: the row driver and resolver are tested through them
# (tests/unit/test_evaluate.py, tests/test_programs.py, tests/test_np_programs.py).


def modules() -> dict[str, Path]:
    """Every module of the package by its dotted name, the runtime sources left out."""
    out = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        if "runtime" in path.relative_to(PACKAGE).parts:
            continue
        parts = path.relative_to(ROOT).with_suffix("").parts
        out[".".join(parts[:-1] if parts[-1] == "__init__" else parts)] = path
    return out


def mirror(module: str) -> str:
    """linkgen.backends.c.printer -> test_backends_c_printer.py; linkgen.status -> test_status.py."""
    return "test_" + "_".join(module.split(".")[1:]) + ".py"


def test_modules_and_classes_are_small():
    long_modules, long_classes = [], []
    for name, path in modules().items():
        text = path.read_text(encoding="utf-8")
        if len(text.splitlines()) > MAX_MODULE_LINES:
            long_modules.append((name, len(text.splitlines())))
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, ast.ClassDef):
                assert node.end_lineno is not None
                size = node.end_lineno - node.lineno + 1
                if size > MAX_CLASS_LINES:
                    long_classes.append((f"{name}.{node.name}", size))
    assert long_modules == [], f"modules over {MAX_MODULE_LINES} lines"
    assert long_classes == [], f"classes over {MAX_CLASS_LINES} lines"


def test_every_module_has_its_unit_test_module():
    found = modules()
    assert "linkgen.backends.c.printer" in found and "linkgen.status" in found
    assert not any("runtime" in name for name in found)
    mirrors = {name: mirror(name) for name in found if name not in UNMIRRORED}
    assert len(set(mirrors.values())) == len(mirrors), "two modules would share a test module"
    missing = sorted(name for name, test in mirrors.items() if not (UNIT / test).is_file())
    assert missing == []
    assert set(UNMIRRORED) <= set(found), "an exception names no module"
    assert not any((UNIT / mirror(name)).is_file() for name in UNMIRRORED), "an exception has a mirror after all"


def test_the_mirror_of_a_module():
    assert mirror("linkgen.backends") == "test_backends.py"
    assert mirror("linkgen.backends.md.spelling") == "test_backends_md_spelling.py"
    assert mirror("linkgen.validate.header") == "test_validate_header.py"
