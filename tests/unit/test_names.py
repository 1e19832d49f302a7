"""The names the generated programs give a meaning to (linkgen.names): what each list refuses or renames,
and that the lists hold every name the generated files and this machine's compiler and Octave define.
How the validator reports a refused name is tests/unit/test_validate.py's."""

from __future__ import annotations

import json as js
import keyword
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from linkgen import names
from linkgen.backends.c import words as c_words
from linkgen.backends.m import words as m_words
from linkgen.backends.py import words as py_words
from linkgen.loader import IDENTIFIER

ROOT = Path(__file__).resolve().parents[2]


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


def test_no_octave_function_ends_in_solve():
    """So NAME_solve.m hides none (the data file says so)."""
    assert [f for f in m_words.FUNCTIONS if f.endswith("_solve")] == []


def test_the_headers_macros_are_no_library_macro_for_any_mechanism_name():
    """NAME_N_INPUTS, NAME_H, ...: no macro of the C library ends like one of them."""
    clash = [m for m in c_words.MACROS for s in c_words.HEADER_MACRO_SUFFIXES if m.endswith(f"_{s}")]
    assert clash == []


def test_the_longest_mechanism_name_leaves_room_for_the_solve_function():
    """MATLAB's namelengthmax is 63: NAME_solve must fit."""
    longest = "m" * m_words.MAX_NAME
    assert names.mechanism_name_problem(longest) == ""
    assert len(f"{longest}_solve") == 63
    assert names.mechanism_name_problem(longest + "m").startswith(f"has {m_words.MAX_NAME + 1} characters")


def test_a_field_has_at_most_63_characters_as_matlab_writes_it():
    assert names.entity_name_problem("B" * 63, "fourbar") == ""
    assert names.entity_name_problem("B" * 64, "fourbar").startswith("has 64 characters")
    # end_ is what MATLAB writes for end: a 62-character keyword would need 63 (none is that long)
    assert max(len(k) for k in m_words.KEYWORDS) + 1 <= 63


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


# -- the lists agree with the generated programs --------------------------------------

SAMPLES = sorted(p for p in (ROOT / "samples").glob("*/expected/*.json"))


def _generated(json: Path, suffix: str) -> str:
    return json.with_name(json.stem + suffix).read_text(encoding="utf-8")


def _uncommented_c(text: str) -> str:
    return re.sub(r"/\*.*?\*/", "", text, flags=re.S)


def _outputs(json: Path) -> list[str]:
    """The pair, point and link names of a sample (the C state's and out's own fields besides these)."""
    log = js.loads(json.read_text(encoding="utf-8"))
    return [c["name"].split(".")[0] for c in log["columns"] if "." in c["name"]]


@pytest.mark.parametrize("json", SAMPLES, ids=lambda p: p.stem)
def test_the_c_header_defines_only_the_names_the_lists_hold(json: Path):
    header = _uncommented_c(_generated(json, ".h"))
    name = json.stem
    body = re.search(r"typedef struct \{([^{}]*)\} " + name + r"_state;", header)[1]
    members = set()
    for declaration in body.split(";"):
        words = declaration.split(None, 1)
        if len(words) == 2:
            members.update(re.sub(r"\[.*?\]", "", d).strip() for d in words[1].split(","))
    own = members - {c_words.WORDS.field(o) for o in _outputs(json)}
    assert own and own <= c_words.STATE_FIELDS
    defined = set(re.findall(r"#define (\w+)", header)) | set(re.findall(r"\} (\w+);", header))
    defined |= set(re.findall(r"^\w+ (\w+)\(", header, re.M))
    assert defined <= c_words.header_names(name) | {f"{name.upper()}_H"}
    source = _uncommented_c(_generated(json, ".c"))
    assert set(re.findall(r"#define (\w+)", source)) <= c_words.SOURCE_MACROS


@pytest.mark.parametrize("json", SAMPLES, ids=lambda p: p.stem)
def test_the_matlab_programs_use_only_the_names_the_lists_hold(json: Path):
    solve = _generated(json, "_solve.m")
    own = set(re.findall(r"\bout\.(\w+)\s*=", solve)) - {m_words.WORDS.field(o) for o in _outputs(json)}
    assert own and own <= m_words.STATE_FIELDS
    script = _generated(json, ".m")
    assigned = set(re.findall(r"^\s*(?:for\s+)?(\w+)\s*=[^=]", script, re.M))
    assigned |= {v.strip() for group in re.findall(r"^\s*\[([^\]]*)\]\s*=", script, re.M) for v in group.split(",")}
    assert assigned and assigned <= m_words.SCRIPT_VARIABLES
    # every function the two files call is a function of the list (or one of NAME_solve.m's own)
    calls, local, variables = set(), set(), set()
    for text in (solve, script):
        code = re.sub(r"(?<=[(,={\s])'[^'\n]*'", "''", text)
        code = re.sub(r"%.*", "", code)
        calls |= set(re.findall(r"(?<![.\w@])([A-Za-z]\w*)\s*\(", code))
        for head in re.findall(r"^function\s+(.*)", code, re.M):
            out, _, rest = head.rpartition("=")
            local.add(rest.split("(")[0].strip())
            variables |= set(re.findall(r"\w+", out + rest.partition("(")[2]))
        variables |= set(re.findall(r"(\w+)\s*(?:\([^()]*\))?\s*=[^=]", code))
        variables |= {v for group in re.findall(r"\[([^\]]*)\]\s*=[^=]", code) for v in re.findall(r"\w+", group)}
    called = calls - local - variables - {f"{json.stem}_solve"}
    assert {"fprintf", "zeros", "size", "atan2"} <= called
    assert called <= m_words.FUNCTIONS, called - m_words.FUNCTIONS


def test_the_c_macro_list_holds_every_macro_of_the_headers_here():
    """Regenerate the data file's list with this machine's compiler: nothing may be missing."""
    gcc = shutil.which("gcc")
    if gcc is None:
        pytest.skip("gcc is not installed")
    includes = "".join(f"#include <{h}.h>\n" for h in ("math", "float", "stdio", "string"))
    for mode in ("-std=c99", "-std=c2x", "-D_GNU_SOURCE", "-D_XOPEN_SOURCE=700"):
        text = subprocess.run([gcc, mode, "-dM", "-E", "-x", "c", "-"], input=includes, capture_output=True,
                              text=True, check=True).stdout
        macros = {m for m in re.findall(r"^#define (\w+)(?![\w(])", text, re.M) if not m.startswith("_")}
        assert "NAN" in macros and macros <= c_words.MACROS, macros - c_words.MACROS


def test_the_octave_list_is_what_this_octave_gives(tmp_path: Path):
    """The data file says how it was made; with that Octave version, making it again gives the same."""
    octave = shutil.which("octave-cli")
    if octave is None:
        pytest.skip("octave-cli is not installed")
    data = (ROOT / "linkgen" / "backends" / "m" / "functions.txt").read_text(encoding="utf-8").splitlines()
    version = re.search(r"GNU Octave (\S+)", data[0])[1]
    script = "\n".join(line[4:] for line in data if line.startswith("#   "))
    here = subprocess.run([octave, "--norc", "--no-init-file", "--quiet", "--eval", "disp(OCTAVE_VERSION)"],
                          capture_output=True, text=True).stdout.strip()
    if here != version:
        pytest.skip(f"the list was made with Octave {version}, this is {here}")
    made = subprocess.run([octave, "--norc", "--no-init-file", "--quiet", "--eval", script], cwd=tmp_path,
                          capture_output=True, text=True).stdout.split()
    assert made == sorted(m_words.FUNCTIONS)
