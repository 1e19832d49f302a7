"""linkgen.backends.m.printer: every primitive printed as a MATLAB/Octave function at each order, run by
octave-cli on random and special arguments (passed and read back as IEEE bits), gives the DSL's own values
bit for bit (tests/dsl_walk.py); selections become if/elseif/else statements."""

from __future__ import annotations

import re
import struct
import subprocess
from functools import cache

import pytest
from dsl_walk import evaluate, rows, same
from programs import need

from linkgen.backends.m.printer import OctaveExprs, octave_function
from linkgen.primitives import PRIMITIVES
from linkgen.primitives.dsl import Cmp, Num, Primitive, Select, Sym, record_fields

ORDERS = (0, 1, 2)
ROWS = 25  # random rows per primitive and order, besides the special ones


def bits(x: float) -> str:
    return f"hex2num('{struct.pack('>d', float(x)).hex()}')"


def _call(prim: Primitive, order: int, row: dict) -> str:
    """One statement calling the order's copy of the primitive and printing status, sigma and fields as bits."""
    args = []
    for p in prim.params:
        if p.is_record:
            pairs = ", ".join(f"'{f}', {bits(row[f'{p.name}_{f}'])}" for f in record_fields(p.kind, order))
            args.append(f"struct({pairs})")
        else:
            args.append(bits(row[p.name]))
    outs = [f"o_{o.name}" for o in prim.outputs]
    st = "st" if prim.status is not None else "st_none"
    sigma = "sg" if prim.sigma is not None else "sg_none"
    targets = outs + (["st"] if prim.status is not None else []) + (["sg"] if prim.sigma is not None else [])
    values = [st, sigma] + [f"o_{o.name}.{f}" for o in prim.outputs for f in record_fields(o.kind, order)]
    printed = " ".join(f"printf('%s ', num2hex({v}));" for v in values)
    return f"[{', '.join(targets)}] = {prim.name}_o{order}({', '.join(args)}); {printed} printf('\\n');"


def _renamed(prim: Primitive, order: int) -> str:
    text = octave_function(prim, order)
    head, _, body = text.partition("\n")
    return head.replace(f"= {prim.name}(", f"= {prim.name}_o{order}(") + "\n" + body


@cache
def cases() -> list[tuple[str, int, dict]]:
    return [(name, order, row) for name in PRIMITIVES for order in ORDERS for row in rows(name, ROWS)]


@pytest.fixture(scope="module")
def octave_results(tmp_path_factory: pytest.TempPathFactory) -> list[list[float]]:
    octave = need("octave-cli")
    folder = tmp_path_factory.mktemp("m_printer")
    functions = "\n".join(_renamed(p, order) for p in PRIMITIVES.values() for order in ORDERS)
    calls = "\n".join(_call(PRIMITIVES[name], order, row) for name, order, row in cases())
    script = f"1;\n{functions}\nst_none = -1; sg_none = NaN;\n{calls}\n"
    (folder / "run_printed.m").write_text(script, encoding="utf-8")
    done = subprocess.run([octave, "--no-gui", "--no-init-file", "--quiet", "run_printed.m"], cwd=folder,
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    out = done.stdout.splitlines()
    assert len(out) == len(cases())
    return [[struct.unpack(">d", bytes.fromhex(h))[0] for h in line.split()] for line in out]


@pytest.mark.parametrize("name", list(PRIMITIVES))
def test_the_octave_functions_compute_what_the_dsl_says_bit_for_bit(name: str, octave_results):
    prim = PRIMITIVES[name]
    checked = 0
    for (case_name, order, row), got in zip(cases(), octave_results):
        if case_name != name:
            continue
        st, sigma, fields = evaluate(prim, order, row)
        assert got[0] == (-1 if st is None else st), (order, row)
        assert same(got[1], sigma if sigma is not None else float("nan")), (order, row)
        assert len(got) - 2 == len(fields)
        bad = [(i, a, b) for i, (a, b) in enumerate(zip(got[2:], fields)) if not same(a, b)]
        assert not bad, (order, row, bad)
        checked += 1
    assert checked == len(ORDERS) * len(rows(name, ROWS))


def test_a_chain_of_selections_is_if_elseif_else():
    e = Select(Cmp("<", Sym("x"), Num(0)), Num(1), Select(Cmp("==", Sym("x"), Num(0)), Num(2), Num(3)))
    assert OctaveExprs(PRIMITIVES["RRR_links"]).assign("y", e) == [
        "    if x < 0", "        y = 1;", "    elseif x == 0", "        y = 2;", "    else", "        y = 3;",
        "    end"]
    with pytest.raises(ValueError, match="no conditional expression"):
        OctaveExprs(PRIMITIVES["RRR_links"]).expr(Select(Sym("c"), Num(1), Num(2)))


def test_outputs_come_first_then_status_and_sigma():
    head = octave_function(PRIMITIVES["RRR_links"], 2).splitlines()[0]
    assert head == "function [jb, st, sigma] = RRR_links(j1, j2, l1, l2, minv)"
    assert octave_function(PRIMITIVES["offset_angle"], 0).splitlines()[0] == "function angle = offset_angle(phi, off)"
    masks = re.findall(r"^    if (st == .*)$", octave_function(PRIMITIVES["RRR_links"], 2), re.M)
    assert masks == ["st == 1", "st == 1 || st == 3"]
