"""Rendering (linkgen.render) reads the step log and the backends, nothing of extraction or evaluation."""

from __future__ import annotations

import json
import subprocess
import sys

STAGES = ("extraction", "evaluate", "singular", "analysis", "pipeline", "prune", "procedure", "topology",
          "validate", "loader", "model", "mobility")


def test_render_and_the_backends_import_no_stage_before_the_step_log():
    code = ("import json, sys, linkgen.render, linkgen.backends as b; b.backends(); "
            "print(json.dumps(sorted(m for m in sys.modules if m.startswith('linkgen'))))")
    loaded = json.loads(subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                                       check=True).stdout)
    assert "linkgen.backends.c" in loaded and "linkgen.steplog" in loaded
    assert [m for m in loaded if m.split(".")[1:2] and m.split(".")[1] in STAGES] == []
