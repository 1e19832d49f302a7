"""The C files in another real type than double: every real of NAME.h and NAME.c is a NAME_real
(a typedef in NAME.h, which NAME_main.c uses too), the math functions are <tgmath.h>'s (sqrtf, atan2l, ... by
the argument's type), literals carry the type's suffix and the resolver's thresholds follow the
type's epsilon (policy.for_real)."""

from __future__ import annotations

import re

SUFFIX = {"float": "f", "double": "", "long double": "L"}
EPSILON = {"float": "FLT_EPSILON", "double": "DBL_EPSILON", "long double": "LDBL_EPSILON"}
PI_DOUBLE = "3.141592653589793"
PI_LONG = "3.14159265358979323846264338327950288"  # pi to 36 digits, past any long double's 113 bits

# C's type-generic math; compiled as C++, math.h holds the float and long double overloads
TGMATH = "#ifdef __cplusplus\n#include <math.h>\n#else\n#include <tgmath.h>\n#endif"
# comments and string literals are left as they are; everything between them is code
_NOT_CODE = re.compile(r'/\*.*?\*/|//[^\n]*|"(?:\\.|[^"\\\n])*"', re.DOTALL)
# a decimal floating literal: digits with a point or an exponent, not part of a name or a longer number
_FLOATING = re.compile(r"(?<![\w.])(?:\d+\.\d*|\.\d+|\d+(?=[eE]))(?:[eE][+-]?\d+)?(?![\w.])")


def _code(text: str, real: str, name: str) -> str:
    text = re.sub(r"\bdouble\b", f"{name}_real", text)
    text = text.replace("DBL_EPSILON", EPSILON[real]).replace("#include <math.h>", TGMATH)
    if real == "long double":
        text = re.sub(rf"(?<![\w.]){re.escape(PI_DOUBLE)}(?![\w.])", PI_LONG, text)
    return _FLOATING.sub(lambda m: m.group(0) + SUFFIX[real], text)


def retype(text: str, real: str, name: str) -> str:
    """A C file computing in ``real`` instead of double (the same text for double)."""
    if real == "double":
        return text
    out, start = [], 0
    for m in _NOT_CODE.finditer(text):
        out += [_code(text[start:m.start()], real, name), m.group(0)]
        start = m.end()
    out.append(_code(text[start:], real, name))
    return "".join(out)


def typedef(header: str, real: str, name: str) -> str:
    """NAME.h with the typedef of NAME_real after its include guard."""
    guard = f"#define {name.upper()}_H\n"
    note = f"\n/* Every real of this library is a {name}_real (options: real in the mechanism file). */\n"
    return header.replace(guard, f"{guard}{note}typedef {real} {name}_real;\n", 1)
