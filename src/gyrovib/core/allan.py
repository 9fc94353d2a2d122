"""The overlapping Allan deviation of a rate record and the noise terms read from it
(docs/model.md section 15; IEEE Std 952-1997 Annex C, allantools' ``oadev``).

With rate samples y_i at interval τ0, the angle x_k = τ0·Σ_{i<k} y_i (x_0 = 0),
cluster size m and τ = m·τ0::

    σ²(τ) = Σ_k (x_{k+2m} − 2x_{k+m} + x_k)² / (2τ²(n + 1 − 2m))    (k = 0 … n − 2m)

Each τ costs O(n) from the cumulative sum, summed a block of k at a time, so the
memory is the angle array plus a few blocks. A constant offset of y does not
change σ (its ramp has no second difference); the mean is removed before the sum
so that the angle stays small and the differences keep their digits.

The noise model (rate in deg/s, τ in s)::

    σ²(τ) = N²/τ + (2 ln 2/π)·B² + K²·τ/3

is fitted by weighted least squares, each point weighted by the variance of its
estimate, 2σ⁴/ν with ν its equivalent degrees of freedom (Stein's approximations,
as allantools' ``edf_simple``, for the noise type that dominates the fitted model
there), coefficients kept non-negative. The fit only says which term dominates
where; the figures are read from the curve itself:

* N: on the slope −½ line through one point of the curve, N = σ(τ)·√τ (its value
  at τ = 1 s), at the point where its uncertainty is least: the statistical part
  N/√(2ν) and the share of the other fitted terms at that point, N·(1 − √share),
  added in quadrature;
* K: likewise on the slope +½ line, K = σ(τ)·√(3/τ) (its value at τ = 3 s);
* B = σ_min/√(2 ln 2/π) = σ_min/0.664 at the curve's minimum, uncertainty
  B/√(2ν) there (flicker noise's ν).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from gyrovib.core._types import FloatArray

IntArray = NDArray[np.int64]

#: k values summed at once: the working memory is a few blocks of this many floats
#: (64 KiB each, in a core's cache). Below OpenBLAS's threading threshold of its dot
#: product, too: with larger blocks it starts threads for every block, which cost
#: 15× the CPU time on a busy machine (docs/performance.md).
BLOCK = 1 << 13
#: √(2 ln 2/π): the flat floor of the Allan deviation of flicker noise per unit B.
FLICKER_FLOOR = math.sqrt(2.0 * math.log(2.0) / math.pi)
#: B = σ_min / 0.664 (the rounded constant the datasheets use).
B_FACTOR = 0.664
#: Points of the τ grid per decade (fewer where there are not as many cluster sizes).
PER_DECADE = 10
#: Noise types, by the power-law exponent α of the rate's PSD (S_y ∝ f^α).
WHITE, FLICKER, RANDOM_WALK = 0, -1, -2


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


def edf(points: int, m: FloatArray, alpha: NDArray[np.int64]) -> FloatArray:
    """Equivalent degrees of freedom of the overlapping Allan variance at cluster sizes
    ``m`` from ``points`` phase points (n + 1), noise type α per point (Stein's
    approximations: white, flicker and random-walk frequency noise), at least 1."""
    big = float(points)
    mm = np.asarray(m, dtype=float)
    white = (3.0 * (big - 1.0) / (2.0 * mm) - 2.0 * (big - 2.0) / big) \
        * 4.0 * mm ** 2 / (4.0 * mm ** 2 + 5.0)
    flicker = np.where(mm == 1, 2.0 * (big - 2.0) / (2.3 * big - 4.9),
                       5.0 * big ** 2 / (4.0 * mm * (big + 3.0 * mm)))
    walk = ((big - 2.0) / mm * ((big - 1.0) ** 2 - 3.0 * mm * (big - 1.0) + 4.0 * mm ** 2)
            / (big - 3.0) ** 2)
    a = np.asarray(alpha)
    nu = np.where(a == WHITE, white, np.where(a == FLICKER, flicker, walk))
    return np.maximum(nu, 1.0)


def _design(tau: FloatArray) -> FloatArray:
    return np.stack([1.0 / tau, np.full_like(tau, FLICKER_FLOOR ** 2), tau / 3.0], axis=1)


def _nnls3(a: FloatArray, b: FloatArray) -> FloatArray:
    """Non-negative least squares of three unknowns: the best of the subsets whose
    unconstrained solution is non-negative."""
    best, best_cost = np.zeros(3), float(np.dot(b, b))
    for mask in range(1, 8):
        cols = [i for i in range(3) if mask >> i & 1]
        sol, *_ = np.linalg.lstsq(a[:, cols], b, rcond=None)
        if np.any(sol < 0):
            continue
        r = a[:, cols] @ sol - b
        cost = float(np.dot(r, r))
        if cost < best_cost:
            best_cost, best = cost, np.zeros(3)
            best[cols] = sol
    return best


def dominant(terms: FloatArray) -> NDArray[np.int64]:
    """The noise type α of the largest of the (N², B-floor, K²) terms per point."""
    kinds = np.array([WHITE, FLICKER, RANDOM_WALK], dtype=np.int64)
    out: NDArray[np.int64] = kinds[np.argmax(terms, axis=1)]
    return out


def fit_terms(tau: FloatArray, adev: FloatArray, points: int,
              m: FloatArray) -> tuple[FloatArray, FloatArray]:
    """(N², B², K²) of σ²(τ) = N²/τ + (2 ln 2/π)B² + K²τ/3 by weighted non-negative least
    squares (weights ν/(2·model²), the model refined three times from the unweighted
    start), and the EDF of each point under the fitted model."""
    design = _design(tau)
    var = adev ** 2
    if not np.any(var > 0):  # a record without noise (constant, or quantised flat)
        return np.zeros(3), edf(points, m, np.full(m.shape, WHITE))
    var = np.maximum(var, var.max() * 1e-30)  # an exact 0 of σ would weigh infinitely
    coef = _nnls3(design / var[:, None], np.ones_like(var))
    nu = np.ones_like(var)
    for _ in range(3):
        model = design @ coef
        model = np.where(model > 0, model, var)
        alpha = dominant(design * coef)
        nu = edf(points, m, alpha)
        w = np.sqrt(nu / 2.0) / model
        coef = _nnls3(design * w[:, None], var * w)
    return coef, nu


@dataclass(frozen=True, slots=True)
class Read:
    """One figure read on its slope line: value, standard uncertainty, the τ read at
    (s), and the share of the model's σ² its own term has there."""

    value: float
    uncertainty: float
    tau: float
    share: float


@dataclass(frozen=True, slots=True)
class NoiseTerms:
    """N (rate·√s), B (rate), K (rate/√s) with their reads, the fitted model's
    coefficients (N², B², K²) and the EDF of each point."""

    arw: Read
    bias_instability: Read
    rrw: Read
    fitted: FloatArray
    edf: FloatArray


def _slope_read(adev: FloatArray, tau: FloatArray, scale: FloatArray, share: FloatArray,
                nu: FloatArray) -> Read:
    """The read on a ±½ slope line with the least uncertainty (statistical and the
    other terms' share, in quadrature); where the term is absent from the fit (share 0
    everywhere) that is the smallest read, an upper bound."""
    value = adev * scale
    share = np.clip(share, 0.0, 1.0)
    u = value * np.hypot(1.0 / np.sqrt(2.0 * nu), 1.0 - np.sqrt(share))
    best = int(np.argmin(u))
    return Read(float(value[best]), float(u[best]), float(tau[best]), float(share[best]))


def noise_terms(tau: FloatArray, adev: FloatArray, points: int, tau0: float) -> NoiseTerms:
    """N, B and K of an Allan deviation curve (see the module docstring); ``points`` =
    n + 1 of the record."""
    m = np.round(tau / tau0)
    coef, nu = fit_terms(tau, adev, points, m)
    design = _design(tau)
    parts = design * coef
    model = parts.sum(axis=1, keepdims=True)
    model = np.where(model > 0, model, adev[:, None] ** 2)
    share = np.divide(parts, model, out=np.zeros_like(parts), where=model > 0)
    arw = _slope_read(adev, tau, np.sqrt(tau), share[:, 0],
                      edf(points, m, np.full(m.shape, WHITE)))
    rrw = _slope_read(adev, tau, np.sqrt(3.0 / tau), share[:, 2],
                      edf(points, m, np.full(m.shape, RANDOM_WALK)))
    low = int(np.argmin(adev))
    nu_low = float(edf(points, m[low:low + 1], np.array([FLICKER]))[0])
    b = float(adev[low]) / B_FACTOR
    bias = Read(b, b / math.sqrt(2.0 * nu_low), float(tau[low]), float(share[low, 1]))
    return NoiseTerms(arw, bias, rrw, coef, nu)


__all__ = ["B_FACTOR", "FLICKER_FLOOR", "NoiseTerms", "Read", "angle", "dominant", "edf",
           "fit_terms", "noise_terms", "oadev", "oadev_from_angle", "tau_grid"]
