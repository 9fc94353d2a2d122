"""Measured rectification: the run-up test (docs/model.md section 16).

The vehicle is held at rest while its vibration is stepped. Per step s (T_s seconds,
mid-time t̄_s) the mean ȳ_s of the raw rate about x3 obeys

    ȳ_s = c + d·t̄_s + Σ_j θ_j·φ_s,j + e_s                                   (16.1)

with c the constant true rate plus bias, d a linear drift, θ the in-situ coefficients
and φ_s,j their rectifying regressors measured on the step's own samples
(:func:`step_regressors`). e_s is the noise of a T_s-second mean, read from the
step's own overlapping Allan variance (:func:`mean_variance`, core/allan.py).
:func:`fit_steps` solves (16.1) by weighted least squares.

Pure numpy; rates in one rate unit (gyrovib passes deg/s), accelerations in g, time
in s, frequencies in Hz.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from gyrovib.core import allan
from gyrovib.core.transmissibility import FloatArray
from gyrovib.frozen import Frozen

#: The terms a run-up can estimate, in the order of :func:`step_regressors`' columns:
#: A1 (unit coefficient: ½(⟨|ω3|⟩ − |⟨Ω_K3⟩|), the ½ of eq. (2)), k2 ⟨x3²⟩, k4 ⟨x3⁴⟩,
#: m31 ⟨x1x3⟩, m32 ⟨x2x3⟩, G_jk ⟨a_j a_k⟩ − ⟨A_j⟩⟨A_k⟩, and vre = G11 = G22 = G33
#: (docs/model.md section 8: the datasheet VRE), whose regressor is Σ_j (⟨a_j²⟩ − ⟨A_j⟩²).
TERMS: tuple[str, ...] = ("A1", "k2", "k4", "m31", "m32", "vre",
                          "G11", "G22", "G33", "G12", "G13", "G23")
#: The pairs (j, k) of the G_jk terms, in TERMS order.
G_PAIRS: tuple[tuple[int, int], ...] = ((0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2))
#: The rate axes (x1 = 0, x2 = 1, x3 = 2) each angular term needs.
RATE_NEEDS: dict[str, tuple[int, ...]] = {"A1": (2,), "k2": (2,), "k4": (2,),
                                          "m31": (0, 2), "m32": (1, 2)}
#: A level change of this many dB (of the running variance of x3 or of a) starts a step.
STEP_THRESHOLD_DB = 3.0
#: Window levels more than this far below the loudest window are the floor (dB).
LEVEL_FLOOR_DB = 80.0
#: Steps shorter than this many windows are transitions, not steps.
MIN_WINDOWS = 4
#: A term whose variance inflation factor exceeds this is (near-)collinear with the others
#: or with time: not identifiable from these steps (R² of 0.99 against the rest).
VIF_LIMIT = 100.0
#: The drift is estimated only when its own variance inflation factor is below this
#: (R² of 0.9 of t̄ against the constant and the regressors): the steps' order separates it.
DRIFT_VIF_LIMIT = 10.0
#: Above this the design is singular: the term is not estimated at all.
SINGULAR_VIF = 1e8
#: A step moved when its angle excursion exceeds this many times the median step's (each
#: per √T, as a Brownian bridge grows): a turn stands out among steps that only shake.
MOVED_FACTOR = 10.0
#: A residual beyond this many standard deviations of its step's mean is flagged.
RESIDUAL_SIGMAS = 3.0


# ----------------------------------------------------------------- steps


def window_levels(x3: ArrayLike, window: int, accel_vibration: ArrayLike | None = None,
                  ) -> FloatArray:
    """Per window of ``window`` samples, the variance of x3 and (when given) of the
    linear vibration a − A summed over its axes, in dB: shape (windows, 1 or 2).
    Each column is floored :data:`LEVEL_FLOOR_DB` below its loudest window (and at
    1e-30): the split's rounding and filter tails in a silent stretch are not levels."""
    v = np.asarray(x3, dtype=float)
    count = v.size // window
    cols = [v[:count * window].reshape(count, window).var(axis=1)]
    if accel_vibration is not None:
        a = np.asarray(accel_vibration, dtype=float)
        blocks = a[:count * window].reshape(count, window, -1)
        cols.append(blocks.var(axis=1).sum(axis=1))
    var = np.column_stack(cols)
    floor = np.maximum(var.max(axis=0, initial=0.0) * 10.0 ** (-LEVEL_FLOOR_DB / 10.0), 1e-30)
    out: FloatArray = 10.0 * np.log10(np.maximum(var, floor))
    return out


def detect_steps(levels: ArrayLike, window: int, threshold_db: float = STEP_THRESHOLD_DB,
                 min_windows: int = MIN_WINDOWS) -> NDArray[np.intp]:
    """Steps of constant vibration from the window levels of :func:`window_levels`:
    (S, 2) start and stop sample indices.

    The levels are smoothed by a running median over 3 windows; a window whose level
    differs from the mean of the current run by more than ``threshold_db`` on any
    column starts a new run. Runs shorter than ``min_windows`` are transitions and
    dropped; each run loses its edge windows more than half the threshold off its median
    level (a ramp), and one window more at either inner end (the change itself), so a
    step is only samples at its settled level.
    """
    lv = np.asarray(levels, dtype=float)
    if lv.ndim == 1:
        lv = lv[:, None]
    count = lv.shape[0]
    if count == 0:
        return np.zeros((0, 2), dtype=np.intp)
    padded = np.concatenate([lv[:1], lv, lv[-1:]])
    smooth = np.median(np.stack([padded[:-2], padded[1:-1], padded[2:]]), axis=0)
    runs: list[list[int]] = [[0, 1]]
    total = smooth[0].copy()
    for w in range(1, count):
        start, stop = runs[-1]
        mean = total / (stop - start)
        if np.any(np.abs(smooth[w] - mean) > threshold_db):
            runs.append([w, w + 1])
            total = smooth[w].copy()
        else:
            runs[-1][1] = w + 1
            total += smooth[w]
    out = []
    for start, stop in runs:
        start, stop = _settled(smooth, start, stop, threshold_db / 2)
        if stop - start < min_windows:
            continue
        lo = start + (1 if start > 0 else 0)
        hi = stop - (1 if stop < count else 0)
        out.append((lo * window, hi * window))
    return np.array(out, dtype=np.intp).reshape(-1, 2)


def _settled(smooth: FloatArray, start: int, stop: int, tolerance: float) -> tuple[int, int]:
    """A run less its edge windows more than ``tolerance`` dB off the run's median level
    (a ramp from one level to the next that stayed within the threshold)."""
    median = np.median(smooth[start:stop], axis=0)
    off = np.any(np.abs(smooth[start:stop] - median) > tolerance, axis=1)
    while start < stop and off[0]:
        start, off = start + 1, off[1:]
    while stop > start and off[-1]:
        stop, off = stop - 1, off[:-1]
    return start, stop


# ----------------------------------------------------------------- regressors


def step_regressors(rate: ArrayLike, carrier: ArrayLike, accel: ArrayLike | None = None,
                    accel_low: ArrayLike | None = None) -> FloatArray:
    """The regressors φ_s of one step at unit coefficient (docs/model.md section 16), in
    :data:`TERMS` order.

    ``rate`` ω (n, 3) and ``carrier`` Ω_K = lowpass(ω) (n, 3) in one rate unit; ``accel``
    a and ``accel_low`` A = lowpass(a) (n, 3) in g, or None (the G terms and vre are
    then NaN). With x = ω − Ω_K::

        A1: ½(⟨|Ω_K3 + x3|⟩ − |⟨Ω_K3⟩|)     k2: ⟨x3²⟩     k4: ⟨x3⁴⟩
        m31: ⟨x1·x3⟩     m32: ⟨x2·x3⟩     G_jk: ⟨a_j·a_k⟩ − ⟨A_j⟩⟨A_k⟩
        vre: Σ_j (⟨a_j²⟩ − ⟨A_j⟩²)

    The ½ makes θ_A1 the A1 of eq. (2) (Δ0(1) = ½·k1·A1·E(Ω), docs/model.md section 4).
    """
    w = np.asarray(rate, dtype=float)
    c = np.asarray(carrier, dtype=float)
    x = w - c
    x3 = x[:, 2]
    x3sq = x3 * x3
    out = np.full(len(TERMS), np.nan)
    out[0] = 0.5 * (float(np.mean(np.abs(w[:, 2]))) - abs(float(np.mean(c[:, 2]))))
    out[1] = float(np.mean(x3sq))
    out[2] = float(np.mean(x3sq * x3sq))
    out[3] = float(np.mean(x[:, 0] * x3))
    out[4] = float(np.mean(x[:, 1] * x3))
    if accel is not None and accel_low is not None:
        a = np.asarray(accel, dtype=float)
        big = np.asarray(accel_low, dtype=float).mean(axis=0)
        for p, (j, k) in enumerate(G_PAIRS):
            out[6 + p] = float(np.mean(a[:, j] * a[:, k])) - big[j] * big[k]
        out[5] = out[6] + out[7] + out[8]
    return out


# ----------------------------------------------------------------- noise of a mean


def mean_variance(rate: ArrayLike, fs: float) -> float:
    """The variance of the mean of a step's rate over its T = n/fs seconds, from the
    step's own overlapping Allan variance (docs/model.md sections 15, 16).

    The rate less its least-squares line (the drift is (16.1)'s own term) gives σ²(τ)
    on cluster sizes from n/16 to n/4; each is carried to τ = T as white noise,
    σ²(τ)·τ/T — for white noise exactly the variance of a T-average, since
    σ²(τ) = N²/τ — and the largest is taken: flicker or random-walk noise, whose
    σ²(τ)·τ grows with τ, is then not under-read at the τ the estimate reaches.
    """
    y = np.asarray(rate, dtype=float)
    n = y.size
    if n < 4:
        return float(np.var(y)) / max(n, 1) if n > 1 else math.inf
    t = np.arange(n, dtype=float)
    slope, intercept = np.polyfit(t, y, 1)
    resid = y - (slope * t + intercept)
    lo, hi = max(1, n // 16), max(1, n // 4)
    m = np.unique(np.round(np.geomspace(lo, hi, 5)).astype(np.int64))
    tau0 = 1.0 / fs
    tau, adev = allan.oadev(resid, tau0, m)
    return float(np.max(adev**2 * tau)) / (n * tau0)


def angle_excursion(carrier: ArrayLike, fs: float) -> FloatArray:
    """Per column, the largest |θ(t)| of θ = ∫ (Ω_K − its least-squares line) dt over the
    step (deg for deg/s): how far the vehicle turned and came back within the step. A
    steady offset (rectification) and a linear drift of the rate leave it at the noise's
    Brownian bridge, of the order N·√T/2; a roll of 10° and back, at 10°."""
    c = np.asarray(carrier, dtype=float)
    c = c.reshape(c.shape[0], -1)
    n = c.shape[0]
    if n < 3:
        return np.zeros(c.shape[1])
    t = np.arange(n, dtype=float)
    fit = np.polynomial.polynomial.polyfit(t, c, 1)
    resid = c - (fit[0] + np.outer(t, fit[1]))
    out: FloatArray = np.abs(np.cumsum(resid, axis=0)).max(axis=0) / fs
    return out


# ----------------------------------------------------------------- the fit


@dataclass(frozen=True, eq=False, repr=False)
class StepFit(Frozen):
    """The weighted least squares of (16.1).

    ``values``/``sigma`` (P,): θ_j and their standard uncertainties (inflated by the
    reduced χ² when it exceeds 1; NaN where the design cannot estimate the term at
    all); ``covariance`` (P, P) likewise; ``constant`` c and ``drift`` d (NaN when not
    estimated) with ``drift_sigma``; ``fitted`` (S,) ŷ_s; ``residuals`` (S,) ȳ_s − ŷ_s;
    ``chi2`` Σ r²/var, ``dof`` S − unknowns, ``inflation`` max(1, χ²/dof) (1 with no
    degree of freedom); ``vif`` (P,) each term's variance inflation factor against the
    constant, the drift and the other terms; ``partner`` (P,): the column it is most
    collinear with (−1 time, −2 too few steps, −3 the same on every step, index of another
    term, or P for none);
    ``drift_vif``: the drift's own factor (whether the steps' order separates it).
    """

    values: FloatArray
    sigma: FloatArray
    covariance: FloatArray
    constant: float
    drift: float
    drift_sigma: float
    fitted: FloatArray
    residuals: FloatArray
    chi2: float
    dof: int
    inflation: float
    vif: FloatArray
    partner: NDArray[np.intp]
    drift_vif: float

    @property
    def identifiable(self) -> NDArray[np.bool_]:
        """Separable by these steps (VIF ≤ :data:`VIF_LIMIT`) and its uncertainty below its
        value (docs/model.md section 16)."""
        ok: NDArray[np.bool_] = (np.isfinite(self.values) & (self.vif <= VIF_LIMIT)
                                 & (self.sigma < np.abs(self.values)))
        return ok

    @property
    def separable(self) -> NDArray[np.bool_]:
        """The design separates the term from the others and from time."""
        ok: NDArray[np.bool_] = np.isfinite(self.values) & (self.vif <= VIF_LIMIT)
        return ok


def _vif(x: FloatArray, w: FloatArray, j: int) -> tuple[float, int]:
    """Variance inflation factor of weighted column j against the other columns of x
    (column 0 the constant), and the other column (≥ 1) most correlated with it."""
    sw = np.sqrt(w)
    target = x[:, j] * sw
    others = [k for k in range(x.shape[1]) if k != j]
    basis = x[:, others] * sw[:, None]
    coef, *_ = np.linalg.lstsq(basis, target, rcond=None)
    resid = target - basis @ coef
    mean = np.sum(w * x[:, j]) / np.sum(w)
    spread = float(np.sum(w * (x[:, j] - mean) ** 2))
    rss = float(resid @ resid)
    vif = math.inf if rss <= 1e-24 * max(spread, 1e-300) else max(1.0, spread / rss)
    best, partner = -1.0, -1
    for k in others:
        if k == 0:
            continue
        mk = np.sum(w * x[:, k]) / np.sum(w)
        num = np.sum(w * (x[:, j] - mean) * (x[:, k] - mk))
        den = math.sqrt(spread * float(np.sum(w * (x[:, k] - mk) ** 2)))
        r = abs(float(num) / den) if den > 0 else 1.0
        if r > best:
            best, partner = r, k
    return vif, partner


def _design(phi: FloatArray, t: FloatArray, drift: bool) -> FloatArray:
    cols = [np.ones(phi.shape[0])]
    if drift:
        cols.append(t - float(np.mean(t)))
    return np.column_stack([*cols, phi])


def drift_separable(phi: ArrayLike, t: ArrayLike, var: ArrayLike) -> tuple[bool, float]:
    """Whether the steps' order separates a drift from the regressors: the VIF of t̄
    against the constant and φ is at most :data:`DRIFT_VIF_LIMIT`, and a degree of
    freedom remains; with the VIF."""
    p = np.asarray(phi, dtype=float)
    w = 1.0 / np.asarray(var, dtype=float)
    x = _design(p, np.asarray(t, dtype=float), True)
    if p.shape[0] <= x.shape[1]:
        return False, math.inf
    vif, _ = _vif(x, w, 1)
    return vif <= DRIFT_VIF_LIMIT, vif


def fit_steps(y: ArrayLike, t: ArrayLike, phi: ArrayLike, var: ArrayLike,
              drift: bool | None = None) -> StepFit:
    """Weighted least squares of (16.1) over the steps (docs/model.md section 16).

    ``y`` (S,) step means, ``t`` (S,) mid-times (s), ``phi`` (S, P) regressors, ``var``
    (S,) variances of the means; ``drift`` None decides by :func:`drift_separable`.
    Weights 1/var; covariance (XᵀWX)⁻¹ times max(1, χ²/(S − unknowns)). A term whose
    VIF exceeds :data:`SINGULAR_VIF` is left out of the fit (value NaN); the others are
    estimated jointly.
    """
    ys, ts = np.asarray(y, dtype=float), np.asarray(t, dtype=float)
    p = np.asarray(phi, dtype=float).reshape(ys.size, -1)
    v = np.asarray(var, dtype=float)
    w = 1.0 / v
    n_terms = p.shape[1]
    drift_vif = drift_separable(p, ts, v)[1]
    use_drift = drift_vif <= DRIFT_VIF_LIMIT if drift is None else drift
    offset = 2 if use_drift else 1
    x = _design(p, ts, use_drift)
    vif, partner = _term_vifs(x, w, n_terms, offset, ys.size)
    keep = [k for k in range(x.shape[1]) if k < offset or vif[k - offset] <= SINGULAR_VIF]
    xk = x[:, keep]
    sw = np.sqrt(w)
    # columns scaled to unit weighted norm: the regressors span many decades (⟨x3⁴⟩
    # against ½⟨|x3|⟩), and the normal matrix squares their condition number
    scale = np.sqrt(np.sum((xk * sw[:, None]) ** 2, axis=0))
    scale[scale == 0] = 1.0
    xs = xk / scale
    cov_s = np.linalg.pinv((xs * w[:, None]).T @ xs)
    cov_k = cov_s / np.outer(scale, scale)
    beta_k = (cov_s @ (xs.T @ (w * ys))) / scale
    fitted = xk @ beta_k
    resid = ys - fitted
    chi2 = float(np.sum((resid * sw) ** 2))
    dof = ys.size - len(keep)
    inflation = max(1.0, chi2 / dof) if dof > 0 else 1.0
    cov = np.full((x.shape[1], x.shape[1]), np.nan)
    cov[np.ix_(keep, keep)] = cov_k * inflation
    beta = np.full(x.shape[1], np.nan)
    beta[keep] = beta_k
    sigma = np.sqrt(np.diag(cov))
    return StepFit(
        values=beta[offset:], sigma=sigma[offset:], covariance=cov[offset:, offset:],
        constant=float(beta[0] - (beta[1] * np.mean(ts) if use_drift else 0.0)),
        drift=float(beta[1]) if use_drift else math.nan,
        drift_sigma=float(sigma[1]) if use_drift else math.nan,
        fitted=fitted, residuals=resid, chi2=chi2, dof=dof, inflation=inflation,
        vif=vif, partner=partner, drift_vif=drift_vif)


def _term_vifs(x: FloatArray, w: FloatArray, n_terms: int, offset: int,
               steps: int) -> tuple[FloatArray, NDArray[np.intp]]:
    """VIF and most-collinear partner of each term (partner codes of :class:`StepFit`)."""
    vif = np.full(n_terms, math.inf)
    partner = np.full(n_terms, n_terms, dtype=np.intp)
    if steps <= x.shape[1]:
        partner[:] = -2
    for j in range(n_terms):
        col = offset + j
        if steps < 2 or float(np.ptp(x[:, col])) == 0.0:
            partner[j] = -2 if steps < 2 else -3
            continue
        value, other = _vif(x, w, col)
        vif[j] = value
        if partner[j] != -2 and value > VIF_LIMIT:
            partner[j] = -1 if (offset == 2 and other == 1) else other - offset
    return vif, partner


def flagged_residuals(residuals: ArrayLike, var: ArrayLike,
                      sigmas: float = RESIDUAL_SIGMAS) -> NDArray[np.bool_]:
    """Steps whose residual exceeds ``sigmas`` standard deviations of their mean."""
    r = np.asarray(residuals, dtype=float)
    out: NDArray[np.bool_] = np.abs(r) > sigmas * np.sqrt(np.asarray(var, dtype=float))
    return out


__all__ = ["DRIFT_VIF_LIMIT", "G_PAIRS", "MIN_WINDOWS", "MOVED_FACTOR", "RATE_NEEDS",
           "RESIDUAL_SIGMAS", "STEP_THRESHOLD_DB", "TERMS", "VIF_LIMIT", "StepFit",
           "angle_excursion", "detect_steps", "drift_separable", "fit_steps",
           "flagged_residuals", "mean_variance", "step_regressors", "window_levels"]
