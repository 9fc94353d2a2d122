"""The random part of a fitted profile: breakpoints for a measured PSD (docs/model.md section 13).

A profile's PSD is a list of breakpoints joined by straight lines on log-log
axes and zero outside them (docs/model.md section 3), so the fit is made in
that representation: with x = ln f and z = ln S of the measured bins, the
fitted ln S is a continuous piecewise-linear function of x whose knots are
the breakpoints.

The fit minimises the power-weighted squared log error

    E = Σ_bins w_i · (ŷ(x_i) − z_i)²,   w_i = S_i / Σ S + τ / N   (τ = 10⁻³)

so the bins that carry the power decide it (a roll-off carrying 10⁻⁶ of the
power weighs next to nothing; the small floor τ/N only keeps every level
determined). The knots are chosen among a log-spaced grid of at most
:data:`CANDIDATES` bins between the band's ends (both ends always kept):

1. each candidate k gets an anchor level y_k, the log of the mean measured
   PSD over the bins nearest to it in ln f (its cell);
2. for every pair of candidates i < j, the error of the straight line from
   (x_i, y_i) to (x_j, y_j) over the bins x_i ≤ x < x_j is summed, all pairs
   at once from prefix sums of w, w·x, w·x², w·z, w·x·z, w·z²;
3. dynamic programming over those pair costs finds the knots (exactly B of
   them, B ≤ the candidates) with the least total E: the optimum over every
   subset of candidates, not a greedy one (:func:`optimal_knots`);
4. the levels at the chosen knots are then the weighted least-squares fit of
   z (a linear problem in the levels: hat functions in x), which can only
   lower E further;
5. one factor scales the levels so that ∫S df of the fit equals Σ S·Δf of
   the measured bins: the band variance is held.

:func:`shape_figures` says how well the shape holds: the power-weighted mean
|dB| between fit and measurement, and the share of the power in bins off by
more than 3 dB.

Cost: O(K²) for the pair costs and O(B·K²) for the programme (K ≤ 160), a
few milliseconds per axis.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from gyrovib.core.transmissibility import FloatArray, loglog_interp, psd_variance
from gyrovib.errors import ModelError

#: At most this many candidate knots, log-spaced between the band's ends.
CANDIDATES = 160
#: The weight floor τ: every bin weighs at least τ/N of the whole (N bins).
WEIGHT_FLOOR = 1e-3
#: A bin is "off" when the fit is more than this many dB from the measured PSD.
OFF_DB = 3.0


def candidate_knots(f: FloatArray, count: int = CANDIDATES) -> NDArray[np.intp]:
    """Indices of at most ``count`` bins of ``f`` (increasing, > 0) nearest in ln f to a
    log-spaced grid between its ends; the first and last bins are always in."""
    if f.size <= count:
        return np.arange(f.size, dtype=np.intp)
    x = np.log(f)
    grid = np.linspace(x[0], x[-1], count)
    hi = np.clip(np.searchsorted(x, grid), 1, x.size - 1)
    nearest = np.where(grid - x[hi - 1] < x[hi] - grid, hi - 1, hi)
    keep = np.concatenate([[0], nearest, [x.size - 1]])
    keep = np.sort(keep)
    out: NDArray[np.intp] = keep[np.concatenate([[True], keep[1:] != keep[:-1]])].astype(np.intp)
    return out


def _prefix(values: FloatArray) -> FloatArray:
    out: FloatArray = np.concatenate([[0.0], np.cumsum(values)])
    return out


def anchor_levels(x: FloatArray, z: FloatArray, cand: NDArray[np.intp]) -> FloatArray:
    """ln of the mean PSD over each candidate's cell (the bins nearest to it in x)."""
    xc = x[cand]
    edges = np.searchsorted(x, 0.5 * (xc[1:] + xc[:-1]), side="left")
    lo = np.concatenate([[0], edges])
    hi = np.concatenate([edges, [x.size]])
    hi = np.maximum(hi, lo + 1)
    top = float(z.max())
    power = _prefix(np.exp(z - top))
    mean = np.maximum((power[hi] - power[lo]) / (hi - lo), np.finfo(float).tiny)
    out: FloatArray = np.log(mean) + top
    return out


def pair_costs(x: FloatArray, z: FloatArray, w: FloatArray, cand: NDArray[np.intp],
               y: FloatArray) -> FloatArray:
    """E of the line from (x_i, y_i) to (x_j, y_j) over the bins cand[i] ≤ n < cand[j],
    for every pair i < j of candidates ((K, K); +inf where j ≤ i)."""
    sums = [_prefix(w * x**p) for p in range(3)]
    sums += [_prefix(w * z), _prefix(w * x * z), _prefix(w * z * z)]
    lo, hi = cand[:, None], cand[None, :]
    s1, sx, sxx, sz, sxz, szz = (s[hi] - s[lo] for s in sums)
    xi, xj = x[cand][:, None], x[cand][None, :]
    upper = xj > xi
    slope = np.where(upper, (y[None, :] - y[:, None]) / np.where(upper, xj - xi, 1.0), 0.0)
    c0 = y[:, None] - slope * xi  # the line c0 + slope·x
    cost = (szz + c0 * c0 * s1 + slope * slope * sxx + 2.0 * c0 * slope * sx
            - 2.0 * c0 * sz - 2.0 * slope * sxz)
    out: FloatArray = np.where(upper, np.maximum(cost, 0.0), np.inf)
    return out


def optimal_knots(cost: FloatArray, count: int) -> tuple[NDArray[np.intp], float]:
    """The ``count`` candidates, first and last included, whose consecutive pairs have the
    least summed ``cost`` (K, K), by dynamic programming; returns (indices, that sum)."""
    k = cost.shape[0]
    count = max(2, min(count, k))
    best = cost[0].copy()  # best[j]: least cost of a chain 0 … j with the knots so far
    back: list[NDArray[np.intp]] = []
    columns = np.arange(k)
    for _ in range(count - 2):
        total = best[:, None] + cost
        arg = np.argmin(total, axis=0)
        best = total[arg, columns]
        back.append(arg)
    path = [k - 1]
    for arg in reversed(back):
        path.append(int(arg[path[-1]]))
    path.append(0)
    return np.array(path[::-1], dtype=np.intp), float(best[k - 1])


def _levels(x: FloatArray, z: FloatArray, w: FloatArray, knots: FloatArray) -> FloatArray:
    """Weighted least-squares levels at ``knots`` for ŷ linear in x between them."""
    seg = np.clip(np.searchsorted(knots, x, side="right") - 1, 0, knots.size - 2)
    t = (x - knots[seg]) / (knots[seg + 1] - knots[seg])
    basis = np.zeros((x.size, knots.size))
    rows = np.arange(x.size)
    basis[rows, seg] = 1.0 - t
    basis[rows, seg + 1] = t
    root = np.sqrt(w)
    out: FloatArray = np.linalg.lstsq(basis * root[:, None], z * root, rcond=None)[0]
    return out


def fit_breakpoints(f: FloatArray, psd: FloatArray, count: int) -> tuple[FloatArray, FloatArray]:
    """At most ``count`` log-log breakpoints (f, S) for a measured PSD (module docstring).

    ``f`` increasing, > 0, evenly spaced; bins with S ≤ 0 are left out. The
    first and last positive bins are always breakpoints, so the fit covers
    the band; its variance equals Σ S·Δf of the band.
    """
    ok = psd > 0
    fb, sb = f[ok], psd[ok]
    if fb.size < 2:
        raise ModelError("the random part has fewer than two positive PSD bins to fit")
    x, z = np.log(fb), np.log(sb)
    w = sb / np.sum(sb) + WEIGHT_FLOOR / sb.size
    cand = candidate_knots(fb)
    anchors = anchor_levels(x, z, cand)
    chosen, _ = optimal_knots(pair_costs(x, z, w, cand, anchors), count)
    idx = cand[chosen]
    levels = _levels(x, z, w, x[idx])
    bf: FloatArray = fb[idx]
    bs: FloatArray = np.exp(levels)
    measured = float(np.sum(sb) * (f[1] - f[0]))
    fitted = psd_variance((bf, bs))
    if fitted > 0 and measured > 0:
        bs = bs * (measured / fitted)
    return bf, bs


def shape_figures(f: FloatArray, psd: FloatArray,
                  table: tuple[FloatArray, FloatArray] | None) -> tuple[float, float]:
    """(shape_db, off_3db) of a fitted table against a measured PSD over the bins given.

    shape_db = Σ S_i·|10·log10(Ŝ_i/S_i)| / Σ S_i, off_3db = the share of Σ S_i in bins
    where that |dB| exceeds 3 (docs/model.md section 13). Bins with S ≤ 0 carry no
    power and count for nothing; a fit that is zero where power was measured is off
    by an infinite number of dB. NaN, NaN when there is no table or no power.
    """
    ok = psd > 0
    if table is None or not np.any(ok):
        return float("nan"), float("nan")
    s = psd[ok]
    fitted = loglog_interp(table, f[ok], hold=False)
    with np.errstate(divide="ignore"):
        db = np.abs(10.0 * np.log10(fitted / s))
    total = float(np.sum(s))
    off = float(np.sum(s[db > OFF_DB]) / total)
    return float(np.sum(s * db) / total), off
