"""The rate-table fit of docs/model.md section 14 (gyrovib.core.fit).

Where the expected numbers come from: the data are made from stated eq. (1)
coefficients, so the fit must give them back (noise-free) or scatter around
them as its own covariance says (a Monte-Carlo of repeated fits); the
nonlinearities are closed forms worked by hand below and a dense grid; the
unit invariances follow from eq. (2)'s definition (docs/model.md section 2).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gyrovib import units
from gyrovib.core.fit import (
    IdentificationError,
    fit_rate_table,
    nonlinearity,
    rate_names,
)

#: A made-up unit in output units (mV): K0, K1 (mV per deg/s), and eq. (2) A1, k2..k5.
K0, K1 = 3.0, 25.0
RATE_FORM = {"A1": 2.0e-3, "k2": 3.0e-6, "k3": -4.0e-9, "k4": 1.5e-12, "k5": 1.0e-14}
LEVELS = np.array([-300.0, -200.0, -100.0, -50.0, -20.0, 0.0, 20.0, 50.0, 100.0, 200.0, 300.0])


def curve(w: np.ndarray, k0: float = K0 / K1, k1: float = K1,
          c: dict[str, float] | None = None, m: dict[str, float] | None = None,
          cross: np.ndarray | None = None) -> np.ndarray:
    """Eq. (1) as K1 times eq. (2): U = K1·(k0 + ω + ½A1|ω| + Σ kn ωⁿ + Σ mi ωi + m3i ω ωi)."""
    c = RATE_FORM if c is None else c
    out = k0 + w + 0.5 * c.get("A1", 0.0) * np.abs(w)
    out = out + sum(c.get(f"k{n}", 0.0) * w**n for n in range(2, 6))
    if cross is not None and m is not None:
        for i in range(cross.shape[1]):
            out = out + m.get(f"m{i + 1}", 0.0) * cross[:, i]
            out = out + m.get(f"m3{i + 1}", 0.0) * w * cross[:, i]
    return k1 * out


def test_noise_free_data_give_the_stated_coefficients() -> None:
    w = np.repeat(LEVELS, 2)
    result = fit_rate_table(w, curve(w))
    assert result.names == ("k0", "A1", "k2", "k3", "k4", "k5")
    expected = {"k0": K0 / K1, **RATE_FORM}
    for name, value in expected.items():
        assert result.value(name) == pytest.approx(value, rel=1e-10), name
    assert result.scale_factor == pytest.approx(K1, rel=1e-12)
    assert result.raw_values[2] == pytest.approx(0.5 * K1 * RATE_FORM["A1"], rel=1e-10)  # h
    assert result.residual_rms < 1e-10 * K1 * 300
    assert result.points == w.size


def test_noise_free_with_cross_rates() -> None:
    # the cross rates ω1, ω2 applied at each Ω: (0,0), (40,0), (0,−40), (30,30)
    w = np.repeat(LEVELS, 4)
    cross = np.tile([[0.0, 0.0], [40.0, 0.0], [0.0, -40.0], [30.0, 30.0]], (LEVELS.size, 1))
    m = {"m1": 2e-3, "m2": -1e-3, "m31": 5e-6, "m32": -3e-6}
    result = fit_rate_table(w, curve(w, m=m, cross=cross), cross=cross)
    assert result.names == (*rate_names(5), "m1", "m2", "m31", "m32")
    for name, value in {**RATE_FORM, **m}.items():
        assert result.value(name) == pytest.approx(value, rel=1e-10), name


def test_a_single_cross_axis_is_named_by_its_axis() -> None:
    w = np.repeat(LEVELS, 2)
    cross = np.tile([[0.0], [50.0]], (LEVELS.size, 1))
    m = {"m2": 1e-3, "m32": 2e-6}
    data = curve(w, m={"m1": m["m2"], "m31": m["m32"]}, cross=cross)
    result = fit_rate_table(w, data, cross=cross, cross_axes=(2,))
    assert result.names[-2:] == ("m2", "m32")
    assert result.value("m2") == pytest.approx(1e-3, rel=1e-10)
    assert result.value("m32") == pytest.approx(2e-6, rel=1e-10)


def test_sigma_agrees_with_repeated_fits() -> None:
    """The delta-method σ and correlations against the scatter of 600 fits of fresh noise.

    The sample standard deviation of N = 600 normal draws has a relative standard
    error 1/√(2(N−1)) ≈ 2.9 %: 12 % is four of them. The noise is small against
    K1·Ω, so the delta method's linearisation error is negligible here.
    """
    rng = np.random.default_rng(20261201)
    w = np.repeat(LEVELS, 2)
    clean = curve(w)
    noise = 0.05  # mV
    fits = [fit_rate_table(w, clean + rng.normal(0.0, noise, w.size)) for _ in range(600)]
    values = np.array([f.values for f in fits])
    reported = np.mean([f.sigma for f in fits], axis=0)
    observed = values.std(axis=0, ddof=1)
    np.testing.assert_allclose(observed, reported, rtol=0.12)
    # unbiased: the mean of the estimates is the truth within 4 standard errors
    truth = np.array([K0 / K1, *RATE_FORM.values()])
    assert np.all(np.abs(values.mean(axis=0) - truth) < 4 * observed / math.sqrt(600))
    # s² estimates the noise variance (mean of s² over the fits)
    s2 = np.mean([f.residual_sigma**2 for f in fits])
    assert s2 == pytest.approx(noise**2, rel=0.05)
    # the correlations too (standard error of a sample correlation ≤ 1/√N ≈ 0.04)
    np.testing.assert_allclose(np.corrcoef(values, rowvar=False),
                               np.mean([f.correlation for f in fits], axis=0), atol=0.12)


def test_t_values_and_the_significance_flag() -> None:
    rng = np.random.default_rng(5)
    w = np.repeat(LEVELS, 2)
    c = {**RATE_FORM, "k4": 0.0}  # a term that is not there has |t| < 2 most of the time
    result = fit_rate_table(w, curve(w, c=c) + rng.normal(0.0, 0.05, w.size))
    np.testing.assert_allclose(result.t, result.values / result.sigma, rtol=1e-14)
    k = result.names.index("k4")
    assert abs(result.t[k]) < 2 and not result.significant[k]
    assert result.significant[result.names.index("A1")]


# --------------------------------------------------------------------------- nonlinearity


@pytest.mark.parametrize(("coefficients", "least_squares", "endpoint"), [
    # ½A1|u| alone: LS line a = A1/4, residual ½A1(|u| − ½), max A1/4; endpoint line at
    # A1/2, max at u = 0 of A1/2 (docs/model.md section 11: "up to A1·R/4")
    ({"A1": 4e-3}, 25 * 4e-3, 50 * 4e-3),
    # k2·ω²: q = u + k2R·u²; LS: k2R(u² − 1/3), max 2k2R/3; endpoint: k2R(u² − 1), max k2R
    ({"k2": 1e-5}, 100 * 2 / 3 * 1e-5 * 200, 100 * 1e-5 * 200),
    # k3·ω³: LS slope 1 + 0.6k3R², residual k3R²(u³ − 0.6u): max 0.4k3R² at u = 1;
    # endpoint: k3R²(u³ − u), max 2/(3√3)·k3R² at u = 1/√3
    ({"k3": 1e-8}, 100 * 0.4 * 1e-8 * 200**2, 100 * 2 / (3 * math.sqrt(3)) * 1e-8 * 200**2),
])
def test_nonlinearity_closed_forms(coefficients: dict[str, float], least_squares: float,
                                   endpoint: float) -> None:
    names = tuple(coefficients)
    result = nonlinearity(list(coefficients.values()), names, 200.0)
    assert result.least_squares_max == pytest.approx(least_squares, rel=1e-12)
    assert result.endpoint_max == pytest.approx(endpoint, rel=1e-12)
    assert result.range == 200.0


def test_nonlinearity_against_a_dense_grid() -> None:
    names = ("k0", "A1", "k2", "k3", "k4", "k5")
    values = np.array([0.3, 1.5e-3, 2e-6, -4e-9, 1e-12, 1e-14])
    r = 300.0
    w = np.linspace(-r, r, 600_001)
    p = values[0] + w + 0.5 * values[1] * np.abs(w) + sum(values[n] * w**n for n in range(2, 6))
    # the discrete least-squares line of a uniform grid: the continuous one within O(1/N)
    slope, intercept = np.polyfit(w, p, 1)
    ls = 100 * np.max(np.abs(p - intercept - slope * w)) / r
    end_slope = (p[-1] - p[0]) / (2 * r)
    end = 100 * np.max(np.abs(p - 0.5 * (p[-1] + p[0]) - end_slope * w)) / r
    result = nonlinearity(values, names, r)
    assert result.least_squares_max == pytest.approx(ls, rel=1e-5)
    assert result.endpoint_max == pytest.approx(end, rel=1e-9)


# --------------------------------------------------------------------------- identification


def _message(exc: pytest.ExceptionInfo[IdentificationError]) -> str:
    return str(exc.value)


def test_rates_of_one_sign_are_refused() -> None:
    w = np.repeat(LEVELS[LEVELS >= 0], 2)
    with pytest.raises(IdentificationError) as exc:
        fit_rate_table(w, curve(w))
    assert "every rate is positive" in _message(exc)
    assert "negative rates" in _message(exc)
    w = -w
    with pytest.raises(IdentificationError, match="every rate is negative"):
        fit_rate_table(w, curve(w))


def test_too_few_levels_for_the_even_part() -> None:
    # ±100, ±200, ±300: three |Ω| levels, the even part K0, h, K2, K4 needs four
    w = np.repeat([-300.0, -200.0, -100.0, 100.0, 200.0, 300.0], 3)
    with pytest.raises(IdentificationError) as exc:
        fit_rate_table(w, curve(w))
    assert "at least 4 distinct |Ω| levels" in _message(exc)
    assert "K0, h, K2, K4" in _message(exc)
    assert "the table has 3" in _message(exc)
    # adding the zero level makes it four: identifiable
    w0 = np.concatenate([w, [0.0, 0.0]])
    assert fit_rate_table(w0, curve(w0)).names[-1] == "k5"
    # order 3 needs K0, h, K2 (3 levels): fine without zero
    assert fit_rate_table(w, curve(w), order=3).names == ("k0", "A1", "k2", "k3")


def test_too_few_nonzero_levels_for_the_odd_part() -> None:
    # 0, ±100, ±200 and only positive at 300: four |Ω| levels but the odd part K1, K3, K5
    # needs three nonzero levels: it has 3 (100, 200, 300) — fine; without 300 it has 2
    w = np.repeat([-200.0, -100.0, 0.0, 100.0, 200.0], 4)
    with pytest.raises(IdentificationError) as exc:
        fit_rate_table(w, curve(w))
    assert "3 distinct nonzero |Ω| levels" in _message(exc)
    assert "K1, K3, K5" in _message(exc)


def test_no_more_points_than_parameters() -> None:
    w = LEVELS[[0, 1, 2, 5, 8, 9]]  # ±100, ±200, −300, 0: six points for six parameters…
    w = np.array([-300.0, -200.0, -100.0, 0.0, 100.0, 200.0, 300.0])  # seven for seven
    with pytest.raises(IdentificationError) as exc:
        fit_rate_table(w, curve(w))
    assert "7 points for 7 parameters" in _message(exc)
    w8 = np.append(w, 300.0)
    assert fit_rate_table(w8, curve(w8)).points == 8


def test_cross_rates_that_never_vary_are_refused() -> None:
    w = np.repeat(LEVELS, 2)
    with pytest.raises(IdentificationError, match="rate_x1 is zero in every row"):
        fit_rate_table(w, curve(w), cross=np.zeros((w.size, 1)))


def test_cross_rate_collinear_with_the_rate_is_named() -> None:
    # ω1 = Ω/2 in every row: M1·ω1 is K1·Ω again
    w = np.repeat(LEVELS, 2)
    with pytest.raises(IdentificationError) as exc:
        fit_rate_table(w, curve(w), cross=(w / 2)[:, None])
    assert "K1" in _message(exc) and "M1" in _message(exc)


def test_output_that_does_not_follow_the_rate() -> None:
    w = np.repeat(LEVELS, 2)
    flat = np.random.default_rng(0).normal(0.0, 1.0, w.size)
    with pytest.raises(IdentificationError, match="does not follow the rate"):
        fit_rate_table(w, flat)


def test_order_out_of_range() -> None:
    w = np.repeat(LEVELS, 2)
    with pytest.raises(IdentificationError, match="order must be 1 to 5"):
        fit_rate_table(w, curve(w), order=6)


def test_non_finite_data() -> None:
    w = np.repeat(LEVELS, 2)
    u = curve(w)
    u[3] = np.nan
    with pytest.raises(IdentificationError, match="finite"):
        fit_rate_table(w, u)


# --------------------------------------------------------------------------- unit invariance

OUTPUT_SCALES = st.sampled_from([1e-3, 1e3, 1.0, 4096 / 5000])  # mV→V, V→mV, LSB per mV
RATE_UNITS = st.sampled_from(["deg/h", "rad/s", "rpm", "deg/s"])


@settings(max_examples=25, deadline=None, derandomize=True)
@given(output_scale=OUTPUT_SCALES, rate_unit=RATE_UNITS, seed=st.integers(0, 2**32 - 1))
def test_eq2_coefficients_do_not_depend_on_the_units(output_scale: float, rate_unit: str,
                                                      seed: int) -> None:
    """Rescaling the output (mV ↔ V) changes no eq. (2) coefficient; rewriting the rates
    in another unit changes each only by its unit factor (docs/model.md section 2):
    kn[U] = kn[deg/s]·s^(n−1), so the fit in U, converted back, is the fit in deg/s."""
    rng = np.random.default_rng(seed)
    w = np.repeat(LEVELS, 2)
    u = curve(w) + rng.normal(0.0, 0.05, w.size)
    base = fit_rate_table(w, u)
    rescaled = fit_rate_table(w, u * output_scale)
    np.testing.assert_allclose(rescaled.values, base.values, rtol=1e-8, atol=0)
    np.testing.assert_allclose(rescaled.sigma, base.sigma, rtol=1e-7)
    s = units.scale(rate_unit)  # deg/s per unit
    other = fit_rate_table(w / s, u * output_scale)
    back = np.array([v * units.coefficient_factor(n, rate_unit, "deg/s")
                     for n, v in zip(other.names, other.values, strict=True)])
    np.testing.assert_allclose(back, base.values, rtol=1e-8)
    sigma_back = np.array([v * abs(units.coefficient_factor(n, rate_unit, "deg/s"))
                           for n, v in zip(other.names, other.sigma, strict=True)])
    np.testing.assert_allclose(sigma_back, base.sigma, rtol=1e-7)
    assert other.nonlinearity.least_squares_max == pytest.approx(
        base.nonlinearity.least_squares_max, rel=1e-8)
