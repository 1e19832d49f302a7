"""Run a list of steps on scalar records with the standard-library runtime (the probe
that ranks Add-link candidates; no resolver, no branch policy)."""

from __future__ import annotations

from ..steplog import Step, Variable, held
from . import PRIMITIVES, python_backend

CANNOT_CLOSE = 1  # the status of a chain that cannot close


def constant_record(v: Variable, order: int, origin: tuple[float, float]) -> tuple:
    """A constant record as the programs hold it (points relative to ``origin``; rates 0)."""
    value = held(v, origin)
    width = 2 if v.kind == "POINT" else 1
    return tuple(value) + (0.0,) * (width * order)


def run_steps(steps: list[Step] | tuple[Step, ...], env: dict, order: int) -> bool:
    """Run the steps' calls in order, writing their outputs into ``env``; False as soon as
    a chain cannot close."""
    fns = python_backend(order)
    for step in steps:
        if not step.function:
            continue
        args = [env[a.var] if a.kind == "var" else int(a.value) if a.kind == "int" else float(a.value)
                for a in step.args]
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
