"""Shares of docs/model.md sections 8 and 10 in the synthesis: vre, k3·M3, k5·M5, split β's.

Every expected number is worked by hand in the comments from docs/model.md sections 6,
8 and 10 (c_A = 0.8320503, c_M = 0.5547002, β = 0.4529108 | 0.2264554 as in
tests/test_synthesis.py).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gyrovib.core.analysis import (
    COLUMN,
    Multipliers,
    profile_multipliers,
    stack_multipliers,
    vibration_error,
)
from gyrovib.core.harmonics import locked_group
from gyrovib.core.linear import acceleration_moments
from gyrovib.core.statistics import vibration_at_sensor
from gyrovib.core.synthesis import (
    BOUNDED,
    ODD_PARTS,
    allocation_constants,
    coefficient_bounds,
)

BUDGET = 0.01
# docs/model.md section 6, eq. (20) with r = 1.5: c_A = r/√(1+r²) = 1.5/√3.25 = 0.8320503,
# c_M = 1/√3.25 = 0.5547002; eq. (24): β_q = v_q·c_M/‖v‖ with v = (1, ½, ½), ‖v‖ = √1.5:
# β1 = 0.5547002/1.2247449 = 0.4529108, β2 = β3 = 0.2264554 (as in test_synthesis.py).
C_A = 0.8320503
BETA = (0.4529108, 0.2264554, 0.2264554)


def one(value: float) -> np.ndarray:
    return np.array([value])


# Odd moments M3 = 0.4, M5 = −1.2 with M2 = 2, M4 = 6, g_A = 0.3, C31 = 1, C32 = ½, Ω̄ = 0.5.
# Additive weights (1, 1, 1, ½, ½) + 1 (k3) + 1 (k5): ‖w‖ = √5.5, α = w·c_A/√5.5:
ALPHA = C_A / math.sqrt(5.5)                       # 0.3547880 for weight 1
ODD = Multipliers(asymmetry=one(0.3), m2=one(2.0), m4=one(6.0), c31=one(1.0), c32=one(0.5),
                  omega=one(0.5), m3=one(0.4), m5=one(-1.2))
ODD_EXPECTED = {
    "A1": ALPHA * BUDGET / 0.3,
    "k2": ALPHA * BUDGET / 2.0,
    "m31": 0.5 * ALPHA * BUDGET / 1.0,
    "m32": 0.5 * ALPHA * BUDGET / 0.5,
    "k3_additive": ALPHA * BUDGET / 0.4,                      # α_k3·Δ*/|M3|
    "k3_linear": BETA[0] / 3 * BUDGET / (0.5 * 3 * 2.0),      # (β1/3)Δ*/(|Ω̄|·3M2)
    "k4_additive": ALPHA * BUDGET / 6.0,                      # α3·Δ*/M4
    "k4_linear": BETA[0] / 3 * BUDGET / (0.5 * 4 * 0.4),      # (β1/3)Δ*/(|Ω̄|·4|M3|)
    "k4_multiplicative": BETA[1] / 2 * BUDGET / (0.25 * 6 * 2.0),   # (β2/2)Δ*/(Ω̄²·6M2)
    "k5_additive": ALPHA * BUDGET / 1.2,                      # α_k5·Δ*/|M5|
    "k5_linear": BETA[0] / 3 * BUDGET / (0.5 * 5 * 6.0),      # (β1/3)Δ*/(|Ω̄|·5M4)
    "k5_quadratic": BETA[1] / 2 * BUDGET / (0.25 * 10 * 0.4),  # (β2/2)Δ*/(Ω̄²·10|M3|)
    "k5_cubic": BETA[2] * BUDGET / (0.125 * 10 * 2.0),       # β3Δ*/(|Ω̄|³·10M2)
}


def test_odd_moment_bounds_by_hand() -> None:
    b = coefficient_bounds(ODD, BUDGET, allocation_constants())
    for name, value in ODD_EXPECTED.items():
        assert float(getattr(b, name)[0]) == pytest.approx(value, rel=2e-6), name
    e = ODD_EXPECTED
    assert float(b.k3[0]) == pytest.approx(min(e["k3_additive"], e["k3_linear"]), rel=2e-6)
    assert float(b.k4[0]) == pytest.approx(
        min(e["k4_additive"], e["k4_linear"], e["k4_multiplicative"]), rel=2e-6)
    assert float(b.k5[0]) == pytest.approx(
        min(e["k5_additive"], e["k5_linear"], e["k5_quadratic"], e["k5_cubic"]), rel=2e-6)
    assert b.vre is None
    assert set(ODD_PARTS) == {"k3_additive", "k3_linear", "k4_linear", "k5_additive",
                              "k5_quadratic"}


def test_symmetric_profiles_keep_the_section_6_shares() -> None:
    # M3 = 0, M5 = 0: no k3/k5 additive share, β1/2 for k3 and k5 (docs/model.md section 6)
    sym = Multipliers(asymmetry=one(0.3), m2=one(2.0), m4=one(6.0), c31=one(1.0),
                      c32=one(0.5), omega=one(0.5), m3=one(0.0), m5=one(0.0))
    b = coefficient_bounds(sym, BUDGET, allocation_constants())
    assert float(b.k3[0]) == pytest.approx(BETA[0] / 2 * BUDGET / 3.0, rel=2e-6)
    assert float(b.k2[0]) == pytest.approx(C_A / math.sqrt(3.5) * BUDGET / 2.0, rel=2e-6)
    assert float(b.k3_additive[0]) == math.inf and float(b.k4_linear[0]) == math.inf


# Linear vibration, Σ⟨a_j²⟩ = 12.25 g² (tests/test_linear.py): w = (1, 1, 1, ½, ½, 1),
# ‖w‖ = √4.5, α6 = c_A/√4.5 = 0.3922323; vre = α6·Δ*/12.25 = 3.201896e-4 rate/g²
MOMENTS = (1.5, 6.0, 4.75, 1.0, 1.4, 0.0)


def test_vre_bound_by_hand_and_sixth_weight() -> None:
    tone = vibration_at_sensor([(80.0, (0.5, 0.2, 1.0), (0.0, 0.0, 0.0))])
    mu = profile_multipliers(tone, np.array([0.5]), acceleration=MOMENTS)
    b = coefficient_bounds(mu, BUDGET, allocation_constants())
    assert float(b.vre[0]) == pytest.approx(C_A / math.sqrt(4.5) * BUDGET / 12.25, rel=2e-6)
    assert float(b.vre[0]) == pytest.approx(3.201896e-4, rel=2e-6)
    # the other additive shares shrink with it: α2 = c_A/√4.5 for k2, M2 = ½
    assert float(b.k2[0]) == pytest.approx(C_A / math.sqrt(4.5) * BUDGET / 0.5, rel=2e-6)
    # a sixth weight w6 = 2: ‖w‖ = √7.5, α6 = 2·c_A/√7.5
    c6 = allocation_constants(1.5, (1, 1, 1, 0.5, 0.5, 2.0))
    b6 = coefficient_bounds(mu, BUDGET, c6)
    assert float(b6.vre[0]) == pytest.approx(2 * C_A / math.sqrt(7.5) * BUDGET / 12.25, rel=2e-6)
    assert list(c6.alpha) == pytest.approx(list(allocation_constants().alpha), rel=1e-15)


def test_profiles_without_extras_are_bit_for_bit_in_a_mixed_stack() -> None:
    tone = vibration_at_sensor([(80.0, (0.5, 0.2, 1.0), (0.0, 0.0, 0.0))])
    g = locked_group([1, 2], [[0, 0, 0.6], [0, 0, 0.3]], [[0, 0, 0], [0, 0, 70]])
    rates = np.array([0.0, 0.5, -2.0])
    plain = profile_multipliers(tone, rates)
    mixed = stack_multipliers([plain, profile_multipliers(tone, rates, locked=[g],
                                                          acceleration=MOMENTS)])
    c = allocation_constants()
    alone = coefficient_bounds(plain, BUDGET, c)
    both = coefficient_bounds(mixed, BUDGET, c)
    for name in (*BOUNDED, "k4_additive", "k4_multiplicative", "k5_linear", "k5_cubic"):
        assert np.array_equal(getattr(both, name)[0], getattr(alone, name)), name
    assert np.all(both.vre[0] == np.inf) and np.all(np.isfinite(both.vre[1]))


@settings(max_examples=60, deadline=None)
@given(
    # amplitudes of 1e-300 (subnormal powers) are not physical: 0 or at least 1e-3
    a1=st.floats(0.05, 3.0), a2=st.one_of(st.just(0.0), st.floats(1e-3, 3.0)),
    a3=st.one_of(st.just(0.0), st.floats(1e-3, 2.0)),
    p2=st.floats(-180, 180), p3=st.floats(-180, 180),
    tone=st.one_of(st.just(0.0), st.floats(1e-3, 2.0)),
    # σ ≥ tone/40: a tone 100× σ costs a 40,000-node phase grid per rate (25 s for two
    # examples) and checks nothing more about the shares; E(Ω) of a tone on a narrow
    # Gaussian has its own brute-force tests (test_statistics.py)
    sigma=st.one_of(st.just(0.0), st.floats(0.05, 2.0)),
    omega=st.floats(-8.0, 8.0).filter(lambda x: x == 0 or abs(x) > 1e-6),
    accel=st.one_of(st.just(0.0), st.floats(1e-3, 5.0)),
    signs=st.lists(st.sampled_from([-1.0, 1.0]), min_size=7, max_size=7),
)
def test_every_coefficient_at_its_bound_keeps_rms_within_budget(
    a1: float, a2: float, a3: float, p2: float, p3: float, tone: float, sigma: float,
    omega: float, accel: float, signs: list[float],
) -> None:
    """Locked group + tone + random + linear vibration, all at their bounds: Δ_V(RMS) ≤ Δ*.

    The shares of sections 6, 8 and 10 satisfy Σα² + Σβ² = 1 over what the profile has,
    and each share splits Δ(1), Δ(2) equally among its coefficients (docs/model.md 10).
    """
    g = locked_group([1, 2, 3], [[0.3 * a1, 0, a1], [0, 0.2 * a2, a2], [0, 0, a3]],
                     [[0, 0, 0], [0, 0, p2], [0, 30, p3]])
    vib = vibration_at_sensor([(50.0, (0.2 * tone, 0.0, tone), (0, 0, 0))],
                              rms=(0.5 * sigma, 0.0, sigma))
    moments = acceleration_moments([[accel, 0.5 * accel, accel]], [[0, 0, 90]],
                                   (0.5 * accel, 0.0, accel), (0.3, 0.0, 0.0))
    mu = profile_multipliers(vib, np.array([omega]), locked=[g], acceleration=moments)
    b = coefficient_bounds(mu, BUDGET, allocation_constants())
    coeffs = np.zeros((1, 11))
    coeffs[0, COLUMN["k1"]] = 1.0
    for s, name in zip(signs, BOUNDED, strict=True):
        value = float(getattr(b, name)[0])
        if math.isfinite(value):
            coeffs[0, COLUMN[name]] = s * value
    vre = float(b.vre[0])
    g2 = np.array([[vre, vre, vre, 0, 0, 0]]) if math.isfinite(vre) else np.zeros((1, 6))
    err = vibration_error(coeffs, mu, g2)
    assert float(err.rms[0, 0]) <= BUDGET * (1 + 1e-9)
