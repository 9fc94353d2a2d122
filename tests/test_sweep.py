"""`gyrovib sweep`: Δ_V and Δ_V(RMS) over Ω_K3, exact and paper, and its plot."""

from __future__ import annotations

import csv
import io
import json
import math
import sys
import textwrap

import numpy as np
import pytest

from gyrovib import api
from tests.conftest import invoke

A_TONE = 2.0      # x3 amplitude of the tone, deg/s
SIGMA = 1.5       # x3 RMS of the random profile, deg/s
A1 = 0.01         # asymmetry of sensor "asym"

CATALOG = textwrap.dedent(f"""\
    gyrovib: 1
    sensors:
      - id: asym
        coefficients: {{A1: {A1}}}
      - id: mixed
        coefficients: {{A1: 0.002, k2: 1.0e-3, k3: -2.0e-6, k4: 1.0e-5, k5: 1.0e-8,
                       m31: 1.0e-3, m32: -5.0e-4}}
        response: [[10, 1.0], [200, 0.7]]
    profiles:
      - id: tone
        rate: [0, 0, 1]
        harmonic:
          - {{frequency: 95, amplitude: [1.0, 0.5, {A_TONE}]}}
      - id: random
        rate: [0, 0, 3]
        random: {{rms: [1.0, 1.0, {SIGMA}], coherence: [0.5, 1.0]}}
      - id: tones
        rate: [0, 0, 2]
        harmonic:
          - {{frequency: 60, amplitude: [0.6, 0.5, 1.8], phase: [0, 30, 0]}}
          - {{frequency: 120, amplitude: [0.4, 0.3, 1.0]}}
      - id: sine-on-random
        harmonic:
          - {{frequency: 150, amplitude: [0.8, 0.8, 4.0]}}
        random:
          psd: {{x3: [[20, 2.5e-4], [2000, 2.5e-4]]}}
        mount: [[20, 1.0], [200, 0.5]]
    """)

RATES = (-7.5, -2.0, 0.0, 0.4, 1.9999, 2.0, 35.0)


@pytest.fixture(scope="module")
def catalog_path(tmp_path_factory: pytest.TempPathFactory) -> str:
    path = tmp_path_factory.mktemp("sweep") / "cat.yaml"
    path.write_text(CATALOG, encoding="utf-8")
    return str(path)


@pytest.mark.parametrize("unit", ["deg/s", "rad/s"])
def test_sweep_equals_analyze_at_each_rate(catalog_path: str, unit: str) -> None:
    """The reference is `analyze --rate R` at the same R (same closed forms, scalar rate)."""
    catalog = api.load([catalog_path])
    scale = 1.0 if unit == "deg/s" else math.pi / 180.0   # output unit per deg/s
    sweep = api.sweep(catalog, RATES, unit=unit)
    for method in ("exact", "paper"):
        swept = getattr(sweep, method)
        for r, rate in enumerate(RATES):
            for j, profile in enumerate(sweep.profiles):
                if method == "paper" and profile in sweep.paper_refused:
                    assert np.all(np.isnan(swept.total[:, j, r]))
                    continue
                one = api.analyze(catalog, profiles=[profile], method=method, rate=[rate],
                                  unit=unit)
                assert one.rates[0, 2] == pytest.approx(rate * scale, rel=1e-15)
                np.testing.assert_allclose(swept.total[:, j, r], one.error.total[:, 0],
                                           rtol=1e-12, atol=0)
                np.testing.assert_allclose(swept.rms[:, j, r], one.error.rms[:, 0],
                                           rtol=1e-12, atol=0)
    assert set(sweep.paper_refused) == {"tones", "sine-on-random"}


def test_sweep_json_equals_analyze_json(catalog_path: str) -> None:
    result = invoke("sweep", catalog_path, "--rate-range", "-4:4:5", "--format", "json")
    assert result.exit_code == 0
    doc = json.loads(result.stdout)
    assert doc["rates"] == [-4.0, -2.0, 0.0, 2.0, 4.0]
    # the note about the paper's refusals is printed once, on stderr
    assert result.stderr.count("paper's columns are empty") == 1
    assert "tones" in result.stderr and "sine-on-random" in result.stderr
    series = {(s["sensor"], s["profile"]): s for s in doc["series"]}
    assert series[("asym", "tones")]["paper"] is None
    result = invoke("analyze", catalog_path, "--rate", "2", "--format", "json")
    assert result.exit_code == 0, result.stderr
    for row in json.loads(result.stdout)["results"]:
        s = series[(row["sensor"], row["profile"])]
        assert s["exact"]["total"][3] == pytest.approx(row["total"], rel=1e-12)
        assert s["exact"]["rms"][3] == pytest.approx(row["rms"], rel=1e-12)


def test_asymmetry_against_paper_for_a_tone(catalog_path: str) -> None:
    """docs/model.md: exact Δ0(1) = 0.5·A1·E(Ω), E(0) = (2/π)·a and E = 0 for
    |Ω| ≥ a; the paper prints 0.673·A1·a at every Ω."""
    catalog = api.load([catalog_path])
    sweep = api.sweep(catalog, [0.0, A_TONE, -A_TONE, 10.0], sensors=["asym"],
                      profiles=["tone"])
    exact, paper = sweep.exact.total[0, 0], sweep.paper.total[0, 0]
    assert exact[0] == pytest.approx(0.5 * A1 * (2.0 / math.pi) * A_TONE, rel=1e-12)
    assert np.all(exact[1:] == 0.0)
    np.testing.assert_allclose(paper, 0.673 * A1 * A_TONE, rtol=1e-12)


def test_asymmetry_against_paper_for_random(catalog_path: str) -> None:
    """docs/model.md: exact 0.5·A1·√(2/π)·σ at Ω = 0, paper 0.5·A1·σ."""
    catalog = api.load([catalog_path])
    sweep = api.sweep(catalog, [0.0], sensors=["asym"], profiles=["random"])
    assert sweep.exact.total[0, 0, 0] == pytest.approx(
        0.5 * A1 * math.sqrt(2.0 / math.pi) * SIGMA, rel=1e-12)
    assert sweep.paper.total[0, 0, 0] == pytest.approx(0.5 * A1 * SIGMA, rel=1e-12)


def test_csv_leaves_refused_paper_cells_empty(catalog_path: str) -> None:
    result = invoke("sweep", catalog_path, "--rate-range", "0:1:2", "--format", "csv",
                    "--sensor", "asym")
    assert result.exit_code == 0
    rows = list(csv.DictReader(io.StringIO(result.stdout)))
    assert len(rows) == 4 * 2     # profiles × rates
    for row in rows:
        empty = row["profile"] in ("tones", "sine-on-random")
        assert (row["paper_total"] == "") is empty
        assert row["exact_total"] != ""


def test_table_and_units(catalog_path: str) -> None:
    result = invoke("sweep", catalog_path, "--rate-range", "-7200:7200:3", "--unit", "deg/h",
                    "--profile", "tone", "--sensor", "asym")
    assert result.exit_code == 0
    assert "Ω_K3 (deg/h)" in result.stdout and "-7200" in result.stdout


@pytest.mark.parametrize("text", ["1:2", "a:2:3", "0:1:0", "0:1:x", "0:1:2:3"])
def test_bad_rate_range_is_a_usage_error(catalog_path: str, text: str) -> None:
    result = invoke("sweep", catalog_path, f"--rate-range={text}")
    assert result.exit_code == 2 and result.stdout == "" and "--rate-range" in result.stderr


def test_default_range_parses(catalog_path: str) -> None:
    result = invoke("sweep", catalog_path, "--format", "json", "--profile", "tone")
    assert result.exit_code == 0
    rates = json.loads(result.stdout)["rates"]
    assert len(rates) == 401 and rates[0] == -200.0 and rates[-1] == 200.0 and rates[200] == 0.0


def test_plot_writes_a_png(catalog_path: str, tmp_path: pytest.TempPathFactory) -> None:
    pytest.importorskip("matplotlib")
    target = tmp_path / "sweep.png"  # type: ignore[operator]
    result = invoke("sweep", catalog_path, "--rate-range", "-5:5:101", "--format", "json",
                    "--plot", str(target), "--budget", "0.01")
    assert result.exit_code == 0 and json.loads(result.stdout)["budget"] == 0.01
    data = target.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    assert len(data) > 20_000  # four profiles × two panels of lines: far above an empty PNG


def test_missing_matplotlib_is_a_clear_error(catalog_path: str, tmp_path: pytest.TempPathFactory,
                                             monkeypatch: pytest.MonkeyPatch) -> None:
    # A None entry in sys.modules makes `import matplotlib.figure` raise ImportError.
    monkeypatch.setitem(sys.modules, "matplotlib", None)
    monkeypatch.setitem(sys.modules, "matplotlib.figure", None)
    target = tmp_path / "x.png"  # type: ignore[operator]
    result = invoke("sweep", catalog_path, "--rate-range", "0:1:2", "--plot", str(target))
    assert result.exit_code == 2
    assert "pip install 'gyrovib[plot]'" in result.stderr
    assert "Traceback" not in result.stderr
    assert not target.exists()


def test_the_paper_note_says_each_reason_once_with_its_profiles() -> None:
    """The bundled profiles with linear vibration share one reason the paper's columns
    are empty: the note names them together, the reason once."""
    result = invoke("sweep", "--sensor", "adxrs453", "--rate-range", "-5:5:3",
                    "--format", "csv")
    assert result.exit_code == 0, result.stderr
    assert result.stderr.count("not linear vibration") == 1, result.stderr
    assert "adis16460-vre-test, adxrs645-vre-test, " in result.stderr
