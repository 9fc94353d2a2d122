"""Recordings: carrier rate and vibration from a time series (docs/model.md section 13).

Pure numpy; ``scipy.signal`` (the Butterworth split, Welch spectra) and
``scipy.ndimage`` (the running median) are imported inside the functions
that need them.

Units are the caller's: rates in one rate unit (gyrovib passes deg/s),
accelerations in g, frequencies in Hz, time in s.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.lib.stride_tricks import sliding_window_view
from numpy.typing import ArrayLike, NDArray

from gyrovib.coefficients import BOUNDED
from gyrovib.core._types import FloatArray, Table
from gyrovib.core.filtfilt import sosfiltfilt_into
from gyrovib.core.transmissibility import loglog_interp
from gyrovib.errors import ModelError
from gyrovib.frozen import Frozen

#: Order of the zero-phase Butterworth low-pass (applied forward and backward).
FILTER_ORDER = 4
#: Half-width (bins) of the running median a line must stand above.
MEDIAN_HALF_WIDTH = 20
#: Half-width (bins) of a line's main lobe under the Hann window (its power is summed there).
LOBE_HALF_WIDTH = 3
#: Lines within this fraction of n·f0 are order n of f0 (docs/model.md section 13).
HARMONIC_TOLERANCE = 0.01
#: The highest order a fitted harmonics group takes (shafts, engines, rotors: low orders).
MAX_FITTED_ORDER = 12
#: Most orders missing between two orders of a fitted group (a consistent series).
MAX_ORDER_GAP = 3
#: A line joins order n of f0 only within this fraction of f0 of n·f0.
ORDER_SPACING = 0.05
#: At most this many histogram bins of Ω_K3 make the fitted mission.
MISSION_BINS = 16
#: The six products a_j·a_k of the g² term, in the order of core.linear.G2_TERMS.
G2_PAIRS: tuple[tuple[int, int], ...] = ((0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2))
#: Columns of :func:`recorded_moments`: ½⟨|ω3|−|Ω3|⟩, ⟨ω3ⁿ−Ω3ⁿ⟩ (n = 2…5), C31, C32.
MOMENTS = BOUNDED
_CHUNK = 1 << 20


def gap_segments(time: ArrayLike, factor: float = 1.5) -> tuple[NDArray[np.intp], float]:
    """Split sample times at gaps: ``(bounds, median interval)``.

    A gap is an interval longer than ``factor`` median intervals (docs/model.md
    section 13). ``bounds`` is (S, 2): start and stop indices of each
    contiguous segment. Times must increase strictly (checked by the caller).
    """
    t = np.asarray(time, dtype=float)
    if t.size < 2:
        return np.array([[0, t.size]], dtype=np.intp), float("nan")
    dt = np.diff(t)
    med = float(np.median(dt))
    cut = np.flatnonzero(dt > factor * med) + 1
    edges = np.concatenate([[0], cut, [t.size]]).astype(np.intp)
    return np.column_stack([edges[:-1], edges[1:]]), med


def lowpass(signal: ArrayLike, fs: float, crossover: float,
            out: FloatArray | None = None) -> FloatArray:
    """Zero-phase 4th-order Butterworth low-pass of each column (docs/model.md section 13).

    ``butter(4, f_c, fs=fs, output="sos")`` applied forward and backward with
    ``sosfiltfilt``'s numbers and its default padding, along axis 0, one
    column at a time and a block at a time (:mod:`gyrovib.core.filtfilt`), so
    the temporaries are a few blocks long. Returns the carrier Ω_K(t) (or
    A(t) for accelerations), same shape as ``signal``, written into ``out``
    when given (float64, same shape, not overlapping ``signal``).
    """
    # lazy: scipy only where a recording is filtered
    from scipy.signal import butter

    x = np.asarray(signal, dtype=float)
    if not 0 < crossover < fs / 2:
        raise ModelError(f"the crossover {crossover:g} Hz must lie in (0, fs/2 = {fs / 2:g} Hz)")
    sos = butter(FILTER_ORDER, crossover, fs=fs, output="sos")
    result = np.empty_like(x) if out is None else out
    if x.ndim == 1:
        return sosfiltfilt_into(sos, x, result)
    for j in range(x.shape[1]):
        sosfiltfilt_into(sos, x[:, j], result[:, j])
    return result


def zero_phase_gain(x: ArrayLike, fs: float, table: Table) -> FloatArray:
    """x filtered by a zero-phase gain ν(f): the FFT of each column times the table's
    gain at each bin (log-log interpolated, held past its ends; docs/model.md sections 3, 13)."""
    v = np.asarray(x, dtype=float)
    n = v.shape[0]
    f = np.fft.rfftfreq(n, 1.0 / fs)
    gain = np.ones_like(f)
    pos = f > 0
    gain[pos] = loglog_interp(table, f[pos])
    gain[0] = float(loglog_interp(table, np.array([max(f[1] if n > 1 else 1.0, 1e-12)]))[0])
    spectrum = np.fft.rfft(v, axis=0)
    spectrum *= gain.reshape(-1, *([1] * (v.ndim - 1)))
    out: FloatArray = np.fft.irfft(spectrum, n=n, axis=0)
    return out


def recorded_moments(rate: ArrayLike, carrier: ArrayLike) -> FloatArray:
    """The sums behind Δ_V,rec (docs/model.md section 13), over the samples given.

    With ω = ``rate`` and Ω_K = ``carrier`` (n, 3) in one rate unit, returns
    the sums (not yet divided by n) of

        ½(|ω3| − |Ω3|),  ω3ⁿ − Ω3ⁿ (n = 2…5),  ω3·ω1 − Ω3·Ω1,  ω3·ω2 − Ω3·Ω2,

    so that, dotted with (k1·A1, k2, k3, k4, k5, m31, m32) and divided by the
    sample count, they give Δ_V,rec without its g² part: the linear terms
    k1·x3, m1·x1, m2·x2 cancel exactly against eq. (2)'s own. Chunked, so
    the temporaries are small.
    """
    w = np.asarray(rate, dtype=float)
    c = np.asarray(carrier, dtype=float)
    out = np.zeros(len(MOMENTS))
    for lo in range(0, w.shape[0], _CHUNK):
        w3, c3 = w[lo:lo + _CHUNK, 2], c[lo:lo + _CHUNK, 2]
        out[0] += 0.5 * (np.abs(w3).sum() - np.abs(c3).sum())
        wp, cp = w3 * w3, c3 * c3
        for k in range(1, 5):
            out[k] += wp.sum() - cp.sum()
            wp *= w3
            cp *= c3
        out[5] += w3 @ w[lo:lo + _CHUNK, 0] - c3 @ c[lo:lo + _CHUNK, 0]
        out[6] += w3 @ w[lo:lo + _CHUNK, 1] - c3 @ c[lo:lo + _CHUNK, 1]
    return out


def recorded_g2_moments(accel: ArrayLike, lowpassed: ArrayLike) -> FloatArray:
    """Sums of a_j·a_k − A_j·A_k over the samples (g²), for the six pairs of :data:`G2_PAIRS`."""
    a = np.asarray(accel, dtype=float)
    b = np.asarray(lowpassed, dtype=float)
    out = np.zeros(len(G2_PAIRS))
    for lo in range(0, a.shape[0], _CHUNK):
        aa, bb = a[lo:lo + _CHUNK], b[lo:lo + _CHUNK]
        for p, (j, k) in enumerate(G2_PAIRS):
            out[p] += aa[:, j] @ aa[:, k] - bb[:, j] @ bb[:, k]
    return out


def recorded_error(coefficients: ArrayLike, moments: ArrayLike, g2: ArrayLike | None = None,
                   g2_moments: ArrayLike | None = None) -> tuple[FloatArray, FloatArray,
                                                                 FloatArray]:
    """Δ_V,rec of every sensor from mean moments (docs/model.md section 13), vectorised.

    ``coefficients`` (N, 11) in the order of core.analysis.COEFFICIENTS;
    ``moments`` (7,) or (N, 7): the means of :func:`recorded_moments`
    (per sensor where input responses differ); ``g2`` (N, 6) G_jk in rate/g²
    with ``g2_moments`` (6,) the mean ⟨a_j a_k − A_j A_k⟩ in g².
    Returns (total (N,), terms (N, 7) for :data:`MOMENTS`, g² part (N,)):

        Δ_V,rec = k1·A1·½⟨|ω3|−|Ω3|⟩ + Σn kn⟨ω3ⁿ−Ω3ⁿ⟩ + Σi m3i⟨ω3ωi−Ω3Ωi⟩
                  + Σ G_jk⟨a_j a_k − A_j A_k⟩
    """
    k = np.atleast_2d(np.asarray(coefficients, dtype=float))
    m = np.asarray(moments, dtype=float)
    factors = np.column_stack([k[:, 1] * k[:, 2], k[:, 3], k[:, 4], k[:, 5], k[:, 6],
                               k[:, 9], k[:, 10]])
    terms: FloatArray = factors * m
    if g2 is None or g2_moments is None:
        g2_part = np.zeros(k.shape[0])
    else:
        g2_part = np.asarray(g2, dtype=float).reshape(-1, 6) @ np.asarray(g2_moments,
                                                                          dtype=float)
    return terms.sum(axis=1) + g2_part, terms, g2_part


# ----------------------------------------------------------------- spectra


def welch_length(fs: float, resolution: float) -> int:
    """Samples in one Welch window: nper = max(8, round(fs / Δf)) (docs/model.md section 13)."""
    return max(8, round(fs / resolution))


def welch_spectra(segments: Sequence[FloatArray], fs: float,
                  resolution: float) -> tuple[FloatArray, NDArray[np.complex128], int]:
    """Welch cross-spectral matrix of (n, m) segments: ``(f, S (m, m, F), windows)``.

    Hann window (periodic), 50 % overlap, nperseg = round(fs / resolution),
    no detrending, one-sided density (units²/Hz):

        S_ij(f) = c·mean_windows[conj(X_i(f))·X_j(f)],  c = 2/(fs·Σw²) (1/(fs·Σw²) at
        DC and at the Nyquist bin of an even window)

    — scipy.signal.csd's estimate, with every window averaged alike across
    segments. Each window is transformed once per column (not once per pair),
    a block of windows at a time, so the temporaries stay small. Segments
    shorter than one window are left out; ``windows`` = 0 when none is long enough.
    """

    nper = welch_length(fs, resolution)
    step = nper - nper // 2
    window = 0.5 - 0.5 * np.cos(2.0 * np.pi * np.arange(nper) / nper)
    freqs: FloatArray = np.fft.rfftfreq(nper, 1.0 / fs).astype(float)
    m = segments[0].shape[1] if segments else 0
    total = np.zeros((m, m, freqs.size), dtype=np.complex128)
    count = 0
    block = max(1, (1 << 20) // nper)
    for seg in segments:
        n = seg.shape[0]
        if n < nper:
            continue
        starts = np.arange(0, n - nper + 1, step)
        views = [sliding_window_view(seg[:, i], nper) for i in range(m)]
        for lo in range(0, starts.size, block):
            st = starts[lo:lo + block]
            spectra = [np.fft.rfft(v[st] * window, axis=1) for v in views]
            for i in range(m):
                for j in range(i, m):
                    total[i, j] += np.einsum("wf,wf->f", spectra[i].conj(), spectra[j])
        count += starts.size
    if count == 0:
        return freqs, np.zeros((0, 0, freqs.size), dtype=np.complex128), 0
    scale = np.full(freqs.size, 2.0 / (fs * float(np.sum(window**2))))
    scale[0] /= 2.0
    if nper % 2 == 0:
        scale[-1] /= 2.0
    mean: NDArray[np.complex128] = total * (scale / count)
    for i in range(m):
        for j in range(i):
            mean[i, j] = np.conj(mean[j, i])
    return freqs, mean, count


def running_median(psd: ArrayLike, half_width: int = MEDIAN_HALF_WIDTH) -> FloatArray:
    """The median over ±``half_width`` bins of each bin (edges: nearest value repeated)."""
    # lazy: scipy only where a recording is filtered
    from scipy.ndimage import median_filter

    out: FloatArray = median_filter(np.asarray(psd, dtype=float), size=2 * half_width + 1,
                                    mode="nearest")
    return out


@dataclass(frozen=True, eq=False, repr=False)
class Line(Frozen):
    """One spectral line: frequency (Hz), per-axis amplitude and phase (deg, relative
    to the largest axis), and the bins of its lobe."""

    frequency: float
    amplitude: FloatArray
    phase: FloatArray
    lo: int
    hi: int


def find_lines(f: FloatArray, spectra: NDArray[np.complex128], threshold_db: float,
               fmin: float = 0.0) -> tuple[tuple[Line, ...], FloatArray]:
    """Spectral lines above the running median (docs/model.md section 13).

    A bin whose PSD exceeds the running median by ``threshold_db`` on any axis
    starts a line; its lobe is the peak ± :data:`LOBE_HALF_WIDTH` bins. Per
    axis, a = √(2·P) with P = Σ_lobe (S − median)·Δf (negative excess counts
    as 0); the frequency is the power-weighted centroid of the lobe on the
    largest axis; the phase of axis i is arg S_ref,i at the peak (the
    cross-spectrum with the largest axis ``ref``). Returns the lines and the
    per-axis running medians (m, F). Bins below ``fmin`` are not searched.
    """
    m = spectra.shape[0]
    psd = np.real(np.stack([spectra[i, i] for i in range(m)]))
    med = np.stack([running_median(p) for p in psd])
    df = float(f[1] - f[0])
    ratio = 10.0 ** (threshold_db / 10.0)
    hot = np.any(psd > ratio * np.maximum(med, np.finfo(float).tiny), axis=0)
    hot[f < fmin] = False
    hot[0] = hot[-1] = False
    lines: list[Line] = []
    taken = np.zeros(f.size, dtype=bool)
    excess = np.clip(psd - med, 0.0, None)
    order = np.argsort(-excess.max(axis=0))
    for peak in order.tolist():
        if not hot[peak] or taken[peak]:
            continue
        lo = max(1, peak - LOBE_HALF_WIDTH)
        hi = min(f.size - 1, peak + LOBE_HALF_WIDTH + 1)
        while lo < hi and taken[lo]:
            lo += 1
        while hi > lo and taken[hi - 1]:
            hi -= 1
        power = excess[:, lo:hi].sum(axis=1) * df
        ref = int(np.argmax(power))
        weights = excess[ref, lo:hi]
        freq = float(np.sum(weights * f[lo:hi]) / np.sum(weights))
        phase = np.rad2deg(np.angle(spectra[ref, :, peak]))
        phase[ref] = 0.0
        lines.append(Line(freq, np.sqrt(2.0 * power), np.mod(phase, 360.0), lo, hi))
        taken[lo:hi] = True
    lines.sort(key=lambda line: line.frequency)
    return tuple(lines), med


def harmonic_groups(frequencies: ArrayLike,
                    tolerance: float = HARMONIC_TOLERANCE) -> list[tuple[float, list[int],
                                                                         list[int]]]:
    """Lines that are integer multiples of a common fundamental (docs/model.md section 13),
    grouped only where the series is plausible.

    Ascending: each line not yet grouped is tried as a fundamental f0 (so the
    fundamental is always a line that was found); a later ungrouped line at f joins
    it as order n = round(f/f0) when

    * n ≥ 2, not yet taken, and n ≤ :data:`MAX_FITTED_ORDER` (a machine's low orders:
      a 180 Hz line is no "order 19" of a 9.39 Hz hull mode);
    * it lies within ``tolerance``·f of n·f0 and within :data:`ORDER_SPACING`·f0 of it
      (at high orders a relative tolerance spans much of the spacing between orders,
      and almost any line would be some order of any f0);
    * the series stays consistent: n is at most :data:`MAX_ORDER_GAP` above the highest
      order taken so far (orders 1, 2, 3, 5 are a series; 1 and 6 alone are not).

    Returns ``(f0, line indices, orders)`` for groups of two lines or more.
    """
    fr = np.asarray(frequencies, dtype=float)
    used = np.zeros(fr.size, dtype=bool)
    groups = []
    ascending = np.argsort(fr).tolist()
    for i in ascending:
        if used[i]:
            continue
        f0 = fr[i]
        members, orders = [i], [1]
        for j in ascending:
            if used[j] or j == i or fr[j] <= f0:
                continue
            n = round(fr[j] / f0)
            off = abs(fr[j] - n * f0)
            if (2 <= n <= min(MAX_FITTED_ORDER, max(orders) + MAX_ORDER_GAP)
                    and n not in orders and off <= tolerance * fr[j]
                    and off <= ORDER_SPACING * f0):
                members.append(j)
                orders.append(n)
        if len(members) > 1:
            used[members] = True
            groups.append((float(f0), members, orders))
    return groups


def affordable_groups(groups: Sequence[tuple[float, list[int], list[int]]],
                      strength: Sequence[float],
                      affordable: Callable[[int, int], bool],
                      ) -> tuple[list[tuple[float, list[int], list[int]]], list[int]]:
    """:func:`harmonic_groups` trimmed until a ``phase: worst`` search over all their
    orders is ``affordable(unknown phases, highest order)`` (a group of n orders, each
    ``phase: worst``, has n − 1 unknown relative phases): the weakest order above a
    fundamental (by ``strength``, per line) leaves its group first, and a group left with
    its fundamental alone is no group. Returns the groups kept and the lines let go (each
    then an independent tone), so that a profile fitted from a recording is always one
    the commands compute."""
    kept = [(f0, list(m), list(o)) for f0, m, o in groups]
    released: list[int] = []
    while kept and not affordable(sum(len(m) - 1 for _, m, _ in kept),
                                  max(max(o) for _, _, o in kept)):
        g, k = min(((g, k) for g, (_, m, o) in enumerate(kept) for k in range(len(m))
                    if o[k] != 1), key=lambda gk: strength[kept[gk[0]][1][gk[1]]])
        released.append(kept[g][1].pop(k))
        kept[g][2].pop(k)
        if len(kept[g][1]) < 2:
            released.extend(kept.pop(g)[1])
    return kept, sorted(released)


#: The objectives a fitted profile's ``phase: worst`` search is sized for: the analysis
#: (one) and the synthesis of ``bounds``/``select`` at the profile's own rate (four).
FITTED_OBJECTIVES = 5


def fitted_groups(frequencies: ArrayLike, strength: Sequence[float],
                  ) -> tuple[list[tuple[float, list[int], list[int]]], list[int]]:
    """The phase-locked groups a fitted profile writes (every order ``phase: worst``):
    :func:`harmonic_groups`, trimmed by :func:`affordable_groups` to a search within
    :data:`~gyrovib.core.phases.MAX_SEARCH_COST` for :data:`FITTED_OBJECTIVES`."""
    from gyrovib.core.phases import MAX_SEARCH_COST, search_cost

    return affordable_groups(
        harmonic_groups(frequencies), strength,
        lambda dims, n_max: search_cost(dims, FITTED_OBJECTIVES, n_max) <= MAX_SEARCH_COST)


def power_sums(x: ArrayLike, order: int = 4) -> FloatArray:
    """Per column, the sums Σx, Σx², …, Σx^order (shape (order, m)), a chunk at a time."""
    v = np.asarray(x, dtype=float)
    out = np.zeros((order, v.shape[1]))
    for lo in range(0, v.shape[0], _CHUNK):
        chunk = v[lo:lo + _CHUNK]
        power = chunk.copy()
        out[0] += power.sum(axis=0)
        for p in range(1, order):
            power *= chunk
            out[p] += power.sum(axis=0)
    return out


def central_moments(sums: ArrayLike, n: int) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Variance, skewness and excess kurtosis (population) from :func:`power_sums` of n
    samples; NaN where the variance is 0."""
    m1, m2, m3, m4 = (np.asarray(sums, dtype=float)[p] / n for p in range(4))
    var = m2 - m1**2
    c3 = m3 - 3 * m1 * m2 + 2 * m1**3
    c4 = m4 - 4 * m1 * m3 + 6 * m1**2 * m2 - 3 * m1**4
    with np.errstate(invalid="ignore", divide="ignore"):
        skew = np.where(var > 0, c3 / var**1.5, np.nan)
        kurt = np.where(var > 0, c4 / var**2 - 3.0, np.nan)
    return var, skew, kurt


def carrier_clusters(carrier: ArrayLike, bins: int = MISSION_BINS, iterations: int = 20,
                     ) -> tuple[FloatArray, FloatArray]:
    """The joint carrier Ω_K = (Ω_K1, Ω_K2, Ω_K3) of a recording in at most ``bins``
    groups: (mean rate (k, 3), sample count (k,)) of the groups that hold samples
    (docs/model.md section 13's fitted mission, on every axis).

    A histogram of Ω_K3 alone keeps the carrier of one axis; a sensor whose x3 lies on
    X or Y (a triad) sees Ω_K1 or Ω_K2. Here the samples are split into ``bins``
    equal-count slices along the carrier's principal direction (deterministic), then
    moved to their nearest group mean by Lloyd's iterations (k-means), so that each
    axis's spread is kept where the carrier spends its time. A constant axis stays
    constant. Distances are taken on each axis divided by its standard deviation (but
    by no less than a quarter of the largest axis's), so that a small yaw carrier
    counts about as much as a large roll (each sensor axis reads its own) while an axis
    that barely moves does not split the groups; the group means are in the rates as
    given.
    """
    c = np.asarray(carrier, dtype=float)
    if c.ndim != 2 or c.shape[1] != 3 or c.shape[0] == 0:
        raise ValueError("the carrier must be (samples, 3)")
    mean = c.mean(axis=0)
    spread = c - mean
    if not np.any(np.abs(spread) > 1e-9 * max(1.0, float(np.max(np.abs(c))))):
        return mean[None, :], np.array([float(c.shape[0])])
    std = np.maximum(spread.std(axis=0), 0.25 * float(np.max(spread.std(axis=0))))
    spread = spread / std
    step = max(1, c.shape[0] // 20_000)  # the centres from a subsample, the counts from all
    sample = spread[::step]
    _, _, vt = np.linalg.svd(sample, full_matrices=False)
    order = np.argsort(sample @ vt[0], kind="stable")
    k = min(bins, sample.shape[0])
    centres = np.stack([sample[part].mean(axis=0) for part in np.array_split(order, k)])
    for _ in range(iterations):
        label = _nearest(sample, centres)
        moved = np.stack([sample[label == j].mean(axis=0) if np.any(label == j)
                          else centres[j] for j in range(k)])
        if np.allclose(moved, centres, rtol=0.0, atol=1e-12):
            break
        centres = moved
    label = _nearest(spread, centres)
    counts = np.bincount(label, minlength=k).astype(float)
    sums = np.stack([np.bincount(label, weights=spread[:, j], minlength=k)
                     for j in range(3)], axis=1)
    keep = counts > 0
    rates: FloatArray = sums[keep] / counts[keep, None] * std + mean
    return rates, counts[keep]


def _nearest(points: FloatArray, centres: FloatArray) -> NDArray[np.intp]:
    """Index of the nearest centre of each point (squared distance), a chunk at a time."""
    out = np.empty(points.shape[0], dtype=np.intp)
    for lo in range(0, points.shape[0], _CHUNK // 16):
        part = points[lo:lo + _CHUNK // 16]
        # axis by axis, summed in the order np.sum takes three terms: the same distances
        # without a (points, centres, 3) temporary
        d = (part[:, 0, None] - centres[None, :, 0]) ** 2
        for j in range(1, points.shape[1]):
            d += (part[:, j, None] - centres[None, :, j]) ** 2
        out[lo:lo + part.shape[0]] = np.argmin(d, axis=1)
    return out
