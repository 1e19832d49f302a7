"""Errors a user can act on: each names the file (and for input errors the line and the key)."""

from __future__ import annotations

import errno
from collections.abc import Iterable


class LinkgenError(Exception):
    """A problem with the user's input or request, reported as ``file:line: key: message``."""

    def __init__(self, message: str, path: str = "", line: int = 0, key: str = ""):
        super().__init__(message)
        self.message = message
        self.path = path
        self.line = line
        self.key = key

    def __str__(self) -> str:
        where = self.path
        if self.line:
            where = f"{where}:{self.line}"
        parts = [p for p in (where, self.key) if p]
        return ": ".join(parts + [self.message])


class InputError(LinkgenError):
    """The mechanism file is malformed or describes an impossible mechanism."""


class ProcedureError(LinkgenError):
    """No systematic-analysis procedure can be extracted for a valid mechanism."""


class FileSystemError(LinkgenError):
    """A file or directory linkgen must read or write cannot be used, reported as ``path: message``."""


# The system's wording where it would puzzle a user in linkgen's sentences.
_REASONS: dict[int | None, str] = {
    errno.ENOENT: "no such file or directory",
    errno.ENOTDIR: "a part of the path is not a directory",
    errno.EISDIR: "it is a directory",
    errno.EROFS: "the file system is read-only",
    errno.ENOSPC: "no space left on the device",
}


def os_reason(exc: OSError) -> str:
    """Why an operating-system call failed, in lower case: 'permission denied', ..."""
    reason = _REASONS.get(exc.errno) or exc.strerror or str(exc)
    return reason[:1].lower() + reason[1:]


def and_list(names: Iterable[str]) -> str:
    """'a', 'a and b', 'a, b and c': names listed in a message."""
    names = list(names)
    return ", ".join(names[:-1]) + " and " + names[-1] if len(names) > 1 else "".join(names)
