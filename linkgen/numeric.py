"""numpy's percentile and unique, bit for bit, without them: each imports numpy.ma (6 ms of every build,
which uses neither otherwise)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

Array = np.ndarray[Any, np.dtype[Any]]


def percentiles(x: Array, qs: tuple[float, ...]) -> list[float]:
    """np.percentile(x, qs) of finite values (its linear method)."""
    s, top, out = np.sort(x), len(x) - 1, []
    for q in qs:
        v = top * (q / 100)  # numpy's index of its linear method; from s[k] to s[k + 1] by g, as its _lerp
        k = min(math.floor(v), top)
        a, b, g = s[k], s[min(k + 1, top)], v - k
        out.append(float(s[-1] if v >= top else b - (b - a) * (1 - g) if g >= 0.5 else a + (b - a) * g))
    return out


def unique(x: Array) -> tuple[Array, Array]:
    """np.unique(x, return_inverse=True) of values that are not nan."""
    order = np.argsort(x, kind="stable")
    ranked = x[order]
    first = np.concatenate([[True], ranked[1:] != ranked[:-1]])
    where = np.empty(len(x), dtype=np.intp)
    where[order] = np.cumsum(first) - 1
    return ranked[first], where
