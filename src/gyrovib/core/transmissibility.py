"""Breakpoint tables on log-log axes: transmissibility ν(f) and PSD integrals.

A table is a pair of arrays ``(f, g)``: frequencies in Hz, non-decreasing
(a repeated frequency is a step), and non-negative values. Between two
breakpoints the value follows a straight line on log-log axes, i.e. a power law
``g(f) = g1·(f/f1)**b`` with ``b = ln(g2/g1)/ln(f2/f1)``; a segment with a zero
end is zero inside. Past the ends a transmissibility is held constant
(docs/model.md) while a PSD is zero.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from gyrovib.core._types import FloatArray, Table


def as_table(table: ArrayLike) -> Table:
    """Coerce ``[[f, g], ...]`` to a ``(f, g)`` pair of float arrays and check it."""
    arr = np.asarray(table, dtype=float)
    if arr.ndim != 2 or arr.shape[1] != 2 or arr.shape[0] < 1:
        raise ValueError("a table is a non-empty list of [frequency, value] pairs")
    f, g = arr[:, 0].copy(), arr[:, 1].copy()
    if not (np.all(np.isfinite(arr)) and np.all(f > 0) and np.all(g >= 0)):
        raise ValueError("table frequencies must be > 0 and values >= 0, all finite")
    if np.any(np.diff(f) < 0):
        raise ValueError("table frequencies must not decrease")
    return f, g


def _segment_powerlaw(
    table: Table, fm: FloatArray, hold: bool
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Power law ``g = c·(f/f_ref)**b`` of ``table`` on the segments holding ``fm``.

    ``fm`` must not coincide with a breakpoint. Returns ``(c, f_ref, b)``.
    """
    tf, tg = table
    n = tf.size
    idx = np.searchsorted(tf, fm, side="right")
    inside = (idx > 0) & (idx < n)
    lo = np.clip(idx - 1, 0, n - 1)
    hi = np.clip(idx, 0, n - 1)
    f1, g1, f2, g2 = tf[lo], tg[lo], tf[hi], tg[hi]
    positive = (g1 > 0) & (g2 > 0) & inside
    with np.errstate(divide="ignore", invalid="ignore"):
        b = np.where(positive, np.log(np.where(positive, g2 / g1, 1.0)) / np.log(
            np.where(positive, f2 / f1, 2.0)), 0.0)
    c = np.where(inside, np.where(positive, g1, 0.0), 0.0)
    if hold:
        c = np.where(idx == 0, tg[0], c)
        c = np.where(idx == n, tg[-1], c)
    f_ref = np.where(inside, f1, 1.0)
    return c, f_ref, b


def loglog_interp(table: Table, f: ArrayLike, hold: bool = True) -> FloatArray:
    """Evaluate a table at frequencies ``f`` (right-continuous at a step).

    ``hold=True`` holds the end values past the ends (transmissibility);
    ``hold=False`` gives zero there (PSD).
    """
    tf, tg = table
    fq = np.asarray(f, dtype=float)
    idx = np.searchsorted(tf, fq, side="right")
    n = tf.size
    at_point = (idx > 0) & (tf[np.clip(idx - 1, 0, n - 1)] == fq)
    c, f_ref, b = _segment_powerlaw(table, fq, hold)
    value = c * (fq / f_ref) ** b
    # exactly on a breakpoint: its own (last, for a step) value
    value = np.where(at_point, tg[np.clip(idx - 1, 0, n - 1)], value)
    if not hold:
        value = np.where((fq < tf[0]) | (fq > tf[-1]), 0.0, value)
    result: FloatArray = value
    return result


def psd_variance(psd: Table, gains: tuple[Table, ...] = ()) -> float:
    """Variance ``σ² = ∫ Π ν_j(f)² · S(f) df`` over the PSD's band (eq. 6).

    Exact: on every interval between consecutive breakpoints of all tables the
    integrand is a single power law ``P(fa)·(f/fa)**B`` whose integral is
    ``P(fa)·fa·L·(e^{(B+1)L} − 1)/((B+1)L)`` with ``L = ln(fb/fa)``.
    """
    pf, _ = psd
    # sorted distinct breakpoints (np.unique would import numpy.ma: slow at start-up)
    grid = np.sort(np.concatenate([pf, *[g[0] for g in gains]]))
    grid = grid[np.concatenate([[True], grid[1:] != grid[:-1]])]
    grid = grid[(grid >= pf[0]) & (grid <= pf[-1])]
    if grid.size < 2:
        return 0.0
    fa, fb = grid[:-1], grid[1:]
    fm = np.sqrt(fa * fb)
    c, f_ref, b = _segment_powerlaw(psd, fm, hold=False)
    value_a = c * (fa / f_ref) ** b
    exponent = b.copy()
    for gain in gains:
        cg, fg, bg = _segment_powerlaw(gain, fm, hold=True)
        value_a = value_a * (cg * (fa / fg) ** bg) ** 2
        exponent = exponent + 2.0 * bg
    L = np.log(fb / fa)
    x = (exponent + 1.0) * L
    small = np.abs(x) < 1e-8
    ratio = np.where(small, 1.0 + 0.5 * x, np.expm1(x) / np.where(small, 1.0, x))
    return float(np.sum(value_a * fa * L * ratio))
