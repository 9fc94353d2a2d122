"""The worst case over a datasheet envelope (docs/model.md section 11, core.envelope).

Expected values come from closed forms worked by hand (the least-squares,
endpoint and Chebyshev lines of |ω|, ω², ω³; V. Markov's coefficient bound for
polynomials bounded on [−1, 1]), from an independent fine-grid LP solved
directly with scipy, from random feasible polynomials (brute force), and from
a general-purpose optimiser for the rms measure.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gyrovib.core import envelope_lp
from gyrovib.core.envelope import (
    TERMS,
    residual,
    spec_bounds,
    term_functionals,
    worst_case,
)
from gyrovib.errors import ModelError

#: One random-vibration profile in deg/s: σ = 2 (M2 = 4, M4 = 3σ⁴ = 48, docs/model.md
#: section 4), g_A = ½·E(Ω) at Ω = 0: ½·σ·√(2/π); plus a phase-locked pair
#: giving odd moments (M3, M5 made up, only their linearity matters here).
SIGMA = 2.0
G_A0 = 0.5 * SIGMA * np.sqrt(2 / np.pi)


def profile(omega: float = 0.0, m3: float = 0.0, m5: float = 0.0) -> np.ndarray:
    return term_functionals(G_A0, SIGMA**2, m3, 3 * SIGMA**4, m5, [omega])


def only(coefficient: int, weight: float = 1.0) -> np.ndarray:
    """terms whose sum is weight·e_coefficient (a functional of one coefficient)."""
    t = np.zeros((1, 8, 5))
    t[0, coefficient, coefficient] = weight
    return t


def midpoints(r: float, n: int) -> np.ndarray:
    """n midpoints of equal cells of [−R, R]: the midpoint rule for means over uniform ω."""
    return -r + (np.arange(n) + 0.5) * (2 * r / n)


def fine_lp(c: np.ndarray, r: float, b: float, fit: str, n: int = 4001) -> float:
    """max cᵀx with |p − L| ≤ b on n uniform points: an upper bound of the continuous optimum."""
    from scipy.optimize import linprog

    w = np.linspace(-r, r, n)
    phi = np.column_stack([0.5 * np.abs(w), w**2, w**3, w**4, w**5])
    if fit == "least-squares":  # subtract each basis function's own least-squares line
        wq = midpoints(r, 20000)
        ls = np.column_stack([np.ones(wq.size), wq])
        phq = np.column_stack([0.5 * np.abs(wq), wq**2, wq**3, wq**4, wq**5])
        coef, *_ = np.linalg.lstsq(ls, phq, rcond=None)
        rows = phi - np.column_stack([np.ones(n), w]) @ coef
        a = rows
    elif fit == "endpoint":
        lo, hi = phi[0], phi[-1]
        a = phi - (0.5 * (lo + hi))[None, :] - np.outer(w, (hi - lo) / (2 * r))
    else:
        a = np.column_stack([phi, -np.ones(n), -w])
        c = np.concatenate([c, [0.0, 0.0]])
    res = linprog(-c, A_ub=np.vstack([a, -a]), b_ub=np.full(2 * n, b),
                  bounds=[(None, None)] * a.shape[1], method="highs")
    assert res.status == 0
    return float(-res.fun)


# --- analytic cases --------------------------------------------------------------


@pytest.mark.parametrize("r", [1.0, 300.0])
def test_asymmetry_alone_deviates_by_a1_r_over_4(r: float) -> None:
    # ½A1|ω| has mean A1·R/4 over [−R, R] and no slope: its least-squares line is the
    # constant A1·R/4, and the residual reaches A1·R/4 at ω = 0 and ω = ±R.
    a1 = 0.02
    x = np.array([a1, 0, 0, 0, 0])
    w = np.linspace(-r, r, 200001)
    wm = midpoints(r, 200000)
    line = np.polyfit(wm, 0.5 * a1 * np.abs(wm), 1)[::-1]
    assert line[0] == pytest.approx(a1 * r / 4, rel=1e-6)
    assert np.max(np.abs(residual(x, line, w))) == pytest.approx(a1 * r / 4, rel=1e-6)
    # the engine's own continuous check of the normalised residual, y1 = 1
    mx, _ = envelope_lp.true_max(np.array([0]), np.array([[1.0, 0, 0, 0, 0]]), np.zeros((1, 2)))
    assert mx[0] == pytest.approx(0.25, rel=1e-12)  # so a pure asymmetry has |A1| ≤ 4b/R


@pytest.mark.parametrize(
    ("fit", "k", "line", "dev"),
    [
        # ω² against its minimax line R²/2 (equioscillates at 0, ±R): R²/2
        ("minimax", 2, (0.5, 0.0), 0.5),
        # ω³ against its Chebyshev line (3R²/4)·ω: ω³ − ¾ω = T3/4, deviation R³/4
        ("minimax", 3, (0.0, 0.75), 0.25),
        # ω² against its least-squares line R²/3 (mean of ω²): 2R²/3 at ±R
        ("least-squares", 2, (1 / 3, 0.0), 2 / 3),
        # ω³ against its least-squares line (3R²/5)·ω (∫ω⁴/∫ω² = 3R²/5): 2R³/5 at ±R
        ("least-squares", 3, (0.0, 0.6), 0.4),
        # endpoint lines: R² and R²·ω; deviations R² (at 0) and 2R³/(3√3) (at R/√3)
        ("endpoint", 2, (1.0, 0.0), 1.0),
        ("endpoint", 3, (0.0, 1.0), 2 / (3 * np.sqrt(3))),
    ],
)
def test_pure_k2_k3_against_their_lines(fit: str, k: int, line: tuple[float, float],
                                        dev: float) -> None:
    r = 7.0
    y = np.zeros((1, 5))
    y[0, k - 1] = 1.0
    f = np.array([envelope_lp.FITS.index(fit)])
    free = np.array([line]) if fit == "minimax" else np.zeros((1, 2))
    mx, _ = envelope_lp.true_max(f, y, free)
    assert mx[0] == pytest.approx(dev, rel=1e-12)
    x = np.zeros(5)
    x[k - 1] = 1.0
    w = np.linspace(-r, r, 100001)
    ln = np.array([line[0] * r**k, line[1] * r ** (k - 1)])
    assert np.max(np.abs(residual(x, ln, w))) == pytest.approx(dev * r**k, rel=1e-8)


@pytest.mark.parametrize(("k", "bound"), [(3, 20.0), (5, 16.0)])
def test_minimax_odd_coefficients_obey_markov(k: int, bound: float) -> None:
    # The odd part of r, y3u³ + y5u⁵ − βu, is bounded by max|r| ≤ 1; V. Markov: a degree-5
    # polynomial bounded by 1 on [−1, 1] has |a3| ≤ 20 and |a5| ≤ 16, both attained by
    # T5 = 16u⁵ − 20u³ + 5u. So max k3 = 20·b/R³ and max k5 = 16·b/R⁵.
    r, b = 3.0, 0.01
    wc = worst_case(only(k - 1), 0.0, [r], [b], "minimax")
    assert wc.nonlinearity[0, 0] == pytest.approx(bound * b / r**k, rel=1e-6)
    assert wc.gap[0, 0] <= 1e-7


def test_pure_asymmetry_spec_caps_a1() -> None:
    # With |A1| ≤ a_max the A1 term's worst is g_A·a_max once a_max is below the
    # envelope's own limit (≈ 29·b/R, docs/model.md section 11).
    r, b = 100.0, 0.1
    wc = worst_case(only(0), 0.0, [r], [b], asymmetry=[1e-3])
    assert wc.nonlinearity[0, 0] == pytest.approx(1e-3, rel=1e-9)
    free = worst_case(only(0), 0.0, [r], [b])
    assert 25 * b / r < free.nonlinearity[0, 0] < 32 * b / r


# --- the worst case against independent computations --------------------------------


@pytest.mark.parametrize("fit", ["least-squares", "minimax", "endpoint"])
@pytest.mark.parametrize("omega", [0.0, 1.5])
def test_worst_case_against_fine_grid_lp(fit: str, omega: float) -> None:
    r, b = 4.0, 0.02
    t = profile(omega, m3=0.7, m5=2.0)
    wc = worst_case(t, 0.0, [r], [b], fit)
    fine = fine_lp(t.sum(axis=1)[0], r, b, fit)
    # the grid LP relaxes the constraint: its optimum is above the continuous one
    assert wc.nonlinearity[0, 0] <= fine * (1 + 1e-7)
    assert wc.nonlinearity[0, 0] >= fine * (1 - 1e-4)


@settings(deadline=None, max_examples=15, derandomize=True)
@given(seed=st.integers(0, 2**32 - 1), fit=st.sampled_from(["least-squares", "endpoint",
                                                             "minimax"]))
def test_random_feasible_polynomials_never_exceed_the_worst(seed: int, fit: str) -> None:
    rng = np.random.default_rng(seed)
    r = float(rng.uniform(0.5, 5.0))
    b = float(rng.uniform(0.001, 0.1))
    t = profile(float(rng.uniform(-2, 2)), m3=float(rng.normal()), m5=float(rng.normal()))
    c = t.sum(axis=1)[0]
    wc = worst_case(t, 0.0, [r], [b], fit)
    worst = wc.nonlinearity[0, 0]
    w = np.linspace(-r, r, 20001)
    # random polynomials, scaled into the envelope: residual from the least-squares line
    # of the dense grid (any line bounds the minimax residual from above)
    x = rng.normal(size=(200, 5)) / r ** np.arange(1, 6) * rng.uniform(0, 1, (200, 1)) ** 3
    p = residual(x, np.zeros((200, 2)), w)
    if fit == "endpoint":
        line = np.column_stack([(p[:, 0] + p[:, -1]) / 2, (p[:, -1] - p[:, 0]) / (2 * r)])
    else:
        wm = midpoints(r, 20000)
        line = np.polyfit(wm, residual(x, np.zeros((200, 2)), wm).T, 1)[::-1].T
    dev = np.max(np.abs(p - line[:, :1] - line[:, 1:] * w), axis=1)
    vals = np.abs(x @ c) * b / dev
    assert np.all(vals <= worst * (1 + 1e-6))
    # the reported polynomial: feasible on a dense grid, attains the value
    xs = wc.coefficients[0, 0]
    assert np.max(np.abs(residual(xs, wc.line[0, 0], w))) <= b * (1 + 1e-9)
    assert xs @ c == pytest.approx(worst, rel=1e-12)
    if fit == "least-squares":  # its line is its least-squares line
        wm = midpoints(r, 20000)
        ps = residual(xs, np.zeros(2), wm)
        np.testing.assert_allclose(wc.line[0, 0], np.polyfit(wm, ps, 1)[::-1], rtol=1e-6,
                                   atol=1e-8 * b)


def test_symmetry_and_vre_term() -> None:
    t = profile(0.8, m3=0.3)
    a = worst_case(t, 2.0, [3.0], [0.01], vre=[5e-4])
    b = worst_case(-t, 2.0, [3.0], [0.01], vre=[-5e-4])
    np.testing.assert_allclose(a.total, b.total, rtol=1e-12)
    np.testing.assert_allclose(a.coefficients, -b.coefficients, rtol=1e-12)
    assert a.total[0, 0] == pytest.approx(a.nonlinearity[0, 0] + 5e-4 * 2.0, rel=1e-14)


@pytest.mark.parametrize("fit", ["least-squares", "minimax", "endpoint"])
def test_mirror_rate_mirrors_the_worst_polynomial(fit: str) -> None:
    # Without odd moments Δ_V(−Ω) is Δ_V(Ω) of the mirrored sensor p(−ω): k3, k5 and the
    # line's slope change sign (docs/model.md section 4: Δ(1), Δ(3) odd in Ω, Δ(2) even).
    t = np.concatenate([profile(0.9), profile(-0.9)])
    wc = worst_case(t, 0.0, [2.0], [0.01], fit)
    assert wc.total[0, 0] == pytest.approx(wc.total[0, 1], rel=1e-12)
    mirror = np.array([1.0, 1.0, -1.0, 1.0, -1.0])
    np.testing.assert_allclose(wc.coefficients[0, 1], mirror * wc.coefficients[0, 0],
                               rtol=1e-12)
    np.testing.assert_allclose(wc.line[0, 1], [1.0, -1.0] * wc.line[0, 0], rtol=1e-12,
                               atol=1e-15)
    # and the mirrored polynomial is feasible: its residual is the mirror image
    w = np.linspace(-2.0, 2.0, 4001)
    np.testing.assert_allclose(residual(wc.coefficients[0, 1], wc.line[0, 1], w),
                               residual(wc.coefficients[0, 0], wc.line[0, 0], -w), atol=1e-15)


def test_per_term_maxima_and_rms_bound() -> None:
    t = profile(1.2, m3=0.4, m5=1.0)
    wc = worst_case(t, 1.0, [2.5], [0.02], vre=[1e-3])
    xs = wc.coefficients[0, 0]
    each = np.abs(t[0] @ xs)  # the terms of the worst polynomial
    assert np.all(each <= wc.terms[0, 0, :8] * (1 + 1e-9))
    # triangle inequality: the worst sum is at most the sum of the worst terms
    assert wc.nonlinearity[0, 0] <= wc.terms[0, 0, :8].sum() * (1 + 1e-9)
    assert wc.terms[0, 0, 8] == pytest.approx(1e-3, rel=1e-14)
    assert wc.rms_bound[0, 0] == pytest.approx(np.sqrt(np.sum(wc.terms[0, 0] ** 2)))
    assert len(TERMS) == 8


def test_vectorised_equals_one_by_one() -> None:
    t = np.concatenate([profile(0.0), profile(1.0, m3=0.2), profile(-2.0)])
    rs = [1.0, 2.0, 2.0, 5.0]
    bs = [0.01, 0.02, 0.03, 0.01]
    fits = ["least-squares", "minimax", "least-squares", "endpoint"]
    meas = ["max", "max", "rms", "rms"]
    asym = [np.inf, 0.05, 0.002, 0.01]
    all_ = worst_case(t, [0, 1, 2], rs, bs, fits, meas, asym, [0, 1e-3, 0, 2e-3])
    for i in range(4):
        one = worst_case(t, [0, 1, 2], [rs[i]], [bs[i]], fits[i], meas[i], [asym[i]],
                         [[0, 1e-3, 0, 2e-3][i]])
        # each within 1e-7 below the continuous optimum (the grids may differ by seeding)
        np.testing.assert_allclose(all_.total[i], one.total[0], rtol=2e-7)
        np.testing.assert_allclose(all_.rms_bound[i], one.rms_bound[0], rtol=2e-7)


def test_worst_case_scales_with_b() -> None:
    t = profile(0.5, m3=0.1)
    wc = worst_case(t, 0.0, [2.0, 2.0], [0.01, 0.03])
    assert wc.total[1, 0] == pytest.approx(3 * wc.total[0, 0], rel=1e-12)


# --- rms measure ---------------------------------------------------------------------


def rms_by_optimiser(d: np.ndarray, fit: int, a: float) -> float:
    from scipy.optimize import minimize

    nodes, weights = np.polynomial.legendre.leggauss(12)  # exact for degree ≤ 23 per side
    u = np.concatenate([(nodes - 1) / 2, (nodes + 1) / 2])
    wq = np.concatenate([weights, weights]) / 4  # mean over [−1, 1]
    psi = envelope_lp.basis(np.full(u.shape, fit), u)

    def ms(y: np.ndarray) -> float:
        return float(wq @ (psi @ y) ** 2)

    best = -np.inf
    for start in np.random.default_rng(0).normal(size=(4, 5)) * 0.1:
        res = minimize(lambda y: -d @ y, start, method="SLSQP",
                       constraints=[{"type": "ineq", "fun": lambda y: 1 - ms(y)}],
                       bounds=[(-a, a)] + [(None, None)] * 4,
                       options={"ftol": 1e-12, "maxiter": 500})
        if ms(res.x) <= 1 + 1e-8:
            best = max(best, -res.fun)
    return best


@pytest.mark.parametrize("fit", [0, 2])
@pytest.mark.parametrize("a", [np.inf, 3.0, 0.5])
def test_rms_closed_form_against_optimiser(fit: int, a: float) -> None:
    rng = np.random.default_rng(fit * 10 + int(a if np.isfinite(a) else 99))
    d = rng.normal(size=5)
    d[0] = 3.0  # lean on A1 so the asymmetry cut is active
    h, y, _, _ = envelope_lp.support(np.array([fit]), np.array([1]), np.array([a]), d[None])
    assert h[0] == pytest.approx(rms_by_optimiser(d, fit, a), rel=1e-5)
    assert y[0] @ envelope_lp.gram(fit) @ y[0] == pytest.approx(1.0, rel=1e-9)
    assert abs(y[0, 0]) <= a * (1 + 1e-12)


def test_gram_matches_quadrature() -> None:
    nodes, weights = np.polynomial.legendre.leggauss(12)
    u = np.concatenate([(nodes - 1) / 2, (nodes + 1) / 2])
    wq = np.concatenate([weights, weights]) / 4
    for fit in range(3):
        psi = envelope_lp.basis(np.full(u.shape, fit), u)
        np.testing.assert_allclose(envelope_lp.gram(fit), psi.T @ (psi * wq[:, None]),
                                   rtol=1e-12, atol=1e-15)


def test_rms_with_minimax_is_refused() -> None:
    with pytest.raises(ModelError, match="least-squares or endpoint"):
        worst_case(profile(), 0.0, [1.0], [0.01], "minimax", "rms")


# --- spec bounds -----------------------------------------------------------------------


@pytest.mark.parametrize(("of", "measure"), [("range", "max"), ("span", "rms"),
                                             ("rate", "max")])
def test_nl_max_times_w1_is_the_share(of: str, measure: str) -> None:
    # S = Σ⟨a_j²⟩ = 0 (no linear vibration) and 9 g². docs/model.md section 11 splits Δ*
    # between envelope and g² term in the ratio (1, 1) over the parts the profile
    # excites: profile 0 gives the envelope all of Δ* (share 1, VRE_max = +inf),
    # profile 1 half each (share ½, VRE_max = ½·Δ*/S = ½·0.01/9).
    t = np.concatenate([profile(0.3), profile(1.0, m3=0.5)])
    s = np.array([0.0, 9.0])
    r, budget = 300.0, 0.01
    sb = spec_bounds(budget, t, s, r, "least-squares", measure, of)
    np.testing.assert_allclose(sb.share_nl, [1.0, 0.5])
    b = nonlinearity_limit(sb.nonlinearity, r, of)
    np.testing.assert_allclose(b * sb.w1, sb.share_nl * budget, rtol=1e-12)
    # a sensor at both limits uses the budget exactly, whatever its polynomial
    for p in range(2):
        wc = worst_case(t[p:p + 1], s[p:p + 1], [r], [b[p]], "least-squares", measure,
                        vre=[sb.vre[p] if np.isfinite(sb.vre[p]) else 0.0])
        assert wc.total[0, 0] == pytest.approx(budget, rel=1e-6)
    assert sb.vre[0] == np.inf
    assert sb.vre[1] == pytest.approx(0.5 * budget / 9.0)


def nonlinearity_limit(value: np.ndarray, range_: float, of: str) -> np.ndarray:
    """b, the residual limit in rate (docs/model.md section 11): value % of R ("range"),
    of 2R ("span"), or the value itself ("rate")."""
    return value * {"range": range_ / 100.0, "span": 2.0 * range_ / 100.0, "rate": 1.0}[of]


def test_nonlinearity_limit() -> None:
    # the helper above, by hand: 0.1 %FS of 300 deg/s = 0.3 deg/s; of the span
    # 600 deg/s: 0.6 deg/s; an absolute rate is the limit itself, 0.25 deg/s
    assert nonlinearity_limit(np.array(0.1), 300.0, "range") == pytest.approx(0.3)
    assert nonlinearity_limit(np.array(0.1), 300.0, "span") == pytest.approx(0.6)
    assert nonlinearity_limit(np.array(0.25), 300.0, "rate") == pytest.approx(0.25)


# --- unit invariance ---------------------------------------------------------------------


@settings(deadline=None, max_examples=10, derandomize=True)
@given(s=st.sampled_from([1 / 3600, 180 / np.pi, 6.0, 0.37]),
       fit=st.sampled_from(["least-squares", "minimax", "endpoint"]),
       measure=st.sampled_from(["max", "rms"]))
def test_unit_change_changes_nothing(s: float, fit: str, measure: str) -> None:
    # One rate unit U = s deg/s (docs/model.md section 2): rates divide by s, M_n by s^n,
    # kn multiply by s^(n−1), A1 and S stay, a VRE in rate/g² divides by s.
    if fit == "minimax" and measure == "rms":
        return
    r, b, om, m3, m5 = 250.0, 0.5, 1.5, 0.8, 3.0
    t1 = term_functionals(G_A0, SIGMA**2, m3, 3 * SIGMA**4, m5, [om])
    t2 = term_functionals(G_A0 / s, SIGMA**2 / s**2, m3 / s**3, 3 * SIGMA**4 / s**4,
                          m5 / s**5, [om / s])
    a = worst_case(t1, 2.0, [r], [b], fit, measure, [1e-3], [1e-4])
    u = worst_case(t2, 2.0, [r / s], [b / s], fit, measure, [1e-3], [1e-4 / s])
    np.testing.assert_allclose(u.total * s, a.total, rtol=1e-6)
    np.testing.assert_allclose(u.rms_bound * s, a.rms_bound, rtol=1e-6)
    np.testing.assert_allclose(u.coefficients[0, 0] / s ** np.arange(0, 5),
                               a.coefficients[0, 0], rtol=1e-5, atol=1e-12)
