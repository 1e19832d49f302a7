"""linkgen.writer: all-or-nothing writes, modes that follow the umask, faults as FileSystemError.

Faults are injected at every system call the writer makes (creating a directory, a
temporary, writing it, linking a backup, each rename), one at a time; after each, the
output directory must be exactly as before: the same names, bytes, modes, inodes and
times, and nothing hidden left behind.
"""

from __future__ import annotations

import builtins
import contextlib
import errno
import os
import stat
from pathlib import Path

import pytest

from linkgen import writer
from linkgen.errors import FileSystemError

FILES = {name: f"new {name}\n".encode() * 100 for name in ("m.c", "m.h", "m.json", "m.md", "m.py")}
OLD = {"m.c": b"old c\n", "m.md": b"old md\n", "m.py": b"old py\n", "notes.txt": b"not an output\n"}


def snapshot(root: Path) -> dict[str, tuple]:
    """Every entry under root, hidden ones too: kind, mode, inode, and for files the times and bytes."""
    out = {}
    for path in sorted(root.rglob("*")):
        st = path.lstat()
        if stat.S_ISDIR(st.st_mode):  # adding and removing a temporary changes a directory's times
            out[str(path.relative_to(root))] = (stat.S_IFDIR, stat.S_IMODE(st.st_mode), st.st_ino)
            continue
        data = path.read_bytes() if stat.S_ISREG(st.st_mode) else None
        out[str(path.relative_to(root))] = (stat.S_IFMT(st.st_mode), stat.S_IMODE(st.st_mode), st.st_ino,
                                            st.st_mtime_ns, data)
    return out


def old_outputs(folder: Path) -> Path:
    """An output directory from an earlier build: three of the five outputs and a file of the user's."""
    folder.mkdir(parents=True)
    for name, data in OLD.items():
        (folder / name).write_bytes(data)
        (folder / name).chmod(0o640)
    return folder


@contextlib.contextmanager
def umask(mask: int):
    old = os.umask(mask)
    try:
        yield
    finally:
        os.umask(old)


@pytest.mark.parametrize("mask", [0o022, 0o002, 0o077])
def test_new_files_and_directories_follow_the_umask(tmp_path: Path, mask: int):
    out = tmp_path / "a" / "b"
    with umask(mask):
        paths = writer.write_all(FILES, str(out))
    assert paths == [str(out / name) for name in sorted(FILES)]
    assert {p.name: p.read_bytes() for p in out.iterdir()} == FILES
    for name in FILES:
        assert stat.S_IMODE((out / name).stat().st_mode) == 0o666 & ~mask
    for folder in (tmp_path / "a", out):
        assert stat.S_IMODE(folder.stat().st_mode) == 0o777 & ~mask


@pytest.mark.parametrize("mask", [0o022, 0o002, 0o077])
def test_replaced_files_get_the_new_files_mode(tmp_path: Path, mask: int):
    out = old_outputs(tmp_path / "out")
    with umask(mask):
        writer.write_all(FILES, str(out))
    assert {p.name: p.read_bytes() for p in out.iterdir()} == FILES | {"notes.txt": OLD["notes.txt"]}
    for name in FILES:
        assert stat.S_IMODE((out / name).stat().st_mode) == 0o666 & ~mask
    assert stat.S_IMODE((out / "notes.txt").stat().st_mode) == 0o640


def test_the_current_directory_is_the_empty_name(tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    monkeypatch.chdir(tmp_path)
    assert writer.write_all({"x.csv": b"a,b\n"}, "") == ["x.csv"]
    assert [p.name for p in tmp_path.iterdir()] == ["x.csv"]


@pytest.mark.parametrize("obstacle", ["directory", "symlink", "fifo"])
def test_something_else_in_the_way_changes_nothing(tmp_path: Path, obstacle: str):
    out = old_outputs(tmp_path / "out")
    blocked = out / "m.json"  # in the middle of the sorted names
    if obstacle == "directory":
        blocked.mkdir()
        (blocked / "inside").write_bytes(b"x")
    elif obstacle == "symlink":
        blocked.symlink_to(out / "notes.txt")
    else:
        os.mkfifo(blocked)
    before = snapshot(tmp_path)
    with pytest.raises(FileSystemError) as caught:
        writer.write_all(FILES, str(out))
    assert str(caught.value).startswith(f"{blocked}: a ")
    assert "is in the way of this output file; move or remove it" in str(caught.value)
    assert snapshot(tmp_path) == before


def test_an_output_directory_that_is_a_file(tmp_path: Path):
    (tmp_path / "f").write_bytes(b"x")
    before = snapshot(tmp_path)
    with pytest.raises(FileSystemError, match=f"^{tmp_path}/f: not a directory$"):
        writer.write_all(FILES, str(tmp_path / "f"))
    with pytest.raises(FileSystemError, match=f"^{tmp_path}/f: not a directory "
                                              r"\(the output directory .*/f/g/h would be inside it\)$"):
        writer.write_all(FILES, str(tmp_path / "f" / "g" / "h"))
    assert snapshot(tmp_path) == before


class Faults:
    """Counts the writer's system calls; makes the one numbered ``fail_at`` of ``kind`` fail."""

    KINDS = ("mkdir", "open", "write", "link", "rename", "replace")

    def __init__(self, monkeypatch: pytest.MonkeyPatch, kind: str = "", fail_at: int = -1,
                 error: BaseException | None = None, hard_links: bool = True):
        self.calls = dict.fromkeys(self.KINDS, 0)
        self.kind, self.fail_at, self.error = kind, fail_at, error or OSError(errno.EIO, "Input/output error")
        for name in ("mkdir", "open", "link", "rename", "replace"):
            original = getattr(os, name) if hard_links or name != "link" else self._no_links
            monkeypatch.setattr(os, name, self._counted(name, original))
        write = self._counted("write", lambda fh, data: fh.write(data))
        monkeypatch.setattr(writer, "open", lambda path, mode: _Writing(builtins.open(path, mode), write),  # noqa: SIM115
                            raising=False)

    def _counted(self, kind, original):
        def call(*args, **kwargs):
            number = self.calls[kind]
            self.calls[kind] += 1
            if kind == self.kind and number == self.fail_at:
                raise self.error
            return original(*args, **kwargs)
        return call

    @staticmethod
    def _no_links(*args, **kwargs):
        raise OSError(errno.EPERM, "Operation not permitted")


class _Writing:
    """A file opened for writing whose write goes through the fault counter."""

    def __init__(self, fh, write):
        self.fh, self.write_through = fh, write

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.fh.close()

    def write(self, data):
        return self.write_through(self.fh, data)


def replace_scenario(root: Path) -> Path:
    """An earlier build to replace: its output directory."""
    return old_outputs(root / "out")


def create_scenario(root: Path) -> Path:
    """No output directory yet, nor its parent: the output directory to create."""
    root.mkdir()
    return root / "a" / "b"


@pytest.mark.parametrize("scenario", [replace_scenario, create_scenario], ids=["replace", "create"])
@pytest.mark.parametrize("hard_links", [True, False], ids=["hard-links", "no-hard-links"])
def test_a_fault_at_any_call_is_undone(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, scenario, hard_links: bool):
    out = scenario(tmp_path / "count")
    with monkeypatch.context() as m:
        counter = Faults(m, hard_links=hard_links)
        writer.write_all(FILES, str(out))
    total = counter.calls
    existing = sum(name in FILES for name in OLD) if scenario is replace_scenario else 0
    assert total == {"mkdir": 0 if existing else 2, "open": len(FILES), "write": len(FILES),
                     "link": existing, "rename": 0 if hard_links else existing, "replace": len(FILES)}
    for kind in Faults.KINDS:
        for k in range(total[kind]):
            root = tmp_path / f"{kind}{k}"
            out = scenario(root)
            before = snapshot(root)
            with monkeypatch.context() as m:
                Faults(m, kind, k, hard_links=hard_links)
                if kind == "link":  # the old file is renamed aside instead
                    writer.write_all(FILES, str(out))
                    assert {p.name: p.read_bytes() for p in out.iterdir()} == FILES | {"notes.txt": OLD["notes.txt"]}
                    continue
                with pytest.raises(FileSystemError) as caught:
                    writer.write_all(FILES, str(out))
            assert str(caught.value).endswith(": input/output error"), caught.value
            assert snapshot(root) == before, f"{kind} #{k}: {caught.value}"


def test_an_interrupt_during_the_renames_is_undone(tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    out = old_outputs(tmp_path / "out")
    before = snapshot(tmp_path)
    for k in range(len(FILES)):
        with monkeypatch.context() as m:
            Faults(m, "replace", k, error=KeyboardInterrupt())
            with pytest.raises(KeyboardInterrupt):
                writer.write_all(FILES, str(out))
        assert snapshot(tmp_path) == before


def test_a_failed_restore_is_reported(tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    out = old_outputs(tmp_path / "out")
    calls = []
    real = os.replace

    def replace(src, dst):
        calls.append((src, dst))
        if len(calls) == 2:  # the second output cannot be renamed into place
            raise OSError(errno.ENOSPC, "No space left on device", dst)
        if len(calls) == 3:  # and the first one's backup cannot be put back
            raise OSError(errno.EIO, "Input/output error", src)
        return real(src, dst)

    monkeypatch.setattr(os, "replace", replace)
    with pytest.raises(FileSystemError) as caught:
        writer.write_all(FILES, str(out))
    backup = calls[2][0]
    assert str(caught.value) == (f"{out}/m.h: cannot create the file: no space left on the device; restoring the "
                                 f"earlier outputs failed too: {backup}: input/output error")
    assert Path(backup).read_bytes() == OLD["m.c"], "the earlier m.c is kept in the backup the message names"


def test_check_against_a_missing_or_unreadable_directory(tmp_path: Path):
    with pytest.raises(FileSystemError, match=f"^{tmp_path}/none: no such directory: nothing to check against"):
        writer.differences(FILES, str(tmp_path / "none"))
    (tmp_path / "f").write_bytes(b"x")
    with pytest.raises(FileSystemError, match=f"^{tmp_path}/f: not a directory: nothing to check against"):
        writer.differences(FILES, str(tmp_path / "f"))
    (tmp_path / "out").mkdir()
    (tmp_path / "out" / "m.h").mkdir()
    with pytest.raises(FileSystemError, match=f"^{tmp_path}/out/m.h: cannot read the file: it is a directory$"):
        writer.differences(FILES, str(tmp_path / "out"))


def test_check_lists_the_files_that_differ(tmp_path: Path):
    writer.write_all(FILES, str(tmp_path))
    (tmp_path / "m.md").write_bytes(b"edited\n")
    (tmp_path / "m.py").unlink()
    diffs = writer.differences(FILES, str(tmp_path))
    assert [d.splitlines()[0] for d in diffs] == [f"--- {tmp_path}/m.md (on disk)", f"--- {tmp_path}/m.py (on disk)"]
    assert "-edited\n" in diffs[0]
