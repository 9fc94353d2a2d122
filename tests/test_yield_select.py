"""`select --yield Y`: production lots judged by their yield (docs/model.md section 14).

Expected yields come from closed forms worked here: a lot whose only uncertain
coefficient is k2, under a random vibration about x3 alone at Ω_K = 0, has
Δ_V = k2·σ3² (eq. 14: the only non-zero term; σ3² = PSD level × band) and
Δ_V(RMS) = |Δ_V|, so with k2 ~ N(μ, s²) the yield of the direct test is
Φ((Δ* − μσ3²)/(sσ3²)) − Φ((−Δ* − μσ3²)/(sσ3²)), which the Monte-Carlo yield of
the RMS test (the same event) must cover with its interval; the yield of the
bound check on k2 is Φ((b − μ)/s) − Φ((−b − μ)/s) with b the bound `select`
reports. The bundled lot is checked against gyrovib.core.lot on the fit itself.
"""

from __future__ import annotations

import io
import json
import math
from pathlib import Path

import numpy as np
import pytest
import yaml

from gyrovib import api
from tests.conftest import invoke

ROOT = Path(__file__).resolve().parent.parent
EXAMPLE = ROOT / "docs" / "examples" / "rate-table-gx100.csv"
ROTOR = ROOT / "docs" / "examples" / "rotor-tone.gyrovib.yaml"

LEVEL, BAND = 1.0e-3, 2000.0  # (deg/s)²/Hz over 20..2020 Hz
SIGMA3_SQ = LEVEL * BAND  # σ3² = 2 (deg/s)²
MU, S = 2.0e-3, 1.0e-3  # k2 of the lot, (deg/s)^-1
BUDGET = 6.0e-3  # deg/s

CATALOGUE = f"""\
gyrovib: 1
sensors:
  - id: lot-k2
    lot:
      units: 10
      mean: {{k2: {MU!r}}}
      sigma: {{k2: {S!r}}}
  - id: unit-k2
    coefficients: {{k2: {MU!r}}}
profiles:
  - id: random-x3
    rate: [0, 0, 0]
    random:
      psd:
        x3: [[20, {LEVEL!r}], [2020, {LEVEL!r}]]
"""


def phi(x: float) -> float:
    """The standard normal CDF, ½·(1 + erf(x/√2))."""
    return 0.5 * (1.0 + math.erf(x / math.sqrt(2.0)))


def within(value: float, mean: float, sd: float) -> float:
    """P(|X| ≤ value) for X ~ N(mean, sd²)."""
    return phi((value - mean) / sd) - phi((-value - mean) / sd)


@pytest.fixture
def catalogue(tmp_path: Path) -> Path:
    path = tmp_path / "lot.yaml"
    path.write_text(CATALOGUE, encoding="utf-8")
    return path


def run(*args: object) -> dict:
    result = invoke("select", *args, "--format", "json")
    assert result.exit_code in (0, 1), result.stderr
    return json.loads(result.stdout)


def cell(document: dict, sensor: str) -> dict:
    entry = next(s for s in document["sensors"] if s["sensor"] == sensor)
    return entry["profiles"][0]


def test_exact_yield_of_the_direct_test(catalogue: Path) -> None:
    document = run(catalogue, "--budget", BUDGET, "--criterion", "worst", "--yield", 0.9)
    expected = within(BUDGET, MU * SIGMA3_SQ, S * SIGMA3_SQ)  # ≈ 0.84
    got = cell(document, "lot-k2")["yield"]
    assert got["method"] == "exact" and got["interval"] is None and got["draws"] == 0
    assert got["value"] == pytest.approx(expected, rel=1e-9)
    assert cell(document, "lot-k2")["pass"] is False  # 0.84 < 0.9
    assert "yield" not in cell(document, "unit-k2")  # a single unit: as before
    assert cell(document, "unit-k2")["pass"] is True  # |Δ_V| = 0.004 ≤ 0.006
    assert document["yield"] == {"target": 0.9, "seed": 0}
    passing = run(catalogue, "--budget", BUDGET, "--criterion", "worst", "--yield", 0.8)
    assert cell(passing, "lot-k2")["pass"] is True


def test_monte_carlo_interval_covers_the_exact_yield(catalogue: Path) -> None:
    """Under this profile the RMS test is the direct test: the Monte-Carlo estimate's 95 %
    interval must contain the exact value, and its width is about 2·1.96·√(p(1−p)/N)."""
    exact = within(BUDGET, MU * SIGMA3_SQ, S * SIGMA3_SQ)
    got = cell(run(catalogue, "--budget", BUDGET, "--criterion", "rms", "--yield", 0.9),
               "lot-k2")["yield"]
    assert got["method"] == "monte-carlo" and got["draws"] == 100_000
    low, high = got["interval"]
    assert low <= exact <= high
    assert low <= got["value"] <= high
    assert high - low == pytest.approx(2 * 1.96 * math.sqrt(exact * (1 - exact) / 1e5),
                                       rel=0.05)


def test_monte_carlo_yield_of_the_bound_checks(catalogue: Path) -> None:
    """--criterion bounds: P(|k2| ≤ b), b the k2 bound select reports for the lot."""
    document = run(catalogue, "--budget", BUDGET, "--criterion", "bounds", "--yield", 0.5)
    lot = cell(document, "lot-k2")
    bound = lot["checks"]["k2"]["bound"]
    exact = within(bound, MU, S)
    low, high = lot["yield"]["interval"]
    assert 0.01 < exact < 0.99 and low <= exact <= high


def test_a_fixed_coefficient_outside_its_bound_fails_every_draw(catalogue: Path,
                                                                tmp_path: Path) -> None:
    """m31 is not uncertain in this lot; with x1 and x3 correlated its term binds, and a
    fixed m31 far above its bound fails every part drawn: yield 0."""
    text = CATALOGUE.replace(f"mean: {{k2: {MU!r}}}", f"mean: {{k2: {MU!r}, m31: 1.0}}")
    text = text.replace(f"x3: [[20, {LEVEL!r}], [2020, {LEVEL!r}]]",
                        f"x1: [[20, {LEVEL!r}], [2020, {LEVEL!r}]]\n"
                        f"        x3: [[20, {LEVEL!r}], [2020, {LEVEL!r}]]\n"
                        "      coherence: [1.0, 0.0]")
    path = tmp_path / "fixed.yaml"
    path.write_text(text, encoding="utf-8")
    document = run(path, "--budget", BUDGET, "--criterion", "bounds", "--yield", 0.5)
    lot = cell(document, "lot-k2")
    assert lot["checks"]["m31"]["pass"] is False
    assert lot["yield"]["value"] == 0.0 and lot["pass"] is False
    assert "yield 0 " in lot["reason"]


def test_seed_and_draws(catalogue: Path) -> None:
    args = (catalogue, "--budget", BUDGET, "--criterion", "rms", "--yield", 0.9)
    first = cell(run(*args, "--seed", 7, "--draws", 5000), "lot-k2")["yield"]
    again = cell(run(*args, "--seed", 7, "--draws", 5000), "lot-k2")["yield"]
    other = cell(run(*args, "--seed", 8, "--draws", 5000), "lot-k2")["yield"]
    assert first == again and first["draws"] == 5000
    assert other["value"] != first["value"]


def test_the_bundled_lot_against_core_lot() -> None:
    """The exact yield select reports for the bundled lot is core.lot.direct_yield of the lot
    as the catalogue writes it (mean, σ and correlations read back with PyYAML, the
    covariance D·R·D built here), within 1e-3 of the fit's full-precision lot (the catalogue
    rounds to the digits the spread supports), and the RMS test's Monte-Carlo interval
    overlaps core.lot.monte_carlo_yield's on the same lot."""
    from gyrovib.core.analysis import profile_multipliers
    from gyrovib.core.lot import direct_yield, monte_carlo_yield, rms_test, sensitivity, term_matrix
    from gyrovib.core.statistics import vibration_at_sensor

    fitted = api.fit(api.read_rate_table(EXAMPLE))
    lot = fitted.lot
    assert lot is not None
    tone = vibration_at_sensor([(180.0, (0.0, 0.0, 20.0), (0.0, 0.0, 0.0))])
    multipliers = profile_multipliers(tone, [5.0])
    g = sensitivity(multipliers, fitted.names)[0]
    catalogue = ROOT / "docs" / "examples" / "rate-table-gx100.gyrovib.yaml"
    written = next(s for s in yaml.safe_load(catalogue.read_text(encoding="utf-8"))["sensors"]
                   if s["id"] == "lot-rate-table-gx100")["lot"]
    mean = np.array([written["mean"][n] for n in fitted.names])
    sigma = np.array([written["sigma"][n] for n in fitted.names])
    r = np.eye(len(fitted.names))
    for pair, rho in written["correlation"].items():
        a, b = (fitted.names.index(n) for n in pair.split())
        r[a, b] = r[b, a] = rho
    expected = float(direct_yield(g, mean, sigma[:, None] * r * sigma[None, :], 0.01))
    assert expected == pytest.approx(float(direct_yield(g, lot.mean, lot.covariance, 0.01)),
                                     abs=1e-3)
    worst = api.select(api.load([catalogue, ROTOR]), budget=0.01, criterion="worst",
                       yield_target=0.99)
    assert worst.yields is not None
    i = worst.sensors.index("lot-rate-table-gx100")
    assert worst.yields.value[i, 0] == pytest.approx(expected, rel=1e-9)
    rms = api.select(api.load([catalogue, ROTOR]), budget=0.01, criterion="rms",
                     yield_target=0.99)
    assert rms.yields is not None
    core = monte_carlo_yield(rms_test(term_matrix(multipliers, fitted.names)[0], 0.01),
                             lot.mean, lot.covariance, np.random.default_rng(1))
    assert rms.yields.low[i, 0] <= core.high and core.low <= rms.yields.high[i, 0]


def test_fit_then_select_on_the_bundled_data(tmp_path: Path) -> None:
    """The whole chain: `gyrovib fit` on the bundled data writes a catalogue that
    `validate` accepts and `select --yield 0.99 --criterion worst` uses."""
    fitted = tmp_path / "gx100.gyrovib.yaml"
    result = invoke("fit", EXAMPLE, "--output-unit", "mV", "-o", fitted)
    assert result.exit_code == 0, result.stderr
    assert invoke("validate", fitted).exit_code == 0
    selected = invoke("select", fitted, ROTOR, "--budget", "36deg/h", "--yield", "0.99",
                      "--criterion", "worst", "--format", "json")
    assert selected.exit_code == 0, selected.stderr  # the measured units pass
    document = json.loads(selected.stdout)
    lot = cell(document, "lot-rate-table-gx100")
    assert lot["yield"]["method"] == "exact"
    assert lot["yield"]["value"] == pytest.approx(0.9805, abs=1e-4)  # docs/rate-table.md
    assert lot["pass"] is False and "below 0.99" in lot["reason"]
    assert all(cell(document, f"gx100-0{k}")["pass"] for k in range(1, 9))


def test_every_format_shows_the_yield(catalogue: Path) -> None:
    args = ("--budget", BUDGET, "--criterion", "rms", "--yield", 0.9, "--draws", 4000)
    document = run(catalogue, *args)
    y = cell(document, "lot-k2")["yield"]
    result = api.select(api.load([catalogue]), budget=BUDGET, criterion="rms",
                        yield_target=0.9, draws=4000)
    frame = result.to_frame()
    row = frame[frame["sensor"] == "lot-k2"].iloc[0]
    assert row["yield_value"] == y["value"] and row["yield_method"] == "monte-carlo"
    assert [row["yield_interval_low"], row["yield_interval_high"]] == y["interval"]
    assert row["yield_draws"] == 4000
    assert math.isnan(frame[frame["sensor"] == "unit-k2"].iloc[0]["yield_value"])
    import pandas

    csv = pandas.read_csv(io.StringIO(invoke("select", catalogue, *args,
                                             "--format", "csv").stdout))
    assert csv[csv["sensor"] == "lot-k2"].iloc[0]["yield_value"] == y["value"]
    table = invoke("select", catalogue, *args, env={"COLUMNS": "200"}).stdout
    assert f"yield {y['value']:.4g}" in table and "below 0.9" in table
    markdown = invoke("select", catalogue, *args, "--format", "markdown").stdout
    assert f"yield {y['value']:.4g}" in markdown
    junit = invoke("select", catalogue, *args, "--format", "junit").stdout
    assert "is below 0.9" in junit


def test_a_small_lot_warns(catalogue: Path, tmp_path: Path) -> None:
    text = CATALOGUE.replace("units: 10", "units: 2").replace(
        f"sigma: {{k2: {S!r}}}", f"sigma: {{k2: {S!r}, A1: 1.0e-4}}\n      "
        "correlation: {A1 k2: 0.5}")
    path = tmp_path / "small.yaml"
    path.write_text(text, encoding="utf-8")
    result = invoke("select", path, "--budget", BUDGET, "--criterion", "worst", "--yield", 0.9)
    assert "gyrovib: warning: lot 'lot-k2': a lot of 2 units" in result.stderr


@pytest.mark.parametrize("value", ["0", "1", "1.5", "-0.2"])
def test_the_target_is_a_probability(catalogue: Path, value: str) -> None:
    result = invoke("select", catalogue, "--budget", BUDGET, "--yield", value)
    assert result.exit_code == 2
    assert "--yield" in result.stderr and "between 0 and 1" in result.stderr


def test_without_yield_a_lot_is_judged_at_its_mean(catalogue: Path) -> None:
    document = run(catalogue, "--budget", BUDGET, "--criterion", "worst")
    assert "yield" not in document and "yield" not in cell(document, "lot-k2")
    assert cell(document, "lot-k2")["pass"] == cell(document, "unit-k2")["pass"] is True


def test_the_report_shows_yields_and_uncertainties(tmp_path: Path) -> None:
    catalogue = ROOT / "docs" / "examples" / "rate-table-gx100.gyrovib.yaml"
    out = tmp_path / "report.html"
    result = invoke("report", catalogue, ROTOR, "--budget", "36deg/h", "--criterion", "rms",
                    "--yield", "0.99", "--draws", "20000", "-o", out)
    assert result.exit_code == 0, result.stderr
    html = out.read_text(encoding="utf-8")
    study = api.select(api.load([catalogue, ROTOR]), budget=0.01, criterion="rms",
                       yield_target=0.99, draws=20000)
    assert study.yields is not None
    i = study.sensors.index("lot-rate-table-gx100")
    assert f"yield {study.yields.value[i, 0]:.4g}" in html
    assert "pass where the yield is at least 0.99 (Monte Carlo, 20000 draws" in html
    analysis = api.analyze(api.load([catalogue, ROTOR]), unit="deg/h")
    assert analysis.uncertainty is not None
    assert f"lot mean Δ_V = {analysis.error.total[i, 0]:.4g} ± " in html
    assert f"Δ_V = {analysis.error.total[0, 0]:.4g} ± {analysis.uncertainty[0, 0]:.2g}" in html


def test_unknown_phases_are_refused_for_a_lot(catalogue: Path, tmp_path: Path) -> None:
    """Under `phase: worst` orders Δ_V is maximised over the phases part by part: no yield
    is computed, the profile is named (exit 2); analyze leaves u(Δ_V) out there."""
    text = CATALOGUE + """\
  - id: locked
    rate: [0, 0, 0]
    harmonics:
      fundamental: 20
      orders:
        - {order: 1, amplitude: [0.5, 0.0, 2.0], phase: [30, 0, 0]}
        - {order: 2, amplitude: [0.0, 0.3, 1.0], phase: worst}
"""
    path = tmp_path / "locked.yaml"
    path.write_text(text, encoding="utf-8")
    result = invoke("select", path, "--budget", BUDGET, "--yield", 0.9, "--criterion", "worst")
    assert result.exit_code == 2
    assert f"{path}:" in result.stderr and "'locked'" in result.stderr
    assert "phase: worst" in result.stderr
    fine = invoke("select", path, "--budget", BUDGET, "--yield", 0.9, "--profile", "random-x3")
    assert fine.exit_code in (0, 1), fine.stderr
    rows = json.loads(invoke("analyze", path, "--format", "json").stdout)["results"]
    lot = {r["profile"]: r for r in rows if r["sensor"] == "lot-k2"}
    assert "uncertainty" in lot["random-x3"] and "uncertainty" not in lot["locked"]


def test_both_is_the_joint_event(catalogue: Path) -> None:
    """--criterion both passes a draw when bounds and rms both do: with the same draws (same
    seed, same lot) its yield is at most either one's and at least their sum minus 1."""
    def value(criterion: str) -> float:
        result = api.select(api.load([catalogue]), budget=BUDGET, criterion=criterion,
                            yield_target=0.5, draws=20000, seed=3)
        assert result.yields is not None
        return float(result.yields.value[0, 0])

    bounds, rms, both = value("bounds"), value("rms"), value("both")
    assert 0 < both < 1
    assert both <= min(bounds, rms) and both >= bounds + rms - 1


def test_yield_without_lots_says_so(tmp_path: Path) -> None:
    path = tmp_path / "units.yaml"
    head, lot = CATALOGUE.split("  - id: lot-k2\n")
    path.write_text(head + "  - id: unit-k2" + lot.split("  - id: unit-k2", 1)[1],
                    encoding="utf-8")
    result = invoke("select", path, "--budget", BUDGET, "--yield", 0.9, "--criterion", "worst",
                    "--format", "json")
    assert result.exit_code == 0, result.stderr
    assert "gyrovib: warning: --yield: no production lot" in result.stderr
    assert "yield" not in json.loads(result.stdout)
    # the library's note names its argument, not the option
    chosen = api.select(api.load([str(path)]), budget=BUDGET, yield_target=0.9,
                        criterion="worst")
    assert any(n.startswith("yield_target: no production lot") for n in chosen.notes)


def test_github_annotations_name_the_yield(catalogue: Path) -> None:
    args = (catalogue, "--budget", BUDGET, "--criterion", "worst", "--format", "github")
    exact = within(BUDGET, MU * SIGMA3_SQ, S * SIGMA3_SQ)  # ≈ 0.84
    passing = invoke("select", *args, "--yield", 0.8).stdout
    assert f"has a yield of at least 0.8 under every profile (lowest {exact:.4g})" in passing
    failing = invoke("select", *args, "--yield", 0.9).stdout
    assert "::error" in failing and f"yield {exact:.4g} (exact) under random-x3" in failing
