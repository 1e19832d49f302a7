"""linkgen.backends.c.printer: every primitive printed as C99 at each order compiles without a warning
(-Wall -Wextra -pedantic -Werror, so every unused parameter is voided) and, run on random and special
arguments, gives the DSL's own values bit for bit (tests/dsl_walk.py): status, sigma and every output
field, masked as the status says."""

from __future__ import annotations

import math
import subprocess
from functools import cache
from pathlib import Path

import pytest
from dsl_walk import evaluate, rows, same, slack_rows, thin_rows
from programs import CFLAGS, need

from linkgen.backends.c.printer import _is_int, c_function, field
from linkgen.primitives import PRIMITIVES
from linkgen.primitives.dsl import Builder, Cmp, Num, Primitive, Select, Sym, record_fields

ORDERS = (0, 1, 2)
ROWS = 40  # random rows per primitive and order, besides the special ones


def _records(order: int) -> str:
    levels = ("P", "DP", "DDP")[: order + 1]
    centre = record_fields("CENTRE", order) or ("none",)  # no field at order 0, where no program has one
    return (f"typedef struct {{ double x, y; }} VEC2;\ntypedef struct {{ VEC2 {', '.join(levels)}; }} POINT;\n"
            f"typedef struct {{ double {', '.join(('the', 'dthe', 'ddthe')[: order + 1])}; }} ANGLE;\n"
            f"typedef struct {{ double {', '.join(('v', 'dv', 'ddv')[: order + 1])}; }} VARIABLE;\n"
            f"typedef struct {{ double {', '.join(centre)}; }} CENTRE;\n")


def _caller(prim: Primitive, order: int) -> str:
    """``case``: read the arguments off v[], call, print status, sigma and the output fields as hex."""
    lines, k = [], 0
    for p in prim.params:
        if p.is_record:
            n = len(record_fields(p.kind, order))
            values = [f"v[{k + i}]" for i in range(n)]
            k += n
            if p.kind == "POINT":
                values = ["{" + ", ".join(values[i:i + 2]) + "}" for i in range(0, n, 2)]
            lines.append(f"{p.kind} {p.name} = {{{', '.join(values)}}};")
        else:
            lines.append(f"{'int' if p.kind == 'INT' else 'double'} {p.name} = {'(int)' if p.kind == 'INT' else ''}"
                         f"v[{k}];")
            k += 1
    lines += [f"{o.kind} out_{o.name};" for o in prim.outputs] + ["double sigma = NAN;", "int st = -1;"]
    args = [f"&{p.name}" if p.is_record else p.name for p in prim.params] + [f"&out_{o.name}" for o in prim.outputs]
    if prim.sigma is not None:
        args.append("&sigma")
    call = f"{prim.name}({', '.join(args)});"
    lines.append(f"st = {call}" if prim.status is not None else call)
    lines.append('printf("%d %a", st, sigma);')
    for o in prim.outputs:
        for f in record_fields(o.kind, order):
            lines.append(f'printf(" %a", out_{o.name}.{field(o.kind, f)});')
    lines.append('printf("\\n");')
    body = "\n        ".join(lines)
    return f'    if (strcmp(name, "{prim.name}") == 0) {{\n        {body}\n        return;\n    }}'


def unit(order: int) -> str:
    """One translation unit: the records at ``order``, every primitive and run_order_N(name, v)."""
    cases = "\n".join(_caller(p, order) for p in PRIMITIVES.values())
    return ("#include <float.h>\n#include <math.h>\n#include <stdio.h>\n#include <string.h>\n\n" + _records(order)
            + "\n" + "\n".join(c_function(p, order) for p in PRIMITIVES.values())
            + f"\nvoid run_order_{order}(const char *name, const double *v);\n"
            + f"void run_order_{order}(const char *name, const double *v)\n{{\n{cases}\n}}\n")


MAIN = """#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void run_order_0(const char *name, const double *v);
void run_order_1(const char *name, const double *v);
void run_order_2(const char *name, const double *v);

/* Each line of stdin: order, primitive, count, then the arguments as hex floats. */
int main(void)
{
    char name[64], number[64];
    double v[64];
    int order, count, i;
    while (scanf("%d %63s %d", &order, name, &count) == 3) {
        for (i = 0; i < count; i++) {
            if (scanf("%63s", number) != 1) return 2;
            v[i] = strtod(number, NULL);
        }
        if (order == 0) run_order_0(name, v);
        else if (order == 1) run_order_1(name, v);
        else run_order_2(name, v);
    }
    return 0;
}
"""


def _flat_args(prim: Primitive, order: int, row: dict) -> list[float]:
    out: list[float] = []
    for p in prim.params:
        if p.is_record:
            out += [row[f"{p.name}_{f}"] for f in record_fields(p.kind, order)]
        else:
            out.append(float(row[p.name]))
    return out


@cache
def cases() -> list[tuple[str, int, dict]]:
    return [(name, order, row) for name in PRIMITIVES for order in ORDERS for row in rows(name, ROWS)]


@pytest.fixture(scope="module")
def c_results(tmp_path_factory: pytest.TempPathFactory) -> list[list[float]]:
    gcc = need("gcc")
    folder: Path = tmp_path_factory.mktemp("c_printer")
    for order in ORDERS:
        (folder / f"order{order}.c").write_text(unit(order), encoding="utf-8")
    (folder / "main.c").write_text(MAIN, encoding="utf-8")
    done = subprocess.run([gcc, *CFLAGS, "order0.c", "order1.c", "order2.c", "main.c", "-lm", "-o", "run"],
                          cwd=folder, capture_output=True, text=True)
    assert done.returncode == 0 and not done.stderr, done.stderr
    lines = []
    for name, order, row in cases():
        args = _flat_args(PRIMITIVES[name], order, row)
        lines.append(f"{order} {name} {len(args)} " + " ".join(float(x).hex() for x in args))
    out = subprocess.run([str(folder / "run")], input="\n".join(lines) + "\n", capture_output=True, text=True,
                         check=True).stdout.splitlines()
    assert len(out) == len(lines)
    return [[float.fromhex(x) for x in line.split()] for line in out]


@pytest.mark.parametrize("name", list(PRIMITIVES))
def test_the_c_functions_compute_what_the_dsl_says_bit_for_bit(name: str, c_results):
    prim = PRIMITIVES[name]
    checked = 0
    for (case_name, order, row), got in zip(cases(), c_results):
        if case_name != name:
            continue
        st, sigma, fields = evaluate(prim, order, row)
        assert int(got[0]) == (-1 if st is None else st), (order, row)
        assert same(got[1], sigma if sigma is not None else float("nan")), (order, row)
        assert len(got) - 2 == len(fields)
        bad = [(i, a, b) for i, (a, b) in enumerate(zip(got[2:], fields)) if not same(a, b)]
        assert not bad, (order, row, bad)
        checked += 1
    assert checked == len(ORDERS) * len(rows(name, ROWS))


def test_the_rows_reach_every_status_of_a_chain():
    """So the comparison above sees closed chains, toggles, failures (all masked), shortfalls either side
    of the toggle slack (which reads eps), and thin chains at status 3 (finite rates masked) and 4."""
    for name in ("RRR_links", "PRR_links", "RPR_links"):
        seen = {evaluate(PRIMITIVES[name], 2, row)[0] for row in rows(name, ROWS)}
        assert {0, 1, 3} <= seen, name
        assert [evaluate(PRIMITIVES[name], 2, row)[0] for row in slack_rows(name)] == [3, 1], name
    singular, near = (evaluate(PRIMITIVES["RRR_links"], 2, row) for row in thin_rows("RRR_links"))
    assert (singular[0], near[0]) == (3, 4)
    assert all(math.isfinite(x) for x in near[2])


def test_a_point_field_is_a_member_of_its_level():
    assert [field("POINT", f) for f in record_fields("POINT", 2)] == ["P.x", "P.y", "DP.x", "DP.y", "DDP.x", "DDP.y"]
    assert field("ANGLE", "dthe") == "dthe" and field("VARIABLE", "ddv") == "ddv"


def test_flags_comparisons_and_their_selections_are_ints():
    """What C declares int: comparisons, INT parameters, int literals and selections between ints."""
    ints = {"minv"}
    assert _is_int(Cmp("<", Sym("x"), Num(0)), ints) and _is_int(Sym("minv"), ints)
    assert _is_int(Select(Cmp("<", Sym("x"), Num(0)), Num(1), Num(0)), ints)
    assert not _is_int(Select(Cmp("<", Sym("x"), Num(0)), Num(1.0), Num(0)), ints)
    assert not _is_int(Sym("x"), ints) and not _is_int(Num(0.5), ints)


def test_a_function_that_cannot_fail_returns_nothing_and_one_that_can_its_status():
    assert "static inline void crank_input(" in c_function(PRIMITIVES["crank_input"], 2)
    text = c_function(PRIMITIVES["RRR_links"], 2)
    head = ("static inline int RRR_links(const POINT *j1, const POINT *j2, const VARIABLE *l1, const VARIABLE *l2, "
            "int minv, POINT *jb, double *sigma_out)")
    assert head in text and text.rstrip().endswith("return st;\n}")


def test_a_parameter_an_order_does_not_read_is_voided(tmp_path: Path):
    """k scales only the rates: at order 0 the function reads neither k nor x's rates, and compiles
    without a warning all the same."""
    b = Builder("scaled_rates", "y = x with its rates times k")
    x = b.record("x", "VARIABLE")
    k = b.scalar("k")
    b.output("y", "VARIABLE", v=x.v, dv=k * x.dv, ddv=k * x.ddv)
    prim = b.build()
    text = c_function(prim, 0)
    assert "    (void)k;" in text and "(void)x;" not in text
    main = ("#include <math.h>\n#include <stdio.h>\n" + _records(0) + text
            + "int main(void)\n{\n    VARIABLE x = {2.5}, y;\n    scaled_rates(&x, 3.0, &y);\n"
              '    printf("%a\\n", y.v);\n    return 0;\n}\n')
    (tmp_path / "t.c").write_text(main, encoding="utf-8")
    done = subprocess.run([need("gcc"), *CFLAGS, "t.c", "-o", "t"], cwd=tmp_path, capture_output=True, text=True)
    assert done.returncode == 0 and not done.stderr, done.stderr
    out = subprocess.run([str(tmp_path / "t")], capture_output=True, text=True, check=True).stdout
    assert float.fromhex(out.strip()) == 2.5


def test_rrr_links_branches_on_its_open_test():
    """The C of RRR_links computes q, 1/q and Kahan's sorted sides only on the toggle side of its open test (the
    values the other side selects are the same: test_the_c_functions_compute_what_the_dsl_says_bit_for_bit)."""
    text = c_function(PRIMITIVES["RRR_links"], 2)
    before, branch, rest = text.partition("    if ((3 * o1 > s2) & (3 * o2 > dd)) {\n")
    opened, other, after = rest.partition("    } else {\n")
    toggle, end, after = after.partition("\n    }\n")
    assert branch and other and end
    assert "double area4, e1x, e1y, ar, a2r;" in before and "sqrt(dd)" not in before + opened + after
    assert "        const double q = sqrt(dd);" in toggle and "        fail = (k < " in toggle
    assert "        fail = 0;" in opened and "        area4 = sqrt(o1 * o2);" in opened
