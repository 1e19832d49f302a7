"""linkgen.backends.c.real: the C text in another real type; literals in code take the type's suffix,
comments and strings keep theirs, double becomes NAME_real, DBL_EPSILON the type's, the math functions the type's
(sqrtf, fabsl: named, since newlib has no usable tgmath.h),
and long double gets pi to its own precision."""

from __future__ import annotations

import pytest

from linkgen.backends.c.real import PI_LONG, retype, typedef

CODE = '''#include <math.h>
/* 0.5 of a double, 1e-3 */
static double half(double x) { printf("%.17g 2.0", x);
    return 0.5 * x + 1e-3 + 2 + .25 + 3.141592653589793 + DBL_EPSILON + sqrt(fabs(x)) + p_cos(x); }
'''


def test_double_is_left_as_it_is():
    assert retype(CODE, "double", "m") == CODE


def test_float_suffixes_code_literals_only():
    out = retype(CODE, "float", "m")
    assert "tgmath" not in out and "sqrtf(fabsf(x)) + p_cos(x)" in out
    assert "/* 0.5 of a double, 1e-3 */" in out and '"%.17g 2.0"' in out
    assert "static m_real half(m_real x)" in out
    assert "0.5f * x + 1e-3f + 2 + .25f + 3.141592653589793f + FLT_EPSILON" in out


def test_long_double_takes_pi_to_its_own_precision():
    out = retype(CODE, "long double", "m")
    assert f"{PI_LONG}L + LDBL_EPSILON + sqrtl(fabsl(x)) + p_cos(x)" in out and "static m_real half" in out
    assert abs(float(PI_LONG) - 3.141592653589793) == 0.0 and len(PI_LONG.split(".")[1]) >= 34


@pytest.mark.parametrize("real", ["float", "double", "long double"])
def test_the_header_defines_the_real_type_after_its_guard(real: str):
    text = typedef("#ifndef M_H\n#define M_H\nint x;\n#endif\n", real, "m")
    lines = text.splitlines()
    assert lines[:2] == ["#ifndef M_H", "#define M_H"] and f"typedef {real} m_real;" in lines
    assert lines.index(f"typedef {real} m_real;") < lines.index("int x;")


def test_float_calls_its_own_atan2_in_code_only():
    code = "#include <math.h>\n/* atan2(y, x) */\nstatic double f(double y, double x) { return atan2(y, x); }\n"
    out = retype(code, "float", "m")
    assert "/* atan2(y, x) */" in out and "return atan2_real(y, x);" in out
    assert out.index("static inline m_real atan2_real(m_real y, m_real x)") < out.index("static m_real f(")
    assert "atan2_real" not in retype(code, "long double", "m") and retype(code, "double", "m") == code
