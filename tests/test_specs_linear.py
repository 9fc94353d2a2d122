"""Datasheet (spec-form) sensors under linear vibration, through the command line.

The bundled ADIS16460 and ADXRS645 are spec-form sensors with a VRE spec v
(docs/model.md section 11); the bundled linear profiles (docs/model.md section 8) give
Σ_j⟨a_j²⟩. Their worst case adds |v|·Σ_j⟨a_j²⟩ to the envelope's worst |Δ_V|
(the VRE term takes the sign that makes |Δ_V| largest). Also: the merged
``select`` checks, where a coefficient sensor's effective-VRE check and a
spec-form sensor's datasheet checks stand side by side.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest
import yaml

import gyrovib
from gyrovib.catalog.loader import bundled_paths
from tests.conftest import LINEAR_PROFILE
from tests.conftest import invoke as run

# Flat PSDs of the bundled profiles (their comments in profiles.gyrovib.yaml):
#   adis16460-vre-test: 1.26263e-2 g²/Hz over 20–2000 Hz -> 24.99999 g² (5 g rms) on the
#     tested axis x3 alone (the data sheet's one-axis test): Σ⟨a_j²⟩ = 1 × σ²;
#   hg4930-operating-random: 3.0e-3 g²/Hz over 10–2000 Hz -> 5.97 g² on each of the three
#     axes: Σ⟨a_j²⟩ = 3 × σ².
SIGMA2 = {"adis16460-vre-test": 1.26263e-2 * 1980.0, "hg4930-operating-random": 3.0e-3 * 1990.0}
AXES = {"adis16460-vre-test": 1, "hg4930-operating-random": 3}
# VRE specs of the bundled data sheets (sensors.gyrovib.yaml): deg/s per g².
VRE = {"adis16460": 4.0e-4, "adxrs645": 6.0e-4}


def cli_json(*args: str) -> dict[str, Any]:
    done = run(*args, "--format", "json")
    assert done.exit_code in (0, 1), done.output
    return json.loads(done.stdout)


def test_bundled_datasheet_vre_term_through_the_cli() -> None:
    # Pure linear profiles at Ω = 0 without angular vibration: the envelope part is 0,
    # so worst |Δ_V| = Δ0 g² = |v|·Σ⟨a_j²⟩, and the RMS bound is that one term.
    # ADIS16460 at its own condition (one axis): 4e-4·25 = 0.01 deg/s (= 36 deg/h), the
    # data sheet's VRE × level²; under HG4930's PSD: 4e-4·3·5.97 = 7.164e-3 deg/s;
    # ADXRS645 (6e-4): 0.015 and 1.0746e-2 deg/s.
    doc = cli_json("analyze", "--sensor", "adis16460", "--sensor", "adxrs645",
                   "--profile", "adis16460-vre-test", "--profile", "hg4930-operating-random")
    assert len(doc["results"]) == 4
    for row in doc["results"]:
        expected = VRE[row["sensor"]] * AXES[row["profile"]] * SIGMA2[row["profile"]]
        assert row["source"] == "specs"
        assert row["additive_terms"]["g2"] == pytest.approx(expected, rel=1e-12)
        assert row["total"] == pytest.approx(expected, rel=1e-12)
        assert row["envelope"]["rms_bound"] == pytest.approx(expected, rel=1e-12)
    by_hand = {(r["sensor"], r["profile"]): r["total"] for r in doc["results"]}
    assert by_hand[("adis16460", "adis16460-vre-test")] == pytest.approx(0.01, rel=1e-5)
    assert by_hand[("adis16460", "hg4930-operating-random")] == pytest.approx(7.164e-3,
                                                                              rel=1e-12)


def _without_vre(tmp_path: Path) -> Path:
    """The bundled ADIS16460 entry with its ``specs.vre`` removed, as its own file."""
    sensors = next(p for p in bundled_paths() if p.name.startswith("sensors"))
    entry = next(s for s in yaml.safe_load(sensors.read_text(encoding="utf-8"))["sensors"]
                 if s["id"] == "adis16460")
    del entry["specs"]["vre"]
    entry["id"] = "adis16460-no-vre"
    path = tmp_path / "novre.yaml"
    path.write_text(yaml.safe_dump({"gyrovib": 1, "units": {"rate": "deg/s"},
                                    "sensors": [entry]}), encoding="utf-8")
    return path


def test_vre_spec_adds_v_times_sigma2_to_the_worst_case_under_angular_vibration(
        tmp_path: Path) -> None:
    # cruise-hard-mounted has angular vibration and the HG4930 PSD unmounted
    # (Σ⟨a_j²⟩ = 3·5.97 g²): the ADIS16460's worst |Δ_V| exceeds that of the same
    # datasheet with its VRE taken as 0 (select --assume-unknown zero) by exactly
    # 4e-4·3·5.97 = 7.164e-3 deg/s, in select --criterion worst and in analyze; analyze
    # writes the worst case of the datasheet without a VRE unknown (null), not that number.
    profiles = next(p for p in bundled_paths() if p.name.startswith("profiles"))
    sensors = next(p for p in bundled_paths() if p.name.startswith("sensors"))
    files = [str(sensors), str(_without_vre(tmp_path)), str(profiles)]
    doc = cli_json("analyze", *files, "--sensor", "adis16460", "--sensor", "adis16460-no-vre",
                   "--profile", "cruise-hard-mounted")
    total = {r["sensor"]: r["total"] for r in doc["results"]}
    assert total["adis16460-no-vre"] is None
    term = VRE["adis16460"] * 3 * SIGMA2["hg4930-operating-random"]
    chosen = cli_json("select", *files, "--sensor", "adis16460", "--sensor",
                      "adis16460-no-vre", "--profile", "cruise-hard-mounted",
                      "--criterion", "worst", "--budget", "1", "--assume-unknown", "zero")
    worst = {s["sensor"]: s["profiles"][0]["total"] for s in chosen["sensors"]}
    assert worst["adis16460-no-vre"] > 0  # the envelope part is there too
    assert worst["adis16460"] - worst["adis16460-no-vre"] == pytest.approx(term, rel=1e-9)
    assert worst["adis16460"] == pytest.approx(total["adis16460"], rel=1e-12)


MIXED = """
gyrovib: 1
sensors:
  - id: coefficient-part
    vre: -4.0e-4
    coefficients: {k2: 0.0}
  - id: datasheet-part
    specs:
      range: 100
      nonlinearity: {value: 0.001, unit: "%FS", fit: least-squares, measure: max}
      vre: 0.0004
profiles:
""" + LINEAR_PROFILE


def test_select_mixes_the_coefficient_vre_check_and_the_datasheet_checks(
        tmp_path: Path) -> None:
    # The profile and budget of test_linear_api.test_select_fails_a_part_whose_vre_exceeds_
    # its_bound: the coefficient part's vre bound is 3.2019e-4 deg/s/g², and its effective
    # VRE is |v| = 4e-4 (its other coefficients are 0), so it fails on the vre check
    # alone; the reason comes from gyrovib.reasons, the same text in JSON and frame.
    path = tmp_path / "mixed.yaml"
    path.write_text(MIXED, encoding="utf-8")
    bound = (1.5 / 3.25**0.5) / 4.5**0.5 * 0.01 / 12.25
    doc = cli_json("select", str(path), "--budget", "0.01")
    coefficient, datasheet = doc["sensors"]
    assert (coefficient["source"], datasheet["source"]) == ("coefficients", "specs")
    cell = coefficient["profiles"][0]
    assert set(cell["checks"]) == {"A1", "k2", "k3", "k4", "k5", "m31", "m32", "vre"}
    assert cell["checks"]["vre"]["value"] == pytest.approx(4.0e-4, rel=1e-12)
    assert cell["checks"]["vre"]["bound"] == pytest.approx(bound, rel=1e-12)
    assert cell["checks"]["vre"]["pass"] is False
    assert cell["reason"] == (f"effective VRE |Δ0(6)|/Σ⟨a_j²⟩ = 0.0004 deg/s/g^2 exceeds "
                              f"its bound {bound:.4g} deg/s/g^2")
    spec_cell = datasheet["profiles"][0]
    assert set(spec_cell["checks"]) == {"nonlinearity", "vre"}
    assert spec_cell["checks"]["vre"]["value"] == pytest.approx(4.0e-4, rel=1e-12)
    result = gyrovib.select(str(path), budget=0.01)
    assert result.limits[0].name == "vre"
    frame = result.to_frame()
    assert frame["reason"].iloc[0] == cell["reason"]
    assert list(frame["pass_vre"]) == [False, spec_cell["checks"]["vre"]["pass"]]
    # it passes on its datasheet, but lin's angular x1, x2 are correlated with x3 (the
    # default coherence 1): m31, m32, not on a datasheet, can decide it -> unverified
    assert (spec_cell["status"], spec_cell["unknown"]) == ("unverified", ["m31", "m32"])
    assert spec_cell["pass"] is False and frame["status"].iloc[1] == "unverified"
    assert spec_cell["reason"].startswith("unverified: passes on its published figures, "
                                          "but m31 not published")
    # the library names the argument where the command line names its option
    assert frame["reason"].iloc[1] == spec_cell["reason"].replace(
        "--assume-unknown zero", "assume_unknown='zero'")
    zero = gyrovib.select(str(path), budget=0.01, assume_unknown="zero").to_frame()
    assert zero["reason"].isna().iloc[1] and zero["status"].iloc[1] == "pass"  # it passes
