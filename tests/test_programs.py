"""Every generated program is compiled or run, and all agree with the evaluator.

C under gcc -std=c99 -Wall -Wextra -Werror -pedantic (and once more under
AddressSanitizer and UBSan), Python in a subprocess with -I (standard library
only), MATLAB/Octave in octave-cli; their CSVs agree with each other and with
`linkgen run` to 1e-9 (the spec's rule), status codes and nan rows included, and
the three programs compute the same bits.
"""

from __future__ import annotations

import dataclasses
import functools
import importlib.util
import math
import re
import signal
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path

import mpmath
import pytest
import sympy as sp
from programs import (
    ROOT,
    SAMPLES,
    STRICT,
    build,
    compare,
    compile_step,
    different_bits,
    host_source,
    need,
    parse,
    run_c,
    run_octave,
    run_python,
    scales,
)

from linkgen.evaluate import evaluate
from linkgen.render import render_all
from linkgen.render.view import build_view
from linkgen.rows import input_rows
from linkgen.table import csv
from linkgen.writer import write_all

MECHANISMS = SAMPLES + sorted((ROOT / "tests" / "mechanisms").glob("*.yaml"))
OCTAVE_ROWS = 25  # Octave is slow: its sweep is checked on fewer rows of the same ranges
# Octave and the sanitizers on every sample in `make test`, on the test mechanisms in `make test-long`
SAMPLES_NOW = [pytest.param(p, id=p.stem, marks=() if p in SAMPLES else pytest.mark.long) for p in MECHANISMS]


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


@pytest.mark.parametrize("built", SAMPLES_NOW, indirect=True)
def test_c_is_clean_under_sanitizers(built):
    log, outdir, _ = built
    plain = run_c(log, outdir)
    checked = run_c(log, outdir, ("-g", "-fsanitize=address,undefined", "-fno-sanitize-recover=all"))
    assert checked == plain


@pytest.mark.parametrize("built", SAMPLES_NOW, indirect=True)
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
                if re.fullmatch(r"enum\s*\{[\w\s,]*\};", line):
                    continue  # named constants only: no declarator, so no storage
                if re.match(r"^static\s+(?!const\b)(?!inline\b)(?!(int|void|double)\s+\w+\()", line):
                    pytest.fail(f"{fname}: mutable static: {line}")
                if re.match(r"^(?!static|typedef|#|/|\s|}|{|int main|void |int |$)\w", line):
                    pytest.fail(f"{fname}: global: {line}")
                if re.match(r"^\s+static\s+(?!const\b)", line):
                    pytest.fail(f"{fname}: static local: {line}")


def test_only_used_runtime_functions_are_emitted(sources):
    all_functions = ("crank_input", "slider_input", "link_angle", "offset_angle", "coupler_point", "link_point",
                     "pair_point", "RRR_links", "PRR_links", "PRP_links", "RPR_links", "PPR_links", "link_residual")
    for _, (log, files) in sources.items():
        used = {s.function for s in log.steps if s.function}
        c_text = files[f"{log.name}.c"].decode()
        py_text = files[f"{log.name}.py"].decode()
        m_text = files[f"{log.name}_solve.m"].decode()
        for fn in all_functions:
            assert (f"static inline int {fn}(" in c_text or f"static inline void {fn}(" in c_text) == (fn in used)
            assert (f"\ndef {fn}(" in py_text) == (fn in used)
            assert bool(re.search(rf"^function .*= {fn}\(", m_text, re.M)) == (fn in used)
        assert ("newton" in c_text) == bool(log.groups)


# -- callers: wrong calls are refused, a closed pipe ends a sweep quietly -------

CALLERS = {  # one input at order 2; two inputs; a resolver; order 1 (ddin is not read)
    name: ROOT / "samples" / name / f"{name}.yaml" for name in ("fourbar", "fivebar", "sixbar_fig14", "jansen_foot")}
ARRAYS = ("inputs", "d_inputs", "dd_inputs")


@pytest.fixture(scope="module", params=sorted(CALLERS), ids=str)
def caller(request, tmp_path_factory):
    outdir = tmp_path_factory.mktemp(f"caller_{request.param}")
    log = build(CALLERS[request.param], outdir)
    spec = importlib.util.spec_from_file_location(f"caller_{log.name}", outdir / f"{log.name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return log, outdir, module, build_view(log).record_order + 1


def _good_call(log) -> list[list[float]]:
    return [[float(x) for x in rows[1]] for rows in input_rows(log, 3)]


def test_python_refuses_a_wrong_count(caller):
    log, _, module, _ = caller
    n = len(log.inputs)
    assert module.solve(*_good_call(log))["status"] <= 0
    for a, what in enumerate(ARRAYS):
        for count in (0, n + 1):
            args = _good_call(log)
            args[a] = [0.5] * count
            with pytest.raises(ValueError, match=rf"^{log.name}\.solve: expected {n} {what}, got {count}$"):
                module.solve(*args)
        args = _good_call(log)
        args[a] = 0.5
        with pytest.raises(TypeError, match=rf"^{log.name}\.solve: {what} must be a sequence of {n} numbers"):
            module.solve(*args)


def test_python_refuses_a_number_that_is_not_finite(caller):
    log, _, module, reads = caller
    for a, what in enumerate(ARRAYS):
        for k in range(len(log.inputs)):
            for value in (math.nan, math.inf, -math.inf, 1e300, -1.5e30):
                args = _good_call(log)
                args[a][k] = value
                if a < reads:
                    with pytest.raises(ValueError, match=rf"^{log.name}\.solve: {what}\[{k}\] is not finite or larger "
                                                         r"than 1e\+30: "):
                        module.solve(*args)
                else:  # not read at this order: the same answer as the finite call
                    assert repr(module.solve(*args)) == repr(module.solve(*_good_call(log)))


def test_octave_refuses_wrong_calls_with_identifiers(caller):
    log, outdir, _, reads = caller
    n = len(log.inputs)
    cases = []  # (the statement that spoils the call, the error identifier expected: none where not read)
    for a in range(3):
        cases += [(f"args{{{a + 1}}} = zeros(1, {count});", "inputs") for count in (0, n + 1)]
        cases += [(f"args{{{a + 1}}}({k + 1}) = {value};", "finite" if a < reads else "")
                  for k in range(n) for value in ("NaN", "Inf", "-Inf", "1e300", "-1.5e30")]
    good = ", ".join("[" + " ".join(repr(x) for x in row) + "]" for row in _good_call(log))
    lines = []
    for bad, _ in cases:
        lines += [f"args = {{{good}}};", bad,
                  f"try; [out, status] = {log.name}_solve(args{{:}}); disp(sprintf('ok %d', status)); "
                  "catch e; disp(e.identifier); end"]
    (outdir / "refusals.m").write_text("\n".join(lines) + "\n")
    done = subprocess.run([need("octave-cli"), "--no-gui", "--no-init-file", "--no-history", "--quiet",
                           "refusals.m"], cwd=outdir, capture_output=True, text=True)
    assert done.returncode == 0 and not done.stderr, done.stderr
    answers = done.stdout.split("\n")[:-1]
    assert len(answers) == len(cases)
    for (bad, kind), answer in zip(cases, answers):
        assert answer == (f"{log.name}:solve:{kind}" if kind else "ok 0"), (bad, answer)


def test_c_refuses_a_number_that_is_not_finite(caller):
    """The host calls with nan, inf and -inf in every entry half way through the sweep: status
    NAME_STATUS_BAD_INPUT with every output nan where the program reads the entry, the finite
    call's answer where it does not; the state keeps its warm start (the rest of the sweep is
    NAME_main.c's)."""
    log, outdir, _, reads = caller
    (outdir / "host.c").write_text(host_source(log, reads))
    cc = need("gcc")
    compile_step([cc, *STRICT, "-O2", "host.c", f"{log.name}.c", "-lm", "-o", "host"], outdir)
    host = subprocess.run(["./host"], cwd=outdir, capture_output=True, text=True)
    assert host.returncode == 0 and not host.stderr, host.stderr
    assert host.stdout == run_c(log, outdir)


def _into_head(cmd: list[str], cwd: Path, ignore_sigpipe: bool = False) -> tuple[bytes, bytes, int]:
    """Run cmd | head -n 2: what head printed, what cmd wrote to stderr, cmd's exit status."""
    def ignore():
        signal.signal(signal.SIGPIPE, signal.SIG_IGN)
    writer = subprocess.Popen(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                              preexec_fn=ignore if ignore_sigpipe else None)
    head = subprocess.Popen(["head", "-n", "2"], stdin=writer.stdout, stdout=subprocess.PIPE)
    writer.stdout.close()  # head holds the only reader: when it exits, the pipe is closed
    printed = head.communicate()[0]
    err = writer.stderr.read()
    writer.stderr.close()
    return printed, err, writer.wait()


@pytest.fixture(scope="module")
def sweep(tmp_path_factory):
    """fourbar's 361 rows (about 300 kB, more than a pipe holds) in the three languages, and the full C output."""
    outdir = tmp_path_factory.mktemp("pipe")
    log = build(CALLERS["fourbar"], outdir)
    full = run_c(log, outdir)
    assert len(full) > 1 << 17
    return log, outdir, full.encode().split(b"\n", 2)


def test_c_sweep_ends_quietly_on_a_closed_pipe(sweep):
    log, outdir, first = sweep
    printed, err, status = _into_head([f"./{log.name}_c"], outdir)
    assert (printed, err, status) == (first[0] + b"\n" + first[1] + b"\n", b"", -signal.SIGPIPE)
    printed, err, status = _into_head([f"./{log.name}_c"], outdir, ignore_sigpipe=True)  # write errors instead
    assert (printed, err, status) == (first[0] + b"\n" + first[1] + b"\n", b"", 1)


def test_python_sweep_ends_quietly_on_a_closed_pipe(sweep):
    log, outdir, first = sweep
    printed, err, status = _into_head([sys.executable, "-I", f"{log.name}.py"], outdir)
    assert (printed, err, status) == (first[0] + b"\n" + first[1] + b"\n", b"", 1)


def test_octave_sweep_ends_quietly_on_a_closed_pipe(sweep):
    """Octave sees no write error on a closed pipe: the sweep runs to its end, silently (with
    --no-history: Octave 7 otherwise reports at every exit that it cannot save its history)."""
    log, outdir, first = sweep
    printed, err, status = _into_head([need("octave-cli"), "--no-gui", "--no-init-file", "--no-history", "--quiet",
                                       f"{log.name}.m"], outdir)
    assert (printed, err, status) == (first[0] + b"\n" + first[1] + b"\n", b"", 0)


@functools.cache
def _whitworth_closed_form() -> tuple[list[tuple[str, int]], Callable]:
    """The Whitworth quick-return of tests/mechanisms/whitworth.yaml by hand, not by its procedure:
    ([(column, derivative order)], f(t) -> the columns' values at unit crank rate, in mpmath).

    The crank pin A = O1 + r (cos t, sin t) (O1 = (0, 20), r = |(30, 20)|) lies on the slot, a line
    through the lever's pivot O2 = (0, 0), so the lever's angle is psi = atan2(A); its far arm ends
    at C = -30 (cos psi, sin psi); the ram D rides on y = -10 at 50 from C, to the right (the
    sketch's D = (30, -10)), and R's s is D.x - 30.  Velocities and accelerations are sympy's first
    and second derivatives in the crank angle (times omega and omega^2: the crank turns uniformly).
    """
    t = sp.Symbol("t", real=True)
    r = sp.sqrt(30**2 + 20**2)
    ax, ay = r * sp.cos(t), 20 + r * sp.sin(t)
    cx, cy = -30 * ax / sp.sqrt(ax**2 + ay**2), -30 * ay / sp.sqrt(ax**2 + ay**2)
    dx = cx + sp.sqrt(50**2 - (-10 - cy) ** 2)
    fields = {"x": ("x", "vx", "ax"), "y": ("y", "vy", "ay"), "s": ("s", "ds", "dds"), "phi": ("phi", "omega", "alpha")}
    names, exprs = [], []
    for name, e in (("R.x", dx), ("R.y", sp.Integer(-10)), ("R.s", dx - 30), ("C.x", cx), ("C.y", cy),
                    ("lever.phi", sp.atan2(ay, ax)), ("rod.phi", sp.atan2(-10 - cy, dx - cx))):
        stem, field = name.split(".")
        d1 = sp.diff(e, t)
        names += [(f"{stem}.{n}", k) for k, n in enumerate(fields[field])]
        exprs += [e, d1, sp.diff(d1, t)]
    return names, sp.lambdify(t, exprs, "mpmath")


def test_whitworth_agrees_with_its_closed_form(tmp_path):
    """The RPR chain (the slotted lever) and the 2R1P chain (the ram) against geometry alone, every
    row of the C sweep, by the spec's rule (1e-9 of the column's class scale); the other languages
    agree with C in the tests above."""
    log = build(ROOT / "tests" / "mechanisms" / "whitworth.yaml", tmp_path)
    header, data, status = parse(run_c(log, tmp_path))
    assert set(status) == {0}
    scale = dict(zip(header, scales(log, data)))
    omega = log.inputs[0].speed  # rad/s (the file gives 60 deg/s)
    names, closed_form = _whitworth_closed_form()
    assert sorted(n for n, _ in names) == sorted(header[1:-1])
    for row in data:
        got = dict(zip(header, row))
        with mpmath.workdps(30):
            values = closed_form(mpmath.mpf(row[0]))
        for (name, order), value in zip(names, values):
            want = float(value) * omega**order
            diff = got[name] - want
            if name.endswith(".phi"):
                diff = math.remainder(diff, 2 * math.pi)
            assert abs(diff) <= 1e-9 * max(abs(got[name]), abs(want), scale[name]), (row[0], name, got[name], want)
