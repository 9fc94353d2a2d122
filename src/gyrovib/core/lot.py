"""The uncertainty of the vibration error and the yield of a production lot.

docs/model.md section 14. For a given profile, Ω_K and sensor, every term of Δ_V
is linear in the coefficients c = (A1, k2, k3, k4, k5, m31, m32, …) with
k1 = 1 (eq. 13–15): Δ_V = gᵀc, g made of the section 4–10 multipliers
(:func:`sensitivity` builds it from :func:`gyrovib.core.analysis.vibration_error`
on the unit vectors, so it is the engine's own). Hence, exactly,

    u(Δ_V) = √(gᵀ·Σ·g)                                          (:func:`dispersion`)

A lot: the coefficient vectors c_u of n units give the mean μ and the sample
covariance Σ (n − 1 in the denominator); with n ≤ p, p the number of
coefficients Δ_V is linear in (A1, k2…k5, m31, m32: not the bias k0 nor m1, m2,
which do not rectify), Σ of them is singular and only its diagonal is used,
with a warning (:func:`lot_statistics`, :func:`lot_covariance`). A part drawn
from the lot is c ~ N(μ, Σ); its **yield**, the probability that it meets the budget Δ*:

* the direct test, exactly (:func:`direct_yield`): Δ_V ~ N(m, s²), m = gᵀμ,
  s² = gᵀΣg, P(|Δ_V| ≤ Δ*) = Φ((Δ* − m)/s) − Φ((−Δ* − m)/s);
* any other test (the RMS test ‖G·c‖ ≤ Δ*, a quadratic form in Gaussians; the
  bound checks) by Monte Carlo (:func:`monte_carlo_yield`): N draws (default
  100 000) from a seeded ``numpy.random.Generator``, with the 95 % Wilson
  score interval.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from gyrovib.core._types import FloatArray
from gyrovib.core.analysis import BOUNDED, COEFFICIENTS, Multipliers, vibration_error
from gyrovib.core.special import erfc
from gyrovib.errors import ModelError, Note, literal
from gyrovib.frozen import Frozen

#: Monte-Carlo draws of the yield unless told otherwise (docs/model.md section 14).
DEFAULT_DRAWS = 100_000
#: Draws evaluated at once (memory: chunk × p floats).
CHUNK = 20_000
#: z of the two-sided 95 % interval: Φ⁻¹(0.975).
WILSON_Z = 1.959963984540054
#: A correlation matrix whose smallest eigenvalue is below −this is not one.
PSD_TOLERANCE = 1e-8
#: A lot's spread is not measured (docs/model.md section 14, :func:`spread_problem`) where a
#: coefficient's σ is at most this fraction of |μ| (units that agree to rounding: the mean
#: of equal numbers is not always exactly that number), or where the correlation matrix's
#: smallest eigenvalue is at most this fraction of its largest (a singular covariance).
SPREAD_RTOL = 1e-9


class LotError(ModelError):
    """Lot or uncertainty data that do not describe a distribution (a correlation
    outside [−1, 1], a matrix that is not positive semi-definite, …)."""


# --------------------------------------------------------------------------- normal law

def normal_cdf(x: ArrayLike) -> FloatArray:
    """Φ(x) = ½·erfc(−x/√2), elementwise (:func:`gyrovib.core.special.erfc`: no scipy
    at run time)."""
    z = np.asarray(x, dtype=float)
    out: FloatArray = 0.5 * erfc(-z / math.sqrt(2.0))
    return out


def _interval_probability(lo: FloatArray, hi: FloatArray) -> FloatArray:
    """Φ(hi) − Φ(lo) for lo ≤ hi, from the nearer tail so that it keeps its precision
    when both are far out (Φ(hi) − Φ(lo) = Φ(−lo) − Φ(−hi))."""
    right = lo > 0
    a = np.where(right, -hi, lo)
    b = np.where(right, -lo, hi)
    out: FloatArray = normal_cdf(b) - normal_cdf(a)
    return out


def dispersion(g: ArrayLike, covariance: ArrayLike) -> FloatArray:
    """u(Δ_V) = √(gᵀ·Σ·g) for every row of ``g`` (shape (..., p)); Σ (p, p)."""
    gv = np.asarray(g, dtype=float)
    cov = np.asarray(covariance, dtype=float)
    quad = np.einsum("...i,ij,...j->...", gv, cov, gv)
    out: FloatArray = np.sqrt(np.clip(quad, 0.0, None))
    return out


def direct_yield(g: ArrayLike, mean: ArrayLike, covariance: ArrayLike,
                 budget: ArrayLike) -> FloatArray:
    """The exact yield of the direct test, P(|Δ_V| ≤ Δ*) for Δ_V = gᵀc, c ~ N(μ, Σ).

    Δ_V ~ N(m, s²) with m = gᵀμ, s = √(gᵀΣg), so the yield is
    Φ((Δ* − m)/s) − Φ((−Δ* − m)/s) (docs/model.md section 14); where s = 0 it is 1
    when |m| ≤ Δ*, else 0. ``g`` (..., p), ``mean`` (p,), Σ (p, p), ``budget``
    Δ* > 0 broadcast against g's leading shape; all in consistent units.
    """
    gv = np.asarray(g, dtype=float)
    m = gv @ np.asarray(mean, dtype=float)
    s = dispersion(gv, covariance)
    limit = np.asarray(budget, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        lo = (-limit - m) / s
        hi = (limit - m) / s
    exact = _interval_probability(np.where(s > 0, lo, 0.0), np.where(s > 0, hi, 0.0))
    out: FloatArray = np.where(s > 0, exact, (np.abs(m) <= limit).astype(float))
    return out


# --------------------------------------------------------------------------- Monte Carlo


@dataclass(frozen=True, eq=False, repr=False)
class YieldEstimate(Frozen):
    """A yield with how it was obtained.

    ``value``: the fraction of draws that pass (or the exact probability);
    ``low``/``high``: the 95 % Wilson score interval (NaN for ``"exact"``);
    ``draws``: the number of draws (0 for ``"exact"``); ``method``:
    ``"exact"`` or ``"monte-carlo"``. Arrays have the shape of the test's output
    per draw (a scalar test: shape ()).
    """

    value: FloatArray
    low: FloatArray
    high: FloatArray
    draws: int
    method: str


def wilson_interval(successes: ArrayLike, n: int, z: float = WILSON_Z
                    ) -> tuple[FloatArray, FloatArray]:
    """The Wilson score interval of a binomial proportion: with p̂ = k/n,

        centre = (p̂ + z²/2n)/(1 + z²/n),
        half   = z·√(p̂(1 − p̂)/n + z²/4n²)/(1 + z²/n),

    (centre − half, centre + half), within [0, 1]; z = 1.96 for 95 %.
    """
    if n <= 0:
        raise ValueError("n must be positive")
    k = np.asarray(successes, dtype=float)
    p = k / n
    z2 = z * z
    denominator = 1.0 + z2 / n
    centre = (p + z2 / (2 * n)) / denominator
    half = z * np.sqrt(p * (1.0 - p) / n + z2 / (4.0 * n * n)) / denominator
    lo: FloatArray = np.clip(centre - half, 0.0, 1.0)
    hi: FloatArray = np.clip(centre + half, 0.0, 1.0)
    return lo, hi


def normal_factor(covariance: ArrayLike) -> FloatArray:
    """A factor L with L·Lᵀ = Σ for a positive semi-definite Σ (singular allowed):
    V·√λ from its eigen-decomposition, eigenvalues down to −1e-12·max clipped to 0.

    Raises :class:`LotError` when Σ is not symmetric or has a clearly negative
    eigenvalue (it is then no covariance).
    """
    cov = np.asarray(covariance, dtype=float)
    if cov.ndim != 2 or cov.shape[0] != cov.shape[1] or not np.all(np.isfinite(cov)):
        raise LotError("a covariance must be a finite square matrix")
    if not np.allclose(cov, cov.T, rtol=1e-10, atol=0.0):
        raise LotError("a covariance must be symmetric")
    eigenvalues, vectors = np.linalg.eigh(cov)
    top = float(max(np.max(np.abs(eigenvalues)), 0.0)) if eigenvalues.size else 0.0
    if eigenvalues.size and eigenvalues[0] < -1e-10 * max(top, 1e-300):
        raise LotError("the covariance is not positive semi-definite (an eigenvalue "
                       f"{eigenvalues[0]:.3g} < 0)")
    out: FloatArray = vectors * np.sqrt(np.clip(eigenvalues, 0.0, None))
    return out


def monte_carlo_yield(test: Callable[[FloatArray], ArrayLike], mean: ArrayLike,
                      covariance: ArrayLike, rng: np.random.Generator,
                      draws: int = DEFAULT_DRAWS, chunk: int = CHUNK) -> YieldEstimate:
    """The yield of ``test`` over c ~ N(μ, Σ) by Monte Carlo (docs/model.md section 14).

    ``test`` takes a (k, p) array of coefficient draws and returns k booleans
    (pass), or (k, ...) for several tests at once (e.g. one per profile).
    The draws come from ``rng`` in chunks of ``chunk`` (μ + L·z, L from
    :func:`normal_factor`), so the result depends only on the generator's
    seed, ``draws`` and ``chunk``. The interval is the 95 % Wilson interval.
    """
    if draws <= 0 or chunk <= 0:
        raise ValueError("draws and chunk must be positive")
    mu = np.asarray(mean, dtype=float)
    factor = normal_factor(covariance)
    if factor.shape[0] != mu.size:
        raise ValueError("mean and covariance disagree in size")
    passed: NDArray[np.int64] | None = None
    done = 0
    while done < draws:
        k = min(chunk, draws - done)
        z = rng.standard_normal((k, mu.size))
        sample = mu + z @ factor.T
        ok = np.asarray(test(sample), dtype=bool)
        if ok.shape[:1] != (k,):
            raise ValueError("the test must return one verdict per draw (first axis)")
        count = ok.sum(axis=0, dtype=np.int64)
        passed = count if passed is None else passed + count
        done += k
    assert passed is not None
    value = np.asarray(passed, dtype=float) / draws
    lo, hi = wilson_interval(passed, draws)
    return YieldEstimate(value=value, low=lo, high=hi, draws=draws, method="monte-carlo")


def rms_test(terms: ArrayLike, budget: ArrayLike) -> Callable[[FloatArray], NDArray[np.bool_]]:
    """The RMS test (eq. 16, 17) √(Σ_t (G_t·c)²) ≤ Δ* as a function of draws c (k, p);
    ``terms`` G (..., T, p) holds one row per term of eq. (16) (:func:`term_matrix`)."""
    gm = np.asarray(terms, dtype=float)
    limit = np.asarray(budget, dtype=float)

    def test(c: FloatArray) -> NDArray[np.bool_]:
        values = np.einsum("kp,...tp->k...t", c, gm)
        out: NDArray[np.bool_] = np.sqrt(np.sum(values**2, axis=-1)) <= limit
        return out

    return test


def bounds_test(bounds: ArrayLike) -> Callable[[FloatArray], NDArray[np.bool_]]:
    """The bound checks (eq. 23, 25) |c_i| ≤ b_i for every coefficient as a function of
    draws c (k, p); ``bounds`` (..., p), +inf where a coefficient is unconstrained, gives
    verdicts (k, ...)."""
    limit = np.asarray(bounds, dtype=float)

    def test(c: FloatArray) -> NDArray[np.bool_]:
        expand = (slice(None),) + (None,) * (limit.ndim - 1) + (slice(None),)
        out: NDArray[np.bool_] = np.all(np.abs(c[expand]) <= limit, axis=-1)
        return out

    return test


# --------------------------------------------------------------------------- g from the engine


def _unit_rows(names: Sequence[str]) -> FloatArray:
    """One coefficient matrix row (k1 = 1, :data:`COEFFICIENTS` order) per name with
    that coefficient 1 and the others 0."""
    unknown = [n for n in names if n not in COEFFICIENTS or n == "k1"]
    if unknown:
        raise LotError(f"not a coefficient of eq. (2) with k1 = 1: {', '.join(unknown)}")
    rows = np.zeros((len(names), len(COEFFICIENTS)))
    rows[:, COEFFICIENTS.index("k1")] = 1.0
    rows[np.arange(len(names)), [COEFFICIENTS.index(n) for n in names]] += 1.0
    return rows


def sensitivity(multipliers: Multipliers, names: Sequence[str]) -> FloatArray:
    """g with Δ_V = gᵀc for the coefficients ``names`` (k1 = 1; eq. 13–15 and docs/model.md
    sections 8–10): g_i = Δ_V(e_i) − Δ_V(0), by the engine itself. Shape
    ``multipliers.omega.shape + (len(names),)``; rate units as the multipliers'."""
    rows = _unit_rows(names)
    base = np.zeros((1, len(COEFFICIENTS)))
    base[0, COEFFICIENTS.index("k1")] = 1.0
    total = vibration_error(np.vstack([base, rows]), multipliers).total
    out: FloatArray = np.moveaxis(total[1:] - total[0], 0, -1)
    return out


def term_matrix(multipliers: Multipliers, names: Sequence[str]) -> FloatArray:
    """G with the terms of eq. (16) = G·c: the additive terms Δ0 (and those of docs/model.md
    sections 8, 10) and the multiplicative terms Δ(q)·Ω^q, per coefficient of ``names``.
    Shape ``multipliers.omega.shape + (terms, len(names))``; Δ_V(RMS) = ‖G·c‖."""
    rows = _unit_rows(names)
    base = np.zeros((1, len(COEFFICIENTS)))
    base[0, COEFFICIENTS.index("k1")] = 1.0
    error = vibration_error(np.vstack([base, rows]), multipliers)
    powers = np.stack([multipliers.omega ** q for q in (1, 2, 3)], axis=-1)
    terms = np.concatenate([error.additive_terms, error.extra_terms,
                            error.multiplicative_coefficients * powers[None]], axis=-1)
    out: FloatArray = np.moveaxis(terms[1:] - terms[0], 0, -1)
    return out


# --------------------------------------------------------------------------- a lot


def correlation_from_pairs(names: Sequence[str], pairs: Mapping[str, float]) -> FloatArray:
    """The correlation matrix of ``names`` from pairs ``{"A1 k2": 0.3}`` (pairs not named
    are 0; the catalogue's and the JSON's mapping, docs/rate-table.md). Checked by
    :func:`check_correlation`."""
    index = {n: i for i, n in enumerate(names)}
    out = np.eye(len(names))
    for key, value in pairs.items():
        parts = key.split()
        if len(parts) != 2 or parts[0] == parts[1]:
            raise LotError(f"correlation {key!r}: name two different coefficients, "
                           "separated by a space (e.g. 'A1 k2')")
        missing = [p for p in parts if p not in index]
        if missing:
            raise LotError(f"correlation {key!r}: {', '.join(missing)} has no sigma")
        i, j = index[parts[0]], index[parts[1]]
        if out[i, j] != 0.0 and i != j:
            raise LotError(f"correlation {key!r}: the pair is given twice")
        out[i, j] = out[j, i] = float(value)
    check_correlation(out, names)
    return out


def check_correlation(correlation: ArrayLike, names: Sequence[str] | None = None) -> None:
    """Raise :class:`LotError` unless ``correlation`` is a correlation matrix: symmetric,
    unit diagonal, entries in [−1, 1], positive semi-definite (smallest eigenvalue
    ≥ −:data:`PSD_TOLERANCE`)."""
    r = np.asarray(correlation, dtype=float)
    p = r.shape[0] if r.ndim == 2 else -1
    if r.ndim != 2 or r.shape != (p, p) or not np.all(np.isfinite(r)):
        raise LotError("a correlation matrix must be a finite square matrix")
    label = list(names) if names is not None else [str(i) for i in range(p)]
    if not np.allclose(r, r.T, rtol=0.0, atol=1e-12):
        raise LotError("a correlation matrix must be symmetric")
    if not np.allclose(np.diag(r), 1.0, rtol=0.0, atol=1e-12):
        raise LotError("a correlation matrix has ones on its diagonal")
    bad = np.argwhere(np.abs(r) > 1.0)
    if bad.size:
        i, j = bad[0]
        raise LotError(f"correlation {label[i]} {label[j]} = {r[i, j]:.6g} is outside [−1, 1]")
    smallest = float(np.linalg.eigvalsh(r)[0]) if p else 0.0
    if smallest < -PSD_TOLERANCE:
        raise LotError(
            f"the correlations of {', '.join(label)} are not consistent (the matrix is not "
            f"positive semi-definite: smallest eigenvalue {smallest:.3g}); no distribution "
            "has them")


def covariance_from(sigma: ArrayLike, correlation: ArrayLike) -> FloatArray:
    """Σ = diag(σ)·R·diag(σ), σ ≥ 0 finite, R checked by :func:`check_correlation`."""
    s = np.asarray(sigma, dtype=float)
    if not (np.all(np.isfinite(s)) and np.all(s >= 0)):
        raise LotError("standard uncertainties must be finite and ≥ 0")
    r = np.asarray(correlation, dtype=float)
    check_correlation(r)
    out: FloatArray = r * np.outer(s, s)
    return out


def rectifying_count(names: Sequence[str] | None, size: int) -> int:
    """The number p of coefficients among ``names`` that Δ_V is linear in (docs/model.md
    section 14: c = (A1, k2, k3, k4, k5, m31, m32); k0, m1, m2 do not rectify): the
    lot's Σ of them is singular when n ≤ p. Without names, all ``size``."""
    if names is None:
        return size
    return sum(1 for n in names if n in BOUNDED)


def diagonal_warning(units: int, p: int) -> str:
    """The warning of a lot too small for its covariance (n ≤ p)."""
    return (f"a lot of {units} unit{'s' if units != 1 else ''} cannot estimate the "
            f"correlations of {p} coefficients (n ≤ p makes the sample covariance singular): "
            "only the standard deviations are used, correlations taken as 0")


def spread_problem(mean: ArrayLike, sigma: ArrayLike, correlation: ArrayLike, units: int,
                   names: Sequence[str] | None = None, p: int | None = None) -> str | None:
    """Why a yield from this lot is not a measurement, or None (docs/model.md section 14).

    A lot of ``units`` units whose coefficients ``names`` have mean μ, standard
    deviations σ and correlation matrix R. Its sample covariance is singular, and a
    yield drawn from it says nothing about the parts, when

    * ``units`` ≤ p (``p``, default :func:`rectifying_count` of ``names``): only the
      diagonal is used (:func:`lot_covariance`);
    * a coefficient Δ_V is linear in has σ ≤ :data:`SPREAD_RTOL`·|μ| (σ = 0
      included): identical units, or units that differ in other coefficients only;
    * else, the smallest eigenvalue of R over those coefficients is at most
      :data:`SPREAD_RTOL` times its largest (a spread along fewer directions than
      coefficients).
    """
    mu = np.asarray(mean, dtype=float)
    s = np.asarray(sigma, dtype=float)
    label = list(names) if names is not None else [str(i) for i in range(s.size)]
    size = rectifying_count(names, s.size) if p is None else p
    reasons = []
    if units <= size:
        reasons.append(diagonal_warning(units, size))
    index = [i for i in range(s.size) if names is None or label[i] in BOUNDED]
    flat = [label[i] for i in index if not s[i] > SPREAD_RTOL * abs(mu[i])]
    if flat:
        reasons.append(f"no spread in {', '.join(flat)} (σ = 0, or within {SPREAD_RTOL:g} of "
                       "|mean|: the units agree there to rounding)")
    elif units > size:
        reasons += _singular_correlation(correlation, index, label)
    return "; ".join(reasons) or None


def _singular_correlation(correlation: ArrayLike, index: list[int], label: list[str]
                          ) -> list[str]:
    """Why the correlation matrix of the coefficients ``index`` is singular (its smallest
    eigenvalue at most :data:`SPREAD_RTOL` of its largest), or nothing."""
    if len(index) < 2:
        return []
    r = np.asarray(correlation, dtype=float)[np.ix_(index, index)]
    eigenvalues = np.linalg.eigvalsh(r)
    if eigenvalues[0] > SPREAD_RTOL * eigenvalues[-1]:
        return []
    return [f"the correlations of {', '.join(label[i] for i in index)} make the covariance "
            f"singular (the smallest eigenvalue of their correlation matrix is "
            f"{eigenvalues[0]:.3g}, at most {SPREAD_RTOL:g} of the largest): the units "
            "spread along fewer directions than there are coefficients"]


def unmeasured_warning(lot: str, problem: str) -> Note:
    """The warning of a lot whose yield is not a measurement (:func:`spread_problem`)."""
    return Note(f"lot {literal(repr(lot))}: {literal(problem)}; a yield from this lot is not a "
                "measurement (select with {yield_target} calls it unverified): measure more "
                "units, or units that differ", ("yield_target", None))


def lot_covariance(sigma: ArrayLike, correlation: ArrayLike, units: int,
                   names: Sequence[str] | None = None) -> tuple[FloatArray, str | None]:
    """The covariance of a lot of ``units`` units (docs/model.md section 14) and a warning:
    with units ≤ p (:func:`rectifying_count` of ``names``, the coefficients σ is
    given for; all of them when None) only the diagonal σ² (and the warning of
    :func:`diagonal_warning`), else diag(σ)·R·diag(σ)."""
    s = np.asarray(sigma, dtype=float)
    p = rectifying_count(names, s.size)
    if units <= p:
        return covariance_from(s, np.eye(s.size)), diagonal_warning(units, p)
    return covariance_from(s, correlation), None


@dataclass(frozen=True, eq=False, repr=False)
class LotStatistics(Frozen):
    """A lot estimated from its units' coefficient vectors (docs/model.md section 14).

    ``mean`` μ, ``sigma`` (sample standard deviations, n − 1), ``correlation``
    (the identity when ``diagonal``), ``covariance`` (the one the yield uses:
    diagonal when n ≤ p), ``units`` n, ``warning`` (None unless diagonal);
    ``unmeasured``: why a yield from the lot is not a measurement
    (:func:`spread_problem`), None when it is one.
    """

    mean: FloatArray
    sigma: FloatArray
    correlation: FloatArray
    covariance: FloatArray
    units: int
    diagonal: bool
    warning: str | None
    unmeasured: str | None = None


def lot_statistics(coefficients: ArrayLike, names: Sequence[str] | None = None
                   ) -> LotStatistics:
    """μ and Σ of the rows c_u of ``coefficients`` (n, k), n ≥ 2: Σ with n − 1 in the
    denominator; with n ≤ p only its diagonal, with a warning. p counts the columns
    ``names`` that Δ_V is linear in (:func:`rectifying_count`: k0, m1, m2 excluded,
    docs/model.md section 14), or all k when ``names`` is None."""
    c = np.asarray(coefficients, dtype=float)
    if c.ndim != 2 or c.shape[0] < 2:
        raise LotError("a lot needs the coefficients of at least two units")
    if names is not None and len(names) != c.shape[1]:
        raise ValueError("one name per column of coefficients")
    n, k = c.shape
    p = rectifying_count(names, k)
    mean = c.mean(axis=0)
    full = np.atleast_2d(np.cov(c, rowvar=False, ddof=1))
    sigma = np.sqrt(np.clip(np.diag(full), 0.0, None))
    diagonal = n <= p
    if diagonal:
        correlation = np.eye(k)
    else:
        with np.errstate(divide="ignore", invalid="ignore"):
            correlation = full / np.outer(sigma, sigma)
        correlation = np.where(np.isfinite(correlation), correlation, 0.0)
        np.fill_diagonal(correlation, 1.0)
        correlation = np.clip(correlation, -1.0, 1.0)
    return LotStatistics(
        mean=mean, sigma=sigma, correlation=correlation,
        covariance=correlation * np.outer(sigma, sigma), units=n, diagonal=diagonal,
        warning=diagonal_warning(n, p) if diagonal else None,
        unmeasured=spread_problem(mean, sigma, correlation, n, names, p))
