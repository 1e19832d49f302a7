"""Session hooks: the table of worst errors measured by tests/test_properties.py."""

from __future__ import annotations

import os
import sys


def pytest_terminal_summary(terminalreporter):
    sketches = sys.modules.get("sketches")
    if sketches is None or not sketches.WORST:
        return
    table = sketches.summary()
    terminalreporter.section("worst errors measured by the property tests")
    terminalreporter.write_line(table)
    path = os.environ.get("LINKGEN_PROPERTY_REPORT")
    if path:
        with open(path, "w", encoding="utf-8") as f:
            f.write(table + "\n")
