"""The C files in another real type than double: every real of NAME.h and NAME.c is a NAME_real
(a typedef in NAME.h, which NAME_main.c uses too), the math functions are math.h's of the type (sqrtf,
atan2l, ...: named, not <tgmath.h>'s, which newlib, the C library of most microcontrollers, cannot
compile), literals carry the type's suffix and the resolver's thresholds follow the
type's epsilon (policy.for_real).  In float, atan2 is the program's own (ATAN2_FLOAT): glibc's atan2f
costs twice the double atan2, which left a float program hardly faster than a double one."""

from __future__ import annotations

import re

SUFFIX = {"float": "f", "double": "", "long double": "L"}
EPSILON = {"float": "FLT_EPSILON", "double": "DBL_EPSILON", "long double": "LDBL_EPSILON"}
PI_DOUBLE = "3.141592653589793"
PI_LONG = "3.14159265358979323846264338327950288"  # pi to 36 digits, past any long double's 113 bits

# the math functions the files call (the DSL's and the runtime's), named with the type's suffix
MATH = re.compile(r"\b(sqrt|fabs|sin|cos|tan|atan2|fmin|fmax|floor|ceil|fmod|copysign|hypot)\(")
# comments and string literals are left as they are; everything between them is code
_NOT_CODE = re.compile(r'/\*.*?\*/|//[^\n]*|"(?:\\.|[^"\\\n])*"', re.DOTALL)
# a decimal floating literal: digits with a point or an exponent, not part of a name or a longer number
# atan2 in float arithmetic: the octant's ratio r (|r| <= tan(pi/8), one division) and Cephes'
# atanf polynomial (relative error 1.9e-7 on it), then the quadrant; atan2's zeros, signs and nan
ATAN2_FLOAT = """
/* atan2(y, x) in float: the angle of the octant's ratio r, |r| <= tan(pi/8), from Cephes' atanf polynomial,
   moved to its octant and quadrant by constants in two parts (a float's and the rest): within 2.3 float ulps of
   the exact angle (2e7 random pairs; glibc's atan2f within 1 at three times the cost), with atan2's signed
   zeros and nan.  Inline like the primitives: a call would spill every live real around it. */
#if defined(__GNUC__)
static inline double atan2_real(double y, double x) __attribute__((always_inline));
#endif
static inline double atan2_real(double y, double x)
{
    const double ax = fabs(x), ay = fabs(y);
    double base = 0.0, rest = 0.0, r, z, t;
    if (ay == 0.0 && !isnan(x)) return copysign(signbit(x) ? 3.141592653589793 : 0.0, y);
    if (ay > 2.414213562373095 * ax) {
        base = 1.5707963267948966;
        rest = -4.371138828673793e-08;
        r = -ax / ay;
    } else if (ay > 0.4142135623730950 * ax) {
        base = 0.7853981633974483;
        rest = -2.1855694143368964e-08;
        r = (ay - ax) / (ay + ax);
    } else {
        r = ay / ax;
    }
    z = r * r;
    t = base + (rest + ((((0.0805374449538 * z - 0.138776856032) * z + 0.199777106478) * z - 0.333329491539) * z * r
                        + r));
    if (x < 0.0) t = (3.141592653589793 - t) + -8.742277657347586e-08;
    return signbit(y) ? -t : t;
}
"""
_FLOATING = re.compile(r"(?<![\w.])(?:\d+\.\d*|\.\d+|\d+(?=[eE]))(?:[eE][+-]?\d+)?(?![\w.])")


def _code(text: str, real: str, name: str) -> str:
    text = re.sub(r"\bdouble\b", f"{name}_real", text)
    text = text.replace("DBL_EPSILON", EPSILON[real])
    if real == "long double":
        text = re.sub(rf"(?<![\w.]){re.escape(PI_DOUBLE)}(?![\w.])", PI_LONG, text)
    if real == "float":
        text = re.sub(r"\batan2\(", "atan2_real(", text)
    text = MATH.sub(lambda m: f"{m.group(1)}{SUFFIX[real].lower()}(", text)
    return _FLOATING.sub(lambda m: m.group(0) + SUFFIX[real], text)


def _retyped(text: str, real: str, name: str) -> str:
    out, start = [], 0
    for m in _NOT_CODE.finditer(text):
        out += [_code(text[start:m.start()], real, name), m.group(0)]
        start = m.end()
    out.append(_code(text[start:], real, name))
    return "".join(out)


def retype(text: str, real: str, name: str) -> str:
    """A C file computing in ``real`` instead of double (the same text for double); in float, its
    atan2 calls call atan2_real (ATAN2_FLOAT, after the includes)."""
    if real == "double":
        return text
    text = _retyped(text, real, name)
    if "atan2_real(" in text:
        text = text.replace("#include <math.h>\n", "#include <math.h>\n" + _retyped(ATAN2_FLOAT, real, name), 1)
    return text


def typedef(header: str, real: str, name: str) -> str:
    """NAME.h with the typedef of NAME_real after its include guard."""
    guard = f"#define {name.upper()}_H\n"
    note = f"\n/* Every real of this library is a {name}_real (options: real in the mechanism file). */\n"
    return header.replace(guard, f"{guard}{note}typedef {real} {name}_real;\n", 1)
