"""linkgen.backends.py.words: the one Python file NAME.py is a module, so the mechanism name must not be a
keyword (it cannot be imported), a module of the standard library (it would hide it: shown by running
Python beside such a file) or a built-in; no other user name becomes a Python identifier."""

from __future__ import annotations

import builtins
import keyword
import subprocess
import sys
from pathlib import Path

import pytest

from linkgen.backends.py import words as py_words


def test_the_built_ins_are_pythons_public_ones():
    assert {n for n in dir(builtins) if not n.startswith("_")} == py_words.BUILTINS
    assert {"print", "len", "isinstance", "ValueError"} <= py_words.BUILTINS


@pytest.mark.parametrize("name, problem", [
    ("None", "is a Python keyword, so the module None.py cannot be imported"),
    ("lambda", "is a Python keyword, so the module lambda.py cannot be imported"),
    ("json", "is a module of Python's standard library, which json.py would hide"),
    ("print", "is a Python built-in, which `import print` would hide in the importing module"),
    ("fourbar", ""), ("Json", ""), ("match", ""),  # a soft keyword can name a module
])
def test_why_the_python_file_cannot_carry_a_mechanism_name(name: str, problem: str):
    assert py_words.mechanism_problem(name) == problem
    assert keyword.iskeyword(name) == problem.startswith("is a Python keyword")


def test_a_module_named_like_a_standard_one_hides_it_and_a_keyword_cannot_be_imported(tmp_path: Path):
    (tmp_path / "json.py").write_text("HIDDEN = True\n", encoding="utf-8")
    (tmp_path / "lambda.py").write_text("X = 1\n", encoding="utf-8")
    (tmp_path / "main.py").write_text("import json\nprint(json.HIDDEN)\n", encoding="utf-8")
    shown = subprocess.run([sys.executable, "-E", "-s", "main.py"], cwd=tmp_path, capture_output=True, text=True)
    assert shown.stdout.strip() == "True" and "json" in sys.stdlib_module_names
    (tmp_path / "main.py").write_text("import lambda\n", encoding="utf-8")
    refused = subprocess.run([sys.executable, "-E", "-s", "main.py"], cwd=tmp_path, capture_output=True, text=True)
    assert "SyntaxError" in refused.stderr


def test_no_pair_point_or_link_name_is_a_python_word():
    """They are dict keys ("B.x") in NAME.py: the words rule nothing out and rename nothing."""
    for name in ("if", "print", "json", "B"):
        assert py_words.WORDS.field(name) == name and py_words.WORDS.entity_problem(name, "fourbar") == ""
    assert py_words.WORDS.state == ""
