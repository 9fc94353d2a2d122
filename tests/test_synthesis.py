"""The synthesis of docs/model.md: constants, bounds worked by hand, tightness.

Every expected number below is derived in a comment from docs/model.md; the code
under test is never used to produce an expected value.
"""

from __future__ import annotations

import math
import textwrap
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gyrovib import api, units
from gyrovib.core.analysis import Multipliers, vibration_error
from gyrovib.core.synthesis import (
    BOUNDED,
    PAPER_CONSTANTS,
    allocation_constants,
    coefficient_bounds,
)
from gyrovib.errors import OptionError

BUDGET = 0.01  # Δ* in deg/s throughout

# ---------------------------------------------------------------- constants by hand
# c_A = r/√(1+r²) = 1.5/√3.25 = 0.8320503, c_M = 1/√3.25 = 0.5547002          (eq. 20)
# ‖w‖ = √(1+1+1+¼+¼) = √3.5 = 1.8708287; α1..3 = 0.8320503/1.8708287 = 0.4447496,
#   α4,5 = ½·0.4447496 = 0.2223748                                             (eq. 21)
# ‖v‖ = √(1+¼+¼) = √1.5 = 1.2247449; β1 = 0.5547002/1.2247449 = 0.4529108,
#   β2,3 = 0.2264554                                                          (eq. 24)
# k3 and k5-linear: β1/2 = 0.2264554 (docs/model.md section 6: they add linearly inside Δ(1);
#   the paper prints 0.35 ≈ β1/√2, which can overrun the share by √2)
C_A, C_M = 0.8320503, 0.5547002
ALPHA = (0.4447496, 0.4447496, 0.4447496, 0.2223748, 0.2223748)
BETA = (0.4529108, 0.2264554, 0.2264554)
SHARE_K3 = 0.2264554


def test_default_allocation_constants_by_hand() -> None:
    c = allocation_constants()
    assert c.c_additive == pytest.approx(C_A, rel=1e-6)
    assert c.c_multiplicative == pytest.approx(C_M, rel=1e-6)
    assert c.alpha == pytest.approx(ALPHA, rel=1e-6)
    assert c.beta == pytest.approx(BETA, rel=1e-6)
    assert c.k3 == pytest.approx(SHARE_K3, rel=1e-6)
    assert c.k5_linear == pytest.approx(SHARE_K3, rel=1e-6)
    # the shares exhaust the budget in the RSS sense: Σα² + Σβ² = c_A² + c_M² = 1
    assert float(np.sum(c.alpha**2) + np.sum(c.beta**2)) == pytest.approx(1.0, rel=1e-12)


def test_paper_constants_are_the_printed_numbers() -> None:
    # eq. (22): 0.44 for A1, k2, k4 and 0.22 for m31, m32; eq. (25): 0.49, 0.24, 0.35
    p = PAPER_CONSTANTS
    assert list(p.alpha) == [0.44, 0.44, 0.44, 0.22, 0.22]
    assert list(p.beta) == [0.49, 0.24, 0.24]
    assert p.k3 == 0.35 and p.k5_linear == 0.35
    # the printed α are the derived ones rounded to 2 digits; 0.49 is not (docs/model.md)
    derived = allocation_constants()
    assert [round(x, 2) for x in derived.alpha] == [0.44, 0.44, 0.44, 0.22, 0.22]
    assert round(float(derived.beta[0]), 2) == 0.45 != 0.49


def test_custom_allocation_constants() -> None:
    # r = 3: c_A = 3/√10 = 0.9486833, c_M = 1/√10 = 0.3162278; w = (2,1,1,1,1): ‖w‖ = √8,
    # α1 = 2·0.9486833/2.8284271 = 0.6708204; v = (1,1,1): β = 0.3162278/√3 = 0.1825742
    c = allocation_constants(3.0, (2, 1, 1, 1, 1), (1, 1, 1))
    assert c.alpha[0] == pytest.approx(0.6708204, rel=1e-6)
    assert c.alpha[1] == pytest.approx(0.3354102, rel=1e-6)
    assert c.beta == pytest.approx([0.1825742] * 3, rel=1e-6)
    assert c.k3 == pytest.approx(0.1825742 / 2, rel=1e-6)       # β1/2, docs/model.md section 6


@pytest.mark.parametrize("bad", [
    dict(r=0.0), dict(r=-1.0), dict(r=math.nan), dict(r=math.inf),
    dict(w=(1, 1, 1, 0, 1)), dict(v=(1, -0.5, 0.5)), dict(w=(1, 1, 1)),
])
def test_allocation_refuses_non_positive_or_non_finite(bad: dict) -> None:
    with pytest.raises(ValueError):
        allocation_constants(**bad)


# ---------------------------------------------------------------- catalogues

TONE_PROFILE = """
  - id: tone
    rate: [0, 0, 0.5]
    harmonic:
      - frequency: 100
        amplitude: [1.0, 0.5, 2.0]
"""
RANDOM_PROFILE = """
  - id: noise
    rate: [0, 0, 2.0]
    random:
      rms: [0.5, 0.5, 1.0]
"""


def write(tmp_path: Path, body: str, name: str = "cat.yaml") -> Path:
    path = tmp_path / name
    path.write_text("gyrovib: 1\n" + textwrap.dedent(body))
    return path


def profiles_catalog(tmp_path: Path, extra: str = "") -> api.Catalog:
    return api.load([write(tmp_path, "profiles:" + TONE_PROFILE + RANDOM_PROFILE + extra)])


def bounds_of(result: api.BoundsResult, j: int) -> dict[str, float]:
    b = result.bounds
    names = (*BOUNDED, "k4_additive", "k4_multiplicative", "k5_linear", "k5_cubic")
    return {n: float(getattr(b, n)[j]) for n in names}


# ---------------------------------------------------------------- single tone, by hand
# Tone a3 = 2, a1 = 1, a2 = ½ deg/s, in phase; Ω̄ = 0.5 deg/s; Δ* = 0.01 deg/s.
# Exact moments (docs/model.md): M2 = a²/2 = 2, M4 = 3a⁴/8 = 6, C31 = ½·2·1 = 1, C32 = ½.
# E(0.5) = (2/π)(0.5·asin(0.25) + √(4 − 0.25)) − 0.5
#        = 0.6366198·(0.1263402 + 1.9364917) − 0.5 = 0.8132395;  g_A = ½E = 0.4066198.
TONE_EXACT = {
    "A1": 0.4447496 * BUDGET / 0.4066198,          # α1·Δ*/g_A = 0.0109377
    "k2": 0.4447496 * BUDGET / 2,                  # α2·Δ*/M2 = 0.0022237
    "k4_additive": 0.4447496 * BUDGET / 6,         # α3·Δ*/M4 = 0.00074125
    "k4_multiplicative": 0.2264554 * BUDGET / (0.25 * 6 * 2),   # β2Δ*/(Ω̄²·6M2) = 0.00075485
    "k3": 0.2264554 * BUDGET / (0.5 * 3 * 2),      # (β1/2)Δ*/(|Ω̄|·3M2) = 0.000754851
    "k5_linear": 0.2264554 * BUDGET / (0.5 * 5 * 6),   # /(|Ω̄|·5M4) = 0.000150970
    "k5_cubic": 0.2264554 * BUDGET / (0.125 * 10 * 2),  # β3Δ*/(|Ω̄|³·10M2) = 0.000905822
    "m31": 0.2223748 * BUDGET / 1.0,               # α4·Δ*/|C31|
    "m32": 0.2223748 * BUDGET / 0.5,               # α5·Δ*/|C32|
}
TONE_EXACT["k4"] = TONE_EXACT["k4_additive"]      # 0.00074125 < 0.00075485
TONE_EXACT["k5"] = TONE_EXACT["k5_linear"]        # 0.000150970 < 0.000905822

# Paper (docs/model.md table, harmonic column): g_A = 0.673a = 1.346, M2' = ½a² = 2,
# M4' = 0.375a⁴ = 6, 3M2' = 1.5a² = 6, 5M4' = 1.875a⁴ = 30, 6M2' = 3a² = 12,
# 10M2' = 5a² = 20; printed constants 0.44, 0.22, 0.49, 0.24, 0.35.
TONE_PAPER = {
    "A1": 0.44 * BUDGET / 1.346,                   # 0.00326895
    "k2": 0.44 * BUDGET / 2,                       # 0.0022
    "k4_additive": 0.44 * BUDGET / 6,              # 0.000733333
    "k4_multiplicative": 0.24 * BUDGET / (0.25 * 12),   # 0.0008
    "k3": 0.35 * BUDGET / (0.5 * 6),               # 0.00116667
    "k5_linear": 0.35 * BUDGET / (0.5 * 30),       # 0.000233333
    "k5_cubic": 0.24 * BUDGET / (0.125 * 20),      # 0.00096
    "m31": 0.22 * BUDGET / 1.0,                    # 0.0022
    "m32": 0.22 * BUDGET / 0.5,                    # 0.0044
}
TONE_PAPER["k4"] = TONE_PAPER["k4_additive"]
TONE_PAPER["k5"] = TONE_PAPER["k5_linear"]

# ---------------------------------------------------------------- random, by hand
# Gaussian σ = (0.5, 0.5, 1) deg/s, ρ = 1, Ω̄ = 2 deg/s; Δ* = 0.01.
# Exact: M2 = σ² = 1, M4 = 3σ⁴ = 3, C3i = 1·1·0.5 = 0.5.
# E(2) = σ√(2/π)·e^(−2) + 2·erf(2/√2) − 2 = 0.7978846·0.1353353 + 2·0.9544997 − 2
#      = 0.0169814;  g_A = ½E = 0.00849070.
RANDOM_EXACT = {
    "A1": 0.4447496 * BUDGET / 0.00849070,         # 0.523808
    "k2": 0.4447496 * BUDGET / 1,
    "k4_additive": 0.4447496 * BUDGET / 3,         # 0.00148250
    "k4_multiplicative": 0.2264554 * BUDGET / (4 * 6 * 1),  # 9.43564e-05
    "k3": 0.2264554 * BUDGET / (2 * 3 * 1),        # (β1/2)Δ*/(|Ω̄|·3M2) = 0.000377426
    "k5_linear": 0.2264554 * BUDGET / (2 * 5 * 3),  # (β1/2)Δ*/(|Ω̄|·5M4) = 7.54851e-05
    "k5_cubic": 0.2264554 * BUDGET / (8 * 10 * 1),  # 2.83069e-05
    "m31": 0.2223748 * BUDGET / 0.5,
    "m32": 0.2223748 * BUDGET / 0.5,
}
RANDOM_EXACT["k4"] = RANDOM_EXACT["k4_multiplicative"]
RANDOM_EXACT["k5"] = RANDOM_EXACT["k5_cubic"]
# Paper, random column: g_A = 0.5σ = 0.5, M2' = σ² = 1, M4' = σ⁴ = 1, 3M2' = 3σ² = 3,
# 5M4' = 5σ⁴ = 5, 6M2' = 6σ² = 6, 10M2' = 10σ² = 10.
RANDOM_PAPER = {
    "A1": 0.44 * BUDGET / 0.5,                     # 0.0088
    "k2": 0.44 * BUDGET / 1,                       # 0.0044
    "k4_additive": 0.44 * BUDGET / 1,              # 0.0044
    "k4_multiplicative": 0.24 * BUDGET / (4 * 6),  # 0.0001
    "k3": 0.35 * BUDGET / (2 * 3),                 # 0.000583333
    "k5_linear": 0.35 * BUDGET / (2 * 5),          # 0.00035
    "k5_cubic": 0.24 * BUDGET / (8 * 10),          # 3e-05
    "m31": 0.22 * BUDGET / 0.5,                    # 0.0044
    "m32": 0.22 * BUDGET / 0.5,
}
RANDOM_PAPER["k4"] = RANDOM_PAPER["k4_multiplicative"]
RANDOM_PAPER["k5"] = RANDOM_PAPER["k5_cubic"]


@pytest.mark.parametrize(("method", "profile", "expected"), [
    ("exact", "tone", TONE_EXACT),
    ("paper", "tone", TONE_PAPER),
    ("exact", "noise", RANDOM_EXACT),
    ("paper", "noise", RANDOM_PAPER),
])
def test_bounds_by_hand(tmp_path: Path, method: str, profile: str,
                        expected: dict[str, float]) -> None:
    result = api.bounds(profiles_catalog(tmp_path), profiles=[profile], method=method,
                        budget=BUDGET)
    assert result.profiles == (profile,)
    got = bounds_of(result, 0)
    for name, value in expected.items():
        # hand constants carry 7 digits
        assert got[name] == pytest.approx(value, rel=2e-6), name


def test_hand_numbers_themselves() -> None:
    # guard against a slip in the formulas above: a few values written out in full
    assert TONE_EXACT["A1"] == pytest.approx(0.0109377, rel=1e-5)
    assert TONE_EXACT["k5"] == pytest.approx(0.000150970, rel=1e-5)
    assert RANDOM_EXACT["A1"] == pytest.approx(0.523808, rel=1e-5)
    assert RANDOM_EXACT["k4"] == pytest.approx(9.43564e-05, rel=1e-5)
    assert TONE_PAPER["A1"] == pytest.approx(0.00326895, rel=1e-5)


def test_zero_rate_leaves_multiplicative_coefficients_unconstrained(tmp_path: Path) -> None:
    # Ω̄ = 0: the denominators |Ω̄|·3M2, Ω̄²·6M2, ... vanish → +inf (docs/model.md)
    result = api.bounds(profiles_catalog(tmp_path), profiles=["tone"], rate=[0.0],
                        budget=BUDGET)
    got = bounds_of(result, 0)
    assert got["k3"] == math.inf
    assert got["k5"] == math.inf and got["k5_linear"] == math.inf
    assert got["k4_multiplicative"] == math.inf
    assert got["k4"] == pytest.approx(0.4447496 * BUDGET / 6, rel=2e-6)  # additive only
    # and |Ω̄| ≥ a: no sign change, E = 0, A1 unconstrained (docs/model.md)
    fast = api.bounds(profiles_catalog(tmp_path), profiles=["tone"], rate=[5.0], budget=BUDGET)
    assert bounds_of(fast, 0)["A1"] == math.inf


def test_rate_override_three_components(tmp_path: Path) -> None:
    result = api.bounds(profiles_catalog(tmp_path), profiles=["tone"], rate=[0.0, 0.0, 0.5],
                        budget=BUDGET)
    assert bounds_of(result, 0)["k3"] == pytest.approx(TONE_EXACT["k3"], rel=2e-6)


def test_kernel_is_vectorised_and_linear_in_the_budget() -> None:
    # two "profiles" × three rates at once; bounds scale with Δ*
    omega = np.array([[0.0, 1.0, 2.0], [0.5, -0.5, 3.0]])
    mu = Multipliers(asymmetry=np.full_like(omega, 0.3), m2=np.full_like(omega, 2.0),
                     m4=np.full_like(omega, 6.0), c31=np.full_like(omega, -1.0),
                     c32=np.zeros_like(omega), omega=omega)
    c = allocation_constants()
    one = coefficient_bounds(mu, 0.01, c)
    two = coefficient_bounds(mu, 0.02, c)
    assert one.k3.shape == (2, 3)
    finite = np.isfinite(one.k3)
    assert np.allclose(two.k3[finite], 2 * one.k3[finite])
    assert np.all(one.m32 == np.inf)                     # C32 = 0
    assert np.allclose(one.m31, c.alpha[3] * 0.01 / 1.0)  # |C31| = 1
    # k3 bound is even in Ω̄: 0.5 and -0.5 give the same number
    assert one.k3[1, 0] == one.k3[1, 1]
    # a per-profile budget broadcasts
    per = coefficient_bounds(mu, np.array([[0.01], [0.02]]), c)
    assert np.allclose(per.k2[1], two.k2[1]) and np.allclose(per.k2[0], one.k2[0])


# ---------------------------------------------------------------- tightness

SENSOR_AT = """
sensors:
  - id: s
    coefficients:
      {name}: {value}
"""


def analysis_of(tmp_path: Path, name: str, value: float, profile: str,
                method: str) -> api.AnalysisResult:
    body = "profiles:" + TONE_PROFILE + RANDOM_PROFILE + SENSOR_AT.format(
        name=name, value=f"{value:.17e}")
    return api.analyze(api.load([write(tmp_path, body, f"{name}.yaml")]), profiles=[profile],
                       method=method)


# (bound or part name, coefficient, where its share shows up in the analysis, share index)
TIGHT = [
    ("A1", "A1", "additive", 0),
    ("k2", "k2", "additive", 1),
    ("k4_additive", "k4", "additive", 2),
    ("m31", "m31", "additive", 3),
    ("m32", "m32", "additive", 4),
    ("k3", "k3", "q1", None),
    ("k5_linear", "k5", "q1", None),
    ("k4_multiplicative", "k4", "q2", 1),
    ("k5_cubic", "k5", "q3", 2),
]


# a lopsided allocation, so that a share taken from the wrong slot shows
CUSTOM = (2.0, 1.0, 2.0, 3.0, 4.0, 5.0, 3.0, 2.0, 1.0)


@pytest.mark.parametrize(("method", "allocation"), [
    ("exact", None), ("paper", None), ("exact", CUSTOM)])
@pytest.mark.parametrize("profile", ["tone", "noise"])
@pytest.mark.parametrize(("part", "coefficient", "where", "index"), TIGHT)
def test_a_coefficient_at_its_bound_uses_exactly_its_share(
    tmp_path: Path, method: str, allocation: tuple[float, ...] | None, profile: str,
    part: str, coefficient: str, where: str, index: int | None,
) -> None:
    result = api.bounds(profiles_catalog(tmp_path), profiles=[profile], method=method,
                        budget=BUDGET, allocation=allocation)
    c = result.allocation
    bound = float(getattr(result.bounds, part)[0])
    omega = float(result.rates[0, 2])
    err = analysis_of(tmp_path, coefficient, bound, profile, method).error
    if allocation is not None:
        # the shares themselves, by hand: r = 2 → c_A = 2/√5, c_M = 1/√5;
        # ‖w‖ = √55, ‖v‖ = √14
        alpha = [wp * (2 / math.sqrt(5)) / math.sqrt(55) for wp in CUSTOM[1:6]]
        beta = [vq * (1 / math.sqrt(5)) / math.sqrt(14) for vq in CUSTOM[6:]]
        assert c.alpha == pytest.approx(alpha, rel=1e-12)
        assert c.beta == pytest.approx(beta, rel=1e-12)
        assert c.k3 == pytest.approx(beta[0] / 2, rel=1e-12)  # docs/model.md section 6
    if where == "additive":
        used = float(err.additive_terms[0, 0, index])
        share = float(c.alpha[index])
    else:
        q = int(where[1])
        used = float(err.multiplicative_coefficients[0, 0, q - 1]) * omega**q
        share = c.k3 if part == "k3" else c.k5_linear if part == "k5_linear" else float(
            c.beta[q - 1])
    assert abs(used) == pytest.approx(share * BUDGET, rel=1e-12)


@pytest.mark.parametrize("method", ["exact", "paper"])
@pytest.mark.parametrize("name", BOUNDED)
def test_select_check_at_bound_passes_and_just_above_fails(
    tmp_path: Path, method: str, name: str
) -> None:
    catalog = profiles_catalog(tmp_path)
    bound = float(getattr(api.bounds(catalog, profiles=["tone"], method=method,
                                     budget=BUDGET).bounds, name)[0])
    b = BOUNDED.index(name)
    for factor, expected in ((1.0, True), (1.001, False), (-1.0, True), (-1.001, False)):
        body = ("profiles:" + TONE_PROFILE
                + SENSOR_AT.format(name=name, value=f"{factor * bound:.17e}"))
        cat = api.load([write(tmp_path, body, f"s{factor}.yaml")])
        sel = api.select(cat, profiles=["tone"], method=method, budget=BUDGET)
        assert bool(sel.check_pass[0, 0, b]) is expected, (name, factor)
        assert bool(sel.sensor_pass[0]) is expected
        assert sel.values[0, 0, b] == pytest.approx(abs(factor) * bound, rel=1e-15)
        if not expected:
            assert sel.limits[0].name == name
            assert sel.limits[0].ratio == pytest.approx(1.001, rel=1e-9)


# ---------------------------------------------------------------- sufficiency

@settings(max_examples=60, deadline=None)
@given(
    a=st.floats(0.05, 5.0), sigma=st.one_of(st.just(0.0), st.floats(0.01, 3.0)),
    # a rate of 1e-313 deg/s makes Ω̄³ underflow: not a physical case
    omega=st.floats(-10.0, 10.0).filter(lambda x: x == 0 or abs(x) > 1e-6),
    cross=st.floats(-1.0, 1.0), signs=st.lists(st.sampled_from([-1.0, 1.0]), min_size=7,
                                               max_size=7),
    k5_zero=st.booleans(),
)
def test_within_bounds_keeps_rms_within_budget(a: float, sigma: float, omega: float,
                                               cross: float, signs: list[float],
                                               k5_zero: bool) -> None:
    """Every coefficient at its bound, any signs: Δ_V(RMS) ≤ Δ* (eq. 17).

    k3 and the linear k5 each get β1/2 of Δ* and add linearly inside Δ(1), so even with
    both at their bounds and of one sign |Δ(1)Ω̄| ≤ β1·Δ* (docs/model.md section 6).
    """
    from gyrovib.core.analysis import COLUMN, profile_multipliers
    from gyrovib.core.statistics import vibration_at_sensor

    vib = vibration_at_sensor([(50.0, (a * cross, 0.3 * a, a), (0, 0, 0))],
                              rms=(0.5 * sigma, 0.0, sigma))
    mu = profile_multipliers(vib, np.array([omega]), "exact")
    c = allocation_constants()
    b = coefficient_bounds(mu, BUDGET, c)
    coeffs = np.zeros((1, 11))
    coeffs[0, COLUMN["k1"]] = 1.0
    for s, name in zip(signs, BOUNDED, strict=True):
        value = float(getattr(b, name)[0])
        if math.isfinite(value) and not (k5_zero and name == "k5"):
            coeffs[0, COLUMN[name]] = s * value
    rms = float(vibration_error(coeffs, mu).rms[0, 0])
    assert rms <= BUDGET * (1 + 1e-9)


def test_k3_and_k5_at_their_bounds_with_one_sign_stay_within_budget() -> None:
    """The case that overran by 1.098 with β1/√2 each: now Δ_V(RMS) ≤ Δ* (docs/model.md section 6).

    Tone a3 = 2 deg/s (M2 = 2, M4 = 6), Ω̄ = 0.5: k3 = (β1/2)Δ*/(|Ω̄|·3M2) and
    k5 = (β1/2)Δ*/(|Ω̄|·5M4) (k5's linear part binds: 0.000150970 < 0.000905822), both
    positive; every other coefficient at its bound too. Then Δ(1)Ω̄ = β1·Δ* exactly and the
    shares add up to Σα² + Σβ² = 1 — except that k5 also uses part of β3 through Δ(3).
    """
    from gyrovib.core.analysis import COLUMN, profile_multipliers
    from gyrovib.core.statistics import vibration_at_sensor

    vib = vibration_at_sensor([(50.0, (1.0, 0.5, 2.0), (0, 0, 0))])
    mu = profile_multipliers(vib, np.array([0.5]), "exact")
    c = allocation_constants()
    b = coefficient_bounds(mu, BUDGET, c)
    assert float(b.k3[0]) == pytest.approx(TONE_EXACT["k3"], rel=2e-6)
    assert float(b.k5[0]) == pytest.approx(TONE_EXACT["k5"], rel=2e-6)
    coeffs = np.zeros((1, 11))
    coeffs[0, COLUMN["k1"]] = 1.0
    for name in BOUNDED:
        coeffs[0, COLUMN[name]] = float(getattr(b, name)[0])
    err = vibration_error(coeffs, mu)
    # Δ(1)·Ω̄ = (β1/2 + β1/2)·Δ* = β1·Δ*, the whole Δ(1) share
    assert float(err.multiplicative_coefficients[0, 0, 0]) * 0.5 == pytest.approx(
        BETA[0] * BUDGET, rel=1e-6)
    assert float(err.rms[0, 0]) <= BUDGET * (1 + 1e-12)
    # the paper's 0.35 each (≈ β1/√2) would overrun: |Δ(1)Ω̄| = 0.70·Δ* > β1·Δ*
    paper_k = (0.35 * BUDGET / (0.5 * 3 * 2), 0.35 * BUDGET / (0.5 * 5 * 6))
    coeffs[0, COLUMN["k3"]], coeffs[0, COLUMN["k5"]] = paper_k
    assert float(vibration_error(coeffs, mu).rms[0, 0]) > BUDGET


# ---------------------------------------------------------------- units, allocation


def test_unit_invariance(tmp_path: Path) -> None:
    catalog = profiles_catalog(tmp_path)
    per_s = api.bounds(catalog, budget=BUDGET, unit="deg/s")
    per_h = api.bounds(catalog, budget=BUDGET, unit="deg/h")
    assert per_h.budget == pytest.approx(36.0)            # 0.01 deg/s = 36 deg/h
    assert per_h.rates[0, 2] == pytest.approx(0.5 * 3600)
    s = 1 / 3600                                          # deg/s per deg/h
    # kn[U] = kn[deg/s]·s^(n−1); A1 dimensionless; m3i[U] = m3i[deg/s]·s
    expected_power = {"A1": 0, "k2": 1, "k3": 2, "k4": 3, "k5": 4, "m31": 1, "m32": 1}
    for name, n in expected_power.items():
        got = getattr(per_h.bounds, name)
        want = getattr(per_s.bounds, name) * s**n
        assert np.allclose(got, want, rtol=1e-12), name
        assert n == -units.COEFFICIENT_RATE_POWER[name]
    # the same profiles written in deg/h give the same bounds
    hours = write(tmp_path, """
        units: {rate: deg/h}
        profiles:
          - id: tone
            rate: [0, 0, 1800]
            harmonic:
              - frequency: 100
                amplitude: [3600, 1800, 7200]
        """, "hours.yaml")
    again = api.bounds(api.load([hours]), budget=BUDGET, unit="deg/h")
    assert np.allclose(again.bounds.stacked()[0], per_h.bounds.stacked()[0], rtol=1e-12)


def test_paper_refuses_custom_allocation(tmp_path: Path) -> None:
    catalog = profiles_catalog(tmp_path)
    with pytest.raises(OptionError, match="paper"):
        api.bounds(catalog, method="paper", budget=BUDGET, allocation=[2.0])
    # the paper's own allocation, spelled out, is accepted
    api.bounds(catalog, method="paper", budget=BUDGET,
               allocation=[1.5, 1, 1, 1, 0.5, 0.5, 1, 0.5, 0.5])
    with pytest.raises(OptionError):
        api.bounds(catalog, budget=BUDGET, allocation=[1.5, 1.0])
    with pytest.raises(OptionError):
        api.bounds(catalog, budget=BUDGET, allocation=[0.0])


def test_catalogue_allocation_is_used_and_refused_by_paper(tmp_path: Path) -> None:
    body = "allocation:\n  r: 3.0\nprofiles:" + TONE_PROFILE
    catalog = api.load([write(tmp_path, body)])
    result = api.bounds(catalog, budget=BUDGET)
    # r = 3: c_A = 0.9486833, α2 = c_A/‖w‖ = 0.9486833/1.8708287 = 0.5070926; M2 = 2
    assert float(result.bounds.k2[0]) == pytest.approx(0.5070926 * BUDGET / 2, rel=1e-6)
    # an explicit allocation wins over the catalogue's
    explicit = api.bounds(catalog, budget=BUDGET, allocation=[1.5])
    assert float(explicit.bounds.k2[0]) == pytest.approx(TONE_EXACT["k2"], rel=2e-6)
    with pytest.raises(OptionError, match="allocation"):
        api.bounds(catalog, method="paper", budget=BUDGET)


def test_bad_budget_refused_by_the_library(tmp_path: Path) -> None:
    catalog = profiles_catalog(tmp_path)
    for bad in (0.0, -1.0, math.nan, math.inf):
        with pytest.raises(OptionError):
            api.bounds(catalog, budget=bad)
