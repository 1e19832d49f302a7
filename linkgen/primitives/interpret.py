"""Run a list of steps on scalar records with the standard-library runtime (the probe
that ranks Add-link candidates; no resolver, no branch policy)."""

from __future__ import annotations

from ..status import CANNOT_CLOSE
from ..steplog import Arg, Step, Variable, held
from . import PRIMITIVES, python_backend

Record = tuple[float, ...]


def constant_record(v: Variable, order: int, origin: tuple[float, float]) -> Record:
    """A constant record as the programs hold it (points relative to ``origin``; rates 0)."""
    value = held(v, origin)
    width = 2 if v.kind == "POINT" else 1
    return tuple(value) + (0.0,) * (width * order)


def _value(arg: Arg, env: dict[str, Record]) -> Record | float:
    """An argument as the runtime takes it: a variable's record, an int flag or a real."""
    if arg.kind == "var":
        return env[arg.var]
    return int(arg.value) if arg.kind == "int" else float(arg.value)


def run_steps(steps: list[Step] | tuple[Step, ...], env: dict[str, Record], order: int) -> bool:
    """Run the steps' calls in order, writing their outputs into ``env``; False as soon as
    a chain cannot close."""
    fns = python_backend(order)
    for step in steps:
        if not step.function:
            continue
        args = [_value(a, env) for a in step.args]
        prim = PRIMITIVES[step.function]
        res = fns[step.function](*args)
        if prim.status is None:
            outs = (res,) if len(prim.outputs) == 1 else res
        else:
            if res[0] == CANNOT_CLOSE:
                return False
            outs = res[2:] if prim.sigma is not None else res[1:]
        env.update(zip(step.outputs, outs))
    return True
