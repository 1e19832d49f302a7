"""linkgen.instant, the package: the modules its docstring names are there, each with its docstring."""

from __future__ import annotations

import importlib
import re

import linkgen.instant as instant


def test_the_modules_the_package_names_exist():
    named = [n for n in re.findall(r"``(\w+)``", instant.__doc__ or "") if n != "instant_centre"]
    assert named == ["names", "classify", "steps", "record", "table", "figure"]
    for name in named:
        assert importlib.import_module(f"linkgen.instant.{name}").__doc__
