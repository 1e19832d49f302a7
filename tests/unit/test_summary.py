"""linkgen.summary as a package: its text and records read no evaluation, so the manual's backend,
which writes the summary, imports no stage before the step log (tests/unit/test_render.py)."""

from __future__ import annotations

import json
import subprocess
import sys


def test_text_and_records_import_no_evaluation():
    code = ("import json, sys, linkgen.summary.text; "
            "print(json.dumps(sorted(m for m in sys.modules if m.startswith('linkgen'))))")
    loaded = json.loads(subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                                       check=True).stdout)
    assert "linkgen.summary.records" in loaded
    assert not {"linkgen.summary.compute", "linkgen.evaluate", "linkgen.analysis"} & set(loaded)
