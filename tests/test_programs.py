"""Every generated program is compiled or run, and all agree with the evaluator.

C under gcc -std=c99 -Wall -Wextra -Werror -pedantic (and once more under
AddressSanitizer and UBSan), Python in a subprocess with -I (standard library
only), MATLAB/Octave in octave-cli; their CSVs agree with each other and with
`linkgen run` to 1e-9 (the spec's rule), status codes and nan rows included, and
the three programs compute the same bits.
"""

from __future__ import annotations

import dataclasses
import re
from pathlib import Path

import pytest
from programs import ROOT, SAMPLES, build, compare, different_bits, parse, run_c, run_octave, run_python

from linkgen.evaluate import evaluate, input_rows
from linkgen.render import render_all
from linkgen.table import csv
from linkgen.writer import write_all

MECHANISMS = SAMPLES + sorted((ROOT / "tests" / "mechanisms").glob("*.yaml"))
OCTAVE_ROWS = 25  # Octave is slow: its sweep is checked on fewer rows of the same ranges
# Octave on every sample in `make test`, on the test mechanisms in `make test-long`
OCTAVE = [pytest.param(p, id=p.stem, marks=() if p in SAMPLES else pytest.mark.long) for p in MECHANISMS]


def _id(path: Path) -> str:
    return path.stem


@pytest.fixture(scope="module", params=MECHANISMS, ids=_id)
def built(request, tmp_path_factory):
    outdir = tmp_path_factory.mktemp(request.param.stem)
    log = build(request.param, outdir)
    reference = csv(log, evaluate(log, *input_rows(log, log.samples)))
    return log, outdir, reference


def test_c_agrees_with_the_evaluator(built):
    log, outdir, reference = built
    compare(log, run_c(log, outdir), reference)


def test_python_agrees_with_c(built):
    log, outdir, reference = built
    c = run_c(log, outdir)
    py = run_python(log, outdir)
    compare(log, py, c)
    compare(log, py, reference)


def test_python_and_c_compute_the_same_bits(built):
    """The runtime and the resolver are printed from one definition, in the same order of operations,
    and both languages take cos, sin and atan2 from the C library: every cell is the same double (a
    Python resolver that halved a failing Newton step up to eight times, where C and MATLAB stop after
    three, took another block at a near-singular row of triad_straight_through, 5e-9 off in J2.ax)."""
    log, outdir, _ = built
    differ = different_bits(run_c(log, outdir), run_python(log, outdir))
    assert not differ, differ[:5]


def test_c_is_clean_under_sanitizers(built):
    log, outdir, _ = built
    plain = run_c(log, outdir)
    checked = run_c(log, outdir, ("-g", "-fsanitize=address,undefined", "-fno-sanitize-recover=all"))
    assert checked == plain


@pytest.mark.parametrize("built", OCTAVE, indirect=True)
def test_octave_agrees_with_c(built, tmp_path):
    log, _, _ = built
    small = dataclasses.replace(log, samples=OCTAVE_ROWS)
    write_all(render_all(small), str(tmp_path))
    reference = csv(small, evaluate(small, *input_rows(small, OCTAVE_ROWS)))
    octave, c = run_octave(small, tmp_path), run_c(small, tmp_path)
    compare(small, octave, c)
    compare(small, octave, reference)
    differ = different_bits(octave, c)  # the same order of operations and the same C library
    assert not differ, differ[:5]


def test_failed_rows_are_written_and_the_sweep_goes_on(tmp_path):
    for name in ("fourbar_partial", "sixbar_partial"):
        log = build(ROOT / "tests" / "mechanisms" / f"{name}.yaml", tmp_path / name)
        header, data, status = parse(run_c(log, tmp_path / name))
        failed = [k for k, s in enumerate(status) if s > 0]
        assert failed and len(failed) < len(status)
        n = len(log.inputs)
        for k in failed:
            assert all(x != x for x in data[k][n:])  # every output nan
            assert all(x == x for x in data[k][:n])  # the inputs are written
        assert status[-1] == 0 or failed[-1] == len(status) - 1


# -- the generated sources themselves -----------------------------------------

@pytest.fixture(scope="module")
def sources(tmp_path_factory):
    out = {}
    for path in MECHANISMS:
        log = build(path, tmp_path_factory.mktemp(path.stem))
        out[path.stem] = (log, render_all(log))
    return out


def test_octave_files_use_no_octave_only_syntax(sources):
    """MATLAB is not available here, so its syntax rules are checked on the text."""
    bad = [(r"!=", "!= (use ~=)"), (r"^\s*#", "# comment (use %)"), (r"\+\+|--\s*;|\+=|-=|\*=|/=", "++ or +="),
           (r"\bend(function|if|for|while|switch)\b", "endfunction/endif"), (r'"', "double-quoted string"),
           (r"\bprintf\(", "printf (use fprintf)"), (r"\bputs\(|\bdisp\(", "puts/disp")]
    for log, files in sources.values():
        for fname in (f"{log.name}_solve.m", f"{log.name}.m"):
            for n, line in enumerate(files[fname].decode().splitlines(), 1):
                code = line.split("%", 1)[0] if "'" not in line.split("%", 1)[0] else line
                for pattern, what in bad:
                    assert not re.search(pattern, code), f"{fname}:{n}: {what}: {line}"


def test_script_defines_no_function_and_function_file_starts_with_its_function(sources):
    for _, (log, files) in sources.items():
        script = files[f"{log.name}.m"].decode()
        assert not re.search(r"^\s*function\b", script, re.M)
        solve = files[f"{log.name}_solve.m"].decode()
        assert solve.startswith(f"function [out, status, warm] = {log.name}_solve(")


def test_c_has_no_mutable_static_or_global_state(sources):
    for _, (log, files) in sources.items():
        for fname in (f"{log.name}.c", f"{log.name}_main.c"):
            text = files[fname].decode()
            for line in text.splitlines():
                if re.match(r"^static\s+(?!const\b)(?!int\s+\w+\()(?!void\s+\w+\()(?!double\s+\w+\()", line):
                    pytest.fail(f"{fname}: mutable static: {line}")
                if re.match(r"^(?!static|typedef|#|/|\s|}|{|int main|void |int |$)\w", line):
                    pytest.fail(f"{fname}: global: {line}")
                if re.match(r"^\s+static\s+(?!const\b)", line):
                    pytest.fail(f"{fname}: static local: {line}")


def test_only_used_runtime_functions_are_emitted(sources):
    all_functions = ("crank_input", "slider_input", "link_angle", "offset_angle", "coupler_point", "RRR_links",
                     "PRR_links", "PRP_links", "RPR_links", "PPR_links", "link_residual")
    for _, (log, files) in sources.items():
        used = {s.function for s in log.steps if s.function}
        c_text = files[f"{log.name}.c"].decode()
        py_text = files[f"{log.name}.py"].decode()
        m_text = files[f"{log.name}_solve.m"].decode()
        for fn in all_functions:
            assert (f"static int {fn}(" in c_text or f"static void {fn}(" in c_text) == (fn in used)
            assert (f"\ndef {fn}(" in py_text) == (fn in used)
            assert bool(re.search(rf"^function .*= {fn}\(", m_text, re.M)) == (fn in used)
        assert ("newton" in c_text) == bool(log.groups)
