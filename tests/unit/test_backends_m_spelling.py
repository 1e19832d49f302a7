"""linkgen.backends.m.spelling: the MATLAB/Octave program's constants (structs in the work struct), input
records and calls, run by octave-cli for the samples without a resolver, compute every record as
linkgen.primitives.interpret does (tests/spelled.py), bit for bit, and note each failing step with its own
codes; a resolver step's conditioning is noted through if/elseif; the reach check ends a row past the
reach with the reach's codes."""

from __future__ import annotations

import struct
import subprocess
from pathlib import Path

import pytest
from programs import need
from spelled import NAMES, ROOT, called, computed, reference, row, same, view

from linkgen import status
from linkgen.backends.m import RUNTIME
from linkgen.backends.m.printer import octave_function
from linkgen.backends.m.spelling import Octave
from linkgen.pipeline import build_log
from linkgen.primitives.dsl import Primitive, record_fields
from linkgen.render.view import View, build_view


def bits(x: float) -> str:
    return f"hex2num('{struct.pack('>d', float(x)).hex()}')"


def functions(v: View, name: str, moved: dict[str, str] | None = None) -> str:
    """proc_NAME (the procedure as Octave spells it) and run_NAME (the row, then the code, the notes and, for
    a row that ran through, every computed field as IEEE bits).  ``moved``: initializers in place of the
    spelling's."""
    spell = Octave(v)
    values, rates, accelerations = row(v)
    lines = [f"function [status, w] = proc_{name}(w, in, din, ddin)", "    status = 0;"]
    lines += [f"    {spell.input_record(var, k)}" for k, var in enumerate(v.inputs)]
    lines += [f"    {line}" for s in v.run if s.function for line in spell.call(s, None)]
    lines += ["end", f"function run_{name}()", "    w = struct();", f"    w.sigma = ones(1, {v.last_step});"]
    lines += [f"    w.{c.name} = {(moved or {}).get(c.name) or spell.initializer(c)};" for c in v.constants]
    lines.append(f"    [status, w] = proc_{name}(w, [{' '.join(map(bits, values))}], [{' '.join(map(bits, rates))}], "
                 f"[{' '.join(map(bits, accelerations))}]);")
    lines.append("    printf('code %d\\n', status);")
    lines.append("    if status == 0")
    lines += [f"        printf('{rec}.{f} %s\\n', num2hex(w.{rec}.{f}));" for rec, f in computed(v)]
    lines += ["    end", "end"]
    return "\n".join(lines)


NOTE = "function w = note(w, st, singular, near)\n    printf('note %d %d %d\\n', st, singular, near);\nend"


def run_script(order: int, bodies: dict[str, str], folder: Path, used: list[Primitive]) -> dict[str, list[str]]:
    """One octave-cli run of the primitives at ``order``, note() and each body's run_NAME; output by name."""
    script = "\n".join(["1;", *[octave_function(p, order) for p in used], NOTE,
                        *bodies.values(), *[f"printf('unit {n}\\n'); run_{n}();" for n in bodies]]) + "\n"
    path = folder / f"spelled_{order}.m"
    path.write_text(script, encoding="utf-8")
    done = subprocess.run([need("octave-cli"), "--no-gui", "--no-init-file", "--quiet", path.name], cwd=folder,
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    out: dict[str, list[str]] = {}
    for line in done.stdout.splitlines():
        if line.startswith("unit "):
            current = line[5:]
            out[current] = []
        else:
            out[current].append(line)
    return out


@pytest.fixture(scope="module")
def outputs(tmp_path_factory: pytest.TempPathFactory) -> dict[str, list[str]]:
    folder = tmp_path_factory.mktemp("m_spelling")
    out: dict[str, list[str]] = {}
    for order in sorted({view(n).record_order for n in NAMES}):
        names = [n for n in NAMES if view(n).record_order == order]
        used = list({p.name: p for n in names for p in called(view(n))}.values())
        out.update(run_script(order, {n: functions(view(n), n) for n in names}, folder, used))
    return out


@pytest.mark.parametrize("name", NAMES)
def test_the_spelled_procedure_computes_every_record(name: str, outputs):
    v = view(name)
    lines = outputs[name]
    assert lines[-len(computed(v)) - 1] == "code 0"
    got = dict(line.split() for line in lines[-len(computed(v)):])
    want = reference(v)
    kinds = {r.name: r.kind for r in v.records}
    for rec, f in computed(v):
        k = record_fields(kinds[rec], v.record_order).index(f)
        assert same(struct.unpack(">d", bytes.fromhex(got[f"{rec}.{f}"]))[0], want[rec][k]), (rec, f)
    notes = [tuple(int(x) for x in line.split()[1:]) for line in lines if line.startswith("note ")]
    assert notes == [(0, status.code(s.number, status.SINGULAR), status.code(s.number, status.NEAR_SINGULAR))
                     for s in v.run if s.fails]


def test_a_chain_that_cannot_close_ends_the_row_with_its_steps_code(tmp_path: Path):
    v = view("fourbar")
    chain = next(s for s in v.run if s.function == "RRR_links")
    grounded = next(c for c in v.constants if c.role == "pair" and any(a.var == c.name for a in chain.args))
    far = "struct('x', 1e6, 'y', 1e6, 'dx', 0, 'dy', 0, 'ddx', 0, 'ddy', 0)"
    out = run_script(2, {"far": functions(v, "far", {grounded.name: far})}, tmp_path, called(v))
    assert f"code {status.code(chain.number, status.CANNOT_CLOSE)}" in out["far"]


def test_constants_live_in_the_work_struct_and_a_resolvers_note_is_if_elseif():
    log = build_log(str(ROOT / "tests" / "mechanisms" / "cylinder_triad.yaml"), None, None, sweep=False)
    v = build_view(log)
    spell = Octave(v)
    const = v.constants[0]
    assert spell.ref(const.name, None) == f"w.{const.name}"
    step = log.step(log.groups[0].step)
    p = log.policy
    assert spell.note_sigma(step) == [
        f"if w.sigma({step.number}) < {spell.lit(p.singular)}", f"    w = note(w, 3, {step.number}3, -{step.number}4);",
        f"elseif w.sigma({step.number}) < {spell.lit(p.near_singular)}",
        f"    w = note(w, 4, {step.number}3, -{step.number}4);", "end"]
    assert spell.zero_struct() == "struct('v', 0, 'dv', 0, 'ddv', 0)"
    assert spell.rates("POINT") == ("dx", "dy", "ddx", "ddy") and spell.rates("ANGLE") == ("dthe", "ddthe")


def test_the_reach_check_ends_a_row_past_the_reach_with_its_codes(tmp_path: Path):
    log = build_log(str(ROOT / "tests" / "mechanisms" / "stephenson_circuit.yaml"), None, None, sweep=False)
    spell = Octave(build_view(log))
    assert log.reach is not None and log.reach.low is not None and log.reach.high is not None
    low, high = log.reach.codes()
    probes = (log.reach.low - 0.1, (log.reach.low + log.reach.high) / 2, log.reach.high + 0.1)
    body = "\n".join(f"    {line}" for line in spell.reach_check())
    script = (f"1;\n{RUNTIME.source('reach')}\nfunction status = check(in)\n    status = 0;\n{body}\nend\n"
              + "".join(f"printf('%d\\n', check({bits(x)}));\n" for x in probes))
    (tmp_path / "reach_check.m").write_text(script, encoding="utf-8")
    done = subprocess.run([need("octave-cli"), "--no-gui", "--no-init-file", "--quiet", "reach_check.m"],
                          cwd=tmp_path, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == [str(low), "0", str(high)]
