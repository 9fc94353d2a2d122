"""An independent second implementation of docs/model.md section 14, held against gyrovib.

Everything below the imports up to the tests is written from docs/model.md
sections 2, 11 and 14 alone, with numpy and math (no gyrovib code), by other
routes than the library's:

* eq. (1) as U = K0 + K1·Ω + h·|Ω| + Σ Kn·Ωⁿ [+ Mi·ωi + M3i·Ω·ωi], h = ½·K1·A1
  (K1·(1 + ½A1·sign Ω)·Ω = K1·Ω + ½K1A1·|Ω|), solved from the normal
  equations in exact rational arithmetic (``fractions``) on the very floats
  the library receives (the library: QR of a scaled, column-normalised matrix
  in floating point); Cov(θ̂) = s²·(XᵀX)⁻¹, s² = RSS/(n − p);
* eq. (2) by division by K1, the Jacobian written out entry by entry
  (∂(c·N/K1)/∂N = c/K1, ∂/∂K1 = −c·N/K1², c = 2 for A1);
* the nonlinearity in % of R (docs/model.md section 11, ``of: range``): the
  least-squares line over uniform ω ∈ [−R, R] from Gauss–Legendre moments on
  each half (exact for these piecewise polynomials), the endpoint line through
  p(±R), the largest deviation at ±R, 0 and the real roots (``numpy.roots``)
  of the residual's derivative on each half;
* the exact yield P(|Δ_V| ≤ Δ*) for Δ_V ~ N(gᵀμ, gᵀΣg) from ``math.erfc``,
  and the Wilson interval as the two roots of (p − p̂)² = z²·p(1 − p)/n;
* g for one tone on the sensitive axis in closed form: with ω3 = Ω + a·sin θ,
  the mean of Ω_F3(ω3) − Ω_F3(Ω) over θ is ½A1·(⟨|ω3|⟩ − |Ω|) + k2·a²/2 +
  k3·3Ωa²/2 + k4·(3Ω²a² + 3a⁴/8) + k5·(5Ω³a² + 15Ωa⁴/8), ⟨|ω3|⟩ =
  (2/π)(Ω·asin(Ω/a) + √(a² − Ω²)) for a ≥ |Ω|.

The library agrees with this exact solution to 1e-10 (relative to the larger
of a value and its standard uncertainty: round-off in an ill-conditioned fit
is on that scale) on the bundled example and on random tables.
"""

from __future__ import annotations

import csv
import math
from fractions import Fraction
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from gyrovib.core.fit import fit_rate_table
from gyrovib.core.lot import direct_yield, lot_statistics, wilson_interval

ROOT = Path(__file__).resolve().parent.parent
EXAMPLE = ROOT / "docs" / "examples" / "rate-table-gx100.csv"
TOLERANCE = 1e-10

# --------------------------------------------------------------------------- the reference


def _solve_exact(a: list[list[Fraction]]) -> list[list[Fraction]]:
    """The inverse of the square rational matrix ``a`` by Gauss–Jordan elimination."""
    p = len(a)
    m = [row[:] + [Fraction(int(i == j)) for j in range(p)] for i, row in enumerate(a)]
    for i in range(p):
        pivot = next(k for k in range(i, p) if m[k][i] != 0)
        m[i], m[pivot] = m[pivot], m[i]
        lead = m[i][i]
        m[i] = [v / lead for v in m[i]]
        for k in range(p):
            if k != i and m[k][i] != 0:
                f = m[k][i]
                m[k] = [v - f * w for v, w in zip(m[k], m[i], strict=True)]
    return [row[p:] for row in m]


def reference_fit(rate: Any, output: Any, order: int,
                  cross: Any = None) -> dict[str, Any]:
    """OLS of eq. (1) and eq. (2) with the delta-method covariance (see the module
    docstring), in exact rational arithmetic on the floats given (rounded to float
    only at the end). ``cross`` (n, k): ω1[, ω2]. Returns theta/cov_theta (K0, K1,
    h, K2..KN, M1.., M31..), c/cov_c (k0, A1, k2..kN, m1.., m31..), rms = √(RSS/n),
    s = √(RSS/(n − p)), R = max |Ω|."""
    w = [Fraction(float(v)) for v in np.asarray(rate, dtype=float)]
    u = [Fraction(float(v)) for v in np.asarray(output, dtype=float)]
    crossed = ([[Fraction(float(v)) for v in row]
                for row in np.asarray(cross, dtype=float).reshape(len(w), -1)]
               if cross is not None else [[] for _ in w])
    # the design matrix in Ω itself (no scaling is needed in exact arithmetic)
    design = [[Fraction(1), wi, abs(wi), *(wi**n for n in range(2, order + 1)),
               *row, *(wi * v for v in row)] for wi, row in zip(w, crossed, strict=True)]
    n, p = len(design), len(design[0])
    normal = [[sum((r[i] * r[j] for r in design), Fraction(0)) for j in range(p)] for i in range(p)]
    inverse = _solve_exact(normal)
    xty = [sum(r[i] * ui for r, ui in zip(design, u, strict=True)) for i in range(p)]
    theta = [sum(inverse[i][j] * xty[j] for j in range(p)) for i in range(p)]
    residual = [ui - sum(t * x for t, x in zip(theta, r, strict=True))
                for r, ui in zip(design, u, strict=True)]
    rss = sum(e * e for e in residual)
    s2 = rss / (n - p)
    cov_theta = [[s2 * inverse[i][j] for j in range(p)] for i in range(p)]
    k1 = theta[1]
    # numerators: every parameter but K1; A1 = 2h/K1, the others N/K1
    numerators = [0, *range(2, p)]
    c: list[Fraction] = []
    jac: list[list[Fraction]] = []
    for j in numerators:
        factor = Fraction(2 if j == 2 else 1)
        c.append(factor * theta[j] / k1)
        row = [Fraction(0)] * p
        row[j] = factor / k1
        row[1] = -factor * theta[j] / k1**2
        jac.append(row)
    cov_c = [[sum(jac[a][i] * cov_theta[i][j] * jac[b][j] for i in range(p) for j in range(p))
              for b in range(len(c))] for a in range(len(c))]

    def real(v: Fraction) -> float:
        try:
            return float(v)
        except OverflowError:  # beyond double precision (a variance of outputs ~1e300)
            return math.inf if v > 0 else -math.inf

    def floats(m: Any) -> np.ndarray:
        return np.array([[real(v) for v in row] for row in m])

    return {"theta": np.array([real(v) for v in theta]), "cov_theta": floats(cov_theta),
            "c": np.array([real(v) for v in c]), "cov_c": floats(cov_c),
            "rms": math.sqrt(real(rss / n)), "s": math.sqrt(real(s2)),
            "R": float(max(abs(v) for v in w))}


def _gauss_legendre(f: Any, a: float, b: float, points: int = 24) -> float:
    t, weight = np.polynomial.legendre.leggauss(points)
    return 0.5 * (b - a) * float(np.sum(weight * f(0.5 * (a + b) + 0.5 * (b - a) * t)))


def reference_nonlinearity(c: Any, big_r: float) -> tuple[float, float]:
    """(least-squares, endpoint) max deviation of p(ω) = k0 + ω + ½A1|ω| + Σ kn ωⁿ from
    its line over [−R, R], in % of R; c = (k0, A1, k2, ...)."""
    k0, a1, kn = float(c[0]), float(c[1]), np.asarray(c[2:], dtype=float)

    def p(w: Any) -> Any:
        w = np.asarray(w, dtype=float)
        return k0 + w + 0.5 * a1 * np.abs(w) + sum(k * w ** (j + 2) for j, k in enumerate(kn))

    mean = (_gauss_legendre(p, -big_r, 0.0) + _gauss_legendre(p, 0.0, big_r)) / (2 * big_r)
    first = (_gauss_legendre(lambda w: w * p(w), -big_r, 0.0)
             + _gauss_legendre(lambda w: w * p(w), 0.0, big_r)) / (2 * big_r)
    least_squares = (mean, first / (big_r**2 / 3.0))  # E[ω] = 0, E[ω²] = R²/3
    top, bottom = float(p(big_r)), float(p(-big_r))
    endpoint = (0.5 * (top + bottom), (top - bottom) / (2 * big_r))

    def deviation(line: tuple[float, float]) -> float:
        best = 0.0
        for side in (1.0, -1.0):
            ascending = np.zeros(2 + kn.size)
            ascending[0] = k0 - line[0]
            ascending[1] = 1.0 + side * 0.5 * a1 - line[1]
            ascending[2:] = kn
            points = [0.0, side * big_r]
            derivative = np.trim_zeros(np.arange(1, ascending.size) * ascending[1:], "b")
            if derivative.size > 1:
                for root in np.roots(derivative[::-1]):
                    if abs(root.imag) <= 1e-9 * big_r and 0.0 <= side * root.real <= big_r:
                        points.append(float(root.real))
            best = max(best, *(abs(float(np.polyval(ascending[::-1], v))) for v in points))
        return 100.0 * best / big_r

    return deviation(least_squares), deviation(endpoint)


def reference_yield(g: Any, mu: Any, sigma: Any, budget: float) -> float:
    """P(|Δ_V| ≤ Δ*), Δ_V ~ N(m, s²), m = gᵀμ, s² = gᵀΣg, from math.erfc."""
    def phi(v: float) -> float:
        return 0.5 * math.erfc(-v / math.sqrt(2.0))

    gv = np.asarray(g, dtype=float)
    m = float(gv @ np.asarray(mu, dtype=float))
    s = math.sqrt(float(gv @ np.asarray(sigma, dtype=float) @ gv))
    if s == 0.0:
        return float(abs(m) <= budget)
    lo, hi = (-budget - m) / s, (budget - m) / s
    return phi(-lo) - phi(-hi) if lo > 0 else phi(hi) - phi(lo)


def reference_wilson(k: int, n: int, z: float = 1.959963984540054) -> tuple[float, float]:
    """The roots in p of (p − k/n)² = z²·p(1 − p)/n."""
    ph = k / n
    a, b, c = 1.0 + z * z / n, -(2.0 * ph + z * z / n), ph * ph
    root = math.sqrt(max(b * b - 4.0 * a * c, 0.0))
    return max((-b - root) / (2 * a), 0.0), min((-b + root) / (2 * a), 1.0)


def tone_g(omega: float, amplitude: float) -> np.ndarray:
    """g of (k0, A1, k2, k3, k4, k5) for ω3 = Ω + a·sin θ, a ≥ |Ω| (module docstring)."""
    w, a = omega, amplitude
    mean_abs = (2.0 / math.pi) * (w * math.asin(w / a) + math.sqrt(a * a - w * w))
    return np.array([0.0, 0.5 * (mean_abs - abs(w)), a * a / 2, 1.5 * w * a * a,
                     3 * w * w * a * a + 3 * a**4 / 8, 5 * w**3 * a * a + 15 * w * a**4 / 8])


# --------------------------------------------------------------------------- helpers


def example_units() -> dict[str, tuple[np.ndarray, np.ndarray]]:
    with EXAMPLE.open(encoding="utf-8") as handle:
        rows = list(csv.reader(line for line in handle if not line.startswith("#")))
    units: dict[str, list[tuple[float, float]]] = {}
    for unit, rate, output in rows[1:]:
        units.setdefault(unit, []).append((float(rate), float(output)))
    return {u: (np.array(v)[:, 0], np.array(v)[:, 1]) for u, v in units.items()}


def assert_same_fit(fit: Any, ref: dict[str, Any]) -> None:
    """Values to 1e-10 of max(|value|, σ); covariances to 1e-10 of σi·σj."""
    sigma = np.sqrt(np.diag(ref["cov_c"]))
    scale = np.maximum(np.abs(ref["c"]), sigma)
    assert np.all(np.abs(fit.values - ref["c"]) <= TOLERANCE * scale)
    assert np.all(np.abs(fit.covariance - ref["cov_c"]) <= TOLERANCE * np.outer(sigma, sigma))
    raw_sigma = np.sqrt(np.diag(ref["cov_theta"]))
    raw_scale = np.maximum(np.abs(ref["theta"]), raw_sigma)
    assert np.all(np.abs(fit.raw_values - ref["theta"]) <= TOLERANCE * raw_scale)
    assert np.all(np.abs(fit.raw_covariance - ref["cov_theta"])
                  <= TOLERANCE * np.outer(raw_sigma, raw_sigma))
    assert fit.residual_rms == pytest.approx(ref["rms"], rel=TOLERANCE)
    assert fit.residual_sigma == pytest.approx(ref["s"], rel=TOLERANCE)
    # the nonlinearity of the library's own coefficients (compared above), by the reference
    least_squares, endpoint = reference_nonlinearity(fit.values[:fit.order + 1], ref["R"])
    assert fit.nonlinearity.range == ref["R"]
    assert fit.nonlinearity.least_squares_max == pytest.approx(least_squares, rel=TOLERANCE)
    assert fit.nonlinearity.endpoint_max == pytest.approx(endpoint, rel=TOLERANCE)


# --------------------------------------------------------------------------- the tests


def test_the_reference_recovers_stated_coefficients() -> None:
    """The reference itself, on noise-free data from stated eq. (2) coefficients."""
    w = np.repeat([-300.0, -200.0, -100.0, -50.0, 0.0, 50.0, 100.0, 200.0, 300.0], 2)
    c = [0.2, 2e-3, 3e-6, -4e-9, 1.5e-12, 1e-14]
    u = 25.0 * (c[0] + w + 0.5 * c[1] * np.abs(w)
                + sum(c[n] * w**n for n in range(2, 6)))
    ref = reference_fit(w, u, 5)
    assert np.allclose(ref["c"], c, rtol=1e-9, atol=0.0)
    assert ref["theta"][2] == pytest.approx(0.5 * 25.0 * c[1], rel=1e-9)  # h = ½K1A1


def test_the_bundled_example_agrees_with_the_reference() -> None:
    units = example_units()
    assert len(units) == 8
    coefficients = []
    for rate, output in units.values():
        fit = fit_rate_table(rate, output, 5)
        ref = reference_fit(rate, output, 5)
        assert_same_fit(fit, ref)
        coefficients.append(ref["c"])
    c = np.array(coefficients)
    lot = lot_statistics(c)
    centred = c - c.mean(axis=0)
    sample = centred.T @ centred / (len(c) - 1)  # n − 1 in the denominator
    assert np.allclose(lot.mean, c.mean(axis=0), rtol=TOLERANCE, atol=0.0)
    assert np.allclose(lot.sigma, np.sqrt(np.diag(sample)), rtol=1e-8, atol=0.0)
    # yield of the direct test for the docs' tone (20 deg/s at 180 Hz on x3, Ω = 5 deg/s)
    g = tone_g(5.0, 20.0)
    for budget in (0.005, 0.01, 0.02):
        assert float(direct_yield(g, lot.mean, lot.covariance, budget)) == pytest.approx(
            reference_yield(g, c.mean(axis=0), sample, budget), rel=1e-9, abs=1e-12)


@pytest.mark.parametrize("seed", range(12))
def test_random_tables_agree_with_the_reference(seed: int) -> None:
    rng = np.random.default_rng(seed)
    for _ in range(10):
        order = int(rng.integers(1, 6))
        big_r = 10 ** rng.uniform(-2, 4)
        levels = np.sort(rng.uniform(0.05, 1.0, size=order + 3)) * big_r
        levels[-1] = big_r
        w = np.repeat(np.concatenate([levels, -levels, [0.0]]), int(rng.integers(1, 4)))
        k1 = 10 ** rng.uniform(-3, 3) * rng.choice([-1.0, 1.0])
        c = [rng.normal() * big_r * 1e-3, rng.normal() * 1e-2,
             *(rng.normal() * 1e-3 / big_r ** (n - 1) for n in range(2, order + 1))]
        u = k1 * (c[0] + w + 0.5 * c[1] * np.abs(w)
                  + sum(c[n] * w**n for n in range(2, order + 1)))
        u = u + rng.normal(size=w.size) * abs(k1) * big_r * 10 ** rng.uniform(-6, -2)
        assert_same_fit(fit_rate_table(w, u, order), reference_fit(w, u, order))


def test_cross_rate_terms_agree_with_the_reference() -> None:
    rng = np.random.default_rng(5)
    base = np.array([-200.0, -100.0, -50.0, 0.0, 50.0, 100.0, 200.0])
    w = np.concatenate([base, base, base])
    cross = np.column_stack([np.repeat([0.0, 30.0, -20.0], base.size),
                             np.repeat([10.0, 0.0, 25.0], base.size)])
    u = 12.0 * (0.1 + w + 0.5 * 1e-3 * np.abs(w) + 2e-6 * w**2 - 3e-9 * w**3
                + 2e-3 * cross[:, 0] - 1e-3 * cross[:, 1]
                + 4e-6 * w * cross[:, 0] + 1e-6 * w * cross[:, 1])
    u = u + rng.normal(0.0, 0.01, size=w.size)
    fit = fit_rate_table(w, u, 3, cross)
    assert fit.names == ("k0", "A1", "k2", "k3", "m1", "m2", "m31", "m32")
    assert_same_fit(fit, reference_fit(w, u, 3, cross))


def test_exact_yield_agrees_with_the_reference() -> None:
    rng = np.random.default_rng(11)
    for _ in range(200):
        g, mu = rng.normal(size=4), rng.normal(size=4) * rng.uniform(0.1, 3.0)
        a = rng.normal(size=(4, 4))
        sigma = a @ a.T * rng.uniform(0.01, 2.0)
        budget = abs(rng.normal()) * 3 + 1e-3
        assert float(direct_yield(g, mu, sigma, budget)) == pytest.approx(
            reference_yield(g, mu, sigma, budget), rel=1e-10, abs=1e-14)


@pytest.mark.parametrize("k, n", [(0, 10), (1, 10), (5, 10), (10, 10), (3, 100_000),
                                  (50_000, 100_000), (99_000, 100_000), (100_000, 100_000)])
def test_wilson_interval_agrees_with_the_reference(k: int, n: int) -> None:
    lo, hi = wilson_interval(k, n)
    ref_lo, ref_hi = reference_wilson(k, n)
    assert float(lo) == pytest.approx(ref_lo, abs=TOLERANCE)
    assert float(hi) == pytest.approx(ref_hi, abs=TOLERANCE)


def test_the_engine_g_of_a_tone_is_the_closed_form() -> None:
    """g for the direct test (docs/model.md section 14) from the engine, against the
    closed-form mean over the tone's phase (module docstring)."""
    from gyrovib.core.analysis import profile_multipliers
    from gyrovib.core.lot import sensitivity
    from gyrovib.core.statistics import vibration_at_sensor

    tone = vibration_at_sensor([(180.0, (0.0, 0.0, 20.0), (0.0, 0.0, 0.0))])
    for omega in (0.0, 5.0, -12.0):
        g = sensitivity(profile_multipliers(tone, [omega]),
                        ("k0", "A1", "k2", "k3", "k4", "k5"))[0]
        expected = tone_g(omega, 20.0)
        assert np.allclose(g, expected, rtol=1e-10, atol=1e-10 * np.max(np.abs(expected)))


# --------------------------------------------------------------------------- disagreements


def test_a_lot_counts_the_coefficients_of_delta_v_not_the_bias() -> None:
    """docs/model.md section 14: the lot is over c = (A1, k2, k3, k4, k5, m31, m32, G…), the
    coefficients Δ_V is linear in; Σ is singular, and only its diagonal used, when
    n ≤ the number of them. The bias k0 (and m1, m2) does not rectify (section 11) and
    is not in c: six units at order 5 (c of 5) give a regular Σ of c and keep their
    correlations, which change the yield (the docs' lot has ρ(A1, k2) ≈ −0.96)."""
    from gyrovib.core.lot import lot_covariance

    names = ("k0", "A1", "k2", "k3", "k4", "k5")
    units = example_units()
    fits = [fit_rate_table(rate, output, 5) for rate, output in list(units.values())[:6]]
    c = np.array([f.values for f in fits])
    lot = lot_statistics(c, names)
    assert not lot.diagonal and lot.warning is None
    sample = np.cov(c, rowvar=False, ddof=1)
    assert np.allclose(lot.covariance, sample, rtol=1e-9, atol=0.0)
    block = np.corrcoef(c[:, 1:], rowvar=False)  # c proper: regular with 6 units
    assert np.min(np.linalg.eigvalsh(block)) > 1e-6
    g = tone_g(5.0, 20.0)
    assert float(direct_yield(g, lot.mean, lot.covariance, 0.01)) == pytest.approx(
        reference_yield(g, c.mean(axis=0), sample, 0.01), rel=1e-9)
    # five units: n = 5 ≤ 5 coefficients of c, the diagonal and the warning
    small = lot_statistics(c[:5], names)
    assert small.diagonal and "5 units" in (small.warning or "")
    assert "5 coefficients" in (small.warning or "")
    # the same rule where a catalogue's lot entry is read back
    correlation = np.corrcoef(c, rowvar=False)
    cov, warning = lot_covariance(c.std(axis=0, ddof=1), correlation, 6, names)
    assert warning is None and cov[1, 2] != 0.0
    cov, warning = lot_covariance(c.std(axis=0, ddof=1), correlation, 5, names)
    assert warning is not None and cov[1, 2] == 0.0


def test_the_fit_command_keeps_the_correlations_of_six_units(tmp_path: Path) -> None:
    """`gyrovib fit` on six units at order 5: the lot entry carries its correlations and
    no warning (docs/model.md section 14, c without k0)."""
    import json

    from tests.conftest import invoke

    lines = EXAMPLE.read_text(encoding="utf-8").splitlines()
    keep = {f"gx100-0{k}" for k in range(1, 7)}
    table = tmp_path / "six.csv"
    table.write_text("\n".join(line for line in lines
                               if line.startswith(("#", "unit,")) or line.split(",")[0] in keep)
                     + "\n", encoding="utf-8")
    result = invoke("fit", table, "--format", "json")
    assert result.exit_code == 0, result.stderr
    document = json.loads(result.stdout)
    assert document["lot"]["units"] == 6 and document["warnings"] == []
    assert "A1 k2" in document["lot"]["correlation"]


def _gx100_01() -> tuple[np.ndarray, np.ndarray]:
    return example_units()["gx100-01"]


@pytest.mark.parametrize("factor", [1e300, 1e-300, 1e-310])
def test_outputs_of_any_magnitude_give_the_same_coefficients(factor: float) -> None:
    """Eq. (2) does not depend on the output unit (docs/model.md section 2): the output
    column times 1e300 or 1e-300 gives the coefficients of the reference on those very
    numbers (s² = RSS/(n − p) of outputs near 1e300 overflows in double precision, and
    subnormal outputs lose their digits, unless the output is scaled first), and K1's
    σ is finite."""
    rate, output = _gx100_01()
    scaled = output * factor
    fit = fit_rate_table(rate, scaled, 5)
    ref = reference_fit(rate, scaled, 5)
    sigma = np.sqrt(np.diag(ref["cov_c"]))
    tolerance = TOLERANCE if factor > 1e-305 else 1e-6  # subnormal inputs carry few digits
    assert np.all(np.abs(fit.values - ref["c"]) <= tolerance * np.maximum(np.abs(ref["c"]),
                                                                          sigma))
    assert np.all(np.abs(fit.covariance - ref["cov_c"]) <= tolerance * np.outer(sigma, sigma))
    plain = reference_fit(rate, output, 5)
    assert fit.scale_factor == pytest.approx(plain["theta"][1] * factor, rel=1e-6)
    assert fit.scale_factor_sigma == pytest.approx(
        math.sqrt(plain["cov_theta"][1, 1]) * factor, rel=1e-6)
    assert fit.residual_rms == pytest.approx(plain["rms"] * factor, rel=1e-6)


def test_huge_outputs_through_the_command(tmp_path: Path) -> None:
    """`gyrovib fit` on outputs near 1e300: the coefficients, not 'the output does not
    follow the rate (K1 = 1e+300 ± inf)'."""
    import json

    from tests.conftest import invoke

    rate, output = _gx100_01()
    table = tmp_path / "huge.csv"
    table.write_text("rate,output\n" + "".join(f"{float(w)!r},{float(u) * 1e300!r}\n"
                                               for w, u in zip(rate, output, strict=True)),
                     encoding="utf-8")
    result = invoke("fit", table, "--format", "json")
    assert result.exit_code == 0, result.stderr
    values = json.loads(result.stdout)["units"][0]["coefficients"]
    ref = reference_fit(rate, output * 1e300, 5)
    assert values["A1"] == pytest.approx(ref["c"][1], rel=1e-9)
    assert values["k3"] == pytest.approx(ref["c"][3], rel=1e-9)
    text = invoke("fit", table)
    assert text.exit_code == 0 and "inf" not in text.stdout


@pytest.mark.parametrize("factor", [1e300, 1e-300, 1e100, 1e-100])
def test_rates_whose_powers_leave_double_precision_are_refused(tmp_path: Path,
                                                              factor: float) -> None:
    """Rates near 1e±300 (or 1e±100 at order 5: R⁵ = 1e±500): kn scales as R^(1−n) and
    its variance as R^(2−2n), outside double precision. Exit 2 with the unit's line and
    what is wrong, not an internal error (OverflowError in R**k)."""
    from tests.conftest import invoke

    rate, output = _gx100_01()
    table = tmp_path / "fast.csv"
    table.write_text("unit,rate,output\n" + "".join(
        f"u,{float(w) * factor / 300!r},{float(u)!r}\n"
        for w, u in zip(rate, output, strict=True)),
        encoding="utf-8")
    result = invoke("fit", table)
    assert result.exit_code == 2, result.stderr
    assert f"{table}:2:1: unit 'u' (22 points): the largest |rate| is " in result.stderr
    assert "double precision" in result.stderr


def test_a_large_rate_range_at_order_one_is_fitted() -> None:
    """R = 1e100 at order 1 (k0 ~ R, A1 dimensionless: nothing leaves double precision):
    the reference's coefficients; the nonlinearity no longer raises OverflowError on
    R⁴ for the absent k5."""
    rate = _gx100_01()[0]
    w = rate * (1e100 / 300)
    u = 2.0 * w + 1e-3 * np.abs(w) + 1e97 * np.cos(rate)
    fit = fit_rate_table(w, u, 1)
    ref = reference_fit(w, u, 1)
    assert_same_fit(fit, ref)


def test_a_cross_rate_of_extreme_magnitude_is_refused() -> None:
    """A cross rate of 1e-300: M1 = m1·K1 scales as 1e300 and its variance as 1e600."""
    from gyrovib.core.fit import IdentificationError

    w = np.tile([-200.0, -100.0, -50.0, 0.0, 50.0, 100.0, 200.0], 3)
    x1 = np.repeat([0.0, 1e-300, -2e-300], 7)
    u = 25.0 * w + 0.01 * w**2 + 3e300 * x1 + np.cos(w) * 0.01
    with pytest.raises(IdentificationError, match=r"the largest \|rate_x1\| is 2e-300"):
        fit_rate_table(w, u, 3, x1[:, None])


def test_many_units_that_cannot_be_fitted_give_a_bounded_report(tmp_path: Path) -> None:
    """A table of 10 000 one-point units: every unit is refused, but the report
    names the first 20 and counts the rest (as the reader does with bad cells) instead
    of 10 000 lines (a 12 MB table of 10⁶ such units took 3 minutes and 4.9 GB).
    10 000 units, 500 times the 20 listed, check the bound as 100 000 did (the command
    refuses unit by unit, no limit lies between the two sizes) at a tenth of the cost."""
    from tests.conftest import invoke

    table = tmp_path / "many.csv"
    table.write_text("unit,rate,output\n" + "".join(f"u{k},1,2\n" for k in range(10_000)),
                     encoding="utf-8")
    result = invoke("fit", table)
    assert result.exit_code == 2
    lines = result.stderr.splitlines()
    assert len(lines) == 21
    assert lines[0].startswith(f"{table}:2:1: unit 'u0' (1 point): every rate is positive")
    assert lines[-1] == f"{table}: ... and 9980 more units that cannot be fitted"


@pytest.mark.parametrize("factor", [1e20, 1e-20])
def test_rates_up_to_1e20_at_order_five_keep_their_uncertainty(factor: float) -> None:
    """R = 1e±20 at order 5: the reference's coefficients and σ (the variances of k5,
    ~R^-8, are far from underflow)."""
    rate = _gx100_01()[0]
    x = rate / 300.0
    u = 25.0 * (0.1 + x + 1e-3 * np.abs(x) + 1e-4 * x**2 + 1e-5 * x**3 + 1e-6 * x**4
                + 1e-7 * x**5) + 1e-10 * np.cos(rate)
    w = x * factor
    fit = fit_rate_table(w, u, 5)
    ref = reference_fit(w, u, 5)
    sigma = np.sqrt(np.diag(ref["cov_c"]))
    assert np.all(np.abs(fit.values - ref["c"]) <= 1e-8 * np.maximum(np.abs(ref["c"]), sigma))
    assert np.allclose(fit.sigma, sigma, rtol=1e-4, atol=0.0)  # s of 1e-10 noise: round-off


def test_rates_of_1e30_at_order_five_are_refused_not_given_sigma_zero() -> None:
    """R = 1e30: Var(k5) ~ R^-8·Var(K5·R⁵) of a near noise-free table was below the
    smallest double and came out as σ = 0 (t = inf), an unknown reported as zero."""
    from gyrovib.core.fit import IdentificationError

    rate = _gx100_01()[0]
    x = rate / 300.0
    u = 25.0 * (0.1 + x + 1e-3 * np.abs(x) + 1e-4 * x**2 + 1e-5 * x**3 + 1e-6 * x**4
                + 1e-7 * x**5) + 1e-13 * np.cos(rate)
    with pytest.raises(IdentificationError, match=r"the largest \|rate\| is 1e\+30"):
        fit_rate_table(x * 1e30, u, 5)
    fit = fit_rate_table(x * 1e30, u, 2)  # order 2: R² = 1e60, well inside
    assert np.all(fit.sigma > 0)
