"""The vibration error of eq. (13)-(16): hand-worked terms, brute force, the paper."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gyrovib.core.analysis import (
    COEFFICIENTS,
    profile_multipliers,
    vibration_error,
)
from gyrovib.core.statistics import vibration_at_sensor
from gyrovib.errors import ModelError

from . import reference


def coefficient_row(**values: float) -> np.ndarray:
    base = {name: 0.0 for name in COEFFICIENTS}
    base["k1"] = 1.0
    base.update(values)
    return np.array([[base[name] for name in COEFFICIENTS]])


TONE = vibration_at_sensor([(100.0, (1.0, 0.5, 2.0), (0.0, 0.0, 0.0))])  # a3 = 2
RANDOM = vibration_at_sensor(rms=(1.0, 0.5, 2.0), coherence=(0.5, 1.0))  # σ3 = 2


def error_of(vibration, omega, method="exact", **coefficients):
    return vibration_error(coefficient_row(**coefficients),
                           profile_multipliers(vibration, np.array([omega]), method))


class TestTermsByHand:
    """Each term of docs/model.md for a3 = 2 (tone) or σ3 = 2 (random)."""

    def test_asymmetry_tone_at_rest(self):
        # Δ0(1) = ½·k1·A1·(2/π)·a = ½·1e-3·(2/π)·2 = 6.366197723675814e-4
        e = error_of(TONE, 0.0, A1=1e-3)
        assert e.additive_terms[0, 0, 0] == pytest.approx(2e-3 / math.pi, rel=1e-14)

    def test_asymmetry_vanishes_beyond_the_amplitude(self):
        # |Ω| = 3 ≥ a = 2: ω3 never changes sign, so the asymmetry rectifies nothing
        assert error_of(TONE, 3.0, A1=1e-3).additive_terms[0, 0, 0] == 0.0

    def test_asymmetry_random_at_rest(self):
        # ½·A1·√(2/π)·σ = ½·1e-3·0.7978845608·2 = 7.978845608028654e-4
        e = error_of(RANDOM, 0.0, A1=1e-3)
        assert e.additive_terms[0, 0, 0] == pytest.approx(1e-3 * math.sqrt(2 / math.pi))

    def test_k2_term(self):
        # tone: k2·a²/2 = 1e-4·2 = 2e-4; random: k2·σ² = 1e-4·4 = 4e-4
        assert error_of(TONE, 0.0, k2=1e-4).additive_terms[0, 0, 1] == pytest.approx(2e-4)
        assert error_of(RANDOM, 0.0, k2=1e-4).additive_terms[0, 0, 1] == pytest.approx(4e-4)

    def test_k4_terms(self):
        # tone: Δ0(3) = k4·3a⁴/8 = 1e-6·6; Δ(2) = 6·k4·a²/2 = 1.2e-5; at Ω = 10: ×100
        e = error_of(TONE, 10.0, k4=1e-6)
        assert e.additive_terms[0, 0, 2] == pytest.approx(6e-6)
        assert e.multiplicative_coefficients[0, 0, 1] == pytest.approx(1.2e-5)
        assert e.multiplicative[0, 0] == pytest.approx(1.2e-3)
        # random: Δ0(3) = k4·3σ⁴ = 1e-6·48
        assert error_of(RANDOM, 0.0, k4=1e-6).additive_terms[0, 0, 2] == pytest.approx(4.8e-5)

    def test_k3_and_k5_terms(self):
        # tone, Ω = 10: Δ(1) = 3·k3·M2 + 5·k5·M4 = 3·1e-5·2 + 5·1e-7·6 = 6.3e-5
        # Δ(3) = 10·k5·M2 = 2e-6; Δ_VM = 6.3e-5·10 + 2e-6·1000 = 2.63e-3
        e = error_of(TONE, 10.0, k3=1e-5, k5=1e-7)
        assert e.multiplicative_coefficients[0, 0].tolist() == pytest.approx([6.3e-5, 0, 2e-6])
        assert e.multiplicative[0, 0] == pytest.approx(2.63e-3)
        # RMS: √((6.3e-5·10)² + (2e-6·1000)²) = √(3.969e-7 + 4e-6)
        assert e.rms[0, 0] == pytest.approx(math.sqrt(3.969e-7 + 4e-6))

    def test_cross_terms(self):
        # tone: m31·½·a3·a1 = 1e-3·½·2·1 = 1e-3; m32·½·2·0.5 = 2e-3·0.5
        e = error_of(TONE, 0.0, m31=1e-3, m32=2e-3)
        assert e.additive_terms[0, 0, 3:].tolist() == pytest.approx([1e-3, 1e-3])
        # random: m31·ρ31·σ3·σ1 = 1e-3·0.5·2·1 = 1e-3; m32·1·2·0.5 = 2e-3
        e = error_of(RANDOM, 0.0, m31=1e-3, m32=2e-3)
        assert e.additive_terms[0, 0, 3:].tolist() == pytest.approx([1e-3, 2e-3])

    def test_bias_scale_factor_and_additive_cross_axis_do_not_rectify(self):
        e = error_of(TONE, 5.0, k0=1.0, k1=1.2, m1=0.1, m2=0.2)
        assert e.total[0, 0] == 0.0


class TestPaperFormulas:
    """`paper` reproduces the printed eq. (14) and (15) (docs/model.md table)."""

    def test_tone(self):
        # Δ0(1) = k1·A1·0.673·a; Δ0(3) = k4·0.375·a⁴; Δ(1) = k3·1.5a² + k5·1.875a⁴
        e = error_of(TONE, 3.0, "paper", A1=1e-3, k3=1e-5, k4=1e-6, k5=1e-7)
        assert e.additive_terms[0, 0, 0] == pytest.approx(0.673e-3 * 2)  # even for |Ω| ≥ a
        assert e.additive_terms[0, 0, 2] == pytest.approx(1e-6 * 0.375 * 16)
        assert e.multiplicative_coefficients[0, 0].tolist() == pytest.approx(
            [1e-5 * 1.5 * 4 + 1e-7 * 1.875 * 16, 3 * 1e-6 * 4, 5 * 1e-7 * 4])

    def test_random(self):
        # Δ0(1) = k1·A1·0.5·σ; Δ0(3) = k4·σ⁴; Δ(1) = 3k3σ² + 5k5σ⁴; Δ(2) = 6k4σ²; Δ(3) = 10k5σ²
        e = error_of(RANDOM, 1.0, "paper", A1=1e-3, k3=1e-5, k4=1e-6, k5=1e-7)
        assert e.additive_terms[0, 0, 0] == pytest.approx(0.5e-3 * 2)
        assert e.additive_terms[0, 0, 2] == pytest.approx(1e-6 * 16)
        assert e.multiplicative_coefficients[0, 0].tolist() == pytest.approx(
            [3e-5 * 4 + 5e-7 * 16, 6e-6 * 4, 10e-7 * 4])

    @pytest.mark.parametrize(
        "vibration",
        [
            vibration_at_sensor([(1.0, (0, 0, 1), (0, 0, 0)), (2.0, (0, 0, 1), (0, 0, 0))]),
            vibration_at_sensor([(1.0, (0, 0, 1), (0, 0, 0))], rms=(0, 0, 1)),
        ],
        ids=["two tones", "sine on random"],
    )
    def test_refuses_what_the_paper_does_not_cover(self, vibration):
        # core words the refusal in the model's terms; the library adds the advice
        with pytest.raises(ModelError, match="paper's formulas cover one harmonic tone") as info:
            profile_multipliers(vibration, np.array([0.0]), "paper")
        assert info.value.reason == info.value.problems[0].message
        assert "--" not in info.value.reason


# ------------------------------------------------------------ brute force


coef = st.floats(-1e-2, 1e-2)
amp = st.floats(0.0, 3.0)
phase = st.floats(-180, 180)
sig = st.floats(0.2, 2.0)


@st.composite
def sensors(draw):
    return {
        "k0": draw(coef), "k1": draw(st.floats(0.5, 1.5)), "A1": draw(coef),
        "k2": draw(coef), "k3": draw(coef) * 1e-1, "k4": draw(coef) * 1e-2,
        "k5": draw(coef) * 1e-3, "m1": draw(coef), "m2": draw(coef),
        "m31": draw(coef), "m32": draw(coef),
    }


tones = st.lists(
    st.tuples(st.tuples(amp, amp, st.floats(0.1, 3.0)), st.tuples(phase, phase, phase)),
    min_size=0, max_size=2,
)


def _exact_total(c, omega, tone_list, sigma, rho):
    vib = vibration_at_sensor(
        [(10.0 * (k + 1), a, p) for k, (a, p) in enumerate(tone_list)],
        rms=sigma if sigma is not None else None,
        coherence=rho,
    )
    row = np.array([[c[n] for n in COEFFICIENTS]])
    return vibration_error(row, profile_multipliers(vib, np.array([omega[2]]))).total[0, 0]


@settings(max_examples=40, deadline=None)
@given(
    c=sensors(),
    omega=st.tuples(st.floats(-5, 5), st.floats(-5, 5), st.floats(-5, 5)),
    tone_list=tones,
    sigma=st.tuples(sig, sig, sig),
    rho=st.tuples(st.floats(-1, 1), st.floats(-1, 1)),
)
def test_exact_equals_brute_force_with_random_part(c, omega, tone_list, sigma, rho):
    # docs/model.md: 1e-9 relative where σ > 0
    tone_list = tone_list[:1]
    got = _exact_total(c, omega, tone_list, sigma, rho)
    brute = reference.vibration_error(c, omega, tone_list, sigma, rho, n_grid=128)
    scale = sum(abs(v) for v in c.values()) * (1 + 10 ** 4)  # magnitude of the terms
    assert got == pytest.approx(brute, rel=1e-9, abs=1e-13 * scale)


@settings(max_examples=30, deadline=None)
@given(
    c=sensors(),
    omega=st.tuples(st.floats(-5, 5), st.floats(-5, 5), st.floats(-5, 5)),
    tone=st.tuples(st.tuples(amp, amp, st.floats(0.1, 3.0)), st.tuples(phase, phase, phase)),
)
def test_exact_equals_brute_force_single_tone(c, omega, tone):
    # docs/model.md: 1e-9 relative for a single tone
    got = _exact_total(c, omega, [tone], None, (1.0, 1.0))
    brute = reference.vibration_error(c, omega, [tone])
    scale = sum(abs(v) for v in c.values()) * (1 + 10 ** 4)
    assert got == pytest.approx(brute, rel=1e-9, abs=1e-13 * scale)


@settings(max_examples=10, deadline=None)
@given(
    c=sensors(),
    omega=st.tuples(st.floats(-5, 5), st.floats(-5, 5), st.floats(-5, 5)),
    tone_list=st.lists(
        st.tuples(st.tuples(amp, amp, st.floats(0.1, 3.0)), st.tuples(phase, phase, phase)),
        min_size=2, max_size=2,
    ),
)
def test_exact_equals_brute_force_several_tones(c, omega, tone_list):
    # docs/model.md: 1e-6 relative for tones only
    got = _exact_total(c, omega, tone_list, None, (1.0, 1.0))
    brute = reference.vibration_error(c, omega, tone_list, n_grid=512)
    scale = sum(abs(v) for v in c.values()) * (1 + 10 ** 4)
    assert got == pytest.approx(brute, rel=1e-6, abs=1e-12 * scale)
