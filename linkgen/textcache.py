"""Text the package makes from its own code alone, kept per user across processes.

Printing the primitives for the numpy kernel takes 13 ms of every build, and the text depends on
nothing but linkgen's modules.  ``kept(kind, key, make)`` returns make()'s text, read from a store in
the templates' cache directory (render.make_env's, in the temporary directory) when a process made
it before: one JSON file per fingerprint of the package (its place, every module's path, size and
modification time: 1 ms to take), so that a changed module, or another copy of the package, starts a
new store.  Where the directory cannot be read or written, the text is made every time.
"""

from __future__ import annotations

import contextlib
import functools
import hashlib
import json
import os
import tempfile
from collections.abc import Callable
from pathlib import Path

from . import __version__

PACKAGE = Path(__file__).resolve().parent


@functools.cache
def fingerprint() -> str:
    """The package's modules as they are: where it is, and each .py file's path, size and modification time."""
    digest = hashlib.sha256(f"{__version__} {PACKAGE}".encode())
    for folder, subfolders, files in os.walk(PACKAGE):
        subfolders[:] = sorted(s for s in subfolders if s != "__pycache__")
        for name in sorted(f for f in files if f.endswith(".py")):
            st = os.stat(os.path.join(folder, name))
            digest.update(f"{os.path.relpath(folder, PACKAGE)}/{name}:{st.st_size}:{st.st_mtime_ns};".encode())
    return digest.hexdigest()[:32]


class Store:
    """The texts kept for one fingerprint, in ``folder`` (none: nothing is kept)."""

    def __init__(self, folder: str) -> None:
        self.path = Path(folder) / f"linkgen-text-{fingerprint()}.json" if folder else None
        self.texts: dict[str, str] = {}
        if self.path is not None:
            with contextlib.suppress(OSError, ValueError):
                self.texts = json.loads(self.path.read_text(encoding="utf-8"))

    def kept(self, key: str, make: Callable[[], str]) -> str:
        if key in self.texts:
            return self.texts[key]
        text = self.texts[key] = make()
        if self.path is not None:  # written whole and renamed: a reader never sees half a store
            with contextlib.suppress(OSError):
                fd, tmp = tempfile.mkstemp(dir=self.path.parent, prefix=".linkgen-text-")
                try:
                    with os.fdopen(fd, "w", encoding="utf-8") as out:
                        json.dump(self.texts, out)
                    os.replace(tmp, self.path)
                except OSError:
                    os.unlink(tmp)
                    raise
        return text


@functools.cache
def store() -> Store:
    from .render import make_env  # the templates' cache: render imports the backends, which use this module

    cache = make_env().bytecode_cache
    return Store(getattr(cache, "directory", "") or "")


def kept(kind: str, key: tuple[object, ...], make: Callable[[], str]) -> str:
    """make()'s text for (kind, key), kept across processes while the package is unchanged."""
    return store().kept(f"{kind}:{key!r}", make)
