"""The brute-force method (``--method numeric``) against the closed forms.

The reference for every numeric value here is the ``exact`` method of the
same catalogue (docs/model.md), which docs/model.md says brute force
must reproduce: within 6 standard errors where the estimate is statistical,
and to 1e-6 relative where the phase grid is exact (stderr reported as 0).
"""

from __future__ import annotations

import json
import math
import textwrap

import numpy as np
import pytest

from gyrovib import api
from gyrovib.core.analysis import COEFFICIENTS
from gyrovib.core.numeric import conversion, simulate
from gyrovib.core.statistics import vibration_at_sensor
from tests.conftest import invoke

# Sensors: "full" has every coefficient of eq. (2); "poly" is the same without
# the asymmetry A1 (so a tone grid is exact for it); "filtered" adds its own
# frequency response. Magnitudes are chosen so every term matters.
CATALOG = textwrap.dedent("""\
    gyrovib: 1
    units: {rate: deg/s}
    sensors:
      - id: full
        coefficients: {k0: 0.001, k1: 1.0, A1: 0.02, k2: 2.0e-3, k3: -1.0e-4, k4: 3.0e-5,
                       k5: -2.0e-6, m1: 1.0e-3, m2: -1.0e-3, m31: 1.0e-3, m32: 5.0e-4}
      - id: poly
        coefficients: {k0: 0.001, k1: 1.0, k2: 2.0e-3, k3: -1.0e-4, k4: 3.0e-5,
                       k5: -2.0e-6, m1: 1.0e-3, m2: -1.0e-3, m31: 1.0e-3, m32: 5.0e-4}
      - id: filtered
        coefficients: {A1: 0.01, k2: 1.0e-3, k4: 1.0e-5, m31: 2.0e-3}
        response: [[10, 1.0], [100, 0.8], [1000, 0.3]]
    profiles:
      - id: tone
        rate: [0, 0, 0.5]
        harmonic:
          - {frequency: 95, amplitude: [1.2, 0.8, 2.5], phase: [0, 30, 0]}
      - id: tone-fast
        rate: [1, -2, 20]
        harmonic:
          - {frequency: 95, amplitude: [1.2, 0.8, 2.5]}
      - id: tones
        rate: [0, 0, 1]
        harmonic:
          - {frequency: 60, amplitude: [0.6, 0.5, 1.8], phase: [0, 30, 0]}
          - {frequency: 120, amplitude: [0.4, 0.3, 1.0], phase: [90, 0, 0]}
          - {frequency: 240, amplitude: [0.2, 0.2, 0.5], phase: [0, 180, 45]}
      - id: flat-psd
        rate: [0, 0, 0.3]
        random:
          psd:
            x1: [[20, 1.2e-3], [2000, 1.2e-3]]
            x2: [[20, 1.2e-3], [2000, 1.2e-3]]
            x3: [[20, 2.5e-3], [2000, 2.5e-3]]
          coherence: [0.5, 0.2]
      - id: rms
        rate: [0, 0, 4]
        random: {rms: [1.0, 1.0, 2.5], coherence: [0.6, -0.3]}
      - id: sine-on-random
        rate: [0, 0, 1]
        harmonic:
          - {frequency: 150, amplitude: [0.8, 0.8, 4.0]}
        random:
          psd:
            x1: [[20, 1.5e-4], [2000, 1.5e-4]]
            x3: [[20, 2.5e-4], [2000, 2.5e-4]]
      - id: mounted
        rate: [0, 0, 2]
        harmonic:
          - {frequency: 40, amplitude: [0.5, 0.5, 1.5]}
        random:
          psd:
            x3: [[20, 8e-4], [100, 4e-3], [500, 4e-3], [2000, 2.5e-4]]
            x1: [[20, 4e-4], [100, 2e-3], [500, 2e-3], [2000, 1.25e-4]]
        mount: [[10, 1.0], [50, 3.0], [100, 0.4], [1000, 0.02]]
      - id: still
        rate: [0, 0, 7]
    """)

PROFILES = ("tone", "tone-fast", "tones", "flat-psd", "rms", "sine-on-random", "mounted", "still")


@pytest.fixture(scope="module")
def catalog_path(tmp_path_factory: pytest.TempPathFactory) -> str:
    path = tmp_path_factory.mktemp("numeric") / "cat.yaml"
    path.write_text(CATALOG, encoding="utf-8")
    return str(path)


@pytest.fixture(scope="module")
def both(catalog_path: str) -> tuple[api.AnalysisResult, api.AnalysisResult]:
    catalog = api.load([catalog_path])
    exact = api.analyze(catalog, method="exact")
    numeric = api.analyze(catalog, method="numeric", samples=100_000, seed=0)
    return exact, numeric


@pytest.mark.parametrize("profile", PROFILES)
def test_numeric_total_agrees_with_exact(both: tuple[api.AnalysisResult, api.AnalysisResult],
                                         profile: str) -> None:
    exact, numeric = both
    j = exact.profiles.index(profile)
    assert numeric.stderr is not None
    for i, sensor in enumerate(exact.sensors):
        want = float(exact.error.total[i, j])
        got = float(numeric.error.total[i, j])
        se = float(numeric.stderr[i, j])
        if se == 0.0:
            assert got == pytest.approx(want, rel=1e-6, abs=1e-15), (sensor, profile)
        else:
            assert abs(got - want) <= 6.0 * se, (sensor, profile, got, want, se)
            # and the standard error is a useful one: well under the value itself
            assert se < 0.05 * abs(want), (sensor, profile)


def test_stderr_zero_exactly_where_the_grid_is_exact(
        both: tuple[api.AnalysisResult, api.AnalysisResult]) -> None:
    """Grid rule of core.numeric: exact for A1 = 0, or |Ω_K3| ≥ Σ tone amplitudes of x3."""
    _, numeric = both
    assert numeric.stderr is not None
    s = {name: i for i, name in enumerate(numeric.sensors)}
    p = {name: j for j, name in enumerate(numeric.profiles)}
    assert numeric.stderr[s["poly"], p["tone"]] == 0.0       # A1 = 0
    assert numeric.stderr[s["poly"], p["tones"]] == 0.0
    assert numeric.stderr[s["full"], p["tone-fast"]] == 0.0  # |20| ≥ 2.5
    assert numeric.stderr[s["full"], p["tone"]] > 0.0        # |0.5| < 2.5 and A1 ≠ 0
    assert numeric.stderr[s["full"], p["flat-psd"]] > 0.0    # Monte Carlo
    assert np.all(numeric.stderr[:, p["still"]] == 0.0)      # no vibration at all
    assert np.all(numeric.error.total[:, p["still"]] == 0.0)


def test_term_breakdown_adds_up_to_the_brute_force_total(
        both: tuple[api.AnalysisResult, api.AnalysisResult]) -> None:
    """With antithetic pairs / symmetric grids the odd sample moments vanish, so the
    terms from the sample moments sum to the eq. (2) average up to rounding."""
    _, numeric = both
    e = numeric.error
    np.testing.assert_allclose(e.additive + e.multiplicative, e.total, rtol=1e-9, atol=1e-15)


def test_terms_agree_with_exact_terms(both: tuple[api.AnalysisResult, api.AnalysisResult]
                                      ) -> None:
    """Sample moments of 1e5 points: within a few percent of the exact moments (loose
    on purpose; the rigorous check is on the total with its stderr)."""
    exact, numeric = both
    np.testing.assert_allclose(numeric.error.additive_terms, exact.error.additive_terms,
                               rtol=0.05, atol=1e-9)


def test_conversion_is_eq_2() -> None:
    """conversion() against eq. (2) written out by hand at two points."""
    c = np.array([[0.1, 1.1, 0.2, 0.03, 0.004, 5e-4, 6e-5, 0.7, -0.8, 0.09, -0.01]])
    k0, k1, a1, k2, k3, k4, k5, m1, m2, m31, m32 = c[0]
    assert dict(zip(COEFFICIENTS, c[0], strict=True))["A1"] == a1
    for w1, w2, w3 in ((0.5, -1.5, 2.0), (1.0, 2.0, -3.0)):
        sign = math.copysign(1.0, w3)
        want = (k0 + k1 * (1 + 0.5 * a1 * sign) * w3 + k2 * w3**2 + k3 * w3**3 + k4 * w3**4
                + k5 * w3**5 + m1 * w1 + m2 * w2 + m31 * w3 * w1 + m32 * w3 * w2)
        got = conversion(c, np.array([[w1], [w2], [w3]]))[0, 0]
        assert got == pytest.approx(want, rel=1e-14)


def test_odd_terms_cancel_within_antithetic_pairs() -> None:
    """Only odd terms (k0 is removed by the rest subtraction): at Ω = 0 their mean is 0
    exactly for a symmetric vibration, and the pairs make the estimate 0 too."""
    c = np.zeros((1, len(COEFFICIENTS)))
    c[0, [0, 1, 4, 6, 7, 8]] = [0.3, 1.0, 1e-3, 1e-5, 0.01, 0.02]  # k0 k1 k3 k5 m1 m2
    v = vibration_at_sensor([(50.0, [1, 1, 2], [0, 0, 0])], rms=[0.5, 0.5, 1.0])
    est = simulate(c, v, [0.0, 0.0, 0.0], samples=4096, rng=np.random.default_rng(1))
    assert est.scheme == "monte-carlo"
    assert abs(est.total[0]) < 1e-12
    assert est.stderr[0] < 1e-12


def test_sensor_estimate_does_not_depend_on_its_companions(catalog_path: str) -> None:
    catalog = api.load([catalog_path])
    alone = api.analyze(catalog, sensors=["full"], profiles=["rms"], method="numeric",
                        samples=20_000, seed=3)
    together = api.analyze(catalog, profiles=["tone", "rms"], method="numeric", samples=20_000,
                           seed=3)
    assert together.stderr is not None and alone.stderr is not None
    assert alone.error.total[0, 0] == together.error.total[0, 1]
    assert alone.stderr[0, 0] == together.stderr[0, 1]


def test_unit_conversion_uses_the_same_samples(catalog_path: str) -> None:
    """deg/h = deg/s × 3600 (docs/model.md), and the same seed gives the same samples."""
    catalog = api.load([catalog_path])
    kw = {"profiles": ["flat-psd"], "method": "numeric", "samples": 10_000, "seed": 5}
    dps = api.analyze(catalog, unit="deg/s", **kw)  # type: ignore[arg-type]
    dph = api.analyze(catalog, unit="deg/h", **kw)  # type: ignore[arg-type]
    np.testing.assert_allclose(dph.error.total, dps.error.total * 3600.0, rtol=1e-12)
    assert dph.stderr is not None and dps.stderr is not None
    np.testing.assert_allclose(dph.stderr, dps.stderr * 3600.0, rtol=1e-12)


def test_same_seed_same_json_different_seed_differs(catalog_path: str) -> None:
    base = ("analyze", catalog_path, "--method", "numeric", "--samples", "20000",
            "--format", "json", "--profile", "rms", "--profile", "tone")
    one, two, other = (invoke(*base, "--seed", seed) for seed in ("7", "7", "8"))
    assert one.exit_code == two.exit_code == other.exit_code == 0
    assert one.stdout == two.stdout
    assert one.stdout != other.stdout
    doc = json.loads(one.stdout)
    assert doc["method"] == "numeric"
    assert doc["samples"] == 20000 and doc["seed"] == 7
    row = doc["results"][0]
    assert {"total", "stderr", "additive_terms", "rms", "warnings"} <= set(row)
    # the default seed is fixed, so a run without --seed is reproducible too
    assert invoke(*base).stdout == invoke(*base).stdout


def test_numeric_csv_and_table_show_stderr(catalog_path: str) -> None:
    base = ("analyze", catalog_path, "--method", "numeric", "--samples", "2000",
            "--profile", "rms")
    result = invoke(*base, "--format", "csv")
    assert result.exit_code == 0 and result.stderr == ""  # no progress bar off a terminal
    assert result.stdout.splitlines()[0].endswith("total,rms,stderr,saturated,warnings")
    result = invoke(*base)
    assert result.exit_code == 0 and "± stderr" in result.stdout


def test_too_few_samples_is_a_usage_error(catalog_path: str) -> None:
    result = invoke("analyze", catalog_path, "--method", "numeric", "--samples", "5")
    assert result.exit_code == 2 and result.stdout == ""
    assert "--samples" in result.stderr and "32<=x<=100000000" in result.stderr  # MAX_SAMPLES
