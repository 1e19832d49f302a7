"""The vectorised kernel in-process: a step log's NAME_np.py (the numpy backend's), rendered
and run here, so the evaluator computes what the generated module computes, bit for bit.

``kernel(log, order)`` executes the module's source once per log and order (a log at another
order is rendered as the log built at that order); ``runtime()`` holds the numpy runtime's
branch_at and reach_at for the rows the evaluator checks itself.
"""

from __future__ import annotations

import functools
import linecache
from dataclasses import replace
from types import ModuleType
from typing import Any

import numpy as np

from .backends.np import BACKEND, RUNTIME
from .backends.program import LEVEL
from .render import render_backend
from .render.view import build_view
from .steplog import StepLog


def _module(name: str, source: str) -> ModuleType:
    """A module executed from generated source (under a file name its tracebacks show)."""
    filename = f"<linkgen {name}>"
    linecache.cache[filename] = (len(source), None, source.splitlines(True), filename)
    module = ModuleType(name)
    exec(compile(source, filename, "exec"), module.__dict__)
    return module


def at_order(log: StepLog, order: int) -> StepLog:
    """The log as built at another derivative order: its columns up to that order."""
    if order == log.order:
        return log
    return replace(log, order=order, columns=tuple(c for c in log.columns if LEVEL[c.quantity] <= order))


@functools.lru_cache(maxsize=64)
def kernel(log: StepLog, order: int) -> ModuleType:
    """The log's NAME_np.py at ``order``, executed (its _run and solve)."""
    if log.groups:
        raise ValueError(f"{log.name} has resolver groups: its rows are solved one by one")
    source = render_backend(BACKEND, build_view(at_order(log, order)))[f"{log.name}_np.py"].decode("utf-8")
    return _module(f"{log.name}_np", source)


@functools.cache
def runtime() -> dict[str, Any]:
    """The numpy runtime's functions (row_status, reason_of, branch_at, reach_at), as NAME_np.py has them."""
    ns: dict[str, Any] = {"np": np, "PI": np.pi}
    for name in ("status", "branch", "reach"):
        exec(compile(RUNTIME.source(name), f"<linkgen numpy runtime {name}>", "exec"), ns)
    return ns
