"""The overlapping Allan deviation of a record too long to hold: day-long logs at kHz
rates (docs/model.md section 15; docs/performance.md).

The estimator is :func:`gyrovib.core.allan.oadev_from_angle`'s, term for term::

    σ²(τ) = Σ_k (x_{k+2m} − 2x_{k+m} + x_k)² / (2τ²(n + 1 − 2m)),   x_k = τ0·Σ_{i<k}(y_i − ȳ)

but nothing holds the record: ``read_rows(start, stop)`` gives rows of the rate (one
column an axis), a first pass takes the mean, a second writes the angle x of every axis
(float64, n + 1 values a column) to a scratch file a block at a time, and each τ then
reads each column's angle back about once: for short m a window slides along it, for
long m the k go in chains k, k + m, k + 2m, … so that two of the three windows
x_k, x_{k+m}, x_{k+2m} carry over from one step to the next. The working memory is a
few blocks whatever the record's length; the scratch file sits in the operating
system's cache, not in the process.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import BinaryIO

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]

#: Values of a block: 2¹⁶ float64 (512 KiB) a read. The sums of squares are numpy's
#: own loops (``einsum``), not BLAS: OpenBLAS would start its threads for every block
#: of this size, which costs many times the CPU on a busy machine (docs/performance.md).
ROWS = 1 << 16


class _Scratch:
    """The angle of every column in ``scratch``: column j's n + 1 float64 values from
    byte j·(n + 1)·8."""

    def __init__(self, scratch: BinaryIO, n: int) -> None:
        self.file, self.points = scratch, n + 1

    def read(self, col: int, start: int, out: FloatArray) -> FloatArray:
        self.file.seek((col * self.points + start) * 8)
        got = self.file.readinto(out.data.cast("B"))  # type: ignore[attr-defined]
        if got != out.size * 8:
            raise OSError("the scratch file of the angle is shorter than written")
        return out


def write_angle(read_rows: Callable[[int, int], FloatArray], n: int, cols: int, tau0: float,
                scratch: BinaryIO, rows: int = ROWS) -> FloatArray:
    """Writes x (n + 1 values, float64) of every column to ``scratch``, one column after
    the other; returns the means."""
    total = np.zeros(cols)
    for lo in range(0, n, rows):
        total += read_rows(lo, min(n, lo + rows)).sum(axis=0)
    mean = total / n
    last = np.zeros(cols)
    for j in range(cols):
        scratch.seek(j * (n + 1) * 8)
        scratch.write(b"\0" * 8)
    for lo in range(0, n, rows):
        y = read_rows(lo, min(n, lo + rows)) - mean
        x = np.cumsum(y, axis=0)
        x *= tau0
        x += last
        last = x[-1].copy()
        for j in range(cols):
            scratch.seek((j * (n + 1) + lo + 1) * 8)
            scratch.write(np.ascontiguousarray(x[:, j]).tobytes())
    scratch.flush()
    return mean


def _sum_short(x: _Scratch, col: int, count: int, m: int, rows: int) -> float:
    """Σ of the squared second differences for 2m < rows: a window of rows + 2m values
    slides along the angle, each value read once (the window's tail kept)."""
    window = np.empty(rows + 2 * m)
    d = np.empty(rows)
    total, have, start = 0.0, 0, 0
    for lo in range(0, count, rows):
        size = min(count, lo + rows) - lo
        need = size + 2 * m
        if have:
            keep = window[start:start + have]
            window[:have] = keep
        x.read(col, lo + have, window[have:need])
        have, start = 2 * m, size
        part = d[:size]
        np.subtract(window[2 * m:2 * m + size], window[m:m + size], out=part)
        part -= window[m:m + size]
        part += window[:size]
        total += float(np.einsum("i,i->", part, part))
    return total


def _sum_long(x: _Scratch, col: int, count: int, m: int, rows: int) -> float:
    """Σ of the squared second differences for m ≥ rows/2: the k are taken in chains
    lo, lo + m, lo + 2m, … of blocks of at most ``rows``, so that each step reuses two of
    its three windows (x_{k+m}, x_{k+2m} become the next x_k, x_{k+m})."""
    size = min(rows, m)
    bufs = [np.empty(size) for _ in range(3)]
    d = np.empty(size)
    total = 0.0
    for start in range(0, min(m, count), size):
        width = min(size, m - start, count - start)
        a, b, c = (buf[:width] for buf in bufs)
        x.read(col, start, a)
        x.read(col, start + m, b)
        lo = start
        while lo < count:
            w = min(width, count - lo)
            x.read(col, lo + 2 * m, c[:w])
            part = d[:w]
            np.subtract(c[:w], b[:w], out=part)
            part -= b[:w]
            part += a[:w]
            total += float(np.einsum("i,i->", part, part))
            a, b, c = b, c, a
            lo += m
    return total


def oadev_scratch(scratch: BinaryIO, n: int, cols: int, tau0: float, m: NDArray[np.int64],
                  rows: int = ROWS) -> FloatArray:
    """σ(τ) (rows: τ = m·τ0, columns: axes) from the angle that :func:`write_angle`
    wrote to ``scratch``; every τ reads each column's angle about once."""
    x = _Scratch(scratch, n)
    out = np.empty((m.size, cols))
    for j, mm in enumerate(np.asarray(m).tolist()):
        count = n + 1 - 2 * mm
        if count < 1:
            raise ValueError(f"cluster size {mm} needs at least {2 * mm} samples")
        tau = mm * tau0
        for col in range(cols):
            total = (_sum_short(x, col, count, mm, rows) if 2 * mm < rows
                     else _sum_long(x, col, count, mm, rows))
            out[j, col] = math.sqrt(total / (2.0 * tau * tau * count))
    return out


def octave_grid(n: int) -> NDArray[np.int64]:
    """Cluster sizes 1, 2, 4, … up to n // 3: the octave grid of long records."""
    top = max(1, n // 3)
    return np.array([1 << k for k in range(int(math.log2(top)) + 1)], dtype=np.int64)


__all__ = ["ROWS", "oadev_scratch", "octave_grid", "write_angle"]
