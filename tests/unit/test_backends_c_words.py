"""linkgen.backends.c.words: the names C gives a meaning to. Every listed keyword is refused as a struct
field by this gcc (C2x) or g++ (C++2b), bar the C23 keywords newer than the compiler, and its spelling with
a trailing _ compiles in both; the macro list holds every macro of the headers the programs include; the
generated header and source define only the names the lists hold; and each rule's reason."""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import pytest
from generated_samples import SAMPLES, generated, outputs
from programs import need

from linkgen.backends.c import words as c_words

# C23's new keywords (ISO/IEC 9899:2024, 6.4.1): a compiler older than C23 may take them as names.
C23_NEW = frozenset("alignas alignof bool constexpr false nullptr static_assert thread_local true typeof "
                    "typeof_unqual".split())


def _refused_as_fields(compiler: str, flags: list[str], suffix: str, names: list[str], folder: Path) -> set[str]:
    """The names the compiler refuses as a struct field read as the programs read theirs (p->B): one line a
    name, each its own struct and function, so an error's line names the name."""
    lines = [f"struct s{i} {{ double {n}; }}; double get{i}(struct s{i} *p); "
             f"double get{i}(struct s{i} *p) {{ return p->{n}; }}" for i, n in enumerate(names)]
    (folder / f"fields{suffix}").write_text("\n".join(lines) + "\n", encoding="utf-8")
    done = subprocess.run([compiler, *flags, "-fsyntax-only", "-fmax-errors=0", f"fields{suffix}"], cwd=folder,
                          capture_output=True, text=True)
    lines_with_errors = {int(n) for n in re.findall(rf"fields{re.escape(suffix)}:(\d+):\d+: error", done.stderr)}
    assert (done.returncode != 0) == bool(lines_with_errors), done.stderr
    return {names[n - 1] for n in lines_with_errors}


def test_every_listed_keyword_is_refused_as_a_field_and_its_spelling_is_not(tmp_path: Path):
    words = sorted(c_words.KEYWORDS | c_words.CPP_KEYWORDS)
    refused = (_refused_as_fields(need("gcc"), ["-std=c2x"], ".c", words, tmp_path)
               | _refused_as_fields(need("g++"), ["-std=c++2b"], ".cc", words, tmp_path))
    assert set(words) - refused <= C23_NEW, set(words) - refused - C23_NEW
    spelled = [c_words.WORDS.field(w) for w in words]
    assert all(s == f"{w}_" for s, w in zip(spelled, words))
    assert _refused_as_fields(need("gcc"), ["-std=c99"], ".c", spelled, tmp_path) == set()
    assert _refused_as_fields(need("g++"), ["-std=c++11"], ".cc", spelled, tmp_path) == set()


@pytest.mark.parametrize("name, why", [
    ("do", "a C keyword"), ("class", "a C++ keyword"), ("and", "a C++ keyword"), ("NAN", "a macro of the C library"),
    ("errno", "a macro of the C library"), ("EOF", "a macro of the C library"), ("crank", ""), ("Do", ""),
])
def test_why_a_name_is_no_c_field_as_it_is(name: str, why: str):
    assert c_words.word(name) == why
    assert c_words.WORDS.field(name) == (f"{name}_" if why else name)


@pytest.mark.parametrize("name, problem", [
    ("math", "makes math.h, which would hide the C header <math.h> from a compiler given -I"),
    ("STDIO", "makes STDIO.h, which would hide the C header <stdio.h> from a compiler given -I"),
    ("Nul", "is a device name on Windows, which cannot create a file named Nul.c"),
    ("com9", "is a device name on Windows, which cannot create a file named com9.c"),
    ("com10", ""), ("mathematics", ""), ("auto", ""),
])
def test_why_the_c_files_cannot_carry_a_mechanism_name(name: str, problem: str):
    assert c_words.mechanism_problem(name) == problem


def test_a_header_named_like_a_library_one_hides_it(tmp_path: Path):
    """Why <name>.h is refused: given -I the output folder, #include <math.h> finds the generated math.h."""
    (tmp_path / "math.h").write_text("#error the generated math.h\n", encoding="utf-8")
    (tmp_path / "use.c").write_text("#include <math.h>\nint main(void) { return 0; }\n", encoding="utf-8")
    done = subprocess.run([need("gcc"), "-I", ".", "-fsyntax-only", "use.c"], cwd=tmp_path, capture_output=True,
                          text=True)
    assert "the generated math.h" in done.stderr and "math" in c_words.HEADERS


@pytest.mark.parametrize("name, problem", [
    ("a__b", "contains __, which C++ reserves (the generated header is C++ too)"),
    ("LINKGEN_NMAX", "is a macro of the generated fourbar.c"),
    ("fourbar_solve", "is a name the generated header fourbar.h defines"),
    ("FOURBAR_N_INPUTS", "is a name the generated header fourbar.h defines"),
    ("slider_solve", ""), ("a_b", ""),
])
def test_why_a_name_cannot_be_a_field_of_the_c_state(name: str, problem: str):
    assert c_words.entity_problem(name, "fourbar") == problem


def test_the_header_names_of_a_mechanism():
    names = c_words.header_names("crank")
    assert {"crank_state", "crank_solve", "crank_init", "crank_columns", "CRANK_H", "CRANK_N_INPUTS",
            "CRANK_STATUS_BAD_INPUT"} <= names
    assert len(names) == len(c_words.HEADER_SUFFIXES) + len(c_words.HEADER_MACRO_SUFFIXES)


def test_the_headers_macros_are_no_library_macro_for_any_mechanism_name():
    """NAME_N_INPUTS, NAME_H, ...: no macro of the C library ends like one of them."""
    clash = [m for m in c_words.MACROS for s in c_words.HEADER_MACRO_SUFFIXES if m.endswith(f"_{s}")]
    assert clash == []


@pytest.mark.parametrize("json", SAMPLES, ids=lambda p: p.stem)
def test_the_c_header_defines_only_the_names_the_lists_hold(json: Path):
    header = _uncommented_c(generated(json, ".h"))
    name = json.stem
    body = re.search(r"typedef struct \{([^{}]*)\} " + name + r"_state;", header)[1]
    members = set()
    for declaration in body.split(";"):
        words = declaration.split(None, 1)
        if len(words) == 2:
            members.update(re.sub(r"\[.*?\]", "", d).strip() for d in words[1].split(","))
    own = members - {c_words.WORDS.field(o) for o in outputs(json)}
    assert own and own <= c_words.STATE_FIELDS
    defined = set(re.findall(r"#define (\w+)", header)) | set(re.findall(r"\} (\w+);", header))
    defined |= set(re.findall(r"^\w+ (\w+)\(", header, re.M))
    assert defined <= c_words.header_names(name) | {f"{name.upper()}_H"}
    source = _uncommented_c(generated(json, ".c"))
    assert set(re.findall(r"#define (\w+)", source)) <= c_words.SOURCE_MACROS


def test_the_c_macro_list_holds_every_macro_of_the_headers_here():
    """Regenerate the data file's list with this machine's compiler: nothing may be missing."""
    gcc = need("gcc")
    includes = "".join(f"#include <{h}.h>\n" for h in ("math", "float", "stdio", "string"))
    for mode in ("-std=c99", "-std=c2x", "-D_GNU_SOURCE", "-D_XOPEN_SOURCE=700"):
        text = subprocess.run([gcc, mode, "-dM", "-E", "-x", "c", "-"], input=includes, capture_output=True,
                              text=True, check=True).stdout
        macros = {m for m in re.findall(r"^#define (\w+)(?![\w(])", text, re.M) if not m.startswith("_")}
        assert "NAN" in macros and macros <= c_words.MACROS, macros - c_words.MACROS


def _uncommented_c(text: str) -> str:
    return re.sub(r"/\*.*?\*/", "", text, flags=re.S)
