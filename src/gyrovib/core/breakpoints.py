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
determined). The knots are chosen among at most :data:`CANDIDATES` bins (both
ends of the band always kept): most on a log-spaced grid, the rest at the
quantiles of the measured power, so that a narrow resonance has candidates
across it (:func:`candidate_knots`):

1. each candidate k gets an anchor level y_k, the log of the mean measured
   PSD over the bins nearest to it in ln f (its cell);
2. for every pair of candidates i < j, the error of the straight line from
   (x_i, y_i) to (x_j, y_j) over the bins x_i ≤ x < x_j is summed, all pairs
   at once from prefix sums of w, w·x, w·x², w·z, w·x·z, w·z²;
3. dynamic programming over those pair costs finds the knots (exactly B of
   them, B ≤ the candidates) whose chain of anchored lines has the least
   total E: the optimum over every subset of candidates, not a greedy one
   (:func:`optimal_knots`; a test holds it against brute force);
4. the levels at the chosen knots are then those of least E among the fits
   whose ∫S df equals Σ S·Δf of the measured bins (the band variance held):
   the weighted least squares, a linear problem in the levels (hat functions
   in x), then Gauss-Newton steps on that equality-constrained problem. The
   variance is thus taken up where it costs the shape least (a steep edge of
   the band, say), not by one factor that would shift every level alike.

:func:`shape_figures` says how well the shape holds: the power-weighted mean
|dB| between fit and measurement, and the share of the power in bins off by
more than 3 dB.

Cost: O(K²) for the pair costs and O(B·K²) for the programme (K ≤ 160).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from gyrovib.core._types import FloatArray
from gyrovib.core.transmissibility import loglog_interp
from gyrovib.errors import ModelError

#: At most this many candidate knots, log-spaced between the band's ends.
CANDIDATES = 160
#: The share of the candidates placed by power rather than by frequency.
POWER_SHARE = 0.375
#: The weight floor τ: every bin weighs at least τ/N of the whole (N bins).
WEIGHT_FLOOR = 1e-3
#: At most this many Gauss-Newton steps of the variance-constrained levels.
_NEWTON_STEPS = 20
#: A bin is "off" when the fit is more than this many dB from the measured PSD.
OFF_DB = 3.0


def candidate_knots(f: FloatArray, psd: FloatArray,
                    count: int = CANDIDATES) -> NDArray[np.intp]:
    """Indices of at most ``count`` bins of ``f`` (increasing, > 0) as candidate knots.

    :data:`POWER_SHARE` of them follow the power (the bins at the quantiles of the
    cumulative PSD, so a narrow resonance gets candidates across it), the rest the
    bins nearest in ln f to a log-spaced grid between the ends (so every part of the
    band has some); the first and last bins are always in.
    """
    if f.size <= count:
        return np.arange(f.size, dtype=np.intp)
    x = np.log(f)
    by_power = round(POWER_SHARE * count)
    grid = np.linspace(x[0], x[-1], count - by_power - 2)
    hi = np.clip(np.searchsorted(x, grid), 1, x.size - 1)
    nearest = np.where(grid - x[hi - 1] < x[hi] - grid, hi - 1, hi)
    cumulative = np.cumsum(psd)
    quantiles = (np.arange(by_power) + 0.5) / by_power * cumulative[-1]
    heavy = np.minimum(np.searchsorted(cumulative, quantiles), x.size - 1)
    keep = np.sort(np.concatenate([[0], nearest, heavy, [x.size - 1]]))
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


def _hats(x: FloatArray, knots: FloatArray) -> tuple[NDArray[np.intp], FloatArray]:
    """For each x its segment k (knots k, k+1) and position t in it: ŷ = (1−t)·y_k + t·y_k+1."""
    seg = np.clip(np.searchsorted(knots, x, side="right") - 1, 0, knots.size - 2)
    t: FloatArray = (x - knots[seg]) / (knots[seg + 1] - knots[seg])
    return seg, t


def _log_variance(knots: FloatArray, levels: FloatArray) -> tuple[float, FloatArray]:
    """ln ∫S df of the table (e^knots, e^levels) and its gradient in the levels.

    On a segment from x_a to x_b (x = ln f, L = x_b − x_a) the integrand S·f is
    e^{e_a + a·s}, s = (x − x_a)/L, with e = y + x at the ends and a = e_b − e_a, so
    ∫S df = L·∫_0^1 e^{e_a + a·s} ds and its derivatives in y_a and y_b weigh the
    integrand by 1 − s and s. Each segment is taken from its larger end (the exponent
    then never grows: no overflow however steep), the segments relative to the largest.
    """
    length = np.diff(knots)
    ends = levels + knots
    a = np.diff(ends)
    n = -np.abs(a)  # the exponent from the larger end, ≤ 0
    small = n > -1e-3
    safe = np.where(small, -1.0, n)
    # ∫_0^1 e^{n u} du and ∫_0^1 u·e^{n u} du (series where n is small)
    m0 = np.where(small, 1 + n / 2 + n * n / 6 + n**3 / 24, np.expm1(safe) / safe)
    m1 = np.where(small, 0.5 + n / 3 + n * n / 8 + n**3 / 30,
                  (np.exp(safe) * (safe - 1.0) + 1.0) / safe**2)
    rising = a >= 0  # the larger end is the right one: u = 1 − s
    near, far = m0 - m1, m1  # weights of the larger end (1 − u) and of the other (u)
    top = np.maximum(ends[:-1], ends[1:])
    peak = float(top.max())
    scale = length * np.exp(top - peak)
    total = float(np.sum(scale * m0))
    grad = np.zeros(levels.size)
    grad[:-1] += scale * np.where(rising, far, near)
    grad[1:] += scale * np.where(rising, near, far)
    return float(np.log(total)) + peak, grad / total


def _levels(x: FloatArray, z: FloatArray, w: FloatArray, knots: FloatArray,
            log_target: float) -> FloatArray:
    """The levels at ``knots`` (ŷ linear in x between them) of least Σ w·(ŷ − z)² among
    those whose table integrates to e^log_target: the weighted least squares, then
    Gauss-Newton steps on the constrained problem (its KKT system), and a last uniform
    factor for what rounding leaves."""
    n = knots.size
    seg, t = _hats(x, knots)
    # the normal equations of the hat basis, tridiagonal, summed bin by bin (no dense basis)
    normal = np.zeros((n, n))
    diagonal = np.bincount(seg, w * (1 - t) ** 2, n) + np.bincount(seg + 1, w * t * t, n)
    beside = np.bincount(seg, w * t * (1 - t), n - 1)
    normal[np.arange(n), np.arange(n)] = diagonal
    normal[np.arange(n - 1), np.arange(1, n)] = beside
    normal[np.arange(1, n), np.arange(n - 1)] = beside
    rhs = np.bincount(seg, w * z * (1 - t), n) + np.bincount(seg + 1, w * z * t, n)
    free = np.asarray(np.linalg.solve(normal, rhs), dtype=float)
    levels = free.copy()
    kkt = np.zeros((n + 1, n + 1))
    kkt[:n, :n] = normal
    for _ in range(_NEWTON_STEPS):
        value, grad = _log_variance(knots, levels)
        miss = value - log_target
        if abs(miss) < 1e-9:
            break
        kkt[:n, n] = kkt[n, :n] = grad
        step = np.linalg.solve(kkt, np.concatenate([rhs - normal @ levels, [-miss]]))[:n]
        levels = levels + step
    value, _ = _log_variance(knots, levels)
    levels = levels + (log_target - value)
    # never worse than the least-squares levels shifted alike (a safeguard: the steps
    # converge in a few iterations on every spectrum tried)
    shifted = free + (log_target - _log_variance(knots, free)[0])
    error = [float(np.sum(w * ((1 - t) * y[seg] + t * y[seg + 1] - z) ** 2))
             for y in (levels, shifted)]
    out: FloatArray = levels if np.isfinite(error[0]) and error[0] <= error[1] else shifted
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
    cand = candidate_knots(fb, sb)
    anchors = anchor_levels(x, z, cand)
    chosen, _ = optimal_knots(pair_costs(x, z, w, cand, anchors), count)
    idx = cand[chosen]
    measured = float(np.sum(sb) * (f[1] - f[0]))
    levels = _levels(x, z, w, x[idx], float(np.log(measured)))
    bf: FloatArray = fb[idx]
    bs: FloatArray = np.exp(levels)
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
