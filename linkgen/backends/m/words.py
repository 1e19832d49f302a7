"""The names MATLAB and Octave give a meaning to, and what the .m files make of the user's names.

The mechanism name NAME names the script NAME.m and the function NAME_solve (in NAME_solve.m).
A pair, point or link name B is a field of the struct out (``out.B.x``): a MATLAB/Octave keyword
is written with a trailing _ there.
"""

from __future__ import annotations

from .. import Words, word_list

# MATLAB's and Octave's keywords (iskeyword of both; __FILE__ and __LINE__ start with _).
KEYWORDS = frozenset("""
    break case catch classdef continue do else elseif end end_try_catch end_unwind_protect endarguments
    endclassdef endenumeration endevents endfor endfunction endif endmethods endparfor endproperties endspmd
    endswitch endwhile for function global if otherwise parfor persistent return spmd switch try until
    unwind_protect unwind_protect_cleanup while""".split())
# Octave's functions (functions.txt; a superset of what the generated .m files call).
FUNCTIONS = word_list(__name__, "functions.txt")
# The variables of the sweep script NAME.m: after one run, a variable named NAME hides the script.
SCRIPT_VARIABLES = frozenset("start stop speed samples names warm k in out status row c stride".split())
# Fields of the struct out besides the outputs.
STATE_FIELDS = frozenset("sigma iterations columns".split())
MAX_NAME = 57  # MATLAB's 63 characters for NAME_solve
MAX_FIELD = 63  # MATLAB's namelengthmax for a struct field


def word(name: str) -> str:
    """Why a name cannot be a field of out as it is ('' when it can)."""
    return "a MATLAB/Octave keyword" if name in KEYWORDS else ""


def mechanism_problem(name: str) -> str:
    """Why NAME.m and NAME_solve.m cannot carry this mechanism name ('' when they can)."""
    if name.startswith("_"):
        return "starts with _, which MATLAB does not allow in a file name"
    if len(name) > MAX_NAME:
        return f"has {len(name)} characters, but MATLAB allows {MAX_NAME} (63 for the function {name[:8]}..._solve)"
    if name in KEYWORDS:
        return f"is a MATLAB/Octave keyword, so the script {name}.m cannot be run"
    if name in FUNCTIONS:
        return f"is a MATLAB/Octave function, which the script {name}.m would hide"
    if name in SCRIPT_VARIABLES:
        return f"is a variable of the sweep script {name}.m, which after one run would hide the script"
    return ""


def entity_problem(name: str, mechanism: str) -> str:
    """Why a pair, point or link name cannot be a field of out ('' when it can)."""
    if len(WORDS.field(name)) > MAX_FIELD:
        return f"has {len(name)} characters; a MATLAB struct field has at most {MAX_FIELD}"
    return ""


WORDS = Words(word, mechanism_problem, entity_problem, "MATLAB/Octave out", STATE_FIELDS)
