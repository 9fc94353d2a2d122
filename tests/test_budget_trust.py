"""The mission budget says what it rests on (docs/model.md section 15): a typical figure
is named wherever its verdict is shown, and a total is never read as ∞ when it is a
finite number, nor an internal error when it is beyond a float."""

from __future__ import annotations

import csv
import io
import json
import math
from pathlib import Path

import pytest

from tests.conftest import invoke

# One sensor with every figure, its bias instability a typical one; two hours of a tone.
TYPICAL = """\
gyrovib: 1
units: {rate: deg/s}
sensors:
  - id: typical
    coefficients: {k2: 2.0e-6}
    vre: 0
    noise:
      arw: 0.15 deg/sqrt(h)
      bias_instability: "0.5 °/h typ"
      rrw: {value: 0.02, unit: deg/h/sqrt(h), qualifier: typ}
      bias_repeatability: "1 deg/h max"
  - id: guaranteed
    coefficients: {k2: 2.0e-6}
    vre: 0
    noise: {arw: 0.15, bias_instability: 0.5, rrw: 0.02, bias_repeatability: 1}
profiles:
  - id: tone
    rate: [0, 0, 0.5]
    harmonic: [{frequency: 40, amplitude: [0, 0, 2.0]}]
missions:
  - id: two-hours
    segments:
      - {profile: tone, duration: 7200}
"""


@pytest.fixture
def typical(tmp_path: Path) -> Path:
    path = tmp_path / "typ.yaml"
    path.write_text(TYPICAL, encoding="utf-8")
    return path


def test_a_typical_figure_is_carried_into_the_budget_and_its_verdict(typical: Path) -> None:
    args = ("mission", typical, "--angle-budget", "3deg")
    rows = json.loads(invoke(*args, "--format", "json").stdout)["mission"]
    # the qualifiers as written: typ on B (a text) and K (a mapping), max on R
    assert rows[0]["budget"]["typical"] == ["bias_instability", "rrw"]
    assert rows[1]["budget"]["typical"] == []
    assert rows[0]["status"] == "pass"  # √(0.15²·2 + 1² + (0.02·2^1.5/√3)² + 2²) ≈ 2.24 deg
    table = invoke(*args).stdout
    assert "pass (on typ)" in table and "1 typ" in table  # θ_B = 0.5 deg/h · 2 h
    assert table.count("(on typ)") == 1 + table.count("'(on typ)'")
    markdown = invoke(*args, "--format", "markdown").stdout
    line = next(x for x in markdown.splitlines() if x.startswith("| typical"))
    assert line.endswith("| pass (on typ) |")
    guaranteed = next(x for x in markdown.splitlines() if x.startswith("| guaranteed"))
    assert "typ" not in guaranteed
    got = {r["sensor"]: r for r in csv.DictReader(io.StringIO(
        invoke(*args, "--format", "csv").stdout))}
    assert got["typical"]["typical"] == "bias_instability rrw"
    assert got["guaranteed"]["typical"] == ""
    junit = invoke(*args, "--format", "junit").stdout
    assert "the verdict rests on typical (typ) figures: bias_instability, rrw" in junit
    # select --mission shows the same rows
    chosen = json.loads(invoke("select", typical, "--mission", "two-hours", "--angle-budget",
                               "3deg", "--format", "json").stdout)["mission"]
    assert {r["sensor"]: r["budget"]["typical"] for r in chosen} == {
        "typical": ["bias_instability", "rrw"], "guaranteed": []}


def _overflow(tmp_path: Path, duration: str) -> Path:
    path = tmp_path / "big.yaml"
    path.write_text(TYPICAL.replace("duration: 7200", f"duration: {duration}"),
                    encoding="utf-8")
    return path


def test_a_total_whose_squares_overflow_is_finite(tmp_path: Path) -> None:
    # T = 1e200 s = 2.78e196 h: θ_R = 1 deg/h · T = 2.78e196 deg, whose square (7.7e392)
    # is past double precision; the RSS is scaled, so the total is the hand sum
    # √(θ_ARW² + θ_B² + θ_RRW² + θ_R²) with θ_RRW = 0.02·T^1.5/√3 ≈ 5.346e292 dominant
    path = _overflow(tmp_path, "1.0e200")
    r = invoke("mission", path, "--sensor", "guaranteed", "--format", "json")
    assert r.exit_code == 0, r.stderr
    b = json.loads(r.stdout)["mission"][0]["budget"]
    hours = 1e200 / 3600.0
    rrw = 0.02 * hours * math.sqrt(hours) / math.sqrt(3.0)
    assert b["rrw"] == pytest.approx(rrw, rel=1e-12)
    assert b["total"] == pytest.approx(rrw, rel=1e-12)  # the others are 1e-96 of it
    table = invoke("mission", path, "--sensor", "guaranteed").stdout
    assert "∞" not in table and "5.346e+292" in table  # θ_RRW, 4 figures


@pytest.mark.parametrize("duration", ["1.0e300", "1.0e250"])
def test_a_term_beyond_a_float_is_refused_at_the_duration(tmp_path: Path,
                                                         duration: str) -> None:
    # θ_RRW = 0.02·T^1.5/√3 with T = 2.8e296 h (or 2.8e246 h): ≈ 5e442 (5e367) deg
    path = _overflow(tmp_path, duration)
    r = invoke("mission", path, "--sensor", "guaranteed")
    assert r.exit_code == 2 and r.stdout == ""
    line = TYPICAL.splitlines().index("      - {profile: tone, duration: 7200}") + 1
    assert r.stderr.startswith(f"{path}:{line}:")
    assert "its rrw term" in r.stderr and "beyond double precision" in r.stderr
