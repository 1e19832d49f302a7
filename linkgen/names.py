"""User names against the names the generated programs give a meaning to.

Where a name lands (templates/ and render/lang.py):

- The mechanism name NAME names the files NAME.c, NAME.h, NAME_main.c, NAME.py, NAME.m,
  NAME_solve.m, NAME.md, NAME.svg and NAME.json; the Python module NAME; the MATLAB/Octave
  script NAME and function NAME_solve; and, with a suffix, the C header's types, functions
  and macros (NAME_state, NAME_solve, NAME_N_INPUTS with NAME upper-cased, ...).  It is never
  a C identifier by itself, so C keywords do not matter for it.
- A pair, point or link name B is a field of the C state (``out->B.x``), of the MATLAB/Octave
  struct out (``out.B.x``), and text: a CSV column and Python dict key ``"B.x"``.  The programs'
  own variables carry a prefix (``p_B``, ``phi_B``, ``l_B``), so they never meet a user name, and
  no user name becomes a Python identifier.
- An input's column (``theta_J``, ``s_J``, ``d_J1_J2``) is text: a CSV column.

A name that is a word of a language where it becomes a field (a C or C++ keyword, a macro of
the C headers the programs include, a MATLAB/Octave keyword) is written with a trailing _
there (c_field, m_field); every other clash is refused with the reason given here.
"""

from __future__ import annotations

import builtins
import keyword
import sys
from importlib import resources


def _data(name: str) -> frozenset[str]:
    text = (resources.files("linkgen") / "data" / name).read_text(encoding="utf-8")
    return frozenset(line for line in text.splitlines() if line and not line.startswith("#"))


# C11/C23 keywords (names starting with _ are refused before: _Bool, _Atomic, ...).
C_KEYWORDS = frozenset("""
    alignas alignof auto bool break case char const constexpr continue default do double else enum extern false
    float for goto if inline int long nullptr register restrict return short signed sizeof static static_assert
    struct switch thread_local true typedef typeof typeof_unqual union unsigned void volatile while""".split())
# C++23 keywords and alternative tokens: the generated header is included from C++ too.
CPP_KEYWORDS = frozenset("""
    alignas alignof and and_eq asm auto bitand bitor bool break case catch char char8_t char16_t char32_t class
    compl concept const consteval constexpr constinit const_cast continue co_await co_return co_yield decltype
    default delete do double dynamic_cast else enum explicit export extern false float for friend goto if inline
    int long mutable namespace new noexcept not not_eq nullptr operator or or_eq private protected public register
    reinterpret_cast requires return short signed sizeof static static_assert static_cast struct switch template
    this thread_local throw true try typedef typeid typename union unsigned using virtual void volatile wchar_t
    while xor xor_eq""".split())
# Object-like macros of math.h, float.h, stdio.h and string.h (data file), errno (a macro
# wherever a host includes errno.h) and the System V names older math.h files define.
C_MACROS = _data("c_macros.txt") | frozenset("errno DOMAIN SING OVERFLOW UNDERFLOW TLOSS PLOSS HUGE X_TLOSS".split())
# Standard C headers (C89 to C23) and the ones glibc's math.h, stdio.h and string.h include by
# a plain name: NAME.h would hide one of them from a compiler given -I with the output folder.
C_HEADERS = frozenset("""
    assert complex ctype errno fenv float inttypes iso646 limits locale math setjmp signal stdalign stdarg
    stdatomic stdbit stdbool stdckdint stddef stdint stdio stdlib stdnoreturn string tgmath threads time uchar
    wchar wctype features strings""".split())
# Device names: Windows cannot create NAME.c for them, whatever the case or extension.
WINDOWS_DEVICES = frozenset("con prn aux nul".split() + [f"{d}{k}" for d in ("com", "lpt") for k in range(1, 10)])
# MATLAB's and Octave's keywords (iskeyword of both; __FILE__ and __LINE__ start with _).
M_KEYWORDS = frozenset("""
    break case catch classdef continue do else elseif end end_try_catch end_unwind_protect endarguments
    endclassdef endenumeration endevents endfor endfunction endif endmethods endparfor endproperties endspmd
    endswitch endwhile for function global if otherwise parfor persistent return spmd switch try until
    unwind_protect unwind_protect_cleanup while""".split())
# Octave's functions (data file; a superset of what the generated .m files call).
M_FUNCTIONS = _data("octave_functions.txt")
# The variables of the sweep script NAME.m: after one run, a variable named NAME hides the script.
M_SCRIPT_VARIABLES = frozenset("start stop speed samples names warm k in out status row c".split())
PY_BUILTINS = frozenset(n for n in dir(builtins) if not n.startswith("_"))

# Fields of the generated state besides the outputs: which structure has each.
C_STATE = "C NAME_state"
M_OUT = "MATLAB/Octave out"
STATE_FIELDS = {
    "status": (C_STATE,), "sigma": (C_STATE, M_OUT), "iterations": (C_STATE, M_OUT), "columns": (M_OUT,),
    "warm_valid": (C_STATE,), "warm_in": (C_STATE,), "warm_din": (C_STATE,), "warm_a": (C_STATE,),
    "warm_ad": (C_STATE,), "warm_used": (C_STATE,),
}
# What NAME.h defines from the mechanism name (NAME_x, NAME_X with NAME upper-cased) and the macros of NAME.c.
HEADER_SUFFIXES = ("point", "angle", "prismatic", "state", "init", "solve", "columns")
HEADER_MACRO_SUFFIXES = ("H", "N_INPUTS", "N_STEPS", "N_COLUMNS", "ORDER", "SAMPLES", "N_GROUPS", "N_BLOCKS", "NMAX",
                         "STATUS_BAD_INPUT")
SOURCE_MACROS = frozenset(("LINKGEN_NMAX", "LINKGEN_NGROUPS", "LINKGEN_NBLOCKS", "LINKGEN_NINPUTS",
                           "LINKGEN_WALK_PASSES"))
MAX_NAME = 57  # MATLAB's 63 characters for NAME_solve
MAX_FIELD = 63  # MATLAB's namelengthmax for a struct field


def header_names(mechanism: str) -> frozenset[str]:
    """The types, functions and macros the generated NAME.h defines."""
    upper = mechanism.upper()
    return (frozenset(f"{mechanism}_{s}" for s in HEADER_SUFFIXES)
            | frozenset(f"{upper}_{s}" for s in HEADER_MACRO_SUFFIXES))


def c_word(name: str) -> str:
    """Why a name cannot be a C field as it is ('' when it can)."""
    if name in C_KEYWORDS:
        return "a C keyword"
    if name in CPP_KEYWORDS:
        return "a C++ keyword"
    if name in C_MACROS:
        return "a macro of the C library"
    return ""


def c_field(name: str) -> str:
    """A pair, point or link name as a field of the C state."""
    return f"{name}_" if c_word(name) else name


def m_field(name: str) -> str:
    """A pair, point or link name as a field of the MATLAB/Octave struct out."""
    return f"{name}_" if name in M_KEYWORDS else name


def mechanism_name_problem(name: str) -> str:
    """Why the generated files cannot carry this mechanism name ('' when they can)."""
    if name.startswith("_"):
        return "starts with _, which MATLAB does not allow in a file name"
    if len(name) > MAX_NAME:
        return f"has {len(name)} characters, but MATLAB allows {MAX_NAME} (63 for the function {name[:8]}..._solve)"
    if keyword.iskeyword(name):
        return f"is a Python keyword, so the module {name}.py cannot be imported"
    if name in M_KEYWORDS:
        return f"is a MATLAB/Octave keyword, so the script {name}.m cannot be run"
    if name in M_FUNCTIONS:
        return f"is a MATLAB/Octave function, which the script {name}.m would hide"
    if name in M_SCRIPT_VARIABLES:
        return f"is a variable of the sweep script {name}.m, which after one run would hide the script"
    if name in sys.stdlib_module_names:
        return f"is a module of Python's standard library, which {name}.py would hide"
    if name in PY_BUILTINS:
        return f"is a Python built-in, which `import {name}` would hide in the importing module"
    if name.lower() in C_HEADERS:
        return f"makes {name}.h, which would hide the C header <{name.lower()}.h> from a compiler given -I"
    if name.lower() in WINDOWS_DEVICES:
        return f"is a device name on Windows, which cannot create a file named {name}.c"
    return ""


def entity_name_problem(name: str, mechanism: str) -> str:
    """Why a pair, point or link name cannot be an output of the generated programs ('' when it can)."""
    if name.startswith("_"):
        return f"starts with _, which a MATLAB struct field cannot (out.{name}) and C reserves"
    if "__" in name:
        return "contains __, which C++ reserves (the generated header is C++ too)"
    if len(m_field(name)) > MAX_FIELD:
        return f"has {len(name)} characters; a MATLAB struct field has at most {MAX_FIELD}"
    if name in STATE_FIELDS:
        where = ", ".join(STATE_FIELDS[name]).replace("NAME", mechanism)
        return f"is a field of the generated state ({where})"
    if name in SOURCE_MACROS:
        return f"is a macro of the generated {mechanism}.c"
    if name in header_names(mechanism):
        return f"is a name the generated header {mechanism}.h defines"
    return ""


def spellings(name: str) -> tuple[tuple[str, str, str], ...]:
    """(program, field, why) of a pair, point or link name: how the C and the MATLAB/Octave
    programs write it, and why it gets a trailing _ there ('' when it does not)."""
    return (("C", c_field(name), c_word(name)),
            ("MATLAB/Octave", m_field(name), "a MATLAB/Octave keyword" if name in M_KEYWORDS else ""))
