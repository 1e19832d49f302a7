"""A step's call as the row solver makes it (linkgen.rowsolver): the runtime function on the records.

The call is compiled once as a function of its own: a record read as ``env[name]``, a chain's branch
as the env's, else the step's, a number in place, the result unpacked as (status, sigma, outputs).
A row calls a few hundred of them; reading a plan of the arguments on every call took longer.
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Mapping
from types import CodeType, FunctionType
from typing import Any

from .primitives import PRIMITIVES
from .steplog import Step

BRANCH = "branch"  # env key (with a step number) of a chain's branch where it is not the sketch's

Env = dict[Any, Any]  # variable -> record, (BRANCH, step) -> branch

Runner = Callable[[Env], tuple[Any, Any, tuple[Any, ...]]]  # one step's call on the records: (status, sigma, outputs)


def runner(step: Step, fns: Mapping[str, Any], name: str = "") -> Runner:
    """A step's call made once (its runtime function, the one of fns named ``name`` where given,
    else the step's; where each argument comes from, how the result unpacks): run on the records it
    gives what ``call(step.function, args)`` gives."""
    prim = PRIMITIVES[step.function]
    scope: dict[str, Any] = {"fn": fns[name or step.function]}
    args = []
    for k, a in enumerate(step.args):
        if a.kind == "var":
            scope[f"k{k}"] = a.var
            args.append(f"env[k{k}]")
        elif a.kind == "int" and a.label == "minv":
            scope[f"k{k}"], scope[f"d{k}"] = (BRANCH, step.number), int(a.value)
            args.append(f"env.get(k{k}, d{k})")
        else:
            scope[f"k{k}"] = int(a.value) if a.kind == "int" else float(a.value)
            args.append(f"k{k}")
    call = f"fn({', '.join(args)})"
    if prim.status is None:
        body = f"return 0, 1.0, ({call},)" if len(prim.outputs) == 1 else f"return 0, 1.0, {call}"
    elif prim.sigma is None:
        body = f"res = {call}\n    return res[0], 1.0, res[1:]"
    else:
        body = f"res = {call}\n    return res[0], res[1], res[2:]"
    run: Runner = FunctionType(_runner_code(body), scope)
    return run


@functools.cache
def _runner_code(body: str) -> CodeType:
    """The code of a runner's body, compiled once (steps differ in the names it reads, not in its text)."""
    module = compile(f"def run(env):\n    {body}\n", "<linkgen step>", "exec")
    code: CodeType = next(c for c in module.co_consts if isinstance(c, CodeType))
    return code
