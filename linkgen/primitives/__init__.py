"""The mech.cpp-shaped runtime library: one DSL definition per function, printed per language."""

from __future__ import annotations

import functools
import linecache
import math
import sys
from collections.abc import Callable
from typing import Any

import numpy as np

from .library import PRIMITIVES

__all__ = ["PRIMITIVES", "RuntimeFunction", "python_backend", "numpy_backend"]

# A printed primitive: records (tuples) and scalars in; a tuple out, whose items (floats, records or
# arrays; with status and sigma first where the primitive has them) follow its Primitive.
RuntimeFunction = Callable[..., tuple[Any, ...]]


def _compile(source: str, filename: str, namespace: dict[str, Any]) -> dict[str, Any]:
    """Exec generated source under a fake file name so tracebacks show it (the namespace is
    exec's globals: it holds whatever the source defines); its code compiled once per user (kernel.compiled)."""
    from ..kernel import compiled  # the kernel renders through the backends, which import this package

    linecache.cache[filename] = (len(source), None, source.splitlines(True), filename)
    exec(compiled(source, filename), namespace)
    return namespace


@functools.cache
def python_backend(order: int = 2) -> dict[str, RuntimeFunction]:
    """Scalar functions on tuples of floats, with sigma (what generated Python runs)."""
    from ..backends.py.printer import python_function
    from ..textcache import kept

    source = kept("python primitives", (order,),  # printed once per user (textcache): 4-7 ms
                  lambda: "\n\n".join(python_function(p, order) for p in PRIMITIVES.values()))
    ns: dict[str, Any] = {
        "sqrt": math.sqrt, "atan2": math.atan2, "cos": math.cos,
        "sin": math.sin, "EPS": sys.float_info.epsilon, "NAN": math.nan, "PI": math.pi,
    }
    _compile(source, f"<linkgen runtime python order {order}>", ns)
    return {name: ns[name] for name in PRIMITIVES}


@functools.cache
def numpy_backend(order: int = 2) -> dict[str, RuntimeFunction]:
    """Vectorised functions on tuples of arrays, returning (status, sigma, outputs...)."""
    from ..backends.np import RUNTIME
    from ..backends.np.printer import numpy_function

    source = "\n\n".join([RUNTIME.source("trig")] + [numpy_function(p, order) for p in PRIMITIVES.values()])
    ns: dict[str, Any] = {"np": np, "REAL": np.float64, "EPS": float(np.finfo(float).eps), "NAN": np.nan, "PI": np.pi}
    _compile(source, f"<linkgen runtime numpy order {order}>", ns)
    return {name: ns[name] for name in PRIMITIVES}
