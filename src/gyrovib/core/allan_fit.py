"""The noise model fitted to an Allan variance curve, each term with an honest interval
or an upper bound (docs/model.md section 15, fifth round; IEEE Std 952-1997 Annex C).

Rate in deg/s, τ in s, the model is linear in its non-negative coefficients::

    σ²(τ) = 3Q²/τ² + N²/τ + (2 ln 2/π)·B² + K²·τ/3 + R²·τ²/2  [+ σ_GM²·g(τ/τ_c)]

with g the Allan variance of a unit first-order Gauss–Markov process of correlation time
τ_c, g = (2/x)·(1 − (3 − 4e^{−x} + e^{−2x})/(2x)), x = τ/τ_c (→ 2x/3 for x → 0: a rate
random walk; → 2/x for x → ∞: white noise).

**Fit.** Non-negative weighted least squares on all σ̂²(τ) (``scipy.optimize.nnls``), each
point weighted by the inverse variance of its estimate, ν/(2·model²), ν its equivalent
degrees of freedom (:mod:`gyrovib.core.allan_edf`) for the noise type that dominates the
fitted model there; refined three times from an unweighted start. The Gauss–Markov term
is tried on a grid of τ_c only where the five terms leave a weighted misfit of more than
:data:`MISFIT` per point, and kept where it more than halves it (a curve that bends the
way the five terms cannot).

**Intervals: a parametric bootstrap.** Records of the fitted model, as long as the
record (beyond :data:`SIM_CAP` samples: see :func:`_replicate_curves`), are
simulated (:mod:`gyrovib.core.allan_sim`), their Allan variance taken at the same τ and
refitted with the same weights: so each replicate carries the correlation between
neighbouring τ and every other term's pull on the term, which a formula per point does
not. A term θ (the square root of its coefficient) gets the pivot interval
θ̂/q_{(1+c)/2} … θ̂/q_{(1−c)/2}, q the quantiles of the replicates' θ*/θ̂ (a scale
family's interval: exact when the estimate's law scales with the truth).

**Roll-off.** A sensor's low-pass filter flattens the curve below a few times its time
constant: read there, N would come out too small. A leading stretch flatter than white
noise and below the −½ line of the first white point (:func:`roll_off`) is left out of
the fit (and said), and past it the filter's tail, σ² lowered by about c/τ², takes the
place of quantization in the fit (a non-negative c of −1/τ²; quantization behind a
filter is then only bounded).

**Bounds.** A term is *unresolved* when it is absent from the fit, when 2.5 % or more of
the replicates fit it at 0 (its 95 % interval reaches 0), or when it dominates the model
(half its σ²) at no τ of the record (its slope region is absent). It is then given as an
upper bound at 95 %: the least, over τ, of the one-sided χ² upper limit of σ²(τ)
divided by the term's basis function — each point alone caps the term, since the other
terms are non-negative — each limit at 1 − 5 %/P for the P points, so that the least of
them still holds at 95 % (the first study, with 95 % per point, saw such bounds of K
hold in only 6 of 11 records).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from gyrovib.core import allan_edf as edfs
from gyrovib.core.allan import oadev
from gyrovib.core.allan_sim import Truth, simulate

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

#: The five terms, in the model's order.
TERMS = ("quantization", "arw", "bias_instability", "rrw", "rate_ramp")
#: √(2 ln 2/π): the flat floor of the Allan deviation of flicker noise per unit B.
FLICKER_FLOOR = math.sqrt(2.0 * math.log(2.0) / math.pi)
#: Noise type (α) of each term where it dominates.
_ALPHA = (edfs.WHITE_ANGLE, edfs.WHITE, edfs.FLICKER, edfs.RANDOM_WALK, edfs.RANDOM_WALK)
#: Replicates of the parametric bootstrap.
REPLICATES = 200
#: Longest record the bootstrap simulates at the record's own interval.
SIM_CAP = 1 << 15
#: Weighted misfit per point above which the five terms are said not to fit (and a
#: Gauss–Markov term is tried): twice what a fitting model leaves on average.
MISFIT = 2.0
#: Confidence of a bound; share of the model a term must reach somewhere to be resolved.
BOUND_CONFIDENCE, RESOLVED_SHARE = 0.95, 0.5


def gm_basis(tau: FloatArray, tau_c: float) -> FloatArray:
    """g(τ/τ_c): the Allan variance of a unit-variance first-order Gauss–Markov process."""
    x = np.asarray(tau, dtype=float) / tau_c
    small = x < 1e-4
    xs = np.where(small, 1.0, x)
    u = np.expm1(-xs)
    full = (2.0 / xs) * (1.0 - (u * u - 2.0 * u) / (2.0 * xs))
    out: FloatArray = np.where(small, 2.0 * x / 3.0 - x * x / 2.0, full)
    return out


def design(tau: FloatArray, tau_c: float | None = None, filtered: bool = False) -> FloatArray:
    """The basis functions per τ (columns in :data:`TERMS` order, then g if τ_c); for a
    ``filtered`` curve the first column is a filter's −1/τ² instead of quantization's."""
    t = np.asarray(tau, dtype=float)
    cols = [(-1.0 if filtered else 3.0) / t ** 2, 1.0 / t, np.full_like(t, FLICKER_FLOOR ** 2),
            t / 3.0, t * t / 2.0]
    if tau_c is not None:
        cols.append(gm_basis(t, tau_c))
    return np.stack(cols, axis=1)


def nnls(a: FloatArray, b: FloatArray) -> FloatArray:
    """min ‖a·c − b‖ over c ≥ 0, columns scaled to unit norm for the solver."""
    # lazy: scipy only where a curve is fitted
    from scipy.optimize import nnls as solve

    norms = np.linalg.norm(a, axis=0)
    norms = np.where(norms > 0, norms, 1.0)
    c, _ = solve(a / norms, b, maxiter=50 * a.shape[1])
    out: FloatArray = c / norms
    return out


def dominant_alpha(parts: FloatArray, tau: FloatArray, tau_c: float | None) -> IntArray:
    """The noise type α of the largest part of the model per point (a Gauss–Markov part
    counts as a random walk below τ_c and as white noise above)."""
    kinds = list(_ALPHA)
    alpha: IntArray = np.array(kinds, dtype=np.int64)[np.argmax(parts[:, :5], axis=1)]
    if tau_c is not None and parts.shape[1] > 5:
        gm_wins = parts[:, 5] > parts[:, :5].max(axis=1)
        gm_alpha = np.where(tau < tau_c, edfs.RANDOM_WALK, edfs.WHITE)
        alpha = np.where(gm_wins, gm_alpha, alpha).astype(np.int64)
    return alpha


@dataclass(frozen=True, slots=True)
class Fit:
    """Coefficients (Q², N², B², K², R² [, σ_GM²]) in the kernel's units, τ_c (None: no
    Gauss–Markov term), each point's EDF and weight, and the weighted misfit."""

    coef: FloatArray
    tau_c: float | None
    nu: FloatArray
    weight: FloatArray
    cost: float
    filtered: bool = False

    def design(self, tau: FloatArray) -> FloatArray:
        """The fit's basis functions at ``tau``."""
        return design(tau, self.tau_c, self.filtered)

    def model(self, tau: FloatArray) -> FloatArray:
        """The fitted σ²(τ)."""
        out: FloatArray = self.design(tau) @ self.coef
        return out


def _weighted(a: FloatArray, var: FloatArray, weight: FloatArray) -> tuple[FloatArray, float]:
    w = np.sqrt(weight)
    coef = nnls(a * w[:, None], var * w)
    r = (a @ coef - var) * w
    return coef, float(r @ r)


def _refine(tau: FloatArray, var: FloatArray, m: IntArray, points: int,
            tau_c: float | None, filtered: bool) -> Fit:
    a = design(tau, tau_c, filtered)
    coef, _ = _weighted(a, var, 1.0 / var ** 2)
    nu = np.ones_like(var)
    weight = 1.0 / var ** 2
    for _ in range(3):
        model = a @ coef
        model = np.where(model > 0, model, var)
        nu = edfs.edf(dominant_alpha(a * coef, tau, tau_c), m, points)
        weight = nu / (2.0 * model ** 2)
        coef, _ = _weighted(a, var, weight)
    r = (a @ coef - var) * np.sqrt(weight)
    return Fit(coef, tau_c, nu, weight, float(r @ r), filtered)


def fit(tau: FloatArray, var: FloatArray, m: IntArray, points: int,
        gauss_markov: bool = True, filtered: bool = False) -> Fit:
    """The weighted non-negative fit of the module docstring to σ̂² = ``var`` at τ = m·τ0
    (all > 0), ``points`` = n + 1 angle points of the record; ``filtered``: the curve
    follows a filter's roll-off, whose −1/τ² tail takes quantization's column."""
    best = _refine(tau, var, m, points, None, filtered)
    if not gauss_markov or tau.size < 8 or best.cost <= MISFIT * tau.size:
        return best
    for tau_c in np.geomspace(tau[0] * 3.0, tau[-1] / 3.0, 13) if tau[-1] > 9 * tau[0] else []:
        trial = _refine(tau, var, m, points, float(tau_c), filtered)
        if (trial.coef[5] > 0 and trial.cost < 0.5 * best.cost
                and trial.cost < best.cost - 10):  # the best τ_c: the first, or a better one
            best = trial
    return best


def refit(a: FloatArray, var: FloatArray, weight: FloatArray) -> FloatArray:
    """One replicate's coefficients: the same design and weights."""
    return _weighted(a, var, weight)[0]


def _replicate_curves(fitted: Fit, tau: FloatArray, m: IntArray, n: int, tau0: float,
                      replicates: int, rng: np.random.Generator) -> FloatArray:
    """σ̂²(τ) of ``replicates`` records of the fitted model (rows), at the record's τ.

    Beyond :data:`SIM_CAP` samples a replicate is two simulations: one as long as the
    record at a coarser interval k·τ0 (k = ⌈n/SIM_CAP⌉), which gives the points from
    m = 2k on, and one of :data:`SIM_CAP` samples at τ0 for the points below, whose
    relative fluctuations are scaled by √(SIM_CAP/n) (at a fixed short τ the estimate's
    spread falls as 1/√n) — so that those points keep their correlation across τ."""
    c = fitted.coef
    truth = Truth(quantization=0.0 if fitted.filtered else math.sqrt(c[0]), arw=math.sqrt(c[1]),
                  bias_instability=math.sqrt(c[2]), rrw=math.sqrt(c[3]),
                  rate_ramp=math.sqrt(c[4]),
                  gm_sigma=math.sqrt(c[5]) if fitted.tau_c is not None else 0.0,
                  gm_tau=fitted.tau_c or 0.0)
    k = max(1, math.ceil(n / SIM_CAP))
    model = fitted.model(tau)
    coarse = m >= 2 * k if k > 1 else np.ones(m.shape, dtype=bool)
    mk = np.maximum(np.round(m[coarse] / k), 1).astype(np.int64)
    uniq, inverse = np.unique(mk, return_inverse=True)
    tau_k = np.multiply(uniq, k * tau0, dtype=np.float64)
    fine = np.flatnonzero(~coarse)
    short = fine[m[fine] <= SIM_CAP // 3]
    drawn = fine[m[fine] > SIM_CAP // 3]
    shrink = math.sqrt(SIM_CAP / n)
    out = np.empty((replicates, tau.size))
    for i in range(replicates):
        y = simulate(truth, n // k, k * tau0, rng)
        ratio = oadev(y, k * tau0, uniq)[1] ** 2 / fitted.model(tau_k)
        out[i, coarse] = model[coarse] * ratio[inverse]
        if short.size:
            y = simulate(truth, SIM_CAP, tau0, rng)
            r = oadev(y, tau0, m[short])[1] ** 2 / model[short]
            out[i, short] = model[short] * (1.0 + (r - 1.0) * shrink)
        if drawn.size:
            nu = fitted.nu[drawn]
            out[i, drawn] = model[drawn] * rng.chisquare(nu) / nu
    return out


@dataclass(frozen=True, slots=True)
class Term:
    """One term as reported: its value (√ of its coefficient, kernel units) with the
    interval at each confidence asked, or an upper bound at :data:`BOUND_CONFIDENCE`."""

    value: float | None
    intervals: tuple[tuple[float, float], ...]
    bound: float | None

    @property
    def resolved(self) -> bool:
        """Whether the record resolves the term (a value, not a bound)."""
        return self.bound is None


def envelope_bound(basis: FloatArray, var: FloatArray, nu: FloatArray) -> float:
    """The least over τ of each point's one-sided upper limit of σ² over the basis, √ of
    it. The least of many limits is taken, so each is at 1 − 5 %/P for P points
    (Bonferroni): all P hold together at 95 % at least, and so does their least."""
    level = 1.0 - (1.0 - BOUND_CONFIDENCE) / max(1, var.size)
    upper = var * edfs.chi2_limits(nu, 2.0 * level - 1.0)[1]
    return math.sqrt(float(np.min(upper / basis)))


def terms(fitted: Fit, tau: FloatArray, var: FloatArray, replicates: FloatArray,
          confidences: tuple[float, ...], method: str = "pivot") -> tuple[Term, ...]:
    """Each of the five terms (and the Gauss–Markov σ, sixth, when fitted) from the fit
    and the replicates' coefficients (rows), see the module docstring."""
    a = fitted.design(tau)
    parts = a * fitted.coef
    share = parts / np.maximum(parts.sum(axis=1, keepdims=True), np.finfo(float).tiny)
    basis = design(tau, fitted.tau_c)  # quantization's own column for its bound
    out = []
    for j in range(a.shape[1]):
        value = 0.0 if (j == 0 and fitted.filtered) else math.sqrt(fitted.coef[j])
        star = np.sqrt(np.maximum(replicates[:, j], 0.0))
        zeros = float(np.mean(star <= 0.0))
        resolved = (value > 0 and zeros < (1.0 - BOUND_CONFIDENCE) / 2.0
                    and float(share[:, j].max()) >= RESOLVED_SHARE)
        if not resolved:
            bound = max(envelope_bound(basis[:, j], var, fitted.nu), value)
            out.append(Term(None, (), bound))
            continue
        ratio = star / value
        intervals = []
        for c in confidences:
            lo_q, hi_q = np.quantile(ratio, [(1.0 - c) / 2.0, (1.0 + c) / 2.0])
            if method == "pivot":
                intervals.append((value / float(hi_q), value / float(lo_q)))
            else:  # the percentile interval, for the coverage study's comparison
                intervals.append((value * float(lo_q), value * float(hi_q)))
        out.append(Term(value, tuple(intervals), None))
    return tuple(out)


@dataclass(frozen=True, slots=True)
class Model:
    """The whole noise model of one curve: the fit (of the points from ``start`` on),
    its terms (:data:`TERMS`, then the Gauss–Markov σ when fitted), σ(τ)'s confidence
    limits per point at the first confidence and each point's EDF, and the fitted points
    outside their 99 % limits (a model that does not fit)."""

    fit: Fit
    terms: tuple[Term, ...]
    ci: tuple[FloatArray, FloatArray]
    misfit: IntArray
    start: int
    nu: FloatArray


#: Local slope of log σ against log τ at or below which the curve is white noise (−½)
#: or steeper (quantization, −1); a leading stretch flatter than :data:`ROLL_OFF_SLOPE`
#: and below the white line is a filter's roll-off.
WHITE_SLOPE, ROLL_OFF_SLOPE, SETTLED_SLOPE = -0.4, -0.3, -0.49


def roll_off(tau: FloatArray, adev: FloatArray) -> int:
    """How many leading points lie on a low-pass filter's roll-off: the curve there is
    flatter than white noise (slope above −0.3 on average) and below the −½ line through
    the first point where the slope reaches −0.4 (the first point by 10 % at least),
    which must come within the first half of the curve; the stretch then runs on to
    the first slope of −0.48 (the filter's last few per cent). 0 when there is no such
    stretch."""
    if tau.size < 8:
        return 0
    slope = np.diff(np.log(adev)) / np.diff(np.log(tau))
    white = np.flatnonzero(slope[: tau.size // 2] <= WHITE_SLOPE)
    if white.size == 0 or white[0] == 0:
        return 0
    j = int(white[0])
    line = adev[j] * np.sqrt(tau[j] / tau[:j])
    if (float(np.mean(slope[:j])) <= ROLL_OFF_SLOPE or not np.all(adev[:j] < line)
            or adev[0] > 0.9 * line[0]):
        return 0
    # the filter still lowers the curve a little past it: on to a slope of −0.48
    while j < tau.size // 2 and slope[j] > SETTLED_SLOPE:
        j += 1
    return j


def noise_model(tau: FloatArray, adev: FloatArray, m: IntArray, n: int, tau0: float,
                confidences: tuple[float, ...] = (0.68, 0.95), seed: int = 0,
                replicates: int = REPLICATES, gauss_markov: bool = True,
                method: str = "pivot") -> Model:
    """The fit, bootstrap and bounds of the module docstring for the Allan deviation
    ``adev`` (deg/s, all > 0) at τ = m·τ0 of a record of ``n`` samples; a leading
    stretch on a filter's roll-off (:func:`roll_off`) is left out of the fit."""
    m_all = np.asarray(m, dtype=np.int64)
    start = roll_off(tau, np.asarray(adev, dtype=float))
    var_all = np.asarray(adev, dtype=float) ** 2
    tau, var, m = tau[start:], var_all[start:], m[start:]
    fitted = fit(tau, var, m, n + 1, gauss_markov, filtered=start > 0)
    rng = np.random.default_rng(seed)
    curves = _replicate_curves(fitted, tau, m, n, tau0, replicates, rng)
    a = fitted.design(tau)
    if fitted.filtered:  # the replicates have no filter: its column would only pull N up
        a = a.copy()
        a[:, 0] = 0.0
    coefs = np.array([refit(a, curve, fitted.weight) for curve in curves])
    found = terms(fitted, tau, var, coefs, confidences, method)
    # the points left out (a roll-off) get the EDF of white noise, the type they follow
    nu = np.concatenate([edfs.edf(np.full(start, edfs.WHITE), m_all[:start], n + 1),
                         fitted.nu])
    ci = edfs.confidence_interval(np.sqrt(var_all), nu, confidences[0])
    lo99, hi99 = edfs.confidence_interval(np.sqrt(var), fitted.nu, 0.99)
    model = np.sqrt(fitted.model(tau))
    misfit = start + np.flatnonzero((model < lo99) | (model > hi99)).astype(np.int64)
    return Model(fitted, found, ci, misfit, start, nu)


__all__ = [
    "BOUND_CONFIDENCE",
    "FLICKER_FLOOR",
    "REPLICATES",
    "TERMS",
    "Fit",
    "Model",
    "Term",
    "design",
    "envelope_bound",
    "fit",
    "gm_basis",
    "nnls",
    "noise_model",
    "refit",
    "terms",
]
