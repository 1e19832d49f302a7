"""The target languages: one sub-package a language, each a Backend (README.md: the contract).

``backends()`` finds them: every sub-package of this folder, in name order, is a language whose
``BACKEND`` says what it provides.  linkgen.render writes each backend's files; linkgen.names
asks each which user names its files cannot carry.
"""

from __future__ import annotations

import functools
import importlib
import pkgutil
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from importlib import resources
from typing import TYPE_CHECKING, Any, Generic, Protocol, TypeVar

if TYPE_CHECKING:
    from ..primitives.dsl import Primitive
    from ..render.view import View
    from .spelling import Spelling


S = TypeVar("S", bound="Spelling")


class Template(Protocol):
    """Renders one of the backend's templates (its name inside the backend's template folder)
    with the context every template gets (v, L, banner, name, max_input) and ``context``."""

    def __call__(self, template: str, /, **context: object) -> bytes: ...


def _fits(name: str, mechanism: str = "") -> str:
    return ""


@dataclass(frozen=True)
class Words:
    """What a backend's files make of the user's names (each rule: why not, '' when fine)."""

    field_word: Callable[[str], str] = _fits  # why a pair, point or link name gets a trailing _ as a field
    mechanism_problem: Callable[[str], str] = _fits  # why the mechanism name cannot name the files
    entity_problem: Callable[[str, str], str] = _fits  # (name, mechanism) why a name cannot be an output
    state: str = ""  # the structure holding the outputs, NAME standing for the mechanism's name
    state_fields: frozenset[str] = frozenset()  # its fields besides the outputs

    def field(self, name: str) -> str:
        """A pair, point or link name as a field of the outputs."""
        return f"{name}_" if self.field_word(name) else name


@dataclass(frozen=True)
class Runtime:
    """Hand-written runtime sources (status, branch, reach, resolver, driver), pasted into the
    programs as they are; the evaluator runs the Python ones."""

    package: str  # the package whose folder holds them
    folder: str
    suffix: str  # of each source's file name: .c

    def source(self, name: str) -> str:
        """The source ``name`` (status, branch, reach, resolver, driver)."""
        return _packaged_text(self.package, self.folder, name + self.suffix)


@functools.cache
def _packaged_text(package: str, folder: str, name: str) -> str:
    """A file shipped in a package's folder, read once per process (a build pastes each runtime source
    into several programs and kernels)."""
    return resources.files(package).joinpath(folder).joinpath(name).read_text(encoding="utf-8")


@dataclass(frozen=True)
class Backend(Generic[S]):
    """One target language: what it writes, how it spells the procedure, what it runs on."""

    name: str  # its folder under linkgen/backends/
    language: str  # how messages name it
    templates: str  # its folder under the top-level templates/
    files: tuple[str, ...]  # the files it writes, NAME standing for the mechanism's name
    comment: tuple[str, str]  # how a comment opens and closes ('' where the line's end closes it)
    spelling: type[S]  # the templates' L: references, calls and the literal format
    render: Callable[[View, S, Template], dict[str, bytes]]  # the files, keyed as in ``files``
    filters: Mapping[str, Callable[..., str]] = field(default_factory=dict)  # its templates' own filters
    printer: Callable[[Primitive, int], str] | None = None  # a DSL primitive as a function at an order
    runtime: Runtime | None = None
    words: Words = Words()
    reals: tuple[str, ...] = ("double",)  # the real types (policy.REAL_TYPES) its programs compute in

    def real(self, asked: str) -> str:
        """The real type its files compute in when ``asked`` is asked for, in words for their banners."""
        if asked in self.reals:
            return f"Real type: {asked}."
        return f"Real type: double (linkgen writes {self.language} in double only; {asked} was asked for)."


def word_list(module: str, name: str) -> frozenset[str]:
    """The words of the data file ``name`` beside the module ``module``: one a line, # starting a comment line."""
    text = resources.files(module.rpartition(".")[0]).joinpath(name).read_text(encoding="utf-8")
    return frozenset(line for line in text.splitlines() if line and not line.startswith("#"))


@functools.cache
def backends() -> tuple[Backend[Any], ...]:
    """Every backend: the sub-packages of this folder, in name order."""
    found = []
    for module in sorted(m.name for m in pkgutil.iter_modules(__path__) if m.ispkg):
        backend = importlib.import_module(f"{__name__}.{module}").BACKEND
        if not isinstance(backend, Backend) or backend.name != module:
            raise TypeError(f"linkgen.backends.{module}.BACKEND is not the Backend named {module}")
        found.append(backend)
    return tuple(found)
