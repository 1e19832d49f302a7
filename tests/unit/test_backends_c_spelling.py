"""linkgen.backends.c.spelling: the C program's constants (braced initializers), input records and calls,
compiled with gcc -Werror for the samples without a resolver and run, compute every record as
linkgen.primitives.interpret does (tests/spelled.py), bit for bit, and note each failing step with its own
codes; a chain that cannot close returns its step's code; the reach check, compiled, ends a row past the
reach with the reach's codes."""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest
from programs import CFLAGS, need
from spelled import NAMES, ROOT, called, computed, reference, row, same, view

from linkgen import status
from linkgen.backends.c import RUNTIME
from linkgen.backends.c.printer import c_function, field
from linkgen.backends.c.spelling import C
from linkgen.pipeline import build_log
from linkgen.primitives.dsl import record_fields
from linkgen.render.view import View, build_view


def records(order: int) -> str:
    levels = ("P", "DP", "DDP")[: order + 1]
    return (f"typedef struct {{ double x, y; }} VEC2;\ntypedef struct {{ VEC2 {', '.join(levels)}; }} POINT;\n"
            f"typedef struct {{ double {', '.join(('the', 'dthe', 'ddthe')[: order + 1])}; }} ANGLE;\n"
            f"typedef struct {{ double {', '.join(('v', 'dv', 'ddv')[: order + 1])}; }} VARIABLE;\n")


def unit(v: View, name: str, moved: dict[str, str] | None = None) -> str:
    """One translation unit: the procedure of the sample as C spells it, run at ``row(v)``, printing the
    returned code, every note and every computed field (hex).  ``moved``: initializers put in place of the
    spelling's (by constant)."""
    spell = C(v)
    order = v.record_order
    values, rates, accelerations = row(v)
    lines = ["#include <float.h>", "#include <math.h>", "#include <stdio.h>", "", records(order)]
    lines += [c_function(p, order) for p in called(v)]
    lines += [f"static const {c.kind} {c.name} = {(moved or {}).get(c.name) or spell.initializer(c)};"
              for c in v.constants]
    lines.append("typedef struct {")
    lines += [f"    {r.kind} {r.name};" for r in v.records]
    lines += ["} work;", ""]
    lines += ["static void note(work *w, int st, int singular, int near)", "{",
              '    printf("note %d %d %d %d\\n", st, singular, near, (int)(w != NULL));', "}", "", FAILED]
    lines += ["static int run(work *w, const double in[], const double din[], const double ddin[], state *out)", "{",
              "    int st;", "    (void)st; (void)in; (void)din; (void)ddin;"]
    lines += [f"    {spell.input_record(var, k)}" for k, var in enumerate(v.inputs)]
    lines += [f"    {line}" for s in v.run if s.function for line in spell.call(s, None)]
    lines += ["    return 0;", "}", "", f"void run_{name}(void);", f"void run_{name}(void)", "{"]
    lines += [f"    static const double in[] = {{{', '.join(repr(x) for x in values)}}};",
              f"    static const double din[] = {{{', '.join(repr(x) for x in rates)}}};",
              f"    static const double ddin[] = {{{', '.join(repr(x) for x in accelerations)}}};",
              "    work w;", "    state failure = {0, 0, {0.0}};", "    int code = run(&w, in, din, ddin, &failure);",
              '    printf("code %d failed %d at %d\\n", code, failure.code, failure.step);']
    for rec, f in computed(v):
        kind = next(r.kind for r in v.records if r.name == rec)
        lines.append(f'    printf("{rec}.{f} %a\\n", w.{rec}.{field(kind, f)});')
    lines.append("}")
    return "\n".join(lines) + "\n"


# the public state the steps write their conditioning into, and failed() of the program: the row ends with a
# failure's code at a step (here noted in out->code)
FAILED = ("typedef struct { int code, step; double sigma[64]; } state;\n"
          "static int failed(state *out, int code, int step)\n"
          "{\n    out->code = code;\n    out->step = step;\n    return code;\n}\n")


def run_units(units: dict[str, str], folder: Path) -> dict[str, list[str]]:
    """Compile the units with a main that runs each, in one gcc call; each unit's output lines."""
    for name, text in units.items():
        (folder / f"{name}.c").write_text(text, encoding="utf-8")
    main = "".join(f"void run_{n}(void);\n" for n in units) + "int main(void)\n{\n" + "".join(
        f'    printf("unit {n}\\n");\n    run_{n}();\n' for n in units) + "    return 0;\n}\n"
    (folder / "main.c").write_text("#include <stdio.h>\n" + main, encoding="utf-8")
    done = subprocess.run([need("gcc"), *CFLAGS, *[f"{n}.c" for n in units], "main.c", "-lm", "-o", "run"],
                          cwd=folder, capture_output=True, text=True)
    assert done.returncode == 0 and not done.stderr, done.stderr
    out: dict[str, list[str]] = {}
    current = ""
    for line in subprocess.run([str(folder / "run")], capture_output=True, text=True, check=True).stdout.splitlines():
        if line.startswith("unit "):
            current = line[5:]
            out[current] = []
        else:
            out[current].append(line)
    return out


@pytest.fixture(scope="module")
def outputs(tmp_path_factory: pytest.TempPathFactory) -> dict[str, list[str]]:
    return run_units({name: unit(view(name), name) for name in NAMES}, tmp_path_factory.mktemp("c_spelling"))


@pytest.mark.parametrize("name", NAMES)
def test_the_spelled_procedure_computes_every_record(name: str, outputs):
    v = view(name)
    lines = outputs[name]
    assert lines[-len(computed(v)) - 1] == "code 0 failed 0 at 0"
    got = dict(line.split() for line in lines[-len(computed(v)):])
    want = reference(v)
    kinds = {r.name: r.kind for r in v.records}
    for rec, f in computed(v):
        k = record_fields(kinds[rec], v.record_order).index(f)
        assert same(float.fromhex(got[f"{rec}.{f}"]), want[rec][k]), (rec, f)
    notes = [tuple(int(x) for x in line.split()[1:]) for line in lines if line.startswith("note ")]
    assert notes == [(0, status.code(s.number, status.SINGULAR), status.code(s.number, status.NEAR_SINGULAR), 1)
                     for s in v.run if s.fails]


def test_a_chain_that_cannot_close_returns_its_steps_code(tmp_path: Path):
    v = view("fourbar")
    chain = next(s for s in v.run if s.function == "RRR_links")
    grounded = next(c for c in v.constants if c.role == "pair" and any(a.var == c.name for a in chain.args))
    text = unit(v, "far", {grounded.name: "{{1e6, 1e6}, {0.0, 0.0}, {0.0, 0.0}}"})  # its pair far away
    lines = run_units({"far": text}, tmp_path)["far"]
    code = status.code(chain.number, status.CANNOT_CLOSE)
    # through failed(), which publishes the failed row (the conditioning of the steps after it reset)
    assert f"code {code} failed {code} at {chain.number}" in lines


def test_constants_are_braced_initializers_with_zero_rates():
    v = view("fourbar")
    spell = C(v)
    pair = next(c for c in v.constants if c.kind == "POINT")
    x, y = pair.value[0] - v.log.origin[0], pair.value[1] - v.log.origin[1]
    assert spell.initializer(pair) == f"{{{{{spell.lit(x)}, {spell.lit(y)}}}, {{0.0, 0.0}}, {{0.0, 0.0}}}}"
    length = next(c for c in v.constants if c.kind == "VARIABLE")
    assert spell.initializer(length) == f"{{{spell.lit(length.value[0])}, 0.0, 0.0}}"
    assert spell.member("POINT", "ddy") == ".DDP.y" and spell.ref(pair.name, None) == pair.name


def test_the_reach_check_ends_a_row_past_the_reach_with_its_codes(tmp_path: Path):
    """A crank whose reach is an arc (low, high): past high by a little is nearer high's gap, below low by a
    little nearer low's (its step is another: the codes differ)."""
    log = build_log(str(ROOT / "tests" / "mechanisms" / "stephenson_circuit.yaml"), None, None, sweep=False)
    spell = C(build_view(log))
    assert log.reach is not None and log.reach.low is not None and log.reach.high is not None
    low, high = log.reach.codes()
    assert low != high
    body = "\n".join(f"    {line}" for line in spell.reach_check())
    probes = (log.reach.low - 0.1, (log.reach.low + log.reach.high) / 2, log.reach.high + 0.1)
    text = (f"#include <math.h>\n#include <stdio.h>\n{RUNTIME.source('reach')}\n{FAILED}"
            "static int check(const double in[])\n{\n    int st;\n"
            "    state failure = {0, 0, {0.0}}, *out = &failure;\n"
            f"{body}\n    return 0;\n}}\n"
            "void run_reach(void);\nvoid run_reach(void)\n{\n"
            + "".join(f"    {{ const double in[] = {{{x!r}}}; printf(\"%d\\n\", check(in)); }}\n" for x in probes)
            + "}\n")
    assert run_units({"reach": text}, tmp_path)["reach"] == [str(low), "0", str(high)]
