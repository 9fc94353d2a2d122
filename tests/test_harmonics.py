"""Phase-locked harmonics (docs/model.md section 10): moments, E(Ω), the error terms.

References: closed forms worked by hand in the comments (docs/model.md section 10's
M3 for orders 1 and 2), and brute-force averages over one period computed here
on fine uniform grids, with scipy's adaptive quadrature where the integrand has
kinks — never gyrovib's own closed forms.
"""

from __future__ import annotations

import functools
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import integrate, special

from gyrovib.core.analysis import (
    COEFFICIENTS,
    EXTRA_TERMS,
    profile_multipliers,
    stack_multipliers,
    vibration_error,
)
from gyrovib.core.harmonics import (
    combine_moments,
    group_moments,
    locked_abs_excess,
    locked_group,
    locked_peak,
    locked_rectified_excess,
)
from gyrovib.core.numeric import simulate
from gyrovib.core.statistics import vibration_at_sensor
from gyrovib.errors import ModelError


def x_of(orders, amps, phases_deg, theta):
    """x(θ) per axis (3, T) written out: Σ_n a_n·sin(nθ + φ_n)."""
    out = np.zeros((3, theta.size))
    for n, a, p in zip(orders, np.asarray(amps, float), np.asarray(phases_deg, float),
                       strict=True):
        for axis in range(3):
            out[axis] += a[axis] * np.sin(n * theta + math.radians(p[axis]))
    return out


def midpoints(n: int) -> np.ndarray:
    return 2 * math.pi * (np.arange(n) + 0.5) / n


# orders 1–4 with mixed per-axis phases (degrees)
ORDERS = (1, 2, 3, 4)
AMPS = [[0.3, 0.1, 1.0], [0.2, 0.25, 0.6], [0.0, 0.1, 0.35], [0.1, 0.0, 0.2]]
PHASES = [[0, 40, 10], [90, 0, 75], [0, 200, -30], [45, 0, 160]]
GROUP = locked_group(ORDERS, AMPS, PHASES)


@settings(max_examples=60, deadline=None)
@given(a1=st.floats(0.01, 5.0), a2=st.floats(0.0, 5.0), p1=st.floats(-180, 180),
       p2=st.floats(-180, 180))
def test_m3_of_orders_1_and_2(a1: float, a2: float, p1: float, p2: float) -> None:
    """docs/model.md section 10: M3 = −¾·a1²·a2·sin(φ2 − 2φ1)."""
    g = locked_group([1, 2], [[0, 0, a1], [0, 0, a2]], [[0, 0, p1], [0, 0, p2]])
    expected = -0.75 * a1**2 * a2 * math.sin(math.radians(p2 - 2 * p1))
    got = float(group_moments(g.orders, g.phasors).m3)
    assert got == pytest.approx(expected, abs=1e-14 * (a1 + a2) ** 3)  # rounding of M3


def test_moments_equal_a_fine_period_average() -> None:
    theta = midpoints(1 << 16)
    x = x_of(ORDERS, AMPS, PHASES, theta)
    x3 = x[2]
    mo = group_moments(GROUP.orders, GROUP.phasors)
    for got, want in ((mo.m2, np.mean(x3**2)), (mo.m3, np.mean(x3**3)), (mo.m4, np.mean(x3**4)),
                      (mo.m5, np.mean(x3**5)), (mo.c31, np.mean(x3 * x[0])),
                      (mo.c32, np.mean(x3 * x[1]))):
        assert float(got) == pytest.approx(float(want), rel=1e-12, abs=1e-15)
    # M2 = Σ a²/2 whatever the phases: (1 + 0.36 + 0.1225 + 0.04)/2 = 0.76125
    assert float(mo.m2) == pytest.approx(0.76125, rel=1e-14)


def test_cumulant_combination_equals_a_product_average() -> None:
    """Group + independent tone + Gaussian: combine_moments vs an exact product rule.

    Phases of the group (64 nodes) × the tone (64 nodes) × 12 Gauss–Hermite nodes are
    exact for these polynomial moments.
    """
    a, sigma = 0.7, 0.4
    mo = group_moments(GROUP.orders, GROUP.phasors)
    m2, m3, m4, m5 = combine_moments(
        [mo.m2, a * a / 2, sigma**2], [mo.m3, 0.0, 0.0],
        [mo.m4, 3 * a**4 / 8, 3 * sigma**4], [mo.m5, 0.0, 0.0])
    g = x_of(ORDERS, AMPS, PHASES, midpoints(64))[2]
    t = a * np.sin(midpoints(64))
    z, w = np.polynomial.hermite_e.hermegauss(12)
    w = w / w.sum()
    y = g[:, None, None] + t[None, :, None] + sigma * z[None, None, :]
    weight = np.broadcast_to(w[None, None, :] / 64**2, y.shape)
    for got, n in ((m2, 2), (m3, 3), (m4, 4), (m5, 5)):
        assert float(got) == pytest.approx(float(np.sum(weight * y**n)), rel=1e-12)


@functools.cache
def fine_x3(orders: tuple[int, ...]) -> np.ndarray:
    idx = [o - 1 for o in orders]
    return x_of(orders, [AMPS[i] for i in idx], [PHASES[i] for i in idx], midpoints(1 << 21))[2]


def brute_abs_excess(omega: float, x3: np.ndarray) -> float:
    return float(np.mean(np.abs(omega + x3)) - abs(omega))


@pytest.mark.parametrize("orders", [(1,), (1, 2), (1, 2, 3), (1, 2, 3, 4), (2, 3)])
@pytest.mark.parametrize("where", [0.0, 0.3, -0.6, 0.95, -1.05, 2.5])
def test_group_alone_e_matches_brute_force(orders: tuple[int, ...], where: float) -> None:
    """E(Ω) through the zero crossings vs a 2²¹-point period average (1e-7).

    ``where`` is Ω as a fraction of the group's peak (inside < 1 < outside).
    """
    idx = [o - 1 for o in orders]
    g = locked_group(orders, [AMPS[i] for i in idx], [PHASES[i] for i in idx])
    x3 = fine_x3(orders)
    peak = float(np.max(np.abs(x3)))
    omega = where * peak
    got = float(locked_abs_excess(np.array([omega]), g.orders, g.phasors[:, 2])[0])
    want = brute_abs_excess(omega, x3)
    if abs(where) >= 1.0:
        assert got == 0.0 and abs(want) < 1e-12
    else:
        assert got == pytest.approx(want, rel=1e-7)
    # the same through the general entry (no other components)
    assert float(locked_rectified_excess(omega, g)) == got


def folded_excess(omega: float, s: np.ndarray, sigma: float) -> float:
    """<|s + σZ|> − |Ω| averaged over shifts s with mean Ω (folded normal mean, written out).

    With u = s/(σ√2): <|s + σZ|> = σ√(2/π)·e^(−u²) + s·erf(u); since <s> = Ω this is
    <σ√(2/π)·e^(−u²) − |s|·erfc(u·sign Ω)>-like: for Ω ≥ 0, <|s+σZ|> − s =
    σ√(2/π)·e^(−u²) − s·erfc(u) (no cancellation in the tails), mirrored for Ω < 0.
    """
    m = s if omega >= 0 else -s
    u = m / (sigma * math.sqrt(2))
    return float(np.mean(sigma * math.sqrt(2 / math.pi) * np.exp(-u * u) - m * special.erfc(u)))


@pytest.mark.parametrize("where", [0.0, 0.4, -0.8, 1.2, -1.6])
def test_e_with_a_random_part_and_a_tone_matches_brute_force(where: float) -> None:
    """Group + independent tone + Gaussian: E to 1e-9 relative.

    Brute force: the folded-normal mean averaged over a 1024 × 1024 grid of the group's
    and the tone's phases (analytic integrand: the midpoint rule converges geometrically).
    """
    a, sigma = 0.5, 0.3
    g3 = x_of(ORDERS, AMPS, PHASES, midpoints(1024))[2]
    peak = locked_peak(GROUP.orders, GROUP.phasors[:, 2])
    omega = where * (peak + a)
    t = a * np.sin(midpoints(1024))
    s = omega + g3[:, None] + t[None, :]
    want = folded_excess(omega, s, sigma)
    got = float(locked_rectified_excess(omega, GROUP, [a], sigma))
    assert got == pytest.approx(want, rel=1e-9)


def test_e_with_a_random_part_only_matches_brute_force() -> None:
    sigma = 0.05  # narrow kernel against the group's swing: many nodes needed
    g3 = x_of(ORDERS, AMPS, PHASES, midpoints(1 << 16))[2]
    peak = locked_peak(GROUP.orders, GROUP.phasors[:, 2])
    for omega in (0.0, 0.7, -1.3, peak + 0.1, -(peak + 0.2)):  # inside; 2σ and 4σ outside
        want = folded_excess(omega, omega + g3, sigma)
        got = float(locked_rectified_excess(omega, GROUP, (), sigma))
        assert got == pytest.approx(want, rel=1e-9)


@pytest.mark.parametrize("omega", [0.0, 0.5, -1.2, 2.0])
def test_e_with_an_independent_tone_only(omega: float) -> None:
    """Group + one tone, no random part: algebraic convergence, 1e-7 (docstring).

    Reference: adaptive quadrature over the group's period of the tone's closed-form
    <|s + a·sin φ|> (arcsine law, worked by hand: (2/π)(s·asin(s/a) + √(a² − s²)) inside).
    """
    a = 0.8

    def tone_mean(s: float) -> float:
        if abs(s) >= a:
            return abs(s)
        return (2 / math.pi) * (s * math.asin(s / a) + math.sqrt(a * a - s * s))

    def f(theta: float) -> float:
        return tone_mean(omega + float(x_of(ORDERS, AMPS, PHASES, np.array([theta]))[2, 0]))

    want, _ = integrate.quad(f, 0, 2 * math.pi, limit=400, epsabs=1e-12, epsrel=1e-11)
    want = want / (2 * math.pi) - abs(omega)
    got = float(locked_rectified_excess(omega, GROUP, [a], 0.0))
    assert got == pytest.approx(want, rel=1e-7)


def test_locked_peak_by_hand() -> None:
    # sin θ + ½ sin 2θ: d/dθ = cos θ + cos 2θ = 0 → cos θ = ½, θ = 60°:
    # peak = sin 60° + ½ sin 120° = 3√3/4 = 1.2990381
    assert locked_peak([1, 2], [1.0, 0.5]) == pytest.approx(3 * math.sqrt(3) / 4, rel=1e-14)


@pytest.mark.parametrize(("bad", "message"), [
    (dict(orders=[1, 1]), "once"), (dict(orders=[0, 2]), "positive integers"),
    (dict(orders=[1.5, 2]), "positive integers"), (dict(fundamental=0.0), "positive"),
])
def test_bad_groups_are_refused(bad: dict, message: str) -> None:
    args = dict(orders=[1, 2], amplitudes=[[0, 0, 1], [0, 0, 1]], phases=np.zeros((2, 3)))
    args.update(bad)
    with pytest.raises(ValueError, match=message):
        locked_group(**args)


def coefficient_rows(*rows: dict[str, float]) -> np.ndarray:
    out = np.zeros((len(rows), len(COEFFICIENTS)))
    for i, row in enumerate(rows):
        for name, value in {"k1": 1.0, **row}.items():
            out[i, COEFFICIENTS.index(name)] = value
    return out


POLY = coefficient_rows(
    {"k0": 1e-3, "k2": 2e-3, "k3": -1e-3, "k4": 3e-4, "k5": -2e-4, "m1": 1e-3, "m31": 1e-3,
     "m32": 5e-4},
    {"k3": 2e-3, "k5": 1e-3},
)
TONE = vibration_at_sensor([(13.0, (0.2, 0.1, 0.5), (0.0, 30.0, 0.0))])


@pytest.mark.parametrize("omega", [0.0, 0.8, -1.7, 3.0])
def test_error_terms_match_brute_force_of_eq_2(omega: float) -> None:
    """Δ_V with a locked group + a tone: closed form (section 10) = brute force on an exact grid.

    Without A1 the grid of more than 5·n_max nodes per period is exact (docs/model.md 7, 10).
    """
    mu = profile_multipliers(TONE, np.array(omega), locked=[GROUP])
    closed = vibration_error(POLY, mu)
    est = simulate(POLY, TONE, (0.0, 0.0, omega), samples=1 << 14,
                   rng=np.random.default_rng(3), locked=[GROUP])
    assert est.scheme == "grid"
    assert est.total == pytest.approx(closed.total, rel=1e-9, abs=1e-15)
    # the sample moments of the grid equal the combined moments
    for name in ("m2", "m3", "m4", "m5", "c31", "c32"):
        assert float(getattr(est.multipliers, name)) == pytest.approx(
            float(getattr(mu, name)), rel=1e-10), name
    # the odd terms are there: k3·M3 and k5·M5
    assert EXTRA_TERMS[1:] == ("k3", "k5")
    assert closed.extra_terms[0, 1] == pytest.approx(-1e-3 * float(mu.m3), rel=1e-14)
    assert closed.extra_terms[0, 2] == pytest.approx(-2e-4 * float(mu.m5), rel=1e-14)
    # Δ(1) = 3k3·M2 + 4k4·M3 + 5k5·M4;  Δ(2) = 6k4·M2 + 10k5·M3;  Δ(3) = 10k5·M2
    m2, m3, m4 = float(mu.m2), float(mu.m3), float(mu.m4)
    q = closed.multiplicative_coefficients[0]
    assert q[0] == pytest.approx(3 * -1e-3 * m2 + 4 * 3e-4 * m3 + 5 * -2e-4 * m4, rel=1e-13)
    assert q[1] == pytest.approx(6 * 3e-4 * m2 + 10 * -2e-4 * m3, rel=1e-13)
    assert q[2] == pytest.approx(10 * -2e-4 * m2, rel=1e-13)


def test_asymmetry_with_a_random_part_matches_monte_carlo() -> None:
    noisy = vibration_at_sensor([(13.0, (0.2, 0.1, 0.5), (0.0, 30.0, 0.0))],
                                rms=(0.1, 0.1, 0.3), coherence=(0.5, 0.0))
    c = coefficient_rows({"A1": 0.05, "k3": 1e-3, "k4": 2e-3})
    omega = 0.6
    closed = vibration_error(c, profile_multipliers(noisy, np.array(omega), locked=[GROUP]))
    est = simulate(c, noisy, (0.0, 0.0, omega), samples=400_000,
                   rng=np.random.default_rng(5), locked=[GROUP])
    assert est.scheme == "monte-carlo"
    assert abs(float(est.total[0]) - float(closed.total[0])) < 6 * float(est.stderr[0])


def test_two_groups_match_brute_force() -> None:
    other = locked_group([1, 3], [[0, 0, 0.4], [0.1, 0, 0.2]], [[0, 0, 30], [0, 0, 100]])
    omega = 0.9
    mu = profile_multipliers(TONE, np.array(omega), locked=[GROUP, other])
    est = simulate(POLY, TONE, (0.0, 0.0, omega), samples=1 << 18,
                   rng=np.random.default_rng(2), locked=[GROUP, other])
    assert est.scheme == "grid"
    assert est.total == pytest.approx(vibration_error(POLY, mu).total, rel=1e-9)


@pytest.mark.parametrize("omega", [0.0, 0.3, 0.7, 1.1])
def test_two_groups_alone_e_to_1e_6(omega: float) -> None:
    # docs/model.md section 4 asks 1e-6 for tones-only mixtures. Reference: brute force,
    # <|Ω + x3(θ1) + y3(θ2)|> − |Ω| on a 3000 × 3000 midpoint grid of the two periods
    # (its own error, against 8000²: below 1e-7 at these rates). The former
    # 256-node grid over the second group was 2.6e-5 off at Ω = 1.1, 1.2e-6 at 0.7.
    g1 = locked_group([1, 2], [[0, 0, 0.5], [0, 0, 0.3]], [[0, 0, 0], [0, 0, 90]])
    g2 = locked_group([1, 3], [[0, 0, 0.4], [0, 0, 0.2]], [[0, 0, 30], [0, 0, 0]])
    theta = midpoints(3000)
    x1 = x_of((1, 2), [[0, 0, 0.5], [0, 0, 0.3]], [[0, 0, 0], [0, 0, 90]], theta)[2]
    y3 = x_of((1, 3), [[0, 0, 0.4], [0, 0, 0.2]], [[0, 0, 30], [0, 0, 0]], theta)[2]
    want = sum(float(np.abs(omega + x1[i:i + 500, None] + y3[None, :]).sum())
               for i in range(0, 3000, 500)) / 3000**2 - abs(omega)
    mu = profile_multipliers(vibration_at_sensor([]), np.array([omega]), locked=[g1, g2])
    assert 2 * float(mu.asymmetry[0]) == pytest.approx(want, rel=3e-7)


def test_symmetric_profiles_have_no_odd_terms_and_stack() -> None:
    plain = profile_multipliers(TONE, np.array([0.5, 1.0]))
    locked = profile_multipliers(TONE, np.array([0.5, 1.0]), locked=[GROUP])
    both = stack_multipliers([plain, locked])
    assert plain.m3 is None and both.m3 is not None
    assert np.all(both.m3[0] == 0) and np.all(both.m3[1] == locked.m3)
    err = vibration_error(POLY, both)
    assert np.array_equal(err.total[:, 0], vibration_error(POLY, plain).total)


def test_paper_refuses_locked_harmonics() -> None:
    with pytest.raises(ModelError, match="phase-locked harmonics"):
        profile_multipliers(TONE, np.array([0.0]), "paper", locked=[GROUP])


@settings(max_examples=25, deadline=None)
@given(
    orders=st.lists(st.integers(1, 4), min_size=1, max_size=4, unique=True),
    amps=st.lists(st.floats(0.05, 2.0), min_size=12, max_size=12),
    phases=st.lists(st.floats(-180, 180), min_size=12, max_size=12),
    omega=st.floats(-4.0, 4.0),
)
def test_closed_form_equals_brute_force_for_any_group(orders: list[int], amps: list[float],
                                                      phases: list[float],
                                                      omega: float) -> None:
    """Section 10's Δ_V = the average of eq. (2) over one period (exact grid, no A1)."""
    n = len(orders)
    g = locked_group(orders, np.reshape(amps[: 3 * n], (n, 3)),
                     np.reshape(phases[: 3 * n], (n, 3)))
    mu = profile_multipliers(TONE, np.array(omega), locked=[g])
    closed = vibration_error(POLY, mu).total
    est = simulate(POLY, TONE, (0.0, 0.0, omega), samples=1 << 15,
                   rng=np.random.default_rng(0), locked=[g])
    assert est.scheme == "grid"
    scale = float(np.max(np.abs(closed))) + 1e-12
    assert np.all(np.abs(est.total - closed) <= 1e-9 * scale)


def test_monte_carlo_with_a_group_a_random_part_and_linear_vibration() -> None:
    from gyrovib.core.linear import linear_vibration

    noisy = vibration_at_sensor(rms=(0.2, 0.1, 0.4), coherence=(0.3, 0.0))
    lin = linear_vibration([[1.0, 0.5, 2.0]], [[0, 45, 0]], (0.5, 0.5, 1.0), (0.2, 0.0, 0.1))
    c = coefficient_rows({"A1": 0.03, "k2": 1e-3, "k3": 2e-3, "k5": -1e-3})
    g2 = [[4e-4, 4e-4, 4e-4, 1e-4, 0.0, -1e-4]]
    omega = -0.4
    mu = profile_multipliers(noisy, np.array(omega), locked=[GROUP], acceleration=lin.moments())
    closed = vibration_error(c, mu, g2)
    est = simulate(c, noisy, (0.0, 0.0, omega), samples=400_000, rng=np.random.default_rng(9),
                   locked=[GROUP], linear=lin, g2_sensitivity=g2)
    assert est.scheme == "monte-carlo"
    assert abs(float(est.total[0]) - float(closed.total[0])) < 6 * float(est.stderr[0])
    assert closed.extra_terms[0, 0] != 0  # the g² term is in the comparison
