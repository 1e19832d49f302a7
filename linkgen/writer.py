"""Write rendered files all or nothing, or compare them with what is on disk.

``write_all`` works in two phases in the output directory:

1. Prepare, where nothing a reader looks for changes: create the output directory (and
   its missing parents), check every target (it must be absent or a regular file the user
   may write: a directory, link, special or read-only file in the way is an error), write
   every file to a hidden temporary ``.NAME.XXXXXXXX.tmp`` beside its target.
2. Commit: keep a backup of each existing target (a hard link ``.NAME.XXXXXXXX.old``;
   where the file system has no hard links the old file is renamed to it, so the target
   is missing for a moment), then rename each temporary over its target.

Guaranteed: when anything fails (an error of the system, or Ctrl-C) before the last
rename, every step is undone before ``FileSystemError`` (or the interrupt) is raised:
the earlier outputs are back byte for byte (the same files: inode, mode and times),
files and directories that did not exist before are gone, and no temporary or backup
is left (should an undo step fail too, the error says which).  New files get the mode
any new file of the user gets (0666 less the umask, e.g. 0644 under umask 0022); a
replaced file gets that mode too, not the old file's.

Not guaranteed (POSIX has no rename of several files at once): a process killed by a
signal it cannot catch (SIGKILL, or SIGTERM, which Python does not turn into an
exception), or a machine losing power, between the first and the last rename leaves a
mix of old and new outputs and the hidden ``.tmp``/``.old`` files (delete them; the next
build writes every output again).  Files are not flushed to the disk (no fsync), so after
a power loss a file just written may be empty.  Another program writing the same
directory at the same time, or reading it during the renames, sees a mix.
"""

from __future__ import annotations

import contextlib
import difflib
import errno
import functools
import os
import secrets
import stat
from collections.abc import Callable, Iterator

from .errors import FileSystemError, os_reason


@contextlib.contextmanager
def _doing(action: str, path: str, creating: bool = False) -> Iterator[None]:
    """Report a failing system call as ``path: action: reason``."""
    try:
        yield
    except OSError as exc:
        reason = os_reason(exc)
        if creating and exc.errno == errno.ENOENT:  # the directory is there: /proc, /sys, ...
            reason = "the file system does not allow it"
        raise FileSystemError(f"{action}: {reason}", path) from None


def _hidden(final: str, suffix: str, make: Callable[[str], None]) -> str:
    """Make ``.NAME.XXXXXXXX<suffix>`` beside final with make(path), which raises
    FileExistsError when the name is taken; return its path."""
    directory, name = os.path.split(final)
    while True:
        path = os.path.join(directory, f".{name}.{secrets.token_hex(4)}{suffix}")
        try:
            make(path)
            return path
        except FileExistsError:
            continue


def _make_directory(outdir: str, undo: list[Callable[[], None]]) -> None:
    """Create outdir and its missing parents, each with its removal on undo."""
    outdir = outdir.rstrip(os.sep) or outdir
    missing = []
    path = outdir
    while path and not os.path.lexists(path):
        missing.append(path)
        path = os.path.dirname(path)
    if path and not os.path.isdir(path):
        inside = "" if path == outdir else f" (the output directory {outdir} would be inside it)"
        raise FileSystemError(f"not a directory{inside}", path)
    for path in reversed(missing):
        with _doing("cannot create the directory", path, creating=True):
            os.mkdir(path)
        undo.append(functools.partial(os.rmdir, path))


def _check_target(path: str) -> bool:
    """Whether path exists; raise if it exists and is not a regular file the user may replace."""
    try:
        mode = os.lstat(path).st_mode
    except FileNotFoundError:
        return False
    except OSError as exc:
        raise FileSystemError(f"cannot look at the file: {os_reason(exc)}", path) from None
    if stat.S_ISDIR(mode):
        raise FileSystemError("a directory is in the way of this output file; move or remove it", path)
    if not stat.S_ISREG(mode):
        raise FileSystemError("a link or a special file is in the way of this output file; move or remove it",
                              path)
    if not os.access(path, os.W_OK):
        raise FileSystemError("the file is read-only; make it writable (chmod u+w) or remove it", path)
    return True


def _write_temporary(final: str, data: bytes, undo: list[Callable[[], None]]) -> str:
    """Write data to a new hidden file beside final, made as open() makes a new file."""
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL
    with _doing("cannot create files in this directory", os.path.dirname(final) or ".", creating=True):
        tmp = _hidden(final, ".tmp", lambda p: os.close(os.open(p, flags, 0o666)))
    undo.append(lambda: _remove(tmp))
    with _doing("cannot write the file", final), open(tmp, "wb") as fh:
        fh.write(data)
    return tmp


def _back_up(final: str, undo: list[Callable[[], None]]) -> str:
    """Keep the old final as a hidden hard link (or, without hard links, renamed aside)."""
    try:
        backup = _hidden(final, ".old", lambda p: os.link(final, p))
    except OSError:
        with _doing("cannot move the earlier file aside", final):
            backup = _hidden(final, ".old", lambda p: _rename_to_free_name(final, p))
    undo.append(lambda: _restore(backup, final))
    return backup


def _restore(backup: str, final: str) -> None:
    os.replace(backup, final)
    _remove(backup)  # still there when final was not replaced yet: rename between two links of a file does nothing


def _rename_to_free_name(path: str, new: str) -> None:
    if os.path.lexists(new):
        raise FileExistsError(new)
    os.rename(path, new)


def _remove(path: str) -> None:
    with contextlib.suppress(FileNotFoundError):
        os.unlink(path)


def _roll_back(undo: list[Callable[[], None]]) -> list[str]:
    """Undo every step, last first; return the steps that failed too."""
    failed = []
    for step in reversed(undo):
        try:
            step()
        except OSError as exc:
            failed.append(f"{exc.filename}: {os_reason(exc)}")
    return failed


def write_all(files: dict[str, bytes], outdir: str) -> list[str]:
    """Write every file (name -> bytes) into outdir, all or nothing; return their paths.

    Raises FileSystemError (``path: message``) with everything undone when a file cannot
    be written; see the module's docstring for what is and is not guaranteed.
    """
    undo: list[Callable[[], None]] = []
    backups = []
    names = sorted(files)
    targets = [os.path.join(outdir, name) for name in names]
    try:
        _make_directory(outdir, undo)
        exists = [_check_target(final) for final in targets]
        temporaries = [_write_temporary(final, files[name], undo) for final, name in zip(targets, names)]
        for tmp, final, old in zip(temporaries, targets, exists):
            if old:
                backups.append(_back_up(final, undo))
            with _doing("cannot replace the file" if old else "cannot create the file", final):
                os.replace(tmp, final)
            if not old:
                undo.append(functools.partial(os.unlink, final))
    except FileSystemError as exc:
        failed = _roll_back(undo)
        if failed:
            exc.message += "; restoring the earlier outputs failed too: " + "; ".join(failed)
        raise
    except BaseException:
        _roll_back(undo)
        raise
    for backup in backups:
        with contextlib.suppress(OSError):  # the outputs are complete; a stray backup is harmless
            os.unlink(backup)
    return targets


def _read(path: str) -> bytes | None:
    """The file's bytes, or None where it does not exist."""
    try:
        with open(path, "rb") as fh:
            return fh.read()
    except FileNotFoundError:
        return None
    except OSError as exc:
        raise FileSystemError(f"cannot read the file: {os_reason(exc)}", path) from None


def differences(files: dict[str, bytes], outdir: str) -> list[str]:
    """Unified diffs of every file that differs from (or is missing in) outdir."""
    if not os.path.isdir(outdir):
        why = "not a directory" if os.path.lexists(outdir) else "no such directory"
        raise FileSystemError(f"{why}: nothing to check against (linkgen build writes it)", outdir)
    out = []
    for name in sorted(files):
        path = os.path.join(outdir, name)
        old = _read(path)
        if old == files[name]:
            continue
        old_lines = [] if old is None else old.decode("utf-8", "replace").splitlines(keepends=True)
        new_lines = files[name].decode("utf-8").splitlines(keepends=True)
        diff = difflib.unified_diff(old_lines, new_lines, f"{path} (on disk)", f"{path} (rebuilt)")
        out.append("".join(diff) or f"{path}: missing\n")
    return out
