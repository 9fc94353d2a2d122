"""The noise model fitted to an Allan variance curve, each term with an honest interval
or an upper bound (docs/model.md section 15; IEEE Std 952-1997 Annex C).

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
refitted by the record's own estimator (weights refined from each replicate, as the
record's were): so each replicate carries the correlation between neighbouring τ,
every other term's pull on the term and the weights' own variability, which a formula
per point does not. The interval of a term inverts a studentized root
(:func:`studentized`): c = θ² is in it where q_lo ≤ (ĉ − c)/s(c) ≤ q_hi, s(c) the
standard error the fit's information gives c with the term held at c and the other
resolved terms refitted, q the quantiles of the replicates' (c* − ĉ)/s(ĉ). Only s's
dependence on c is taken from the information (which ignores the correlation between
τ); its scale, the skew and any bias come from the replicates. Where s grows as c (a
term alone in its stretch of the curve) this is the pivot θ̂/q'_hi … θ̂/q'_lo of the
replicates' ratios θ*/θ̂; where s hardly moves with c (a rate random walk seen against
white noise and flicker, whose scatter is the other terms') it is the difference
interval; and where a term's scatter grows with another term that the record knows
poorly (bias instability with a random walk beside it), holding the term lower lets
the other grow, and the interval follows, read at the level the coverage study set per
term (:func:`terms`, :mod:`.allan_levels`). For the study's comparison: the pivot ("pivot"),
the percentile interval, and the fast double bootstrap's level (:mod:`.allan_fdb`).

**Roll-off.** A sensor's low-pass filter flattens the curve below a few times its time
constant: read there, N would come out too small. A leading stretch flatter than white
noise and below the −½ line of the first white point (:func:`roll_off`) is left out of
the fit (and said), and past it the filter's tail, σ² lowered by about c/τ², takes the
place of quantization in the fit (c·(−1/τ²), c of either sign: the filter's tail
less any quantization behind it, so that the estimate is never held at a limit the
bootstrap would not reproduce; quantization behind a filter is then only bounded).

**Bounds.** A term is *unresolved* when it is absent from the fit, when 2.5 % or more of
the replicates fit it at 0 or its 95 % interval reaches 0, or when it dominates the model
(half its σ²) at no τ of the record (its slope region is absent). It is then given as an
upper bound at 95 %: the least, over τ, of the one-sided χ² upper limit of σ²(τ)
divided by the term's basis function — each point alone caps the term, since the other
terms are non-negative — each limit at 1 − 5 %/P for the P points, so that the least of
them still holds at 95 % (the first study, with 95 % per point, saw such bounds of K
hold in only 6 of 11 records).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from gyrovib.core import allan_edf as edfs
from gyrovib.core._types import FloatArray
from gyrovib.core.allan import oadev
from gyrovib.core.allan_fdb import calibrated, inverted
from gyrovib.core.allan_levels import read_level
from gyrovib.core.allan_sim import Truth, simulate

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
#: The interval of a resolved term (:func:`terms`), and every method :func:`intervals`
#: knows (the others for the coverage study's comparison).
METHOD = "studentized"
METHODS = ("studentized", "calibrated", "pivot", "percentile")
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


def _weighted(a: FloatArray, var: FloatArray, weight: FloatArray,
              signed_first: bool = False) -> tuple[FloatArray, float]:
    """The weighted non-negative fit; ``signed_first``: the first coefficient takes either
    sign (a filtered curve's 1/τ² term, see :func:`design`)."""
    w = np.sqrt(weight)
    aw = a * w[:, None]
    if signed_first:  # c₀ = c₀⁺ − c₀⁻, both non-negative
        both = nnls(np.column_stack([aw, -aw[:, 0]]), var * w)
        coef = both[:-1].copy()
        coef[0] -= both[-1]
    else:
        coef = nnls(aw, var * w)
    r = (a @ coef - var) * w
    return coef, float(r @ r)


def _refine(tau: FloatArray, var: FloatArray, m: IntArray, points: int,
            tau_c: float | None, filtered: bool) -> Fit:
    a = design(tau, tau_c, filtered)
    coef, _ = _weighted(a, var, 1.0 / var ** 2, filtered)
    nu = np.ones_like(var)
    weight = 1.0 / var ** 2
    for _ in range(3):
        model = a @ coef
        model = np.where(model > 0, model, var)
        nu = edfs.edf(dominant_alpha(a * coef, tau, tau_c), m, points)
        weight = nu / (2.0 * model ** 2)
        coef, _ = _weighted(a, var, weight, filtered)
    r = (a @ coef - var) * np.sqrt(weight)
    return Fit(coef, tau_c, nu, weight, float(r @ r), filtered)


def fit(tau: FloatArray, var: FloatArray, m: IntArray, points: int,
        gauss_markov: bool = True, filtered: bool = False) -> Fit:
    """The weighted non-negative fit of the module docstring to σ̂² = ``var`` at τ = m·τ0
    (all > 0), ``points`` = n + 1 angle points of the record; ``filtered``: the curve
    follows a filter's roll-off, whose −1/τ² tail takes quantization's column, its
    coefficient of either sign (the filter's tail less any quantization behind it: an
    estimate inside its range, which the bootstrap reproduces, not one held at 0)."""
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
    """One curve's coefficients with the design and weights held (no reweighting)."""
    return _weighted(a, var, weight)[0]


def simulated_truth(fitted: Fit) -> Truth:
    """The bootstrap's world: the fitted terms as a record's truth (a filter's tail is
    not a noise term: the simulation has no filter)."""
    c = fitted.coef
    return Truth(quantization=0.0 if fitted.filtered else math.sqrt(c[0]), arw=math.sqrt(c[1]),
                 bias_instability=math.sqrt(c[2]), rrw=math.sqrt(c[3]),
                 rate_ramp=math.sqrt(c[4]),
                 gm_sigma=math.sqrt(c[5]) if fitted.tau_c is not None else 0.0,
                 gm_tau=fitted.tau_c or 0.0)


def _replicate_curves(fitted: Fit, tau: FloatArray, m: IntArray, n: int, tau0: float,
                      replicates: int, rng: np.random.Generator,
                      sim_cap: int = SIM_CAP) -> FloatArray:
    """σ̂²(τ) of ``replicates`` records of the fitted model (rows), at the record's τ.

    Each replicate is the fitted model times the relative fluctuation of a simulated
    record about its own expectation (:func:`simulated_truth`): the same as the
    simulated curve where the model is the simulation's, and where the fit holds a
    filter's tail (which the simulation has not) the fluctuation is put on the filtered
    model, so that a replicate is a curve as the record's would be.

    Beyond ``sim_cap`` samples a replicate is two simulations: one as long as the
    record at a coarser interval k·τ0 (k = ⌈n/sim_cap⌉), which gives the points from
    m = 2k on, and one of ``sim_cap`` samples at τ0 for the points below, whose
    relative fluctuations are scaled by √(sim_cap/n) (at a fixed short τ the estimate's
    spread falls as 1/√n); points of the second beyond its own reach (m > sim_cap/3)
    are drawn from χ² with their EDF."""
    truth = simulated_truth(fitted)
    sim_coef = fitted.coef.copy()
    if fitted.filtered:
        sim_coef[0] = 0.0
    tiny = np.finfo(float).tiny
    plain = np.maximum(design(tau, fitted.tau_c) @ sim_coef, tiny)
    model = fitted.model(tau)
    model = np.where(model > 0, model, plain)  # a replicate's fit may overshoot its tail
    k = max(1, math.ceil(n / sim_cap))
    coarse = m >= 2 * k if k > 1 else np.ones(m.shape, dtype=bool)
    mk = np.maximum(np.round(m[coarse] / k), 1).astype(np.int64)
    uniq, inverse = np.unique(mk, return_inverse=True)
    tau_k = np.multiply(uniq, k * tau0, dtype=np.float64)
    plain_k = np.maximum(design(tau_k, fitted.tau_c) @ sim_coef, tiny)
    fine = np.flatnonzero(~coarse)
    short = fine[m[fine] <= sim_cap // 3]
    drawn = fine[m[fine] > sim_cap // 3]
    shrink = math.sqrt(sim_cap / n)
    out = np.empty((replicates, tau.size))
    for i in range(replicates):
        y = simulate(truth, n // k, k * tau0, rng)
        ratio = oadev(y, k * tau0, uniq)[1] ** 2 / plain_k
        out[i, coarse] = model[coarse] * ratio[inverse]
        if short.size:
            y = simulate(truth, sim_cap, tau0, rng)
            r = oadev(y, tau0, m[short])[1] ** 2 / plain[short]
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


def resolution(fitted: Fit, tau: FloatArray, replicates: FloatArray) -> NDArray[np.bool_]:
    """Which coefficients the record resolves (module docstring: present, fewer than
    2.5 % of the replicates at 0, and half the model somewhere); a filter's tail never."""
    parts = np.maximum(fitted.design(tau) * fitted.coef, 0.0)  # a filter's tail: no noise
    share = parts / np.maximum(parts.sum(axis=1, keepdims=True), np.finfo(float).tiny)
    zeros = np.mean(replicates <= 0.0, axis=0)
    out: NDArray[np.bool_] = ((fitted.coef > 0) & (zeros < (1.0 - BOUND_CONFIDENCE) / 2.0)
                              & (share.max(axis=0) >= RESOLVED_SHARE))
    if fitted.filtered:
        out[0] = False
    return out


@dataclass(frozen=True, slots=True)
class Curve:
    """What the studentized interval needs of the record: its fitted points (τ, σ̂², m),
    angle points n + 1, and the fit."""

    tau: FloatArray
    var: FloatArray
    m: IntArray
    points: int
    fitted: Fit


def scale(curve: Curve, coef: FloatArray, j: int, active: NDArray[np.bool_]) -> float:
    """s_j(c): the standard error of coefficient j that the fit's information gives at
    coefficients ``coef`` — inverse of Aᵀ·W·A over the ``active`` columns, W = ν/(2·model²)
    with ν the EDF of the type that dominates ``coef``'s model at each τ. It ignores the
    correlation between neighbouring τ, so only its dependence on ``coef`` is used (the
    bootstrap sets the scale)."""
    fitted = curve.fitted
    a = fitted.design(curve.tau)
    model = a @ coef
    if not np.all(model > 0):
        return math.inf
    nu = edfs.edf(dominant_alpha(a * coef, curve.tau, fitted.tau_c), curve.m, curve.points)
    idx = np.flatnonzero(active)
    info = (a[:, idx] * (nu / (2.0 * model ** 2))[:, None]).T @ a[:, idx]
    try:
        cov = np.linalg.inv(info)
    except np.linalg.LinAlgError:
        return math.inf
    k = int(np.flatnonzero(idx == j)[0])
    return math.sqrt(max(float(cov[k, k]), 0.0)) or math.inf


def profile(curve: Curve, j: int, cj: float, free: NDArray[np.bool_]) -> FloatArray:
    """The fit's coefficients with c_j held at ``cj`` and the ``free`` columns refitted
    (the fit's weights; the others held at their fitted values)."""
    fitted = curve.fitted
    a = fitted.design(curve.tau)
    coef = fitted.coef.copy()
    coef[j] = cj
    cols = np.flatnonzero(free)
    if cols.size:
        held = np.setdiff1d(np.arange(coef.size), cols)
        rest = curve.var - a[:, held] @ coef[held]
        coef[cols] = _weighted(a[:, cols], rest, fitted.weight,
                               signed_first=bool(fitted.filtered and cols[0] == 0))[0]
    return coef


def studentized_root(curve: Curve, j: int, replicates: FloatArray, resolved: NDArray[np.bool_]
                     ) -> tuple[FloatArray, Callable[[float], float], NDArray[np.bool_]] | None:
    """Term j's studentized root (:func:`studentized`): the replicates' (c* − ĉ)/s(ĉ), the
    record's c ↦ (ĉ − c)/s(c), the columns s is taken over; None: s(ĉ) is not finite."""
    fitted = curve.fitted
    free = resolved.copy()
    free[j] = False
    free[0] |= fitted.filtered
    if fitted.tau_c is not None:
        free[5] = True
    active = free.copy()
    active[j] = True
    c_hat = float(fitted.coef[j])
    s_hat = scale(curve, fitted.coef, j, active)
    if not math.isfinite(s_hat):
        return None
    t_star: FloatArray = (replicates[:, j] - c_hat) / s_hat

    def root(c: float) -> float:
        return (c_hat - c) / scale(curve, profile(curve, j, c, free), j, active)

    return t_star, root, active


def studentized(curve: Curve, j: int, replicates: FloatArray, resolved: NDArray[np.bool_],
                confidences: tuple[float, ...], inner: FloatArray | None = None
                ) -> list[tuple[float, float] | None]:
    """The interval of θ_j = √c_j at each confidence by inverting the studentized root:
    the c with q_lo ≤ (ĉ − c)/s(c) ≤ q_hi, s(c) = :func:`scale` at the fit with c_j = c
    and the other resolved terms refitted (:func:`profile`), q the quantiles of the
    replicates' (c* − ĉ)/s(ĉ) — with ``inner`` (:func:`double_bootstrap`) read at the
    levels the inner roots (c** − c*)/s(c*) calibrate. None where it has no upper end or
    the fit no standard error (the pivot's interval is then used)."""
    if (found := studentized_root(curve, j, replicates, resolved)) is None:
        return [None] * len(confidences)  # no information at the fit itself: the pivot's
    t_star, root, active = found
    t_inner = np.array([] if inner is None else [
        (c2[j] - c1[j]) / scale(curve, c1, j, active)
        for c1, c2 in zip(replicates, inner, strict=True)])
    out: list[tuple[float, float] | None] = []
    for confidence in confidences:
        q_lo, q_hi = calibrated(t_star, t_inner, [(1.0 - confidence) / 2.0,
                                                  (1.0 + confidence) / 2.0])
        out.append(inverted(root, float(curve.fitted.coef[j]), q_lo, q_hi))
    return out


def terms(fitted: Fit, tau: FloatArray, var: FloatArray, replicates: FloatArray,
          confidences: tuple[float, ...], method: str = "pivot",
          curve: Curve | None = None, inner: FloatArray | None = None) -> tuple[Term, ...]:
    """Each of the five terms (and the Gauss–Markov σ, sixth, when fitted) from the fit
    and the replicates' coefficients (rows), see the module docstring; ``method``
    "studentized" needs the ``curve`` (and is read at :func:`.allan_levels.read_level`'s
    levels), "calibrated" also the ``inner`` replicates."""
    resolved = resolution(fitted, tau, replicates)
    basis = design(tau, fitted.tau_c)  # quantization's own column for its bound
    out = []
    for j in range(fitted.coef.size):
        value = 0.0 if (j == 0 and fitted.filtered) else math.sqrt(max(fitted.coef[j], 0.0))
        levels = tuple(read_level(j, c) for c in confidences) if method == METHOD else confidences
        found = intervals(value, j, replicates, levels, method, curve,
                          resolved, inner) if resolved[j] else None
        if found is None or found[-1][0] <= 0.0:  # its 95 % interval reaches 0
            bound = max(envelope_bound(basis[:, j], var, fitted.nu), value)
            out.append(Term(None, (), bound))
            continue
        out.append(Term(value, found, None))
    return tuple(out)


def intervals(value: float, j: int, replicates: FloatArray, confidences: tuple[float, ...],
              method: str, curve: Curve | None, resolved: NDArray[np.bool_],
              inner: FloatArray | None = None) -> tuple[tuple[float, float], ...]:
    """Term j's interval at each confidence (see :func:`terms`); "calibrated" without
    ``inner`` is "studentized", and its pivot (where the studentized root has none) is
    read at the calibrated levels too, the inner ratios θ**/θ* beside the θ*/θ̂."""
    if method not in METHODS:
        raise ValueError(f"unknown interval method {method!r}: one of {', '.join(METHODS)}")
    root = np.sqrt(np.maximum(replicates[:, j], 0.0))
    ratio = root / value
    inner = inner if method == "calibrated" else None
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio2 = np.array([]) if inner is None else np.sqrt(np.maximum(inner[:, j], 0.0)) / root
    tried = (studentized(curve, j, replicates, resolved, confidences, inner)
             if method in ("studentized", "calibrated") and curve is not None else None)
    # one construction for every confidence, so that the intervals nest: the pivot for
    # all of them where the studentized root has no interval at one
    found = (None if tried is None or any(f is None for f in tried)
             else [f for f in tried if f is not None])
    out = []
    for k, c in enumerate(confidences):
        lo_q, hi_q = calibrated(ratio, ratio2, [(1.0 - c) / 2.0, (1.0 + c) / 2.0])
        pivot = (value / hi_q, value / lo_q if lo_q > 0 else math.inf)
        if found is not None:
            out.append(found[k])
        elif method == "percentile":  # for the coverage study's comparison
            out.append((value * lo_q, value * hi_q))
        else:
            out.append(pivot)
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


def bootstrap(fitted: Fit, tau: FloatArray, m: IntArray, n: int, tau0: float,
              replicates: int = REPLICATES, seed: int = 0,
              sim_cap: int = SIM_CAP) -> FloatArray:
    """The replicates' coefficients (rows): records of the fitted model
    (:func:`_replicate_curves`), each refitted by the record's own estimator (its weights
    refined from the replicate, the record's τ_c and filter), so that their spread is the
    estimator's."""
    curves = _replicate_curves(fitted, tau, m, n, tau0, replicates,
                               np.random.default_rng(seed), sim_cap)
    return np.array([_refine(tau, curve, m, n + 1, fitted.tau_c, fitted.filtered).coef
                     for curve in curves])


def double_bootstrap(fitted: Fit, tau: FloatArray, m: IntArray, n: int, tau0: float,
                     replicates: int = REPLICATES, seed: int = 0,
                     sim_cap: int = SIM_CAP) -> tuple[FloatArray, FloatArray]:
    """:func:`bootstrap`'s replicates (the same for the same seed) and, row for row, the
    coefficients of one record of each replicate's own fit, refitted the same way: the
    fast double bootstrap's second level (:mod:`gyrovib.core.allan_fdb`)."""
    curves = _replicate_curves(fitted, tau, m, n, tau0, replicates,
                               np.random.default_rng(seed), sim_cap)
    rng = np.random.default_rng([seed, 1])
    outer, inner = [], []
    for curve in curves:
        once = _refine(tau, curve, m, n + 1, fitted.tau_c, fitted.filtered)
        again = _replicate_curves(once, tau, m, n, tau0, 1, rng, sim_cap)[0]
        outer.append(once.coef)
        inner.append(_refine(tau, again, m, n + 1, fitted.tau_c, fitted.filtered).coef)
    return np.array(outer), np.array(inner)


def noise_model(tau: FloatArray, adev: FloatArray, m: IntArray, n: int, tau0: float,
                confidences: tuple[float, ...] = (0.68, 0.95), seed: int = 0,
                replicates: int = REPLICATES, gauss_markov: bool = True,
                method: str = METHOD, sim_cap: int = SIM_CAP) -> Model:
    """The fit, bootstrap and bounds of the module docstring for the Allan deviation
    ``adev`` (deg/s, all > 0) at τ = m·τ0 of a record of ``n`` samples; a leading
    stretch on a filter's roll-off (:func:`roll_off`) is left out of the fit. ``method``:
    the interval ("calibrated", "studentized", "pivot" or "percentile"); ``sim_cap``: the
    longest record the bootstrap simulates whole (:func:`_replicate_curves`)."""
    m_all = np.asarray(m, dtype=np.int64)
    start = roll_off(tau, np.asarray(adev, dtype=float))
    var_all = np.asarray(adev, dtype=float) ** 2
    tau, var, m = tau[start:], var_all[start:], m[start:]
    fitted = fit(tau, var, m, n + 1, gauss_markov, filtered=start > 0)
    inner = None
    if method == "calibrated":
        coefs, inner = double_bootstrap(fitted, tau, m, n, tau0, replicates, seed, sim_cap)
    else:
        coefs = bootstrap(fitted, tau, m, n, tau0, replicates, seed, sim_cap)
    found = terms(fitted, tau, var, coefs, confidences, method,
                  Curve(tau, var, m, n + 1, fitted), inner)
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
    "METHOD",
    "REPLICATES",
    "TERMS",
    "Curve",
    "Fit",
    "Model",
    "Term",
    "bootstrap",
    "design",
    "double_bootstrap",
    "envelope_bound",
    "fit",
    "gm_basis",
    "intervals",
    "nnls",
    "noise_model",
    "refit",
    "terms",
]
