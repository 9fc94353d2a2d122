"""Linear vibration and the g² term Δ0(6) (docs/model.md section 8).

Expected values are worked by hand from docs/model.md section 8 in the comments, or
come from the brute-force quadrature of gyrovib.core.numeric.linear_average
(averaging Σ G_jk·a_j·a_k over the vibration itself).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gyrovib.core.analysis import (
    ADDITIVE_TERMS,
    COEFFICIENTS,
    EXTRA_TERMS,
    profile_multipliers,
    stack_multipliers,
    vibration_error,
)
from gyrovib.core.linear import (
    acceleration_moments,
    effective_vre,
    g2_term,
    linear_vibration,
    mean_square,
)
from gyrovib.core.numeric import linear_average, simulate
from gyrovib.core.statistics import vibration_at_sensor
from gyrovib.errors import ModelError

G0 = 9.80665  # m/s² per g

# Tones A = (1, 2, 3) g with phases (0, 90, 0)°, random σ = (1, 2, 0.5) g with
# ρ12 = 0.5, ρ13 = −0.2, ρ23 = 0 (docs/model.md section 8):
#   ⟨a1²⟩ = ½·1² + 1² = 1.5        ⟨a2²⟩ = ½·2² + 2² = 6        ⟨a3²⟩ = ½·3² + 0.5² = 4.75
#   ⟨a1a2⟩ = ½·1·2·cos(−90°) + 0.5·1·2 = 1
#   ⟨a1a3⟩ = ½·1·3·cos(0) − 0.2·1·0.5 = 1.4
#   ⟨a2a3⟩ = ½·2·3·cos(90°) + 0 = 0
AMPS = [[1.0, 2.0, 3.0]]
PHASES = [[0.0, 90.0, 0.0]]
SIGMA = (1.0, 2.0, 0.5)
RHO = (0.5, -0.2, 0.0)
MOMENTS = (1.5, 6.0, 4.75, 1.0, 1.4, 0.0)
# G = (4e-4, 4e-4, 4e-4, 1e-4, −2e-4, 3e-4) deg/s/g²:
#   Δ0(6) = 4e-4·(1.5 + 6 + 4.75) + 1e-4·1 − 2e-4·1.4 + 3e-4·0 = 4.9e-3 − 1.8e-4 = 4.72e-3
G = (4e-4, 4e-4, 4e-4, 1e-4, -2e-4, 3e-4)
DELTA6 = 4.72e-3


def test_moments_by_hand() -> None:
    got = acceleration_moments(AMPS, PHASES, SIGMA, RHO)
    assert got == pytest.approx(MOMENTS, abs=1e-15)


def test_g2_term_by_hand_and_vectorised() -> None:
    one = acceleration_moments(AMPS, PHASES, SIGMA, RHO)
    # two profiles: the one above and the same vibration doubled (moments × 4)
    moments = np.stack([one, 4 * one])
    sens = np.array([G, [2 * g for g in G], [0.0] * 6])
    got = g2_term(sens, moments)
    assert got.shape == (3, 2)
    assert got[0, 0] == pytest.approx(DELTA6, rel=1e-12)
    assert got[0, 1] == pytest.approx(4 * DELTA6, rel=1e-12)
    assert got[1, 0] == pytest.approx(2 * DELTA6, rel=1e-12)
    assert np.all(got[2] == 0)
    # Σ⟨a_j²⟩ = 12.25 g²; effective VRE = |Δ0(6)|/12.25
    assert mean_square(one) == pytest.approx(12.25)
    assert effective_vre(sens, moments)[0, 0] == pytest.approx(DELTA6 / 12.25, rel=1e-12)


def test_batched_profiles_broadcast() -> None:
    # (profiles=2, K=1, 3): the second profile has no tone, only the random part
    amps = np.array([AMPS, [[0.0, 0.0, 0.0]]])
    got = acceleration_moments(amps, np.zeros_like(amps), np.array([SIGMA, SIGMA]),
                               np.array([RHO, RHO]))
    assert got.shape == (2, 6)
    # random only: σ² = (1, 4, 0.25), ρσσ = (1, −0.1, 0)
    assert got[1] == pytest.approx((1.0, 4.0, 0.25, 1.0, -0.1, 0.0), abs=1e-15)


def test_adis16460_scale_of_the_effect() -> None:
    # docs/model.md section 8: VRE 0.0004 °/s/g² under 3 g rms per axis, independent axes:
    # 0.0004·27 = 0.0108 °/s ≈ 39 °/h
    moments = acceleration_moments(np.zeros((0, 3)), np.zeros((0, 3)), (3.0, 3.0, 3.0))
    got = g2_term([[4e-4, 4e-4, 4e-4, 0, 0, 0]], moments)[0]
    assert got == pytest.approx(0.0108, rel=1e-12)
    assert got * 3600 == pytest.approx(38.88, rel=1e-12)


@pytest.mark.parametrize("bad", [
    dict(sigma=(-1.0, 0.0, 0.0)), dict(coherence=(1.5, 0.0, 0.0)),
    dict(amplitudes=[[math.nan, 0.0, 0.0]]),
])
def test_bad_input_refused(bad: dict) -> None:
    args = dict(amplitudes=AMPS, phases=PHASES, sigma=SIGMA, coherence=RHO)
    args.update(bad)
    with pytest.raises(ValueError):
        acceleration_moments(**args)


def test_brute_force_quadrature_matches_closed_form() -> None:
    lin = linear_vibration(AMPS, PHASES, SIGMA, RHO)
    total, moments = linear_average([G], lin)
    assert moments == pytest.approx(MOMENTS, abs=1e-13)
    assert total[0] == pytest.approx(DELTA6, rel=1e-12)


@settings(max_examples=40, deadline=None)
@given(
    amps=st.lists(st.lists(st.floats(0.0, 5.0), min_size=3, max_size=3), max_size=3),
    phase=st.floats(-180.0, 180.0),
    sigma=st.lists(st.floats(0.0, 4.0), min_size=3, max_size=3),
    rho=st.floats(-0.9, 0.9),
    g=st.lists(st.floats(-1e-3, 1e-3), min_size=6, max_size=6),
)
def test_closed_form_equals_brute_force(amps: list, phase: float, sigma: list, rho: float,
                                        g: list) -> None:
    """Δ0(6) of docs/model.md section 8 = the average of Σ G_jk a_j a_k over the vibration."""
    a = np.array(amps, dtype=float).reshape(-1, 3)
    ph = np.zeros_like(a)
    ph[:, 1] = phase
    coherence = (rho, 0.3 * rho, 0.0)  # det = 1 − 1.09ρ² > 0: a valid correlation matrix
    lin = linear_vibration(a, ph, sigma, coherence)
    total, moments = linear_average([g], lin)
    closed = g2_term([g], acceleration_moments(a, ph, sigma, coherence))[0]
    scale = float(np.sum(np.abs(g)) * (np.sum(a**2) + np.sum(np.square(sigma))) + 1e-300)
    assert abs(total[0] - closed) <= 1e-12 * scale
    assert moments == pytest.approx(lin.moments(), abs=1e-12 * (1 + float(np.max(moments))))


@settings(max_examples=40, deadline=None)
@given(
    amp=st.floats(0.0, 10.0), sigma=st.floats(0.0, 10.0), rho=st.floats(-1.0, 1.0),
    g=st.floats(-1e-3, 1e-3), rate_scale=st.sampled_from([1.0, 3600.0, math.pi / 180]),
)
def test_unit_changes_change_nothing(amp: float, sigma: float, rho: float, g: float,
                                     rate_scale: float) -> None:
    """g ↔ m/s² and the rate unit: G[rate/(m/s²)²] = G[rate/g²]/g0², moments × g0²."""
    in_g = g2_term([[g, 2 * g, -g, g, 0.5 * g, 0.0]],
                   acceleration_moments([[amp, 0.5 * amp, amp]], [[0, 30, 60]],
                                        (sigma, sigma, 0.5 * sigma), (rho, 0.0, 0.0)))[0]
    in_si = g2_term([[x * rate_scale / G0**2 for x in (g, 2 * g, -g, g, 0.5 * g, 0.0)]],
                    acceleration_moments([[amp * G0, 0.5 * amp * G0, amp * G0]], [[0, 30, 60]],
                                         (sigma * G0, sigma * G0, 0.5 * sigma * G0),
                                         (rho, 0.0, 0.0)))[0]
    assert in_si == pytest.approx(in_g * rate_scale, rel=1e-12, abs=1e-300)


def coefficient_rows(*rows: dict[str, float]) -> np.ndarray:
    out = np.zeros((len(rows), len(COEFFICIENTS)))
    for i, row in enumerate(rows):
        values = {"k1": 1.0, **row}
        for name, value in values.items():
            out[i, COEFFICIENTS.index(name)] = value
    return out


ANGULAR = vibration_at_sensor([(80.0, (0.4, 0.2, 1.5), (0.0, 20.0, 0.0))], rms=(0.3, 0.1, 0.6),
                              coherence=(0.4, 0.2))
SENSORS = coefficient_rows({"A1": 0.01, "k2": 1e-3, "k3": -2e-4, "k4": 5e-5, "k5": 1e-5,
                            "m31": 2e-3, "m32": -1e-3},
                           {"k2": -3e-3, "k4": 1e-4})


def test_g2_term_enters_additive_total_and_rms() -> None:
    omega = np.array([0.0, 0.7, -2.0])
    base = profile_multipliers(ANGULAR, omega)
    lin = profile_multipliers(ANGULAR, omega, acceleration=MOMENTS)
    g2 = np.array([G, [0.0, 0.0, 1e-3, 0.0, 0.0, 0.0]])
    before = vibration_error(SENSORS, base)
    after = vibration_error(SENSORS, lin, g2)
    # Δ0(6) per sensor: 4.72e-3 (above) and 1e-3·⟨a3²⟩ = 4.75e-3
    d6 = np.array([DELTA6, 4.75e-3])[:, None]
    assert EXTRA_TERMS[0] == "g2"
    assert after.extra_terms[..., 0] == pytest.approx(np.broadcast_to(d6, (2, 3)), rel=1e-12)
    assert np.array_equal(after.additive_terms, before.additive_terms)
    assert after.additive == pytest.approx(before.additive + d6, rel=1e-12)
    assert after.total == pytest.approx(before.total + d6, rel=1e-12)
    assert after.rms == pytest.approx(np.sqrt(before.rms**2 + d6**2), rel=1e-12)


def test_results_without_linear_vibration_are_bit_for_bit_unchanged() -> None:
    omega = np.array([0.0, 0.7, -2.0])
    plain = profile_multipliers(ANGULAR, omega)
    # the old expressions of eq. (14)-(16), written out
    c = SENSORS
    col = {n: c[:, COEFFICIENTS.index(n)][:, None] for n in COEFFICIENTS}
    terms = np.stack([col["k1"] * col["A1"] * plain.asymmetry, col["k2"] * plain.m2,
                      col["k4"] * plain.m4, col["m31"] * plain.c31, col["m32"] * plain.c32],
                     axis=-1)
    q = np.stack([3 * col["k3"] * plain.m2 + 5 * col["k5"] * plain.m4, 6 * col["k4"] * plain.m2,
                  10 * col["k5"] * plain.m2], axis=-1)
    mult = q * np.stack([omega, omega**2, omega**3], axis=-1)
    rms = np.sqrt(np.sum(terms**2, axis=-1) + np.sum(mult**2, axis=-1))
    got = vibration_error(c, plain, np.array([G, G]))  # G given, no linear vibration
    assert len(ADDITIVE_TERMS) == 5
    assert np.array_equal(got.additive_terms, terms)
    assert np.array_equal(got.total, terms.sum(axis=-1) + mult.sum(axis=-1))
    assert np.array_equal(got.rms, rms)
    assert np.all(got.extra_terms == 0)
    # stacked with a profile that has linear vibration: the plain one is still unchanged
    both = stack_multipliers([plain, profile_multipliers(ANGULAR, omega, acceleration=MOMENTS)])
    mixed = vibration_error(c, both, np.array([G, G]))
    assert np.array_equal(mixed.total[:, 0], got.total)
    assert np.array_equal(mixed.rms[:, 0], got.rms)


def test_paper_refuses_linear_vibration_with_a_model_reason() -> None:
    tone = vibration_at_sensor([(80.0, (0.0, 0.0, 1.0), (0.0, 0.0, 0.0))])
    with pytest.raises(ModelError) as info:
        profile_multipliers(tone, np.array([0.0]), "paper", acceleration=MOMENTS)
    message = info.value.problems[0].message
    assert "linear vibration" in message and "section 8" in message
    assert "--" not in message


def test_numeric_includes_the_g2_term() -> None:
    # brute force (tones on the exact grid, A1 = 0 so the grid is exact) = closed form
    tone = vibration_at_sensor([(80.0, (0.4, 0.2, 1.5), (0.0, 20.0, 0.0))])
    lin = linear_vibration(AMPS, PHASES, SIGMA, RHO)
    c = SENSORS[1:]
    est = simulate(c, tone, (0.0, 0.0, 0.7), samples=4096, rng=np.random.default_rng(1),
                   linear=lin, g2_sensitivity=[G])
    closed = vibration_error(c, profile_multipliers(tone, np.array(0.7),
                                                    acceleration=lin.moments()), [G])
    assert est.scheme == "grid" and est.stderr[0] == 0
    assert est.total[0] == pytest.approx(float(closed.total[0]), rel=1e-12)
    assert est.multipliers.acceleration == pytest.approx(MOMENTS, abs=1e-13)
