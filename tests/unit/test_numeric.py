"""linkgen.numeric against numpy's own percentile and unique, on sweeps of 1 to 4097 values, rounded or not."""

from __future__ import annotations

import numpy as np

from linkgen.numeric import percentiles, unique


def test_percentiles_are_numpys_bit_for_bit():
    rng = np.random.default_rng(7)
    qs = (1.0, 99.0, 50.0, 0.0, 100.0, 25.0, 12.5, 33.3)
    for n in [*range(1, 24), 97, 361, 4097]:
        for _ in range(8):
            x = rng.normal(size=n) * 10 ** rng.uniform(-5, 5)
            x = np.round(x, 1) if rng.random() < 0.3 else x
            assert percentiles(x, qs) == [float(v) for v in np.percentile(x, qs)]


def test_unique_is_numpys():
    rng = np.random.default_rng(3)
    for n in (1, 2, 9, 200):
        x = np.round(rng.normal(size=n), 1)
        got, ref = unique(x), np.unique(x, return_inverse=True)
        assert np.array_equal(got[0], ref[0]) and np.array_equal(got[1], ref[1])
