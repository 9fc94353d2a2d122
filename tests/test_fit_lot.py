"""Uncertainty of the vibration error and the yield of a lot (docs/model.md section 14,
gyrovib.core.lot).

Sources of the expected numbers: g is built by the analysis engine itself from
the unit vectors and checked against the section 4 multipliers worked by hand;
u(Δ_V) against the scatter of the engine's Δ_V over coefficient draws; the
exact yield against the standard library's NormalDist; the Monte-Carlo yields
against the exact one where both apply; the Wilson interval against its
closed form at k = 0.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from statistics import NormalDist

import numpy as np
import pytest

from gyrovib.core.analysis import COEFFICIENTS, profile_multipliers, vibration_error
from gyrovib.core.lot import (
    WILSON_Z,
    LotError,
    bounds_test,
    check_correlation,
    correlation_from_pairs,
    covariance_from,
    direct_yield,
    dispersion,
    lot_covariance,
    lot_statistics,
    monte_carlo_yield,
    normal_factor,
    rms_test,
    sensitivity,
    term_matrix,
    wilson_interval,
)
from gyrovib.core.statistics import vibration_at_sensor


def direct_test(g: np.ndarray, budget: float) -> Callable[[np.ndarray], np.ndarray]:
    """The direct test |gᵀc| ≤ Δ* as a test of draws c (k, p) for monte_carlo_yield: by
    its definition, so that the Monte-Carlo yield can be checked against direct_yield."""
    return lambda c: np.abs(np.einsum("kp,...p->k...", c, np.asarray(g, dtype=float))) <= budget

NAMES = ("k0", "A1", "k2", "k3", "k4", "k5", "m31", "m32")
#: One tone a = (1, 0.5, 2) deg/s plus Gaussian σ = (0.5, 0.5, 1) deg/s, at Ω = 0 and 3 deg/s.
VIBRATION = vibration_at_sensor([(100.0, (1.0, 0.5, 2.0), (0.0, 0.0, 0.0))],
                                rms=(0.5, 0.5, 1.0), coherence=(1.0, 1.0))
OMEGA = np.array([0.0, 3.0])
MULTIPLIERS = profile_multipliers(VIBRATION, OMEGA)
MEAN = np.array([0.05, 1.5e-3, 2e-4, -3e-5, 4e-6, -2e-7, 1e-4, -5e-5])
SIGMA = np.array([0.3, 4e-4, 8e-5, 1e-5, 2e-6, 1e-7, 4e-5, 2e-5])
CORRELATION = correlation_from_pairs(NAMES, {"A1 k2": 0.4, "k2 k4": -0.5, "k3 k5": 0.3,
                                             "m31 m32": 0.2})
COVARIANCE = covariance_from(SIGMA, CORRELATION)


def engine_total(c: np.ndarray) -> np.ndarray:
    """Δ_V of coefficient vectors c (k, NAMES) by the engine, k1 = 1: shape (k, rates)."""
    rows = np.zeros((c.shape[0], len(COEFFICIENTS)))
    rows[:, COEFFICIENTS.index("k1")] = 1.0
    for j, name in enumerate(NAMES):
        rows[:, COEFFICIENTS.index(name)] = c[:, j]
    return vibration_error(rows, MULTIPLIERS).total


def test_g_is_the_section_4_multipliers() -> None:
    # M2 = a²/2 + σ² = 2 + 1 = 3; M4 = 3a⁴/8 + 3σ⁴ + 3·[(2+1)² − 2² − 1²] = 6 + 3 + 12 = 21;
    # C31 = ½·2·1 + 1·0.5 = 1.5, C32 = ½·2·0.5 + 0.5 = 1; g_A1 = ½E(Ω) (the engine's own)
    g = sensitivity(MULTIPLIERS, NAMES)
    assert g.shape == (2, len(NAMES))
    for j, w in enumerate(OMEGA):
        expected = {"k0": 0.0, "k2": 3.0, "k3": 3 * 3.0 * w, "k4": 21.0 + 6 * 3.0 * w**2,
                    "k5": 5 * 21.0 * w + 10 * 3.0 * w**3, "m31": 1.5, "m32": 1.0,
                    "A1": float(MULTIPLIERS.asymmetry[j])}
        for k, name in enumerate(NAMES):
            assert g[j, k] == pytest.approx(expected[name], rel=1e-12, abs=1e-15), (w, name)


def test_delta_v_is_linear_in_the_coefficients() -> None:
    rng = np.random.default_rng(7)
    c = MEAN + rng.normal(size=(50, len(NAMES))) * SIGMA
    g = sensitivity(MULTIPLIERS, NAMES)
    np.testing.assert_allclose(engine_total(c), c @ g.T, rtol=1e-12, atol=1e-16)


def test_u_of_delta_v_is_the_scatter_of_the_engine() -> None:
    """u = √(gᵀΣg) against the standard deviation of the engine's Δ_V over 200 000 draws
    c ~ N(μ, Σ) (relative standard error of a sample σ: 1/√(2N) ≈ 0.16 %; 1 % is six)."""
    g = sensitivity(MULTIPLIERS, NAMES)
    u = dispersion(g, COVARIANCE)
    np.testing.assert_allclose(u, np.sqrt(np.einsum("ri,ij,rj->r", g, COVARIANCE, g)),
                               rtol=1e-14)
    draws = np.random.default_rng(11).multivariate_normal(MEAN, COVARIANCE, size=200_000)
    np.testing.assert_allclose(engine_total(draws).std(axis=0), u, rtol=0.01)


def test_u_from_fitted_unit_coefficients() -> None:
    """A unit fitted from rate-table data: u(Δ_V) from its covariance equals the scatter of
    Δ_V over repeated fits of fresh noise (the engine's Δ_V of each fit's coefficients)."""
    from gyrovib.core.fit import fit_rate_table

    levels = np.array([-300, -200, -100, -50, -20, 0, 20, 50, 100, 200, 300.0])
    w = np.repeat(levels, 2)
    c = {"A1": 2e-3, "k2": 3e-6, "k3": -4e-9, "k4": 1.5e-12, "k5": 1e-14}
    clean = 25.0 * (0.1 + w + 0.5 * c["A1"] * abs(w) + sum(c[f"k{n}"] * w**n
                                                          for n in range(2, 6)))
    rng = np.random.default_rng(3)
    fits = [fit_rate_table(w, clean + rng.normal(0, 0.05, w.size)) for _ in range(500)]
    names = fits[0].names
    g = sensitivity(MULTIPLIERS, names)
    totals = np.array([g @ f.values for f in fits])
    u = np.mean([dispersion(g, f.covariance) for f in fits], axis=0)
    # 500 fits: the sample σ has a relative standard error of ≈ 3.2 %
    np.testing.assert_allclose(totals.std(axis=0, ddof=1), u, rtol=0.13)


def test_exact_yield_is_the_normal_cdf() -> None:
    g = sensitivity(MULTIPLIERS, NAMES)
    m, s = g @ MEAN, dispersion(g, COVARIANCE)
    for budget in (1e-4, 1e-3, 3e-3, 1e-2):
        got = direct_yield(g, MEAN, COVARIANCE, budget)
        for r in range(2):
            law = NormalDist(float(m[r]), float(s[r]))
            assert got[r] == pytest.approx(law.cdf(budget) - law.cdf(-budget), abs=1e-14)


def test_exact_yield_keeps_its_precision_in_the_tails() -> None:
    # m = 10, s = 1, Δ* = 3: P = Φ(−7) − Φ(−13) = ½erfc(7/√2) − ½erfc(13/√2) ≈ 1.28e-12
    got = direct_yield(np.array([1.0]), np.array([10.0]), np.array([[1.0]]), 3.0)
    expected = 0.5 * math.erfc(7 / math.sqrt(2)) - 0.5 * math.erfc(13 / math.sqrt(2))
    assert got == pytest.approx(expected, rel=1e-12)


def test_exact_yield_without_spread() -> None:
    g = np.array([[1.0, 0.0], [1.0, 0.0]])
    got = direct_yield(g, np.array([0.5, 9.0]), np.zeros((2, 2)), np.array([1.0, 0.4]))
    np.testing.assert_array_equal(got, [1.0, 0.0])


def test_monte_carlo_interval_covers_the_exact_yield() -> None:
    g = sensitivity(MULTIPLIERS, NAMES)
    # Δ* a little above |m| at each rate: yields well inside (0, 1)
    budget = np.abs(g @ MEAN) + 0.3 * dispersion(g, COVARIANCE)
    exact = direct_yield(g, MEAN, COVARIANCE, budget)
    assert np.all((exact > 0.2) & (exact < 0.99))  # a test that can fail either way
    estimate = monte_carlo_yield(direct_test(g, budget), MEAN, COVARIANCE,
                                 np.random.default_rng(2026))
    assert estimate.draws == 100_000 and estimate.method == "monte-carlo"
    assert np.all(estimate.low <= exact) and np.all(exact <= estimate.high)
    assert np.all(estimate.high - estimate.low < 0.01)
    again = monte_carlo_yield(direct_test(g, budget), MEAN, COVARIANCE,
                              np.random.default_rng(2026))
    np.testing.assert_array_equal(again.value, estimate.value)  # seeded: reproducible


def test_rms_test_of_one_term_is_the_direct_test() -> None:
    """With one coefficient acting, Δ_V(RMS) = |Δ_V|: the Monte-Carlo RMS yield's interval
    must cover the exact direct yield."""
    names = ("k2",)
    terms = term_matrix(MULTIPLIERS, names)
    g = sensitivity(MULTIPLIERS, names)
    mean, cov = np.array([2e-4]), np.array([[(8e-5) ** 2]])
    exact = direct_yield(g, mean, cov, 8e-4)
    estimate = monte_carlo_yield(rms_test(terms, 8e-4), mean, cov, np.random.default_rng(9))
    assert np.all(estimate.low <= exact) and np.all(exact <= estimate.high)


def test_term_matrix_gives_the_engine_rms() -> None:
    rng = np.random.default_rng(1)
    c = MEAN + rng.normal(size=(20, len(NAMES))) * SIGMA
    terms = term_matrix(MULTIPLIERS, NAMES)
    rows = np.zeros((20, len(COEFFICIENTS)))
    rows[:, COEFFICIENTS.index("k1")] = 1.0
    for j, name in enumerate(NAMES):
        rows[:, COEFFICIENTS.index(name)] = c[:, j]
    rms = vibration_error(rows, MULTIPLIERS).rms
    np.testing.assert_allclose(np.linalg.norm(np.einsum("rtp,kp->krt", terms, c), axis=-1),
                               rms, rtol=1e-12)


def test_wilson_interval_closed_forms() -> None:
    # k = 0: (0, z²/(n + z²)); k = n: (n/(n + z²), 1); symmetric about ½ for k = n/2
    z2 = WILSON_Z**2
    lo, hi = wilson_interval(0, 10)
    assert lo == 0.0 and hi == pytest.approx(z2 / (10 + z2), rel=1e-14)
    lo, hi = wilson_interval(10, 10)
    assert lo == pytest.approx(10 / (10 + z2), rel=1e-14) and hi == pytest.approx(1.0)
    lo, hi = wilson_interval(50, 100)
    assert lo + hi == pytest.approx(1.0, rel=1e-14)
    # the textbook value for 50/100: 0.5 ± 0.0962 (Wilson 1927; Newcombe 1998, table I)
    assert lo == pytest.approx(0.4038, abs=1e-4)


def test_lot_statistics() -> None:
    rng = np.random.default_rng(4)
    c = rng.normal(size=(12, 4)) * [1, 2, 3, 4] + [1, 0, -1, 2]
    lot = lot_statistics(c)
    np.testing.assert_allclose(lot.mean, c.mean(axis=0), rtol=1e-14)
    np.testing.assert_allclose(lot.covariance, np.cov(c, rowvar=False, ddof=1), rtol=1e-12)
    assert not lot.diagonal and lot.warning is None and lot.units == 12


def test_a_small_lot_uses_the_diagonal_with_a_warning() -> None:
    c = np.random.default_rng(4).normal(size=(4, 4))
    lot = lot_statistics(c)
    assert lot.diagonal and "4 units" in (lot.warning or "")
    np.testing.assert_allclose(lot.covariance, np.diag(c.var(axis=0, ddof=1)), rtol=1e-12)
    cov, warning = lot_covariance(np.ones(3), np.full((3, 3), 0.5) + 0.5 * np.eye(3), 3)
    assert warning is not None and np.array_equal(cov, np.eye(3))
    cov, warning = lot_covariance([1.0, 2.0], [[1.0, 0.5], [0.5, 1.0]], 12)
    assert warning is None and cov[0, 1] == 1.0


def test_correlations_that_no_distribution_has() -> None:
    with pytest.raises(LotError, match="not positive semi-definite"):
        correlation_from_pairs(("a", "b", "c"), {"a b": 0.9, "a c": 0.9, "b c": -0.9})
    with pytest.raises(LotError, match="outside"):
        check_correlation(np.array([[1.0, 1.2], [1.2, 1.0]]))
    with pytest.raises(LotError, match="has no sigma"):
        correlation_from_pairs(("A1", "k2"), {"A1 k3": 0.1})
    with pytest.raises(LotError, match="two different coefficients"):
        correlation_from_pairs(("A1", "k2"), {"A1": 0.1})
    with pytest.raises(LotError, match="symmetric"):
        check_correlation(np.array([[1.0, 0.2], [0.1, 1.0]]))
    # a singular but valid matrix (ρ = 1) is accepted, and draws from it are possible
    r = correlation_from_pairs(("a", "b"), {"a b": 1.0})
    factor = normal_factor(covariance_from([1.0, 2.0], r))
    np.testing.assert_allclose(factor @ factor.T, [[1.0, 2.0], [2.0, 4.0]], atol=1e-12)


def test_bound_checks_by_monte_carlo() -> None:
    """|c1| ≤ b1 and |c2| ≤ b2 for independent normal c: the exact probability is the
    product of two normal intervals; a second row with c2 unconstrained is the first
    factor alone. The Monte-Carlo interval must cover both."""
    mean, sigma = np.array([1e-3, -2e-4]), np.array([5e-4, 1e-4])
    bounds = np.array([[1.5e-3, 3e-4], [1.5e-3, np.inf]])
    cov = np.diag(sigma**2)

    def interval(m: float, s: float, b: float) -> float:
        law = NormalDist(m, s)
        return law.cdf(b) - law.cdf(-b)

    first = interval(1e-3, 5e-4, 1.5e-3)
    exact = np.array([first * interval(-2e-4, 1e-4, 3e-4), first])
    estimate = monte_carlo_yield(bounds_test(bounds), mean, cov, np.random.default_rng(12))
    assert estimate.value.shape == (2,)
    assert np.all(estimate.low <= exact) and np.all(exact <= estimate.high)


def test_monte_carlo_interval_covers_the_closed_form() -> None:
    mc = monte_carlo_yield(direct_test(np.array([[1.0], [2.0]]), 1.0), np.array([0.0]),
                           np.array([[1.0]]), np.random.default_rng(0), draws=1000)
    assert mc.method == "monte-carlo" and mc.draws == 1000
    lo, hi = float(mc.low[1]), float(mc.high[1])
    assert lo <= float(mc.value[1]) <= hi
    # |2c| ≤ 1 for c ~ N(0, 1): P = 2Φ(½) − 1 = 0.3829
    assert lo <= 2 * NormalDist().cdf(0.5) - 1 <= hi
