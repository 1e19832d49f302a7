"""linkgen.errors: how an error names its place, the system's reasons in linkgen's words, and names
listed in a message.  (tests/test_errors.py runs every error file of tests/errors through the command.)"""

from __future__ import annotations

import errno
import os

import pytest

from linkgen.errors import FileSystemError, InputError, LinkgenError, ProcedureError, and_list, os_reason


@pytest.mark.parametrize("error, text", [
    (InputError("no link is fixed", "m.yaml", 9, "links"), "m.yaml:9: links: no link is fixed"),
    (InputError("the file is empty", "m.yaml", 1), "m.yaml:1: the file is empty"),
    (InputError("not valid YAML: unreadable", "m.yaml"), "m.yaml: not valid YAML: unreadable"),
    (FileSystemError("not a directory", "out/x"), "out/x: not a directory"),
    (ProcedureError("no procedure", "", 0, "inputs"), "inputs: no procedure"),
    (LinkgenError("bare"), "bare"),
])
def test_an_error_reads_file_line_key_message(error: LinkgenError, text: str):
    assert str(error) == text
    assert text.endswith(f": {error.message}") or text == error.message


def test_every_error_is_a_linkgen_error_the_command_reports():
    assert all(issubclass(e, LinkgenError) for e in (InputError, ProcedureError, FileSystemError))


@pytest.mark.parametrize("code, reason", [
    (errno.ENOENT, "no such file or directory"),
    (errno.ENOTDIR, "a part of the path is not a directory"),
    (errno.EISDIR, "it is a directory"),
    (errno.EROFS, "the file system is read-only"),
    (errno.ENOSPC, "no space left on the device"),
])
def test_the_puzzling_reasons_are_reworded(code: int, reason: str):
    assert os_reason(OSError(code, os.strerror(code))) == reason


def test_other_reasons_are_the_systems_in_lower_case():
    assert os_reason(OSError(errno.EACCES, "Permission denied")) == "permission denied"
    assert os_reason(OSError(errno.EMFILE, "Too many open files")) == "too many open files"
    assert os_reason(OSError("No errno at all")) == "no errno at all"


@pytest.mark.parametrize("names, text", [
    ([], ""), (["a"], "a"), (["a", "b"], "a and b"), (["a", "b", "c"], "a, b and c"),
    (["a", "b", "c", "d"], "a, b, c and d"),
])
def test_and_list(names: list[str], text: str):
    assert and_list(names) == text
    assert and_list(iter(names)) == text
