"""No absolute numeric constant in the runtime: every threshold is relative.

The runtime functions and the resolver are printed in every language and scanned
for number literals.  Only dimensionless numbers may appear: 0, 1, 2 and 0.5 of
the formulas, 8 (eps multiples at a toggle), the conditioning thresholds 1e-3 and
1e-7, the status codes 3 and 4, the continuation's 0.1 and 0.01 (a
correction over a tenth of the predicted move is off the path, over a hundredth where the
solving block turned), pi, and the 1000 passes after which a continuation's walk gives up
(a count).  A length such as the lecture's
10e-20 would fail at millimetre or kilometre scale.
"""

from __future__ import annotations

import re
from importlib import resources

import pytest

from linkgen.backends.c.printer import c_function
from linkgen.backends.m.printer import octave_function
from linkgen.backends.py.printer import python_function
from linkgen.primitives import PRIMITIVES

ALLOWED = {0.0, 1.0, 2.0, 0.5, 0.1, 0.01, 8.0, 1e-3, 1e-7, 3.0, 4.0, 3.141592653589793, 1000.0}
NUMBER = re.compile(r"(?<![\w.])(\d+\.\d*(?:e[-+]?\d+)?|\d+e[-+]?\d+|\d+)(?![\w.])")


def _numbers(code: str) -> set[float]:
    code = re.sub(r"(/\*.*?\*/|//[^\n]*|#[^\n]*|%[^\n]*)", "", code, flags=re.S)  # comments
    code = re.sub(r"\"[^\"]*\"|'[^']*'", "", code)  # strings
    code = re.sub(r"\b[A-Za-z_]\w*", "", code)  # names (j1, sg2, ...)
    return {float(x) for x in NUMBER.findall(code)}


@pytest.mark.parametrize("name", sorted(PRIMITIVES))
@pytest.mark.parametrize("printer", [c_function, octave_function, python_function])
def test_runtime_functions_have_only_dimensionless_numbers(name, printer):
    code = printer(PRIMITIVES[name], 2)
    assert _numbers(code) <= ALLOWED, sorted(_numbers(code) - ALLOWED)


@pytest.mark.parametrize("path", ["c/runtime/resolver.c", "m/runtime/resolver.m", "py/runtime/resolver.py"])
def test_resolver_has_only_dimensionless_numbers(path):
    code = resources.files("linkgen.backends").joinpath(path).read_text()
    assert _numbers(code) <= ALLOWED, sorted(_numbers(code) - ALLOWED)


def test_the_scan_sees_a_length_threshold():
    assert _numbers("if (q2 <= 10e-30) return 1; x = 1.5e-20 * y;") == {10e-30, 1.0, 1.5e-20}
