"""Equivalent degrees of freedom of the overlapping Allan variance and the χ² confidence
interval of each σ̂(τ) (docs/model.md section 15).

C. A. Greenhall and W. J. Riley, "Uncertainty of stability variances based on finite
differences" (2003), as NIST SP 1065 section 5.3 tabulates and allantools'
``edf_greenhall`` computes; here only the case this package needs: the unmodified,
overlapping Allan variance (second difference d = 2, filter factor F = m, stride S = m).

The noise type is the power-law exponent α of the rate's spectrum, S_y(f) ∝ f^α: +2
white angle noise (quantization), 0 white rate noise (N), −1 flicker (B), −2 random walk
(K). With N_x = n + 1 angle points and cluster size m, the estimator averages
M = N_x − 2m squared second differences; J = min(M, 3m) lags of their correlation count.
Writing the generalised autocovariance of the noise as

    s_w(t) = −|t| (α = 2),  t² ln|t| (1),  |t|³ (0),  t⁴ ln|t| (−1),  |t|⁵ (−2)
    s_x(t) = F²·(2 s_w(t) − s_w(t − 1/F) − s_w(t + 1/F))     (s_w of α + 2 when F = ∞)
    s_z(t) = 6 s_x(t) − 4 s_x(t ± 1) + s_x(t ± 2)            (both signs summed)

the EDF is  ν = s_z(0)²·M / Σ,  Σ = s_z(0)² + (1 − J/M)·s_z(J/S)²
+ 2·Σ_{j<J} (1 − j/M)·s_z(j/S)²  when J ≤ 100, and otherwise the paper's large-M
forms 1/ν = (a0 − a1/r)/r (r = M/S) with its table of (a0, a1).

Confidence limits of σ² at level c: σ̂²·ν/χ²_ν(1 − (1 − c)/2) … σ̂²·ν/χ²_ν((1 − c)/2).
"""

from __future__ import annotations

import functools
import math

import numpy as np
from numpy.typing import NDArray

from gyrovib.core._types import FloatArray

#: Noise types by α (S_y ∝ f^α).
WHITE_ANGLE, FLICKER_ANGLE, WHITE, FLICKER, RANDOM_WALK = 2, 1, 0, -1, -2
#: Lags summed directly at most (the paper's J_max).
J_MAX = 100
#: Large-M coefficients (a0, a1) of 1/ν = (a0 − a1/r)/r for the Allan variance (d = 2),
#: Greenhall & Riley's table 2, by α.
_LARGE_M = {2: (35.0 / 18.0, 1.0), 1: (790.0, 410.0), 0: (2.0 / 3.0, 1.0 / 3.0),
            -1: (0.852, 0.375), -2: (1.079, 0.368)}
#: Flicker angle noise (α = 1) scales its large-M form by 1/(b0 + b1·ln m)² (table 3).
_FLICKER_ANGLE_LOG = (15.23, 12.0)


def _sw(t: FloatArray, alpha: int) -> FloatArray:
    a = np.abs(t)
    if alpha % 2 == 0:  # the even exponents: |t|^(3 − α), with the sign of α = 2's −|t|
        power = 3 - alpha
        return -a if alpha == 2 else a ** power
    with np.errstate(divide="ignore", invalid="ignore"):
        logs = np.where(a > 0, np.log(np.where(a > 0, a, 1.0)), 0.0)
    return a ** (3 - alpha) * logs


def _sx(t: FloatArray, f: float, alpha: int) -> FloatArray:
    if math.isinf(f):
        return _sw(t, alpha + 2)
    step = 1.0 / f
    return f * f * (2.0 * _sw(t, alpha) - _sw(t - step, alpha) - _sw(t + step, alpha))


def _sz(t: FloatArray, f: float, alpha: int) -> FloatArray:
    return (6.0 * _sx(t, f, alpha) - 4.0 * (_sx(t - 1.0, f, alpha) + _sx(t + 1.0, f, alpha))
            + _sx(t - 2.0, f, alpha) + _sx(t + 2.0, f, alpha))


def _basic_sum(lags: int, big_m: float, stride: float, f: float, alpha: int) -> float:
    j = np.arange(1, lags, dtype=float)
    z0 = float(_sz(np.zeros(1), f, alpha)[0])
    zj = float(_sz(np.array([lags / stride]), f, alpha)[0])
    inner = _sz(j / stride, f, alpha)
    return (z0 * z0 + (1.0 - lags / big_m) * zj * zj
            + 2.0 * float(np.sum((1.0 - j / big_m) * inner * inner)))


def _direct(lags: int, big_m: float, stride: float, f: float, alpha: int) -> float:
    z0 = float(_sz(np.zeros(1), f, alpha)[0])
    return z0 * z0 * big_m / _basic_sum(lags, big_m, stride, f, alpha)


@functools.lru_cache(maxsize=4096)
def edf_one(alpha: int, m: int, points: int) -> float:
    """ν of the overlapping Allan variance at cluster size ``m`` from ``points`` angle
    points (n + 1), noise type ``alpha`` (2, 1, 0, −1 or −2); at least 1. Remembered:
    the bootstrap refits many curves of one record, whose (α, m) pairs repeat."""
    big_m = float(points - 2 * m)
    if big_m < 1:
        raise ValueError(f"cluster size {m} needs at least {2 * m + 1} angle points")
    lags = int(min(big_m, 3 * m))
    r = big_m / m
    if alpha == WHITE_ANGLE:
        a0, a1 = _LARGE_M[2]
        nu = big_m / (a0 - a1 / r) if r > 2.0 else big_m / a0
    elif lags <= J_MAX:
        f = float(m) if (alpha == FLICKER_ANGLE or 3 * m <= J_MAX) else math.inf
        nu = _direct(lags, big_m, float(m), f, alpha)
    elif r > 3.0:
        a0, a1 = _LARGE_M[alpha]
        inv = (a0 - a1 / r) / r
        if alpha == FLICKER_ANGLE:
            b0, b1 = _FLICKER_ANGLE_LOG
            inv /= (b0 + b1 * math.log(m)) ** 2
        nu = 1.0 / inv
    else:
        f = J_MAX / r if alpha == FLICKER_ANGLE else math.inf
        nu = _direct(J_MAX, float(J_MAX), J_MAX / r, f, alpha)
        if alpha == FLICKER_ANGLE:
            b0, b1 = _FLICKER_ANGLE_LOG
            z0 = float(_sz(np.zeros(1), f, alpha)[0])
            nu *= (b0 + b1 * math.log(m)) ** 2 / (z0 * z0)
    return max(float(nu), 1.0)


def edf(alpha: NDArray[np.int64], m: NDArray[np.int64], points: int) -> FloatArray:
    """:func:`edf_one` per point (``alpha`` and ``m`` of equal length)."""
    return np.array([edf_one(int(a), int(mm), points)
                     for a, mm in zip(np.asarray(alpha).tolist(), np.asarray(m).tolist(),
                                      strict=True)], dtype=float)


def chi2_limits(nu: FloatArray, confidence: float) -> tuple[FloatArray, FloatArray]:
    """The factors ν/χ²_ν(1 − (1 − c)/2) and ν/χ²_ν((1 − c)/2) that turn σ̂² into the
    lower and upper limits of σ² at confidence ``c``."""
    # lazy: scipy only where an Allan deviation gets its intervals
    from scipy.stats import chi2

    tail = (1.0 - confidence) / 2.0
    nu = np.asarray(nu, dtype=float)
    return nu / chi2.ppf(1.0 - tail, nu), nu / chi2.ppf(tail, nu)


def confidence_interval(adev: FloatArray, nu: FloatArray, confidence: float
                        ) -> tuple[FloatArray, FloatArray]:
    """σ's limits at ``confidence`` from σ̂ and its EDF ν (χ² with ν degrees of freedom)."""
    lo, hi = chi2_limits(nu, confidence)
    return adev * np.sqrt(lo), adev * np.sqrt(hi)


__all__ = ["FLICKER", "RANDOM_WALK", "WHITE", "WHITE_ANGLE", "chi2_limits",
           "confidence_interval", "edf", "edf_one"]
