"""The Python API (linkgen.api): its doctested examples, and its sweep, rows and summary against
the command line's CSV, the generated C header's exports against the CSV the program writes."""

from __future__ import annotations

import doctest
import os
import pty
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import linkgen
import linkgen.api
from linkgen.evaluate import evaluate
from linkgen.rows import input_rows
from linkgen.table import csv
from tests.programs import CFLAGS, build, need, parse

ROOT = Path(__file__).resolve().parents[2]
SLIDER = ROOT / "samples" / "slider_crank" / "slider_crank.yaml"
SIXBAR = ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"


def test_the_api_examples_run(monkeypatch):
    monkeypatch.chdir(ROOT)
    failed, tried = doctest.testmod(linkgen.api, raise_on_error=False)
    assert tried >= 6 and failed == 0
    failed, tried = doctest.testfile(str(ROOT / "docs" / "api.md"), module_relative=False)
    assert tried >= 3 and failed == 0


@pytest.mark.parametrize("sample", [SLIDER, SIXBAR], ids=lambda p: p.stem)
def test_sweep_is_the_csv_of_linkgen_run(sample, monkeypatch):
    """In chunks (a resolver's warm start carried across them) the same bytes as one evaluation."""
    m = linkgen.load(sample)
    monkeypatch.setattr(linkgen.api, "CHUNK", 50)
    rows = m.sweep(samples=121)
    log = m.log
    assert linkgen.api.csv_text(m, rows) == csv(log, evaluate(log, *input_rows(log, 121)))
    assert rows.dtype.names == m.columns and rows["status"].dtype.kind == "i"
    assert m.sweep(samples=7, order=0).dtype.names == linkgen.load(sample, order=0).columns


def test_at_gives_the_row_of_the_sweep():
    m = linkgen.load(SLIDER)
    rows = m.sweep(samples=13)
    row = m.at([float(rows["theta_O"][5])])
    assert all(row[n] == rows[n][5] or (np.isnan(row[n]) and np.isnan(rows[n][5])) for n in m.columns)
    with pytest.raises(ValueError, match="1 inputs"):
        m.at([1.0, 2.0])


def test_check_is_the_summary_and_load_reports_a_bad_file(tmp_path):
    from linkgen.errors import InputError
    from linkgen.pipeline import build_log
    from linkgen.summary.compute import summarize

    assert linkgen.load(SLIDER).check() == summarize(build_log(str(SLIDER), sweep=False))
    bad = tmp_path / "bad.yaml"
    bad.write_text("linkgen: 1\nname: bad\n")
    with pytest.raises(InputError):
        linkgen.load(bad)


def test_c_header_exports_the_columns_and_the_sweep(tmp_path):
    """A program of the header's macros alone prints the CSV header and the first and last rows' inputs."""
    cc = need("gcc")
    log = build(SIXBAR, tmp_path)
    upper = log.name.upper()
    (tmp_path / "names.c").write_text(f"""#include <stdio.h>
#include "{log.name}.h"

int main(void)
{{
    static const char *const names[{upper}_N_COLUMNS] = {upper}_COLUMN_NAMES;
    static const char *const inputs[{upper}_N_INPUTS] = {upper}_INPUT_NAMES;
    static const double start[{upper}_N_INPUTS] = {upper}_INPUT_START, stop[{upper}_N_INPUTS] = {upper}_INPUT_STOP;
    static const double speed[{upper}_N_INPUTS] = {upper}_INPUT_SPEED;
    int i;
    for (i = 0; i < {upper}_N_COLUMNS; i++) printf("%s,", names[i]);
    printf("status\\n");
    for (i = 0; i < {upper}_N_INPUTS; i++) printf("%s %.17g %.17g %.17g\\n", inputs[i], start[i], stop[i], speed[i]);
    return 0;
}}
""")
    subprocess.run([cc, *CFLAGS, "names.c", "-o", "names"], cwd=tmp_path, check=True)
    out = subprocess.run(["./names"], cwd=tmp_path, check=True, capture_output=True, text=True).stdout.splitlines()
    sweep = subprocess.run([sys.executable, "-I", f"{log.name}.py"], cwd=tmp_path, check=True, capture_output=True,
                           text=True).stdout
    header, data, _ = parse(sweep)
    assert out[0] == sweep.splitlines()[0]
    for k, line in enumerate(out[1:]):
        name, start, stop, speed = line.split()
        assert name == header[k] and float(start) == data[0][k] and float(stop) == data[-1][k]
        assert float(speed) == log.inputs[k].speed


@pytest.mark.long
def test_run_shows_progress_only_on_a_terminal(tmp_path):
    """A long sweep: progress on a terminal's stderr, none into a pipe; stdout the same bytes."""
    linkgen_bin = Path(sys.executable).with_name("linkgen")
    args = [str(linkgen_bin), "run", str(ROOT / "samples" / "fourbar" / "fourbar.yaml"), "--samples", "70001"]
    piped = subprocess.run(args, capture_output=True, check=True)
    assert piped.stderr == b""
    main, follower = pty.openpty()
    with open(tmp_path / "out.csv", "wb") as out:
        done = subprocess.run(args, stdout=out, stderr=follower, check=True)
    os.close(follower)
    shown = b""
    try:
        while chunk := os.read(main, 4096):
            shown += chunk
    except OSError:
        pass
    os.close(main)
    assert done.returncode == 0 and b"rows" in shown and b"100%" in shown
    assert (tmp_path / "out.csv").read_bytes() == piped.stdout
