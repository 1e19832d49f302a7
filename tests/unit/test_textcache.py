"""linkgen.textcache: a text is made once per fingerprint of the package and read back by a later
process (a new store on the same folder); a changed module, or no folder, makes it again."""

from __future__ import annotations

import os
from pathlib import Path

from linkgen import textcache
from linkgen.backends.c.printer import c_function
from linkgen.backends.m.printer import octave_function
from linkgen.backends.np import still
from linkgen.backends.np.printer import numpy_function
from linkgen.backends.program import runtime_sources, used_primitives
from linkgen.backends.py import RUNTIME
from linkgen.backends.py.printer import python_function
from linkgen.backends.still import carried, variant
from linkgen.pipeline import build_log
from linkgen.primitives import PRIMITIVES, python_backend
from linkgen.render.view import build_view

ROOT = Path(__file__).resolve().parents[2]


def _maker(calls: list[str], text: str):
    def make() -> str:
        calls.append(text)
        return text
    return make


def test_a_text_is_made_once_and_read_back_by_a_later_store(tmp_path):
    calls: list[str] = []
    first = textcache.Store(str(tmp_path))
    assert first.kept("k", _maker(calls, "one")) == "one" and first.kept("k", _maker(calls, "two")) == "one"
    later = textcache.Store(str(tmp_path))  # as a new process finds it
    assert later.kept("k", _maker(calls, "three")) == "one" and calls == ["one"]
    assert [p.name for p in tmp_path.iterdir()] == [f"linkgen-text-{textcache.fingerprint()}.json"]


def test_a_changed_module_starts_a_new_store(tmp_path, monkeypatch):
    """The fingerprint of a package of one module (a copy): the module rewritten, another store."""
    package, folder = tmp_path / "package", tmp_path / "cache"
    package.mkdir()
    folder.mkdir()
    (package / "module.py").write_text("A = 1\n")
    monkeypatch.setattr(textcache, "PACKAGE", package)
    textcache.fingerprint.cache_clear()
    calls: list[str] = []
    try:
        before = textcache.fingerprint()
        textcache.Store(str(folder)).kept("k", _maker(calls, "old"))
        (package / "module.py").write_text("A = 22\n")
        textcache.fingerprint.cache_clear()
        assert textcache.fingerprint() != before
        assert textcache.Store(str(folder)).kept("k", _maker(calls, "new")) == "new" and calls == ["old", "new"]
        assert len(list(folder.iterdir())) == 2
    finally:
        textcache.fingerprint.cache_clear()


def test_without_a_folder_or_where_it_cannot_be_written_the_text_is_made_each_time(tmp_path):
    calls: list[str] = []
    assert textcache.Store("").kept("k", _maker(calls, "a")) == "a"
    assert textcache.Store("").kept("k", _maker(calls, "b")) == "b" and calls == ["a", "b"]
    missing = str(tmp_path / "no" / "such" / "folder")
    assert textcache.Store(missing).kept("k", _maker(calls, "c")) == "c" and not os.path.exists(missing)


def test_a_kept_primitive_is_the_printers_text():
    """The primitives as kept (read back from the store of earlier builds, or made now) are what the
    printers print now: the numpy kernel's, the C, Octave and Python programs' and the evaluator's."""
    log = build_log(str(ROOT / "samples" / "fourbar" / "fourbar.yaml"), sweep=False)
    view = build_view(log)
    for name in ("RRR_links", "link_angle"):
        assert still.printed(name, 2) == numpy_function(PRIMITIVES[name], 2)
    for printer in (c_function, octave_function, python_function):
        calls = carried(log, view.record_order, used_primitives(view))  # with the sketch's records held still
        printed = [printer(variant(p, view.measures, still), view.record_order) for p, still in calls]
        assert runtime_sources(view, printer, RUNTIME, status=False)[:len(printed)] == printed
    python_backend(1)  # the evaluator's primitives at order 1: kept by now
    source = "\n\n".join(python_function(p, 1) for p in PRIMITIVES.values())
    assert textcache.kept("python primitives", (1,), lambda: "not this") == source
