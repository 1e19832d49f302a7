"""Write rendered files atomically, or compare them with what is on disk."""

from __future__ import annotations

import difflib
import os
import tempfile


def write_all(files: dict[str, bytes], outdir: str) -> list[str]:
    """Write every file into a temporary file first, then rename them all into place.

    Nothing on disk changes unless every file was written, so a failed build
    leaves the earlier outputs untouched.
    """
    os.makedirs(outdir, exist_ok=True)
    staged: list[tuple[str, str]] = []
    try:
        for name in sorted(files):
            fd, tmp = tempfile.mkstemp(prefix=f".{name}.", suffix=".tmp", dir=outdir)
            with os.fdopen(fd, "wb") as fh:
                fh.write(files[name])
            staged.append((tmp, os.path.join(outdir, name)))
    except BaseException:
        for tmp, _ in staged:
            os.unlink(tmp)
        raise
    for tmp, final in staged:
        os.replace(tmp, final)
    return [final for _, final in staged]


def differences(files: dict[str, bytes], outdir: str) -> list[str]:
    """Unified diffs of every file that differs from (or is missing in) outdir."""
    out = []
    for name in sorted(files):
        path = os.path.join(outdir, name)
        try:
            with open(path, "rb") as fh:
                old = fh.read()
        except FileNotFoundError:
            old = None
        if old == files[name]:
            continue
        old_lines = [] if old is None else old.decode("utf-8", "replace").splitlines(keepends=True)
        new_lines = files[name].decode("utf-8").splitlines(keepends=True)
        diff = difflib.unified_diff(old_lines, new_lines, f"{path} (on disk)", f"{path} (rebuilt)")
        out.append("".join(diff) or f"{path}: missing\n")
    return out
