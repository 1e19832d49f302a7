"""backends.c.tangent: a two-channel copy (NAME_2) is two order-1 calls on the same positions, bit for bit.

Each copy is printed as Python (the same statements as its C) and run against the order-1 primitive run
twice, once with the first channel's rates and once with the second's: positions and status from one
pass, each channel's velocities as its own call gives them."""

from __future__ import annotations

import math
import random
import struct
import sys
from dataclasses import replace

import pytest

from linkgen.backends.c.tangent import SUFFIX, TAPED_STATUS, from_tape, tape, two_channel
from linkgen.backends.py.printer import python_function
from linkgen.primitives import PRIMITIVES
from linkgen.primitives.dsl import RECORD_FIELDS, Param, Sym, record_fields

NAMESPACE = {"sqrt": math.sqrt, "atan2": math.atan2, "cos": math.cos, "sin": math.sin,
             "EPS": sys.float_info.epsilon, "NAN": math.nan, "PI": math.pi}
TWO_CHANNEL = [n for n, p in PRIMITIVES.items() if any(q.is_record for q in p.params) and "CENTRE" not in
               {q.kind for q in (*p.params, *p.outputs)}]


def _function(source: str, name: str):
    ns = dict(NAMESPACE)
    exec(compile(source, f"<{name}>", "exec"), ns)
    return ns[name]


def _bits(value: object) -> object:
    """A result with every float as its bit pattern (nan == nan, -0.0 != 0.0)."""
    if isinstance(value, tuple):
        return tuple(_bits(v) for v in value)
    return struct.pack("<d", value) if isinstance(value, float) else value


def _split(prim, result: tuple) -> tuple[tuple, tuple]:
    """A call's result as (status and sigma, outputs): a primitive without status returns its outputs
    alone, a single output unwrapped."""
    lead = (prim.status is not None) + (prim.sigma is not None)
    if lead == 0 and len(prim.outputs) == 1:
        return (), (result,)
    return tuple(result[:lead]), tuple(result[lead:])


def _argument(kind: str, rng: random.Random) -> object:
    if kind in RECORD_FIELDS:
        return tuple(rng.uniform(-3, 3) for _ in record_fields(kind, 1))
    return rng.choice((-1, 1)) if kind == "INT" else rng.uniform(0.5, 3)


def _with_rates(record: tuple[float, ...], rates: tuple[float, ...]) -> tuple[float, ...]:
    half = len(record) // 2
    return record[:half] + rates[half:]


@pytest.mark.parametrize("name", TWO_CHANNEL)
def test_a_two_channel_copy_is_two_order_one_calls(name):
    prim = PRIMITIVES[name]
    one = _function(python_function(prim, 1), name)
    two = _function(python_function(two_channel(prim), 1), f"{name}_2")
    rng = random.Random(name)
    closed = 0
    for _ in range(200):
        args = [_argument(p.kind, rng) for p in prim.params]
        second = [_argument(p.kind, rng) for p in prim.params if p.is_record]
        records = iter(second)
        args_t = [_with_rates(a, next(records)) if p.is_record else a for p, a in zip(prim.params, args)]
        (head, first), (_, rates) = _split(prim, one(*args)), _split(prim, one(*args_t))
        both, lead, n = two(*args, *second), len(head), len(first)
        assert _bits(both[:lead]) == _bits(head)  # the status (and sigma) of the one pass
        assert _bits(both[lead:lead + n]) == _bits(first)
        assert _bits(both[lead + n:]) == _bits(rates)
        closed += not head or head[0] == 0
    assert closed, "no draw closed the chain: the check saw only failures"


def test_the_second_channel_reads_rates_only_and_writes_copies():
    prim = two_channel(PRIMITIVES["RRR_links"])
    added = [p.name for p in prim.params if p.name.endswith(SUFFIX)]
    assert added == [p.name + SUFFIX for p in PRIMITIVES["RRR_links"].params if p.is_record]
    assert [o.name for o in prim.outputs] == ["jb", "jb" + SUFFIX]
    assert all(let.order <= 1 for let in prim.body)


def _probe(prim):
    """The primitive at order 0 returning (status, the values tangent.tape keeps): the two-channel copy's tape."""
    names = [n for n in tape(prim) if n != TAPED_STATUS]
    outputs = tuple(Param(f"kept{k}", "VARIABLE") for k in range(len(names)))
    results = {f"kept{k}": {"v": Sym(n)} for k, n in enumerate(names)}
    return replace(prim, name=f"{prim.name}_probe", outputs=outputs, results=results, sigma=None), len(names)


@pytest.mark.parametrize("name", TWO_CHANNEL)
def test_a_rates_copy_on_the_kept_positions_is_the_order_two_call(name):
    """NAME_r given the position values a pass keeps (and its status) returns what the order-2 primitive
    returns, bit for bit (fails when a kept value is another's, or the copy recomputes one differently)."""
    prim = PRIMITIVES[name]
    probe, count = _probe(prim)
    whole = _function(python_function(prim, 2), name)
    kept = _function(python_function(probe, 0), probe.name)
    rates = _function(python_function(from_tape(prim), 2), f"{name}_r")
    rng = random.Random(name + "_r")
    closed = 0
    for _ in range(200):
        args = [tuple(rng.uniform(-3, 3) for _ in record_fields(p.kind, 2)) if p.is_record else _argument(p.kind, rng)
                for p in prim.params]
        got = kept(*(a[: len(record_fields(p.kind, 0))] if p.is_record else a for p, a in zip(prim.params, args)))
        status = got[:1] if prim.status is not None else ()
        values = got[len(status):] if count > 1 or status else (got,)
        values = tuple(v[0] if isinstance(v, tuple) else v for v in values)
        head, outputs = _split(prim, whole(*args))
        mine = rates(*args, *values, *status)
        assert _bits(_split(from_tape(prim), mine)[1]) == _bits(outputs)
        assert _bits(_split(from_tape(prim), mine)[0]) == _bits(head[:1])  # the kept status, no conditioning
        closed += not head or head[0] == 0
    assert closed, "no draw closed the chain: the check saw only failures"
