"""The noise model fitted to an Allan variance curve, each term with an interval or an
upper bound (docs/model.md section 15; IEEE Std 952-1997 Annex C).

Rate in deg/s, τ in s, the model is linear in its non-negative coefficients::

    σ²(τ) = 3Q²/τ² + N²/τ + (2 ln 2/π)·B² + K²·τ/3 + R²·τ²/2  [+ σ_GM²·g(τ/τ_c)]

with g the Allan variance of a unit first-order Gauss–Markov process of correlation time
τ_c, g = (2/x)·(1 − (3 − 4e^{−x} + e^{−2x})/(2x)), x = τ/τ_c (→ 2x/3 for x → 0: a rate
random walk; → 2/x for x → ∞: white noise).

**Fit** (:func:`fit`): non-negative least squares on all σ̂²(τ), each point weighted by
ν/(2·model²), ν its EDF (:mod:`gyrovib.core.allan_edf`) for the noise type that
dominates the model there, refined three times; a Gauss–Markov term only where the five
terms leave more than :data:`MISFIT` per point and it more than halves that.

**Intervals** (:func:`bootstrap`, :func:`studentized`): a parametric bootstrap of the
fitted model, each replicate refitted as the record was; a term's interval holds the
c = θ² with q_lo ≤ (ĉ − c)/s(c) ≤ q_hi, s(c) the standard error the fit's information
gives c with the other resolved terms refitted, q the replicates' quantiles of
(c* − ĉ)/s(ĉ) read at the level :mod:`.allan_levels` sets per term; the ratio pivot
θ̂/q'_hi … θ̂/q'_lo where that root has no interval. docs/error-budget.md sections 2 and 5
explain the choice and the coverage measured (benchmarks/bench_allan_coverage.py).

**Roll-off** (:func:`roll_off`): a leading stretch flatter than white noise and below its
−½ line is left out, and the filter's tail c·(−1/τ²), c of either sign, takes
quantization's column.

**Bounds** (:func:`envelope_bound`): a term absent from the fit, fitted at 0 by 2.5 % or
more of the replicates, whose 95 % interval reaches 0, or that is half the model at no τ,
is an upper bound at 95 %: the least over τ of the one-sided χ² limit of σ²(τ) (each at
1 − 5 %/P for P points) over the term's basis function.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from gyrovib.core import allan_edf as edfs
from gyrovib.core._types import FloatArray, IntArray
from gyrovib.core.allan import oadev
from gyrovib.core.allan_levels import read_level
from gyrovib.core.allan_sim import Truth, simulate

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


def quantiles(values: FloatArray, levels: list[float]) -> list[float]:
    """The quantiles of the finite ``values`` at each of ``levels``."""
    return [float(q) for q in np.quantile(values[np.isfinite(values)], levels)]


def bisect(f: Callable[[float], float], lo: float, hi: float, target: float) -> float:
    """x in [lo, hi] where the decreasing f crosses ``target`` (bisection)."""
    for _ in range(48):
        mid = 0.5 * (lo + hi)
        if f(mid) > target:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def inverted(root: Callable[[float], float], c_hat: float, q_lo: float, q_hi: float
             ) -> tuple[float, float] | None:
    """√ of the c where q_lo ≤ root(c) ≤ q_hi (root decreasing, 0 at ĉ); None where it
    has no upper end. Where both quantiles lie on one side of 0 (q_hi ≤ 0 or q_lo ≥ 0)
    that set lies wholly on one side of ĉ; the interval is then taken from ĉ itself to
    its far end, so that it always holds the estimate."""
    # the least c tried is a little above 0: at 0 a term alone in its model has none
    floor = c_hat * 1e-12
    lo = c_hat if q_hi <= 0 else (0.0 if root(floor) <= q_hi
                                  else bisect(root, floor, c_hat, q_hi))
    if q_lo >= 0:
        return math.sqrt(lo), math.sqrt(c_hat)
    top = 2.0 * c_hat
    while root(top) > q_lo:
        top *= 2.0
        if top > c_hat * 2.0 ** 40:
            return None
    return math.sqrt(lo), math.sqrt(bisect(root, c_hat, top, q_lo))


def studentized(curve: Curve, j: int, replicates: FloatArray, resolved: NDArray[np.bool_],
                confidences: tuple[float, ...]) -> list[tuple[float, float] | None]:
    """The interval of θ_j = √c_j at each confidence by inverting the studentized root:
    the c with q_lo ≤ (ĉ − c)/s(c) ≤ q_hi, s(c) = :func:`scale` at the fit with c_j = c
    and the other resolved terms refitted (:func:`profile`), q the quantiles of the
    replicates' (c* − ĉ)/s(ĉ). None where it has no upper end or the fit no standard
    error (the pivot's interval is then used)."""
    if (found := studentized_root(curve, j, replicates, resolved)) is None:
        return [None] * len(confidences)  # no information at the fit itself: the pivot's
    t_star, root, _ = found
    out: list[tuple[float, float] | None] = []
    for confidence in confidences:
        q_lo, q_hi = quantiles(t_star, [(1.0 - confidence) / 2.0, (1.0 + confidence) / 2.0])
        out.append(inverted(root, float(curve.fitted.coef[j]), q_lo, q_hi))
    return out


def pivot(value: float, j: int, replicates: FloatArray, confidences: tuple[float, ...]
          ) -> tuple[tuple[float, float], ...]:
    """The ratio pivot θ̂/q_hi … θ̂/q_lo of term j at each confidence, q the quantiles of
    the replicates' θ*/θ̂ (no upper end where q_lo is 0)."""
    ratio = np.sqrt(np.maximum(replicates[:, j], 0.0)) / value
    out = []
    for c in confidences:
        lo_q, hi_q = quantiles(ratio, [(1.0 - c) / 2.0, (1.0 + c) / 2.0])
        out.append((value / hi_q, value / lo_q if lo_q > 0 else math.inf))
    return tuple(out)


def terms(curve: Curve, replicates: FloatArray, confidences: tuple[float, ...]
          ) -> tuple[Term, ...]:
    """Each of the five terms (and the Gauss–Markov σ, sixth, when fitted) from the fit
    and the replicates' coefficients (rows), see the module docstring; each interval read
    at :func:`.allan_levels.read_level`'s levels."""
    fitted = curve.fitted
    resolved = resolution(fitted, curve.tau, replicates)
    basis = design(curve.tau, fitted.tau_c)  # quantization's own column for its bound
    out = []
    for j in range(fitted.coef.size):
        value = 0.0 if (j == 0 and fitted.filtered) else math.sqrt(max(fitted.coef[j], 0.0))
        levels = tuple(read_level(j, c) for c in confidences)
        found = intervals(value, j, replicates, levels, curve, resolved) if resolved[j] else None
        if found is None or found[-1][0] <= 0.0:  # its 95 % interval reaches 0
            bound = max(envelope_bound(basis[:, j], curve.var, fitted.nu), value)
            out.append(Term(None, (), bound))
            continue
        out.append(Term(value, found, None))
    return tuple(out)


def intervals(value: float, j: int, replicates: FloatArray, confidences: tuple[float, ...],
              curve: Curve, resolved: NDArray[np.bool_]) -> tuple[tuple[float, float], ...]:
    """Term j's interval at each confidence: the studentized one (:func:`studentized`), or
    the :func:`pivot` at every confidence where it has none at one, so that they nest."""
    found = studentized(curve, j, replicates, resolved, confidences)
    if any(f is None for f in found):
        return pivot(value, j, replicates, confidences)
    return tuple(f for f in found if f is not None)


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


def noise_model(tau: FloatArray, adev: FloatArray, m: IntArray, n: int, tau0: float,
                confidences: tuple[float, ...] = (0.68, 0.95), seed: int = 0,
                replicates: int = REPLICATES, gauss_markov: bool = True,
                sim_cap: int = SIM_CAP) -> Model:
    """The fit, bootstrap and bounds of the module docstring for the Allan deviation
    ``adev`` (deg/s, all > 0) at τ = m·τ0 of a record of ``n`` samples; a leading
    stretch on a filter's roll-off (:func:`roll_off`) is left out of the fit. ``sim_cap``:
    the longest record the bootstrap simulates whole (:func:`_replicate_curves`)."""
    m_all = np.asarray(m, dtype=np.int64)
    start = roll_off(tau, np.asarray(adev, dtype=float))
    var_all = np.asarray(adev, dtype=float) ** 2
    tau, var, m = tau[start:], var_all[start:], m[start:]
    fitted = fit(tau, var, m, n + 1, gauss_markov, filtered=start > 0)
    coefs = bootstrap(fitted, tau, m, n, tau0, replicates, seed, sim_cap)
    found = terms(Curve(tau, var, m, n + 1, fitted), coefs, confidences)
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
    "Curve",
    "Fit",
    "Model",
    "Term",
    "bootstrap",
    "design",
    "envelope_bound",
    "fit",
    "gm_basis",
    "intervals",
    "inverted",
    "nnls",
    "noise_model",
    "pivot",
    "terms",
]
