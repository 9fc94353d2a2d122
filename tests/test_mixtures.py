"""E(Ω) for mixtures of many tones, with and without a Gaussian part (docs/model.md §4).

gyrovib computes these by one contour integral of the moment generating
function (core/mixtures.py: _contour_excess). Every expected value here comes
from tests/reference.py by another route: QUADPACK's Fourier integral of
docs/model.md's real-axis formula, the brute-force phase average of the
folded-normal excess, or nested adaptive quadrature over the phases.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gyrovib.core.statistics import rectified_excess
from gyrovib.errors import ModelError

from . import reference

amplitude = st.floats(0.05, 2.0)


@settings(max_examples=25, deadline=None)
@given(amps=st.lists(amplitude, min_size=3, max_size=10), sigma=st.floats(0.1, 2.0),
       where=st.floats(0.02, 0.7))
def test_tones_on_random_equal_the_characteristic_integral(amps, sigma, where):
    # Ω inside the peak (where E is not tiny): docs/model.md's
    # (2/π)∫cos(Ωt)(1 − ΠJ0·e^{−σ²t²/2})/t² dt by QAWF, whose error is absolute
    # (~1e-11 of the scale: the oscillating integrand cancels); the tail is
    # checked against the brute force below
    omega = where * (sum(amps) + sigma)
    got = rectified_excess([omega], amps, sigma)[0]
    expected = reference.excess_characteristic(omega, amps, sigma)
    scale = math.sqrt(sum(a * a for a in amps) / 2 + sigma**2)
    assert got == pytest.approx(expected, rel=1e-9, abs=1e-10 * scale)


@settings(max_examples=25, deadline=None)
@given(amps=st.lists(amplitude, min_size=5, max_size=10), where=st.floats(0.02, 0.7))
def test_tones_alone_equal_the_characteristic_integral(amps, where):
    # five tones or more: ΠJ0 decays like t^-5/2 and QAWF holds ~1e-10 of the
    # scale (with three tones it drifts to 1e-7; those are checked against
    # nested quadrature in test_statistics.py, four tones below)
    omega = where * sum(amps)
    got = rectified_excess([omega], amps, 0.0)[0]
    expected = reference.excess_characteristic(omega, amps, 0.0)
    scale = math.sqrt(sum(a * a for a in amps) / 2)
    assert got == pytest.approx(expected, rel=1e-7, abs=1e-10 * scale)


# Ω outside the peak, down the tail: E from 1e-3 to 1e-40 of the scale. The
# brute force averages the folded-normal excess over n phases per tone
# (product grid; geometric convergence once n ≫ (w + Σa)·a/σ²).
TAIL_RANDOM = [
    (2.0, [1.0, 0.5, 0.3], 0.4, 64),
    (4.0, [1.0, 0.5, 0.3], 0.4, 64),
    (-6.5, [1.0, 0.5, 0.3], 0.4, 96),
    (3.0, [0.6, 0.5, 0.4, 0.3], 0.5, 40),
    (7.5, [0.6, 0.5, 0.4, 0.3], 0.5, 48),
    (1.2, [0.3, 0.3, 0.2, 0.2, 0.1], 0.3, 20),
    (3.5, [0.3, 0.3, 0.2, 0.2, 0.1], 0.3, 24),
]


@pytest.mark.parametrize(("omega", "amps", "sigma", "n"), TAIL_RANDOM)
def test_tones_on_random_keep_relative_precision_in_the_tail(omega, amps, sigma, n):
    expected = reference.excess_phase_grid(omega, amps, sigma, n)
    assert expected > 0
    got = rectified_excess([omega], amps, sigma)[0]
    assert got == pytest.approx(expected, rel=1e-9)


@pytest.mark.parametrize(("omega", "amps"), [
    (1.3, [1.5, 1.2, 0.7, 0.3]),    # inside the peak, E ≈ 0.3
    (3.6, [1.5, 1.2, 0.7, 0.3]),    # 0.1 below the reach Σa = 3.7: E ≈ 1.4e-5
])
def test_four_tones_alone_equal_nested_quadrature(omega, amps):
    expected = reference.excess_four_tones(omega, amps)
    got = rectified_excess([omega], amps, 0.0)[0]
    assert got == pytest.approx(expected, rel=1e-7)


@settings(max_examples=20, deadline=None)
@given(amps=st.lists(amplitude, min_size=2, max_size=64), beyond=st.floats(1.0, 100.0))
def test_tones_alone_rectify_nothing_beyond_their_reach(amps, beyond):
    # |Ω| ≥ Σa: Ω + x3 never changes sign, so E is exactly 0 (docs/model.md §4)
    omega = beyond * math.fsum(amps)
    assert rectified_excess([omega, -omega], amps, 0.0).tolist() == [0.0, 0.0]


@settings(max_examples=15, deadline=None)
@given(amps=st.lists(amplitude, min_size=2, max_size=12), sigma=st.floats(0, 1.0),
       omega=st.lists(st.floats(-20, 20), min_size=1, max_size=40))
def test_a_rate_array_gives_each_rate_alone(amps, sigma, omega):
    # rates share contours in groups: the value at a rate must not depend on its
    # company beyond the quadrature's tolerance (1e-11 with a random part; the
    # truncation of the tones' algebraic tail, 1e-9, for tones alone)
    together = rectified_excess(omega, amps, sigma)
    alone = np.array([rectified_excess([w], amps, sigma)[0] for w in omega])
    assert together == pytest.approx(alone, rel=1e-10 if sigma > 0 else 1e-8, abs=1e-300)


def test_sixty_four_tones_on_random_at_zero_rate():
    # at Ω = 0 and many comparable tones X is nearly Gaussian: E(0) = <|X|> lies
    # between √(2/π)·√M2 (Gaussian) and √M2 (Jensen); the QAWF integral fixes it
    amps = list(np.linspace(0.05, 1.0, 64))
    sigma = 0.5
    got = rectified_excess([0.3], amps, sigma)[0]
    expected = reference.excess_characteristic(0.3, amps, sigma)
    assert got == pytest.approx(expected, rel=1e-9)


def test_a_contour_too_long_is_refused_with_advice(monkeypatch):
    # the cap on Bessel values is a resource limit: past it the model says
    # what to change instead of running out of memory or time (the real cap,
    # 2^23, is not reached by 64 tones; lowered here to reach it)
    from gyrovib.core import mixtures

    monkeypatch.setattr(mixtures, "_MAX_CONTOUR_VALUES", 1000)
    with pytest.raises(ModelError, match="drop it, or merge the smallest tones"):
        rectified_excess([0.1], [1.0, 0.7, 0.5, 0.3], 1e-6)


@pytest.mark.parametrize(("amps", "slack"), [
    ([1.0, 0.7, 0.4], 1e-12),
    ([1.0, 0.7, 0.5, 0.3], 1e-12),
    # two tones: the contour's u^-3 tail is too long for σ = 1e-9, and the
    # phase grid takes over as before, capped at 2^22 nodes (5e-8 relative here)
    ([1.0, 0.7], 1e-7),
])
def test_a_tiny_random_part_changes_almost_nothing(amps, slack):
    # |·| is 1-Lipschitz and convex, so adding σZ moves <|Ω + x|> by at most
    # σ·<|Z|> = σ·√(2/π) and never down; tones alone from the closed routes
    # checked in test_statistics.py and above
    sigma = 1e-9
    rates = [0.0, 0.3, 1.1]
    alone = rectified_excess(rates, amps, 0.0)
    mixed = rectified_excess(rates, amps, sigma)
    assert np.all(mixed >= alone * (1 - slack))
    assert np.all(mixed <= (alone + sigma * math.sqrt(2 / math.pi)) * (1 + slack))


def test_bessel_functions_equal_scipy():
    # the engine's own I0, I1 (trapezoid below |z| = 25, Hankel expansion above)
    # against scipy.special's AMOS/Cephes values; relative 1e-12 away from J0's
    # zeros (z near the imaginary axis), where only the absolute error is small
    from scipy import special

    from gyrovib.core.mixtures import _i0e_i1e, _log_i0e

    rng = np.random.default_rng(14)
    z = np.concatenate([rng.uniform(0, 60, 4000) + 1j * rng.uniform(0, 400, 4000),
                        rng.uniform(0.5, 3, 1000) + 1j * rng.uniform(0, 30, 1000)])
    # (compared as exp of the difference: the logarithms may differ by 2πi·k)
    ratio = np.exp(_log_i0e(z) - np.log(special.ive(0, z)))
    assert ratio == pytest.approx(np.ones(z.size), abs=1e-12)
    x = np.concatenate([np.linspace(0, 100, 2001), np.geomspace(1e-8, 1e8, 400)])
    i0, i1 = _i0e_i1e(x)
    assert i0 == pytest.approx(special.i0e(x), rel=1e-13)
    assert i1 == pytest.approx(special.i1e(x), rel=1e-13)


@pytest.mark.parametrize(("amps", "sigma", "route"), [
    ([2.0, 1.0, 0.5], 0.0, "_few_tones_excess"),
    ([1.0, 0.8, 0.6, 0.4], 0.0, "_contour_excess"),
    ([1.0, 0.8], 0.1, "_contour_excess"),
])
def test_rates_beyond_reach_are_not_computed(monkeypatch, amps, sigma, route):
    # a sweep far past the vibration: only the rates below Σa (+ 40σ) reach the
    # quadrature; the others are 0 without work (E = 0 exactly, or < e^-800)
    from gyrovib.core import statistics

    seen: list[int] = []
    original = getattr(statistics, route)

    def spy(w, *args):
        seen.append(w.size)
        return original(w, *args)

    monkeypatch.setattr(statistics, route, spy)
    rates = np.linspace(-500, 500, 2001)  # step 0.5 deg/s: a handful within reach
    out = rectified_excess(rates, amps, sigma)
    reach = sum(amps) + 40 * sigma
    assert seen == [int(np.sum(np.abs(rates) < reach))]
    assert np.all(out[np.abs(rates) >= reach] == 0.0)
