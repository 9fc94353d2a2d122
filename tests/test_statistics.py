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
