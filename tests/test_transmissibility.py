"""Breakpoint tables: log-log interpolation and the exact PSD integral (eq. 6)."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import integrate

from gyrovib.core.transmissibility import as_table, loglog_interp, psd_variance


def test_loglog_interpolation_is_a_power_law_between_breakpoints():
    # (10 Hz, 1) to (1000 Hz, 0.01): slope -1 on log-log axes, so g(100) = 0.1
    table = as_table([[10, 1.0], [1000, 0.01]])
    assert loglog_interp(table, 100.0) == pytest.approx(0.1, rel=1e-14)
    # held constant past the ends (docs/model.md): 1 below 10 Hz, 0.01 above 1 kHz
    assert loglog_interp(table, [1.0, 1e5]).tolist() == [1.0, 0.01]


def test_psd_is_zero_outside_its_band_and_steps_are_right_continuous():
    table = as_table([[20, 1.0], [100, 1.0], [100, 4.0], [200, 4.0]])
    values = loglog_interp(table, [10, 50, 100, 150, 300], hold=False)
    assert values.tolist() == [0.0, 1.0, 4.0, 4.0, 0.0]


def test_flat_psd_variance_is_level_times_bandwidth():
    # eq. (6): σ² = S·Δf = 1e-3 · (2000 − 20)
    assert psd_variance(as_table([[20, 1e-3], [2000, 1e-3]])) == pytest.approx(1.98, rel=1e-14)


def test_minus_six_db_per_octave_slope():
    # S = S0·(f0/f)², S0 = 1 at f0 = 10 Hz, to 40 Hz: ∫ 100/f² df = 100·(1/10 − 1/40) = 7.5
    assert psd_variance(as_table([[10, 1.0], [40, 1.0 / 16]])) == pytest.approx(7.5, rel=1e-13)


def test_minus_three_db_per_octave_is_the_logarithmic_case():
    # S = 10/f between 10 and 1000 Hz: ∫ 10/f df = 10·ln(100)
    got = psd_variance(as_table([[10, 1.0], [1000, 0.01]]))
    assert got == pytest.approx(10 * math.log(100), rel=1e-13)


def test_mount_gain_scales_psd_by_its_square():
    # flat S = 1 on 10..100 Hz, ν = 0.5 everywhere (held table) → σ² = 0.25·90
    psd = as_table([[10, 1.0], [100, 1.0]])
    assert psd_variance(psd, (as_table([[1, 0.5]]),)) == pytest.approx(22.5, rel=1e-14)


def test_zero_endpoint_makes_the_segment_zero():
    # log-log interpolation towards 0 is undefined; such a segment carries nothing
    assert psd_variance(as_table([[10, 0.0], [100, 1.0], [200, 1.0]])) == pytest.approx(100.0)


positive = st.floats(1e-3, 1e2)


# scipy's quad per segment takes up to ~50 ms an example: no per-example deadline
@settings(max_examples=100, deadline=None)
@given(
    st.lists(st.tuples(st.floats(1, 3000), positive), min_size=2, max_size=6),
    st.lists(st.tuples(st.floats(1, 3000), st.floats(0.05, 3)), min_size=1, max_size=4),
)
def test_psd_integral_equals_adaptive_quadrature(psd_points, gain_points):
    # exact segment integral vs scipy.integrate.quad of the interpolated integrand
    psd_points = sorted(psd_points)
    gain_points = sorted(gain_points)
    psd = as_table(psd_points)
    gain = as_table(gain_points)
    got = psd_variance(psd, (gain,))
    breaks = np.unique(np.concatenate([psd[0], gain[0]]))
    breaks = breaks[(breaks >= psd[0][0]) & (breaks <= psd[0][-1])]
    expected = 0.0

    def integrand(f):
        return float(loglog_interp(psd, f, hold=False) * loglog_interp(gain, f) ** 2)

    for lo, hi in itertools.pairwise(breaks):
        if hi - lo <= 1e-12 * hi:
            # a few ulps wide: quad cannot resolve it, the midpoint rule is exact enough
            expected += (hi - lo) * integrand(0.5 * (lo + hi))
            continue
        val, _ = integrate.quad(integrand, lo, hi, epsrel=1e-12, epsabs=0, limit=200)
        expected += val
    # absolute floor: rounding of the frequencies themselves (quad cannot resolve
    # bands narrower than a few ulp of f)
    floor = 1e-12 * psd[1].max() * gain[1].max() ** 2 * psd[0][-1]
    assert got == pytest.approx(expected, rel=1e-9, abs=floor)
