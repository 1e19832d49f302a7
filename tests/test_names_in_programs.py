"""Pair, point and link names that are words of a generated language (linkgen.backends' words: C and C++
keywords, macros of the C library, MATLAB/Octave keywords) are written with a trailing _ where
they become fields, and the programs compile and compute what the same mechanism with plain
names computes: C under -std=c99 and -std=gnu11 (where linux is a macro), the header from a C++
host, Python, numpy, Octave.  Names the languages do not reserve (an Octave function, a Python
built-in) stay as they are.  The mechanism's own name is a C keyword: it is never a C
identifier by itself."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest
from programs import build, need, parse, run_c, run_numpy, run_octave, run_python

from linkgen.backends.c import words as c_words
from linkgen.backends.m import words as m_words
from linkgen.backends.py import words as py_words

FOURBAR = """linkgen: 1
name: plain
joints:
  O1: [0, 0]
  A: [20, 0]
  B: [80, 50]
  O2: [90, 0]
links:
  frame: {joints: [O1, O2], fixed: true}
  crank: [O1, A]
  coupler: {joints: [A, B], points: {P1: [60, 70], P2: [50, 10], P3: [30, 40], P4: [70, 20], P5: [45, 60]}}
  rocker: [O2, B]
inputs:
  - {joint: O1, link: crank, relative_to: frame, range: [0, 360], speed: 360}
samples: 13
"""
# plain name -> a word of each list (and two names no language reserves)
WORDS = {"plain": "register", "O1": "end", "A": "NAN", "B": "class", "O2": "EOF", "frame": "for", "crank": "linux",
         "coupler": "zeros", "rocker": "until", "P1": "stdin", "P2": "errno", "P3": "M_PI", "P4": "print",
         "P5": "new"}


def _write(folder: Path, renames: dict[str, str]) -> Path:
    text = FOURBAR
    for old, new in renames.items():
        text = re.sub(rf"\b{old}\b", new, text)
    path = folder / "mechanism.yaml"
    path.write_text(text, encoding="utf-8")
    return path


@pytest.fixture(scope="module")
def programs(tmp_path_factory):
    plain_dir, word_dir = tmp_path_factory.mktemp("plain"), tmp_path_factory.mktemp("words")
    plain = build(_write(plain_dir, {}), plain_dir)
    words = build(_write(word_dir, WORDS), word_dir)
    return plain, plain_dir, words, word_dir


def test_every_list_is_represented():
    lists = {"C keyword": c_words.KEYWORDS, "C++ keyword": c_words.CPP_KEYWORDS, "C macro": c_words.MACROS,
             "MATLAB/Octave keyword": m_words.KEYWORDS, "Octave function": m_words.FUNCTIONS,
             "Python built-in": py_words.BUILTINS}
    for members in lists.values():
        assert set(WORDS.values()) & members


def test_the_words_are_fields_with_a_trailing_underscore(programs):
    _, _, log, outdir = programs
    header = (outdir / "register.h").read_text(encoding="utf-8")
    for name in ("NAN", "class", "EOF", "for", "linux", "stdin", "errno", "M_PI", "new"):
        assert re.search(rf"register_\w+ {name}_;", header), name
    for name in ("end", "until", "zeros", "print"):
        assert re.search(rf"register_\w+ {name};", header), name
    solve = (outdir / "register_solve.m").read_text(encoding="utf-8")
    for name in ("end", "until", "for"):
        assert f"out.{name}_.x = " in solve or f"out.{name}_.phi = " in solve, name
    for name in ("NAN", "class", "zeros", "print"):
        assert f"out.{name}." in solve, name
    fields = "end_, NAN, class, EOF, stdin, errno, M_PI, print, new, for_, linux, zeros, until_"
    assert f"out has a field per output ({fields})" in " ".join(solve.replace("%", " ").split())
    assert log.columns[1].name == "end.x"


def _same_rows(plain: str, words: str) -> None:
    """The two CSVs hold the same numbers; the header names the words as the file gives them."""
    hp, dp, sp = parse(plain)
    hw, dw, sw = parse(words)
    mapping = {f"{k}.": f"{v}." for k, v in WORDS.items()}
    assert [re.sub(r"^(\w+)\.", lambda g: mapping.get(g[0], g[0]), h).replace("theta_O1", "theta_end")
            for h in hp] == hw
    assert (dp, sp) == (dw, sw)


@pytest.mark.parametrize("std", ["-std=c99", "-std=gnu11"])
def test_c_compiles_and_computes_as_with_plain_names(programs, std: str):
    plain, plain_dir, words, word_dir = programs
    _same_rows(run_c(plain, plain_dir, (std,)), run_c(words, word_dir, (std,)))


def test_python_computes_as_with_plain_names(programs):
    plain, plain_dir, words, word_dir = programs
    _same_rows(run_python(plain, plain_dir), run_python(words, word_dir))
    _same_rows(run_numpy(plain, plain_dir), run_numpy(words, word_dir))


def test_octave_computes_as_with_plain_names(programs):
    plain, plain_dir, words, word_dir = programs
    _same_rows(run_octave(plain, plain_dir), run_octave(words, word_dir))


def test_the_header_serves_a_cpp_host(programs):
    """The fields are C++ words too (class, new): a C++ host reads them as class_ and new_."""
    _, _, log, outdir = programs
    gcc, gxx = need("gcc"), need("g++")
    (outdir / "host.cpp").write_text("""#include <cmath>
#include <cstdio>
#include "register.h"

int main()
{
    register_state st;
    const double in[REGISTER_N_INPUTS] = {0.5}, din[REGISTER_N_INPUTS] = {1.0}, ddin[REGISTER_N_INPUTS] = {0.0};
    register_init(&st);
    const int status = register_solve(in, din, ddin, &st);
    std::printf("%d %.17g %.17g %.17g\\n", status, st.class_.x, st.new_.vy, st.for_.phi);
    return 0;
}
""", encoding="utf-8")
    for args in ([gcc, "-std=c99", "-c", "register.c", "-o", "register.o"],
                 [gxx, "-std=c++11", "-Wall", "-Wextra", "-Werror", "-pedantic", "host.cpp", "register.o", "-lm",
                  "-o", "host"]):
        done = subprocess.run(args, cwd=outdir, capture_output=True, text=True)
        assert done.returncode == 0, done.stderr
    status, x, vy, phi = subprocess.run(["./host"], cwd=outdir, check=True, capture_output=True,
                                        text=True).stdout.split()
    py = subprocess.run([sys.executable, "-I", "-c", "import sys; sys.path.insert(0, '.'); import register as r; "
                         "o = r.solve([0.5], [1.0], [0.0]); print(o['status'], repr(o['class.x']), repr(o['new.vy']), "
                         "repr(o['for.phi']))"], cwd=outdir, check=True, capture_output=True, text=True).stdout.split()
    assert [int(status), float(x), float(vy), float(phi)] == [int(py[0]), *map(float, py[1:])]
