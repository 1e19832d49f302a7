"""The names C gives a meaning to, and what the C files make of the user's names.

The mechanism name NAME names NAME.c, NAME.h and NAME_main.c and, with a suffix, the header's
types, functions and macros (NAME_state, NAME_solve, NAME_N_INPUTS with NAME upper-cased, ...).
It is never a C identifier by itself, so C keywords do not matter for it.  A pair, point or link
name B is a field of the C state (``out->B.x``): a C or C++ keyword or a macro of the headers
the programs include is written with a trailing _ there.
"""

from __future__ import annotations

from .. import Words, word_list

# C11/C23 keywords (names starting with _ are refused before: _Bool, _Atomic, ...).
KEYWORDS = frozenset("""
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
# Object-like macros of math.h, float.h, stdio.h and string.h (macros.txt), errno (a macro
# wherever a host includes errno.h) and the System V names older math.h files define.
MACROS = word_list(__name__, "macros.txt") | frozenset(
    "errno DOMAIN SING OVERFLOW UNDERFLOW TLOSS PLOSS HUGE X_TLOSS".split())
# Standard C headers (C89 to C23) and the ones glibc's math.h, stdio.h and string.h include by
# a plain name: NAME.h would hide one of them from a compiler given -I with the output folder.
HEADERS = frozenset("""
    assert complex ctype errno fenv float inttypes iso646 limits locale math setjmp signal stdalign stdarg
    stdatomic stdbit stdbool stdckdint stddef stdint stdio stdlib stdnoreturn string tgmath threads time uchar
    wchar wctype features strings""".split())
# Device names: Windows cannot create NAME.c for them, whatever the case or extension.
WINDOWS_DEVICES = frozenset("con prn aux nul".split() + [f"{d}{k}" for d in ("com", "lpt") for k in range(1, 10)])
# Fields of the generated state besides the outputs.
STATE_FIELDS = frozenset("""status sigma iterations warm_valid warm_in warm_din warm_a warm_ad warm_used back_valid
    back_in back_a""".split())
# What NAME.h defines from the mechanism name (NAME_x, NAME_X with NAME upper-cased) and the macros of NAME.c.
HEADER_SUFFIXES = ("point", "angle", "prismatic", "state", "init", "solve", "columns")
HEADER_MACRO_SUFFIXES = ("H", "N_INPUTS", "N_STEPS", "N_COLUMNS", "ORDER", "SAMPLES", "N_GROUPS", "N_BLOCKS", "NMAX",
                         "STATUS_BAD_INPUT", "COLUMN_NAMES", "INPUT_NAMES", "INPUT_START", "INPUT_STOP", "INPUT_SPEED")
SOURCE_MACROS = frozenset(("LINKGEN_NMAX", "LINKGEN_NGROUPS", "LINKGEN_NBLOCKS", "LINKGEN_NINPUTS", "LINKGEN_NADD",
                           "LINKGEN_NSENS", "LINKGEN_RESTRICT", "LINKGEN_LOOPS"))


def header_names(mechanism: str) -> frozenset[str]:
    """The types, functions and macros the generated NAME.h defines."""
    upper = mechanism.upper()
    return (frozenset(f"{mechanism}_{s}" for s in HEADER_SUFFIXES)
            | frozenset(f"{upper}_{s}" for s in HEADER_MACRO_SUFFIXES))


def word(name: str) -> str:
    """Why a name cannot be a C field as it is ('' when it can)."""
    if name in KEYWORDS:
        return "a C keyword"
    if name in CPP_KEYWORDS:
        return "a C++ keyword"
    if name in MACROS:
        return "a macro of the C library"
    return ""


def mechanism_problem(name: str) -> str:
    """Why NAME.c, NAME.h and NAME_main.c cannot carry this mechanism name ('' when they can)."""
    if name.lower() in HEADERS:
        return f"makes {name}.h, which would hide the C header <{name.lower()}.h> from a compiler given -I"
    if name.lower() in WINDOWS_DEVICES:
        return f"is a device name on Windows, which cannot create a file named {name}.c"
    return ""


def entity_problem(name: str, mechanism: str) -> str:
    """Why a pair, point or link name cannot be a field of the C state ('' when it can)."""
    if "__" in name:
        return "contains __, which C++ reserves (the generated header is C++ too)"
    if name in SOURCE_MACROS:
        return f"is a macro of the generated {mechanism}.c"
    if name in header_names(mechanism):
        return f"is a name the generated header {mechanism}.h defines"
    return ""


WORDS = Words(word, mechanism_problem, entity_problem, "C NAME_state", STATE_FIELDS)
