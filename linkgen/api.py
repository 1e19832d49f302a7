"""The Python API: a mechanism file as an object, its procedure, its sweep as a numpy
structured array, its engineering summary, its assemblies and instant centres at one input,
and its generated files.  The command line (linkgen.cli) is a thin layer over it.

>>> import linkgen
>>> m = linkgen.load("samples/slider_crank/slider_crank.yaml")
>>> m.name, len(m.procedure)
('slider_crank', 6)
>>> rows = m.sweep(samples=5, order=0)
>>> rows.dtype.names[:3], len(rows)
(('theta_O', 'O.x', 'O.y'), 5)
>>> round(float(rows["S.s"][0]), 9)  # the crank at 0: B at x = 20 + sqrt(65^2 - 13^2), drawn at 76
7.686733312
>>> summary = m.check()
>>> summary.failed, [t.name for t in summary.travels if t.quantity == "slide"]
(0, ['S.s'])
>>> found = m.assemblies(at=[90])  # the crank at 90 deg: B at x = +-sqrt(65^2 - 33^2) = +-56, s = x - 76
>>> [(a.number, a.sketch, round(a.values["S.s"], 9)) for a in found.census.assemblies]
[(1, True, -20.0), (2, False, -132.0)]
>>> frame_rod = m.centres(at=[90]).by_name("ic:frame:rod")  # the rod translates for an instant
>>> frame_rod.centre.kind, frame_rod.status
('third A', 1)
"""

from __future__ import annotations

import functools
import os
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING

import numpy as np

from .pipeline import build_log
from .steplog import Step, StepLog
from .summary.compute import summarize
from .summary.records import Summary

if TYPE_CHECKING:  # the census needs python-flint: imported when asked for
    from .assemblies import Census
    from .instant.table import Located, Table
    from .model import Mechanism as Model

CHUNK = 65536  # rows evaluated at once by a sweep with progress


class InputCountError(ValueError):
    """Values given for a mechanism's inputs that are not one per input; ``argument`` names the
    argument they were given as (``at``, ``rates``)."""

    def __init__(self, log: StepLog, given: Sequence[float], argument: str) -> None:
        n, names = len(log.inputs), ", ".join(i.column for i in log.inputs)
        super().__init__(f"{len(given)} value{'s' if len(given) != 1 else ''} given; {log.name} has "
                         f"{n} input{'s' if n != 1 else ''} ({names})")
        self.argument = argument


def _one_per_input(log: StepLog, **given: Sequence[float] | None) -> None:
    for argument, values in given.items():
        if values is not None and len(values) != len(log.inputs):
            raise InputCountError(log, values, argument)


@dataclass(frozen=True)
class Assemblies:
    """Every assembly at one input (``Mechanism.assemblies``): the census (linkgen.assemblies:
    ``census.assemblies``, each with its ``number``, ``sketch`` mark, branch ``choices`` and
    column ``values`` at order 0) and the step log it walked (the whole procedure at order 0)."""

    log: StepLog
    census: Census

    def text(self) -> str:
        """The table ``linkgen assemblies`` prints."""
        from .assemblies.report import table

        return table(self.log, self.census)

    def json(self) -> str:
        """The JSON ``linkgen assemblies --json`` prints."""
        from .assemblies.report import to_json

        return to_json(self.log, self.census)

    def figures(self) -> dict[str, bytes]:
        """One SVG per assembly, by file name (NAME_assembly_K.svg), nothing written."""
        from .assemblies.render import render_all

        return render_all(self.log, self.census)


@dataclass(frozen=True)
class Centres:
    """Every instant centre at one row (``Mechanism.centres``): the table (linkgen.instant.table:
    ``table.centres``, each with its class and place) and the step log that located them (every
    centre an output, order 1)."""

    log: StepLog
    table: Table

    def by_name(self, name: str) -> Located:
        """The centre named ``ic:A:B``."""
        return next(c for c in self.table.centres if c.centre.name == name)

    def text(self) -> str:
        """The table ``linkgen ic`` prints."""
        from .instant.table import text

        return text(self.log, self.table)

    def json(self) -> str:
        """The JSON ``linkgen ic --json`` prints."""
        from .instant.table import to_json

        return to_json(self.log, self.table)


@dataclass(frozen=True)
class Mechanism:
    """A mechanism file with the outputs, order and settings to build it with (None: the file's;
    settings: linkgen.options.Options' fields, e.g. {"real": "float"}).  Its step log is made on
    first use; ``build`` adds the conditioning over the sweep that the manual shows."""

    path: str
    outputs: tuple[str, ...] | None = None
    order: int | None = None
    settings: Mapping[str, object] = field(default_factory=dict)

    @functools.cached_property
    def log(self) -> StepLog:
        """The step log without the conditioning over the sweep (what run and check need)."""
        return build_log(self.path, self.outputs, self.order, sweep=False, options=self.settings)

    @functools.cached_property
    def full_log(self) -> StepLog:
        """The step log with the conditioning over the sweep (what build renders)."""
        return build_log(self.path, self.outputs, self.order, options=self.settings)

    @property
    def name(self) -> str:
        """The mechanism's name: from the step log already made (``build``'s, else made now)."""
        return (self.full_log if "full_log" in self.__dict__ else self.log).name

    @property
    def procedure(self) -> tuple[Step, ...]:
        """The numbered steps (fallback blocks' steps included, their ``variant`` > 0)."""
        return self.log.steps

    @property
    def columns(self) -> tuple[str, ...]:
        """The sweep's columns (inputs first), then ``status``."""
        return (*(c.name for c in self.log.columns), "status")

    def files(self) -> dict[str, bytes]:
        """Every generated file, by name: the step log, the manual, its figures (the motion's
        plots too), the page and the programs."""
        from .render import render_all

        return render_all(self.full_log, motion=True)

    def build(self, outdir: str | None = None) -> list[str]:
        """Write the generated files into outdir (default build/NAME); the paths written."""
        from .writer import write_all

        files = self.files()
        return write_all(files, outdir or os.path.join("build", self.name))

    def sweep(self, samples: int | None = None, order: int | None = None,
              progress: Callable[[int], None] | None = None) -> np.ndarray:
        """The sweep (samples rows, default the file's samples; all inputs move together, or every
        combination of them with the file's ``sweep: grid``: samples to the power of the inputs
        rows) as a structured array with one float field per column, as the CSV has them, and an
        int field ``status``;
        ``order`` (0, 1, 2) other than the mechanism's gives the columns of that order.  ``progress``
        is called with the number of rows done after each chunk of CHUNK rows."""
        from .rows import input_rows, line_length
        from .units import sweep_lists

        if order is not None and order != self.log.order:
            return replace(self, order=order).sweep(samples, None, progress)
        n = samples or self.log.samples
        values, rates, accs = input_rows(self.log, n, sweep_lists(self.log))
        return self._rows(values, rates, accs, progress, line_length(self.log, n))

    def at(self, values: Sequence[float], rates: Sequence[float] | None = None,
           accelerations: Sequence[float] | None = None) -> np.void:
        """One row at the inputs' values (the programs' units: radians, or degrees with units: file), their
        rates (default: the inputs' speeds) and accelerations (default 0)."""
        from .units import sweep_lists

        n = len(self.log.inputs)
        if len(values) != n:
            raise ValueError(f"{len(values)} values given; {self.name} has {n} inputs")
        speeds = sweep_lists(self.log)["speed"] if rates is None else list(rates)
        accs = [0.0] * n if accelerations is None else list(accelerations)
        row: np.void = self._rows(np.array([values], dtype=float), np.array([speeds], dtype=float),
                                  np.array([accs], dtype=float), None)[0]
        return row

    def check(self) -> Summary:
        """The engineering summary (linkgen.summary.records): the full log's where it is built,
        else found now (no conditioning over the sweep: faster)."""
        if "full_log" in self.__dict__ and self.full_log.summary is not None:
            return self.full_log.summary
        return summarize(self.log)

    @functools.cached_property
    def model(self) -> Model:
        """The mechanism as the file describes it (linkgen.model), checked."""
        from .validate import read_mechanism

        return read_mechanism(self.path)

    def assemblies(self, at: Sequence[float] | None = None) -> Assemblies:
        """Every assembly at the inputs' values ``at``, one per input in the file's units (degrees
        where the file gives degrees; default: the sketch's), the count certified: both branches
        of every two-link chain, every real root of every class-III group's polynomial.  The
        outputs, order and settings do not matter: the whole procedure is walked, at order 0.
        Raises InputCountError for a wrong count of values, linkgen.errors.ProcedureError where
        the assemblies cannot be counted."""
        from .assemblies import assemblies, whole_log

        log = whole_log(self.path)
        _one_per_input(log, at=at)
        return Assemblies(log, assemblies(self.path, log, at))

    def centres(self, at: Sequence[float] | None = None, rates: Sequence[float] | None = None) -> Centres:
        """Every instant centre at the inputs' values ``at`` and rates ``rates``, one per input in
        the file's units (degrees and degrees per second where the file gives degrees; default:
        the sketch and the inputs' speeds): its class from the topology, its place from the
        links' velocities (with several inputs, their ratio matters).  Raises InputCountError for
        a wrong count of values."""
        from .instant.table import centre_outputs, locate

        log = replace(self, outputs=centre_outputs(self.model), order=1).log
        _one_per_input(log, at=at, rates=rates)
        return Centres(log, locate(log, self.model, at, rates))

    def _rows(self, values: np.ndarray, rates: np.ndarray, accs: np.ndarray,
              progress: Callable[[int], None] | None, line: int = 0) -> np.ndarray:
        """The rows evaluated CHUNK at a time (whole lines of ``line`` rows: see evaluate), each
        chunk from the last one's warm start (a line's first row: from the sketch)."""
        from .evaluate import evaluate
        from .table import columns
        from .units import outputs_from_si, to_si

        log = self.log
        names = [c.name for c in log.columns]
        out = np.zeros(len(values), dtype=[*((n, "f8") for n in names), ("status", "i8")])
        warm = None
        chunk = max(CHUNK // line, 1) * line if line else CHUNK
        for lo in range(0, len(values), chunk):
            hi = min(lo + chunk, len(values))
            with np.errstate(all="ignore"):
                result = evaluate(log, *to_si(log, values[lo:hi], rates[lo:hi], accs[lo:hi]), warm=warm, line=line)
            warm = result.warm[-1] if result.warm and not line else None
            _, data = columns(log, result)
            data[:, :len(log.inputs)] = values[lo:hi]  # the inputs as given
            outputs_from_si(log, data)
            for k, n in enumerate(names):
                out[n][lo:hi] = data[:, k]
            out["status"][lo:hi] = result.status
            if progress is not None:
                progress(hi - lo)
        return out


def load(path: str | os.PathLike[str], outputs: Iterable[str] | None = None, order: int | None = None,
         settings: Mapping[str, object] | None = None) -> Mechanism:
    """The mechanism of a file (read and checked now: a bad file raises linkgen.errors.InputError)."""
    m = Mechanism(os.fspath(path), None if outputs is None else tuple(outputs), order, dict(settings or {}))
    m.log  # noqa: B018 - read the file now, so that a bad one fails here
    return m


def csv_text(m: Mechanism, rows: np.ndarray) -> str:
    """Rows of a sweep as the CSV the programs write."""
    from numpy.lib.recfunctions import structured_to_unstructured

    from .table import number

    names = list(m.columns)
    data = structured_to_unstructured(rows[names[:-1]], dtype=float)
    lines = [",".join(names)]
    for row, st in zip(data.tolist(), rows["status"].tolist()):
        lines.append(",".join([number(x) for x in row] + [str(st)]))
    return "\n".join(lines) + "\n"


__all__ = ["Assemblies", "Centres", "InputCountError", "Mechanism", "csv_text", "load"]
