"""The overlapping Allan deviation kernel and the noise terms read from it
(core/allan.py, docs/model.md section 15)."""

import math

import numpy as np
import pytest

from gyrovib.core.allan import B_FACTOR, noise_terms, oadev, tau_grid


def naive_oadev(y: np.ndarray, tau0: float, m: int) -> float:
    """IEEE 952 overlapping Allan deviation from cluster averages, written out directly:
    σ² = Σ_k (ȳ_{k+m} − ȳ_k)² / (2(n + 1 − 2m)), ȳ_k the mean of y[k:k+m]."""
    n = y.size
    means = np.array([y[k:k + m].mean() for k in range(n - m + 1)])
    d = means[m:] - means[:-m]
    return math.sqrt(float(np.sum(d * d)) / (2.0 * (n + 1 - 2 * m)))


def test_grid_spans_tau0_to_a_third_with_ten_per_decade() -> None:
    m = tau_grid(30_000)
    assert m[0] == 1 and m[-1] == 10_000          # τ0 … n·τ0/3
    assert np.all(np.diff(m) > 0)
    assert np.sum(m >= 10) >= 30                   # three decades above m = 10: ≥ 10 each


@pytest.mark.parametrize("seed", [1, 2])
def test_equals_an_independent_estimator_at_every_tau(seed: int) -> None:
    g = np.random.default_rng(seed)
    n = 1500
    # white noise + a random walk + a large offset: the offset must not cost digits
    y = 40.0 + g.standard_normal(n) + np.cumsum(g.standard_normal(n)) * 0.05
    tau, adev = oadev(y, 0.02, block=97)           # a small block: several blocks per τ
    assert tau[0] == 0.02
    for t, a in zip(tau, adev, strict=True):
        m = round(t / 0.02)
        assert a == pytest.approx(naive_oadev(y, 0.02, m), rel=1e-6)


def test_equals_allantools() -> None:
    allantools = pytest.importorskip("allantools")
    y = np.random.default_rng(5).standard_normal(4000)
    tau, adev = oadev(y, 0.01)
    taus, ad, _, _ = allantools.oadev(y, rate=100.0, data_type="freq",
                                      taus=tau)
    assert np.allclose(taus, tau) and np.allclose(ad, adev, rtol=1e-6, atol=0)


# Simulated truth: N in deg/√s, K in deg/s/√s at τ0 = 0.01 s. White rate noise of
# standard deviation N/√τ0 has σ(τ) = N/√τ; a random walk of steps K·√τ0 has K²τ/3.
# A figure must come within 2 of its stated standard uncertainties (k = 2, about 95 %),
# and the uncertainty must be small enough for that to be a test (below 5 %).
N_TRUE, K_TRUE, TAU0, SAMPLES = 0.01, 1e-4, 0.01, 200_000


@pytest.mark.parametrize("seed", [11, 12])
def test_arw_of_white_noise_within_its_uncertainty(seed: int) -> None:
    y = np.random.default_rng(seed).standard_normal(SAMPLES) * N_TRUE / math.sqrt(TAU0)
    tau, adev = oadev(y, TAU0)
    terms = noise_terms(tau, adev, SAMPLES + 1, TAU0)
    assert abs(terms.arw.value - N_TRUE) <= 2 * terms.arw.uncertainty
    assert terms.arw.uncertainty < 0.05 * N_TRUE


@pytest.mark.parametrize("seed", [21, 22])
def test_rrw_of_a_random_walk_within_its_uncertainty(seed: int) -> None:
    steps = np.random.default_rng(seed).standard_normal(SAMPLES)
    y = np.cumsum(steps) * K_TRUE * math.sqrt(TAU0)
    tau, adev = oadev(y, TAU0)
    terms = noise_terms(tau, adev, SAMPLES + 1, TAU0)
    assert abs(terms.rrw.value - K_TRUE) <= 2 * terms.rrw.uncertainty
    assert terms.rrw.uncertainty < 0.05 * K_TRUE


def test_both_terms_of_a_mixed_record() -> None:
    g = np.random.default_rng(31)
    y = (g.standard_normal(SAMPLES) * N_TRUE / math.sqrt(TAU0)
         + np.cumsum(g.standard_normal(SAMPLES)) * K_TRUE * math.sqrt(TAU0))
    tau, adev = oadev(y, TAU0)
    terms = noise_terms(tau, adev, SAMPLES + 1, TAU0)
    assert abs(terms.arw.value - N_TRUE) <= 2 * terms.arw.uncertainty
    assert abs(terms.rrw.value - K_TRUE) <= 2 * terms.rrw.uncertainty


def test_bias_instability_is_the_curve_minimum_over_0664() -> None:
    g = np.random.default_rng(41)
    y = g.standard_normal(50_000) + np.cumsum(g.standard_normal(50_000)) * 0.01
    tau, adev = oadev(y, 0.01)
    terms = noise_terms(tau, adev, 50_001, 0.01)
    assert terms.bias_instability.value == float(adev.min()) / 0.664
    assert B_FACTOR == 0.664
    assert terms.bias_instability.tau == float(tau[np.argmin(adev)])


def test_a_record_without_noise_reads_zero_not_an_error() -> None:
    # a constant rate (a quantised sensor at rest that never flips a bit): σ = 0 at
    # every τ, and every figure is 0 — not a failed fit
    tau, adev = oadev(np.full(1000, 0.25), 0.1)
    assert not adev.any()
    terms = noise_terms(tau, adev, 1001, 0.1)
    assert (terms.arw.value, terms.bias_instability.value, terms.rrw.value) == (0, 0, 0)
