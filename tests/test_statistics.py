"""Vibration statistics: moments and E(Ω) (docs/model.md)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gyrovib.core.statistics import (
    arcsine_excess,
    folded_normal_excess,
    rectified_excess,
    vibration_at_sensor,
)
from gyrovib.core.transmissibility import as_table

from . import reference


def test_tone_moments_by_hand():
    # one tone a3 = 2: M2 = a²/2 = 2, M4 = 3a⁴/8 = 6; C31 = ½·a3·a1·cos(0) = ½·2·3 = 3
    v = vibration_at_sensor([(50.0, (3.0, 1.0, 2.0), (0.0, 90.0, 0.0))])
    assert v.m2 == pytest.approx(2.0)
    assert v.m4 == pytest.approx(6.0)
    assert v.cross(1) == pytest.approx(3.0)
    # C32 = ½·2·1·cos(0° − 90°) = 0
    assert v.cross(2) == pytest.approx(0.0, abs=1e-15)


def test_gaussian_moments_by_hand():
    # σ = (1, 2, 3), ρ = (0.5, -1): M2 = 9, M4 = 3σ⁴ = 243, C31 = 0.5·3·1, C32 = -1·3·2
    v = vibration_at_sensor(rms=(1.0, 2.0, 3.0), coherence=(0.5, -1.0))
    assert (v.m2, v.m4, v.cross(1), v.cross(2)) == pytest.approx((9.0, 243.0, 1.5, -6.0))


def test_mixture_fourth_moment_by_hand():
    # tone a = 2 (M2 = 2, M4 = 6) and σ = 1 (M2 = 1, M4 = 3):
    # M4 = 6 + 3 + 3·[(2 + 1)² − (2² + 1²)] = 9 + 3·4 = 21
    v = vibration_at_sensor([(10.0, (0, 0, 2.0), (0, 0, 0))], rms=(0, 0, 1.0))
    assert v.m2 == pytest.approx(3.0)
    assert v.m4 == pytest.approx(21.0)


def test_same_frequency_tones_add_as_phasors():
    # 1·sin(θ) + 1·sin(θ + 180°) on x3 cancel: no vibration left
    v = vibration_at_sensor([(10.0, (0, 0, 1.0), (0, 0, 0)), (10.0, (0, 0, 1.0), (0, 0, 180))])
    assert v.m2 == pytest.approx(0.0, abs=1e-30)


def test_transmissibility_scales_tone_amplitude():
    # mount gain 0.5 held everywhere: a = 4 → 2 at the sensor, M2 = 2
    v = vibration_at_sensor([(100.0, (0, 0, 4.0), (0, 0, 0))], gains=[as_table([[1, 0.5]])])
    assert v.m2 == pytest.approx(2.0)


def test_arcsine_excess_by_hand():
    # Ω = 0: E = (2/π)·a; a = 1, Ω = 0.5: (2/π)(0.5·π/6 + √0.75) − 0.5
    a = 1.0
    expected = (2 / math.pi) * (0.5 * math.pi / 6 + math.sqrt(0.75)) - 0.5
    got = arcsine_excess([0.0, 0.5, -0.5, 1.0, 3.0], a)
    assert got == pytest.approx([2 / math.pi, expected, expected, 0.0, 0.0], rel=1e-14)


def test_folded_normal_excess_by_hand():
    # Ω = 0: E = σ·√(2/π); σ = 2 → 1.5957691216057308
    assert folded_normal_excess([0.0], 2.0)[0] == pytest.approx(2 * math.sqrt(2 / math.pi))
    # Ω = σ = 1: √(2/π)·e^{-1/2} + erf(1/√2) − 1 = 0.16666...; computed by hand in
    # double precision from the folded-normal mean formula of docs/model.md
    expected = math.sqrt(2 / math.pi) * math.exp(-0.5) + math.erf(1 / math.sqrt(2)) - 1
    assert folded_normal_excess([1.0], 1.0)[0] == pytest.approx(expected, rel=1e-13)


amplitude = st.floats(0.1, 5.0)
rate = st.floats(-8.0, 8.0)


@settings(max_examples=20, deadline=None)
@given(a=amplitude, sigma=st.floats(0.3, 3.0), omega=rate)
def test_sine_on_random_equals_brute_force(a, sigma, omega):
    # a ≤ 5, σ ≥ 0.3: a/σ ≤ 17; brute force: 128 phases × quad over the normal law
    got = rectified_excess(omega, [a], sigma)[0]
    brute = reference.mean_abs(omega, [a], sigma, n_grid=128) - abs(omega)
    assert got == pytest.approx(brute, rel=1e-9, abs=1e-12 * (a + sigma))


@settings(max_examples=15, deadline=None)
@given(a1=amplitude, a2=amplitude, omega=rate)
def test_two_tones_equal_brute_force(a1, a2, omega):
    # tones only: 1e-6 relative (docs/model.md); brute force: 1024 phases × quad per phase
    got = rectified_excess(omega, [a1, a2], 0.0)[0]
    brute = reference.mean_abs(omega, [a1, a2], 0.0, n_grid=1024) - abs(omega)
    assert got == pytest.approx(brute, rel=1e-6, abs=1e-7 * (a1 + a2))


def test_two_tones_plus_random_equal_brute_force():
    # 64 × 64 phases, each with a quadrature over the normal law
    got = rectified_excess([0.0, 1.3], [2.0, 1.0], 0.5)
    brute = [reference.mean_abs(w, [2.0, 1.0], 0.5, n_grid=64) - abs(w) for w in (0.0, 1.3)]
    assert got == pytest.approx(np.array(brute), rel=1e-9)


# Cases where |Ω| is large against the vibration: E(Ω) is tiny (or exactly 0)
# and must keep its relative precision; the reference is nested adaptive
# quadrature (tests/reference.py: excess), written without subtraction.
TAIL_CASES = [
    (55.0, [4.2], 7.9),            # sine on random, E ~ 8e-11... far tail
    (30.0, [2.0], 3.0),            # E ~ 5e-22
    (0.3587, [0.02445], 0.06097),  # E ~ 1e-10
    (-9.3039, [1.0123, 0.2527], 1.4352),
    (-14.399, [1.9235, 0.02885], 2.6226),
    (1.7265353369777827, [1.1479731402513775, 0.5496681528428298, 0.05465523550682091], 0.0),
    (3.3, [2.0, 1.0, 0.7], 0.0),
    (2.9, [2.0, 1.0], 0.0),
]


@pytest.mark.parametrize(("omega", "amps", "sigma"), TAIL_CASES)
def test_excess_keeps_relative_precision_in_the_tails(omega, amps, sigma):
    expected = reference.excess(omega, amps, sigma)
    assert expected > 0
    got = rectified_excess([omega], amps, sigma)[0]
    assert got == pytest.approx(expected, rel=1e-11)


def test_tones_beyond_their_reach_rectify_nothing():
    # |Ω| = 1.999 > Σa = 1.1007: Ω + x3 never changes sign, E is exactly 0
    assert rectified_excess([1.999, -1.999], [0.7392, 0.0455, 0.316], 0.0).tolist() == [0, 0]
    assert rectified_excess([3.5], [2.0, 1.0], 0.0)[0] == 0.0


@settings(max_examples=20, deadline=None)
@given(a1=amplitude, a2=amplitude, a3=amplitude, omega=rate)
def test_three_tones_equal_nested_quadrature(a1, a2, a3, omega):
    got = rectified_excess([omega], [a1, a2, a3], 0.0)[0]
    expected = reference.excess(omega, [a1, a2, a3], 0.0)
    assert got == pytest.approx(expected, rel=1e-9, abs=1e-15 * (a1 + a2 + a3))


@settings(max_examples=10, deadline=None)
@given(a1=amplitude, a2=amplitude, sigma=st.floats(0.3, 3.0), omega=st.floats(-30, 30))
def test_two_tones_on_random_equal_nested_quadrature(a1, a2, sigma, omega):
    got = rectified_excess([omega], [a1, a2], sigma)[0]
    expected = reference.excess(omega, [a1, a2], sigma)
    assert got == pytest.approx(expected, rel=1e-10, abs=1e-300)


@settings(max_examples=30, deadline=None)
@given(amps=st.lists(amplitude, min_size=1, max_size=3), sigma=st.floats(0, 3.0),
       omega=st.floats(-200, 200))
def test_excess_is_never_negative(amps, sigma, omega):
    # <|Ω + x|> ≥ |<Ω + x>| = |Ω| (Jensen): E ≥ 0 always
    assert rectified_excess([omega], amps, sigma)[0] >= 0.0


def _gauss_legendre(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Gauss-Legendre nodes and weights on [−1, 1] by Newton's method on P_n (as
    core.statistics once computed them at run time)."""
    x = np.cos(math.pi * (np.arange(1, n + 1) - 0.25) / (n + 0.5))
    for _ in range(100):
        p0, p1 = np.ones_like(x), x
        for k in range(2, n + 1):
            p0, p1 = p1, ((2 * k - 1) * x * p1 - (k - 1) * p0) / k
        derivative = n * (x * p1 - p0) / (x * x - 1.0)
        step = p1 / derivative
        x = x - step
        if np.max(np.abs(step)) < 1e-16:
            break
    p0, p1 = np.ones_like(x), x
    for k in range(2, n + 1):
        p0, p1 = p1, ((2 * k - 1) * x * p1 - (k - 1) * p0) / k
    derivative = n * (x * p1 - p0) / (x * x - 1.0)
    weights = 2.0 / ((1.0 - x * x) * derivative**2)
    nodes = x[::-1].copy()
    return nodes, weights[::-1].copy()


def test_the_written_out_gauss_legendre_rule_is_the_computed_one() -> None:
    # core.statistics writes the 24-point rule out (a first-run cost otherwise);
    # it must be what Newton's method on P_24 gives, to the last bit, and integrate
    # x^46 exactly over [-1, 1] (2/47: a 24-point rule is exact to degree 47)
    from gyrovib.core import statistics

    x, w = _gauss_legendre(statistics._GL_N)
    assert np.array_equal(x, np.array(statistics._GL24_X))
    assert np.array_equal(w, np.array(statistics._GL24_W))
    assert float(np.sum(w * x**46)) == pytest.approx(2.0 / 47.0, rel=1e-13)
    # and it is numpy's Golub-Welsch rule (an independent computation) to rounding
    xr, wr = np.polynomial.legendre.leggauss(statistics._GL_N)
    np.testing.assert_allclose(x, xr, rtol=0, atol=1e-15)
    np.testing.assert_allclose(w, wr, rtol=1e-12)  # Golub-Welsch loses ~1e-13 at the ends
