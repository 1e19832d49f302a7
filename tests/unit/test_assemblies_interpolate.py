"""linkgen.assemblies.interpolate: the resultant by evaluation and interpolation is FLINT's own
multivariate resultant (fmpz_mpoly.resultant), on random integer polynomials and where a leading
coefficient vanishes at a node."""

from __future__ import annotations

import random

import flint
import pytest

from linkgen.assemblies.interpolate import coefficients, resultant

NAMES = ("a", "x", "b", "y")  # the class-IV elimination's layout: x (index 1) kept, y (index 3) eliminated


def _random(ctx, rng, degree, bits):
    return ctx.from_dict({(0, i, 0, j): rng.randint(-2**bits, 2**bits) for i in range(degree + 1)
                          for j in range(degree + 1)})


def _as_poly(p):
    """An fmpz_mpoly in x only as an fmpz_poly."""
    d = {int(e[1]): int(c) for e, c in p.to_dict().items()}
    return flint.fmpz_poly([d.get(k, 0) for k in range(max(d, default=0) + 1)])


@pytest.mark.parametrize("seed, degree, bits", [(1, 3, 8), (2, 4, 60), (3, 6, 200)])
def test_the_interpolated_resultant_is_flints(seed, degree, bits):
    rng = random.Random(seed)
    ctx = flint.fmpz_mpoly_ctx.get(NAMES, "lex")
    a, b = _random(ctx, rng, degree, bits), _random(ctx, rng, degree - 1, bits)
    assert resultant(a, b, 3, 1) == _as_poly(a.resultant(b, "y"))


def test_a_node_where_a_leading_coefficient_vanishes_is_skipped():
    """a = x y^2 + y + 1 loses its degree in y at x = 0: the node 0 would give another resultant."""
    ctx = flint.fmpz_mpoly_ctx.get(NAMES, "lex")
    _, x, _, y = ctx.gens()
    a, b = x * y**2 + y + 1, (x + 2) * y**2 - 3 * x * y + x**2 - 5
    assert resultant(a, b, 3, 1) == _as_poly(a.resultant(b, "y"))
    assert [c.degree() for c in coefficients(a, 3, 1)] == [0, 0, 1]
