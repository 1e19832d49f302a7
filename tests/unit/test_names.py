"""linkgen.names, the user's names against every backend's words: each list's names refused as the mechanism
name, each language's words written with a trailing _ in its programs and nowhere else.  That the lists
hold what the generated files, this machine's compiler and Octave define is tested with each backend's
words (test_backends_<lang>_words.py); how the validator reports a refused name, in test_validate_naming.py."""

from __future__ import annotations

import keyword
import sys

import pytest

from linkgen import names
from linkgen.backends.c import words as c_words
from linkgen.backends.m import words as m_words
from linkgen.backends.py import words as py_words
from linkgen.loader import IDENTIFIER

# -- the mechanism name ---------------------------------------------------------

MECHANISM_LISTS = {
    "Python keyword": frozenset(keyword.kwlist),
    "MATLAB/Octave keyword": m_words.KEYWORDS,
    "MATLAB/Octave function": m_words.FUNCTIONS,
    "variable of the sweep script": m_words.SCRIPT_VARIABLES,
    "Python module": frozenset(n for n in sys.stdlib_module_names if not n.startswith("_")),
    "Python built-in": py_words.BUILTINS,
    "C header": c_words.HEADERS | frozenset(h.upper() for h in c_words.HEADERS),
    "Windows device": c_words.WINDOWS_DEVICES | frozenset(d.upper() for d in c_words.WINDOWS_DEVICES),
}


@pytest.mark.parametrize("listed", sorted(MECHANISM_LISTS))
def test_every_name_of_every_list_is_refused_as_the_mechanism_name(listed: str):
    members = MECHANISM_LISTS[listed]
    assert len(members) >= 4
    accepted = [n for n in members if not names.mechanism_name_problem(n)]
    assert accepted == []


# -- pair, point and link names ----------------------------------------------------

RENAMED = {
    "C keyword": (c_words.KEYWORDS, "C"),
    "C++ keyword": (c_words.CPP_KEYWORDS, "C"),
    "C library macro": (c_words.MACROS, "C"),
    "MATLAB/Octave keyword": (m_words.KEYWORDS, "MATLAB/Octave"),
}


@pytest.mark.parametrize("listed", sorted(RENAMED))
def test_every_word_of_a_language_is_written_with_a_trailing_underscore_there(listed: str):
    members, lang = RENAMED[listed]
    assert len(members) >= 20
    for name in members:
        assert IDENTIFIER.fullmatch(name) and not name.startswith("_")
        spelled = dict((g, s) for g, s, _ in names.spellings(name))
        assert spelled[lang] == f"{name}_"
        assert names.entity_name_problem(name, "fourbar") == ""
        # the spelling is no word of either language, and no field or macro of the programs
        written = f"{name}_"
        assert c_words.WORDS.field(written) == m_words.WORDS.field(written) == written
        assert names.entity_name_problem(written, "fourbar") == ""
