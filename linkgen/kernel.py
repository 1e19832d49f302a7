"""The vectorised kernel in-process: a step log's NAME_np.py (the numpy backend's), rendered
and run here, so the evaluator computes what the generated module computes, bit for bit.

``kernel(log, order)`` renders the module's source for a log at an order (a log at another
order is rendered as the log built at that order) and executes each distinct source once: the
analysis evaluates many logs that differ only where the kernel does not look.  A resolver
mechanism's kernel gets its standard-library module NAME.py, rendered and executed the same
way, for the rows it solves one by one.  ``runtime()`` holds the numpy runtime's branch_at and
reach_at for the rows the evaluator checks itself.  ``Records`` holds a kernel's records as a
result does: arrays of the rows, made when first read.
"""

from __future__ import annotations

import functools
import linecache
from collections import OrderedDict
from collections.abc import Iterator, Mapping
from dataclasses import replace
from types import CodeType, ModuleType
from typing import Any

import numpy as np

from .backends import Backend, backends
from .backends.np import BACKEND, RUNTIME
from .backends.program import LEVEL
from .backends.py import BACKEND as PYTHON
from .render import make_env, render_backend
from .render.view import build_view
from .steplog import StepLog

RECENT = 16  # logs whose kernels are found by the log itself, without rendering


def _module(name: str, source: str) -> ModuleType:
    """A module executed from generated source (under a file name its tracebacks show)."""
    filename = f"<linkgen {name}>"
    linecache.cache[filename] = (len(source), None, source.splitlines(True), filename)
    module = ModuleType(name)
    exec(compiled(source, filename), module.__dict__)
    return module


def compiled(source: str, filename: str) -> CodeType:
    """The code of a generated source, compiled once per user: kept in the templates' bytecode cache
    (render.make_env's, in the temporary directory) under the text's own hash, since compiling a
    kernel takes longer than executing it.  Where that cache cannot be written, compiled every time."""
    env = make_env()
    cache = env.bytecode_cache
    if cache is None:
        return compile(source, filename, "exec")
    bucket = cache.get_bucket(env, f"linkgen code {filename}", cache.get_source_checksum(source), source)
    if not isinstance(bucket.code, CodeType):
        bucket.code = compile(source, filename, "exec")
        cache.set_bucket(bucket)
    return bucket.code


@functools.lru_cache(maxsize=64)
def _compiled(name: str, source: str) -> ModuleType:
    """The module of a source text, executed once."""
    return _module(name, source)


def at_order(log: StepLog, order: int) -> StepLog:
    """The log as built at another derivative order: its columns up to that order."""
    if order == log.order:
        return log
    return replace(log, order=order, columns=tuple(c for c in log.columns if LEVEL[c.quantity] <= order))


def source(backend: Backend[Any], log: StepLog, order: int) -> str:
    """The text of the backend's program (the numpy kernel, or NAME.py) for the log at an order,
    in double whatever real type the log asks for (the evaluator's: the analysis runs it); a log
    equal to one of the last few is not rendered again (the analysis makes equal logs anew)."""
    return _source(backend.name, log, order)


@functools.lru_cache(maxsize=8)
def _source(name: str, log: StepLog, order: int) -> str:
    backend = next(b for b in backends() if b.name == name)
    if log.options.real != "double":
        log = replace(log, options=replace(log.options, real="double"))
    files = render_backend(backend, build_view(at_order(log, order)))
    return files[backend.files[0].replace("NAME", log.name)].decode("utf-8")


_recent: OrderedDict[tuple[int, int, bool], tuple[StepLog, ModuleType]] = OrderedDict()


def kernel(log: StepLog, order: int, outputs: bool = True) -> ModuleType:
    """The log's NAME_np.py at ``order``, executed (its solve; _run and _publish where the log has
    no resolver groups); with resolver groups its ROWS is NAME.py, executed too.  Without
    ``outputs`` a log without resolver groups is rendered without its output columns: its _run
    and PARAMS, what the evaluator reads, are the same (spelling a column costs more than a
    step: 24,000 columns of a 1000-dyad chain)."""
    key = (id(log), order, outputs)
    hit = _recent.get(key)
    if hit is not None and hit[0] is log:
        _recent.move_to_end(key)
        return hit[1]
    bare = log if outputs or log.groups else replace(log, columns=())
    module = _compiled(f"{log.name}_np", source(BACKEND, bare, order))
    if log.groups:
        module.ROWS = _compiled(log.name, source(PYTHON, log, order))  # type: ignore[attr-defined]
    _recent[key] = (log, module)
    if len(_recent) > RECENT:
        _recent.popitem(last=False)
    return module


@functools.cache
def runtime() -> dict[str, Any]:
    """The numpy runtime's functions (row_status, reason_of, branch_at, reach_at), as NAME_np.py has them."""
    ns: dict[str, Any] = {"np": np, "PI": np.pi}
    for name in ("status", "branch", "reach"):
        exec(compile(RUNTIME.source(name), f"<linkgen numpy runtime {name}>", "exec"), ns)
    return ns


class Records(Mapping[str, tuple[np.ndarray, ...]]):
    """The kernel's records as a result holds them: each variable's fields as arrays of the rows,
    made when first read (the analysis reads a few of thousands); ``blocks``: the records of each
    call of the kernel and its rows, in the order of the rows."""

    def __init__(self, blocks: list[tuple[dict[str, Any], int]]):
        self._blocks = blocks
        self._made: dict[str, tuple[np.ndarray, ...]] = {}

    def __getitem__(self, name: str) -> tuple[np.ndarray, ...]:
        if name not in self._made:
            if len(self._blocks) == 1:
                records, rows = self._blocks[0]
                self._made[name] = tuple(column(x, rows) for x in records[name])
            else:
                parts = [[column(x, rows) for x in records[name]] for records, rows in self._blocks]
                self._made[name] = tuple(np.concatenate(fields) for fields in zip(*parts))
        return self._made[name]

    def __iter__(self) -> Iterator[str]:
        return iter(self._blocks[0][0])

    def __len__(self) -> int:
        return len(self._blocks[0][0])


def column(x: Any, rows: int) -> np.ndarray:
    """A kernel's value as an array of the rows: its own where the kernel made one (a result is
    read, never changed), else a copy (a number, or a view of the caller's inputs)."""
    if isinstance(x, np.ndarray) and x.base is None and x.shape == (rows,) and x.dtype == np.float64:
        return x
    out: np.ndarray = np.broadcast_to(np.asarray(x, dtype=float), (rows,)).copy()
    return out
