"""The overlapping Allan deviation of a rate record (docs/model.md section 15;
IEEE Std 952-1997 Annex C, allantools' ``oadev``).

With rate samples y_i at interval τ0, the angle x_k = τ0·Σ_{i<k} y_i (x_0 = 0),
cluster size m and τ = m·τ0::

    σ²(τ) = Σ_k (x_{k+2m} − 2x_{k+m} + x_k)² / (2τ²(n + 1 − 2m))    (k = 0 … n − 2m)

Each τ costs O(n) from the cumulative sum, summed a block of k at a time, so the
memory is the angle array plus a few blocks. A constant offset of y does not
change σ (its ramp has no second difference); the mean is removed before the sum
so that the angle stays small and the differences keep their digits.
"""

from __future__ import annotations

import math

import numpy as np

from gyrovib.core._types import FloatArray, IntArray

#: k values summed at once: the working memory is a few blocks of this many floats
#: (64 KiB each, in a core's cache). Below OpenBLAS's threading threshold of its dot
#: product, too: with larger blocks it starts threads for every block, which cost
#: 15× the CPU time on a busy machine (docs/performance.md).
BLOCK = 1 << 13
#: Points of the τ grid per decade (fewer where there are not as many cluster sizes).
PER_DECADE = 10


def tau_grid(n: int, per_decade: int = PER_DECADE) -> IntArray:
    """Cluster sizes m (τ = m·τ0): unique integers on a log grid from 1 to n // 3,
    ``per_decade`` per decade where there are integers for them."""
    if n < 3:
        raise ValueError("the overlapping Allan deviation needs at least 3 samples")
    top = n // 3
    count = max(2, math.ceil(per_decade * math.log10(top)) + 1) if top > 1 else 1
    m = np.unique(np.round(np.logspace(0.0, math.log10(top), count)).astype(np.int64))
    return m[(m >= 1) & (m <= top)]


def angle(rate: FloatArray, tau0: float) -> FloatArray:
    """x_k = τ0·Σ_{i<k} (y_i − ȳ), x_0 = 0: n + 1 values."""
    y = np.asarray(rate, dtype=np.float64)
    x = np.empty(y.size + 1)
    x[0] = 0.0
    np.cumsum(y - y.mean(), out=x[1:])
    x *= tau0
    return x


def oadev_from_angle(x: FloatArray, tau0: float, m: IntArray,
                     block: int = BLOCK) -> FloatArray:
    """σ(τ) at τ = m·τ0 from the angle x (n + 1 values), each in O(n) and blocks."""
    n = x.size - 1
    out = np.empty(m.size)
    buffer = np.empty(min(block, max(n, 1)))
    for j, mm in enumerate(m.tolist()):
        count = n + 1 - 2 * mm
        if count < 1:
            raise ValueError(f"cluster size {mm} needs at least {2 * mm} samples")
        total = 0.0
        for lo in range(0, count, block):
            hi = min(count, lo + block)
            d = buffer[:hi - lo]
            np.subtract(x[lo + 2 * mm:hi + 2 * mm], x[lo + mm:hi + mm], out=d)
            d -= x[lo + mm:hi + mm]
            d += x[lo:hi]
            total += float(np.dot(d, d))
        tau = mm * tau0
        out[j] = math.sqrt(total / (2.0 * tau * tau * count))
    return out


def oadev(rate: FloatArray, tau0: float, m: IntArray | None = None,
          block: int = BLOCK) -> tuple[FloatArray, FloatArray]:
    """(τ, σ(τ)) of a rate record at interval τ0 (the rate's unit); ``m`` defaults to
    :func:`tau_grid`."""
    y = np.asarray(rate, dtype=np.float64)
    grid = tau_grid(y.size) if m is None else np.asarray(m, dtype=np.int64)
    tau = np.multiply(grid, tau0, dtype=np.float64)
    return tau, oadev_from_angle(angle(y, tau0), tau0, grid, block)


__all__ = ["PER_DECADE", "angle", "oadev", "oadev_from_angle", "tau_grid"]
