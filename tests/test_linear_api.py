"""Linear vibration wired end to end: catalogue → api → JSON/tables (docs/model.md section 8).

Every expected Δ0(6) = Σ G_jk·⟨a_j·a_k⟩ is worked by hand in the comments from
docs/model.md section 8 (⟨a_j²⟩ = Σ A_j²/2 + σ_j², ⟨a_j·a_k⟩ = Σ ½A_jA_k·cos(φ_j − φ_k)
+ ρ_jk·σ_jσ_k, σ² = ∫ν²·S df), or compared with the brute force of
gyrovib.core.numeric (the numeric method), or with the same catalogue written
in other units.
"""

from __future__ import annotations

import json
import math
import tempfile
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from hypothesis import given, settings
from hypothesis import strategies as st

from gyrovib.api import analyze, bounds, load, select, sweep
from gyrovib.cli.main import cli
from tests.conftest import LINEAR_PROFILE

G0 = 9.80665  # m/s² per g (the standard gravity of units.acceleration)

# Tones A = (1, 2, 3) g at 100 Hz with phases (0, 90, 0)°, random RMS σ = (1, 2, 0.5) g,
# ρ12 = 0.5, ρ13 = −0.2, ρ23 = 0:
#   ⟨a1²⟩ = ½·1 + 1 = 1.5     ⟨a2²⟩ = ½·4 + 4 = 6     ⟨a3²⟩ = ½·9 + 0.25 = 4.75
#   ⟨a1a2⟩ = ½·1·2·cos(−90°) + 0.5·1·2 = 1
#   ⟨a1a3⟩ = ½·1·3·cos(0°) − 0.2·1·0.5 = 1.4
#   ⟨a2a3⟩ = ½·2·3·cos(90°) + 0 = 0
# G = (4e-4, 4e-4, 4e-4, 1e-4, −2e-4, 3e-4) deg/s/g²:
#   Δ0(6) = 4e-4·12.25 + 1e-4·1 − 2e-4·1.4 = 4.9e-3 + 1e-4 − 2.8e-4 = 4.72e-3 deg/s
#   Σ⟨a_j²⟩ = 12.25 g²; effective VRE = 4.72e-3/12.25 = 3.853e-4 deg/s/g²
TONES_AND_RANDOM = (
    """
gyrovib: 1
units: {rate: deg/s}
sensors:
  - id: aniso
    coefficients: {k2: 1.0e-4}
    g2_sensitivity: {G11: 4.0e-4, G22: 4.0e-4, G33: 4.0e-4, G12: 1.0e-4, G13: -2.0e-4, G23: 3.0e-4}
  - id: no-g2
    coefficients: {k2: 1.0e-4}
profiles:
"""
    + LINEAR_PROFILE
    + """\
  - id: angular-only
    rate: [0, 0, 10]
    random: {rms: [0.5, 0.5, 1.0]}
"""
)
DELTA6 = 4.72e-3

# A flat PSD S = 0.01 g²/Hz over 10–1000 Hz on x3 behind the acceleration's own mount,
# a step ν = 1 below 100 Hz, 0.5 from 100 Hz on (a repeated frequency is a step):
#   σ3² = 0.01·(100 − 10)·1² + 0.01·(1000 − 100)·0.5² = 0.9 + 2.25 = 3.15 g²
# a 500 Hz tone of 2 g on x1 through the same mount: A1 = 2·0.5 = 1 g -> ⟨a1²⟩ = 0.5 g².
# The profile's own mount (ν = 0.1) is overridden by the acceleration's; the sensor's
# response (ν = 0.1) never applies to linear vibration. vre 1e-3 deg/s/g²:
#   Δ0(6) = 1e-3·(0.5 + 3.15) = 3.65e-3 deg/s
MOUNTED = """
gyrovib: 1
sensors:
  - id: vre-part
    vre: 1.0e-3
    coefficients: {k2: 0.0}
    response: [[1, 0.1], [10000, 0.1]]
profiles:
  - id: behind-mount
    rate: [0, 0, 0]
    mount: [[1, 0.1], [10000, 0.1]]
    acceleration:
      harmonic:
        - {frequency: 500, amplitude: [2.0, 0.0, 0.0]}
      random:
        psd:
          x3: [[10, 0.01], [1000, 0.01]]
      mount: [[10, 1.0], [100, 1.0], [100, 0.5], [1000, 0.5]]
  - id: profile-mount
    rate: [0, 0, 0]
    mount: [[10, 1.0], [100, 1.0], [100, 0.5], [1000, 0.5]]
    acceleration:
      random:
        psd:
          x3: [[10, 0.01], [1000, 0.01]]
"""


def write(tmp: Path, text: str, name: str = "cat.yaml") -> str:
    path = tmp / name
    path.write_text(text, encoding="utf-8")
    return str(path)


def run(*args: str) -> object:
    return CliRunner().invoke(cli, list(args), catch_exceptions=False)


def cli_json(*args: str) -> dict:
    result = CliRunner().invoke(cli, [*args, "--format", "json"], catch_exceptions=False)
    assert result.exit_code in (0, 1), result.output
    return json.loads(result.stdout)


# ------------------------------------------------------------------ Δ0(6) by hand


def test_tones_with_phases_and_coherent_random_axes_by_hand(tmp_path: Path) -> None:
    doc = cli_json("analyze", write(tmp_path, TONES_AND_RANDOM))
    rows = {(r["sensor"], r["profile"]): r for r in doc["results"]}
    aniso = rows[("aniso", "lin")]
    assert aniso["additive_terms"]["g2"] == pytest.approx(DELTA6, rel=1e-12)
    # Δ_VA and Δ_V(RMS) take it like the other additive terms (eq. 15, 16)
    terms = aniso["additive_terms"]
    assert aniso["additive"] == pytest.approx(sum(terms.values()), rel=1e-12)
    others = [v for k, v in terms.items() if k != "g2"]
    assert aniso["rms"] == pytest.approx(
        math.sqrt(sum(v * v for v in others) + DELTA6**2
                  + sum((q * 10.0 ** (n + 1)) ** 2 for n, q in
                        enumerate(aniso["multiplicative_coefficients"].values()))), rel=1e-12)
    # a sensor without g² sensitivity: unknown (null), and with it every sum of it; its
    # other terms are known. A profile without linear vibration: 0, a known zero
    unknown = rows[("no-g2", "lin")]
    assert unknown["additive_terms"]["g2"] is None
    assert [unknown[k] for k in ("additive", "total", "rms")] == [None, None, None]
    assert unknown["additive_terms"]["k2"] == aniso["additive_terms"]["k2"] != 0
    assert unknown["multiplicative"] == aniso["multiplicative"]
    assert rows[("aniso", "angular-only")]["additive_terms"]["g2"] == 0.0
    assert rows[("no-g2", "angular-only")]["total"] == rows[("aniso", "angular-only")]["total"]
    # the angular terms do not depend on the linear vibration
    assert rows[("aniso", "lin")]["additive_terms"]["k2"] == \
        rows[("aniso", "angular-only")]["additive_terms"]["k2"]


def test_psd_behind_a_mount_by_hand_and_the_response_never_applies(tmp_path: Path) -> None:
    doc = cli_json("analyze", write(tmp_path, MOUNTED))
    g2 = {r["profile"]: r["additive_terms"]["g2"] for r in doc["results"]}
    assert g2["behind-mount"] == pytest.approx(3.65e-3, rel=1e-12)
    # the profile's mount serves when the acceleration has none: σ3² = 3.15 g² (above)
    assert g2["profile-mount"] == pytest.approx(3.15e-3, rel=1e-12)


def test_metres_per_second_squared_input_by_hand(tmp_path: Path) -> None:
    # a tone of 9.80665 m/s² = 1 g on x1 -> ⟨a1²⟩ = 0.5 g²; vre written per (m/s²)²:
    # 1e-3/9.80665² deg/s/(m/s²)² = 1e-3 deg/s/g² -> Δ0(6) = 5e-4 deg/s; in deg/h ×3600 = 1.8
    text = f"""
gyrovib: 1
units: {{rate: deg/s, acceleration: m/s^2}}
sensors:
  - id: s
    vre: {{value: {1e-3 / G0**2!r}, unit: deg/s/(m/s^2)^2}}
    coefficients: {{k2: 0.0}}
profiles:
  - id: p
    rate: [0, 0, 0]
    acceleration:
      harmonic:
        - {{frequency: 50, amplitude: [{G0!r}, 0, 0]}}
"""
    doc = cli_json("analyze", write(tmp_path, text), "--unit", "deg/h")
    assert doc["results"][0]["additive_terms"]["g2"] == pytest.approx(1.8, rel=1e-12)


@pytest.mark.parametrize("written", ["0.001 deg/s/g^2", "{value: 0.001, unit: deg/s/g²}",
                                     "3.6 deg/h/g^2", "1.0e-3 deg/s/g²"])
def test_a_datasheet_vre_with_its_unit_in_a_metric_file(tmp_path: Path, written: str) -> None:
    # the same tone of 1 g on x1 (⟨a1²⟩ = 0.5 g²) and a VRE of 1e-3 deg/s/g² written with
    # its unit: Δ0(6) = 5e-4 deg/s = 1.8 deg/h, whatever the file's acceleration unit
    text = f"""
gyrovib: 1
units: {{rate: deg/s, acceleration: m/s^2}}
sensors:
  - id: s
    vre: {written}
    coefficients: {{k2: 0.0}}
profiles:
  - id: p
    rate: [0, 0, 0]
    acceleration:
      harmonic:
        - {{frequency: 50, amplitude: [{G0!r}, 0, 0]}}
"""
    doc = cli_json("analyze", write(tmp_path, text), "--unit", "deg/h")
    assert doc["results"][0]["additive_terms"]["g2"] == pytest.approx(1.8, rel=1e-12)


@pytest.mark.parametrize(("key", "at"), [("vre: 0.0004", "6:10"),
                                         ("g2_sensitivity: {G11: 0.0004}", "6:27")])
def test_a_bare_vre_in_a_metric_file_is_refused_with_both_readings(
        tmp_path: Path, key: str, at: str) -> None:
    # a datasheet VRE pasted into a file in m/s² would read 9.80665² = 96.17× larger
    text = f"""
gyrovib: 1
units: {{rate: deg/s, acceleration: m/s^2}}
sensors:
  - id: s
    {key}
    coefficients: {{k2: 0.0}}
profiles:
  - id: p
    acceleration: {{random: {{rms: [29.41995, 0, 0]}}}}
"""
    path = write(tmp_path, text)
    for command in (["validate"], ["analyze"], ["bounds", "--budget", "1"],
                    ["select", "--budget", "1"]):
        result = run(command[0], path, *command[1:])
        assert result.exit_code == 2, command
        first = result.stderr.splitlines()[0]
        assert first.startswith(f"{path}:{at}: sensor 's': "), first
        for needle in ("0.0004 read per g² is 0.0004 deg/s/g²",
                       "per (m/s^2)² it would be 0.03847 deg/s/g², 96.2× larger",
                       "0.0004 deg/s/g^2", "unit: deg/s/(m/s^2)^2"):
            assert needle in first, first
    # zero is zero in every unit; in a file in g a bare number is per g²
    assert run("validate", write(tmp_path, text.replace("0.0004", "0"), "z.yaml")).exit_code == 0
    text_g = text.replace("m/s^2}", "g}").replace("29.41995", "3")
    doc = cli_json("analyze", write(tmp_path, text_g, "g.yaml"))
    # 0.0004 deg/s/g² × (3 g)² = 0.0036 deg/s
    assert doc["results"][0]["additive_terms"]["g2"] == pytest.approx(0.0036, rel=1e-12)


# ------------------------------------------------------------------ numeric method


def test_numeric_method_includes_linear_vibration(tmp_path: Path) -> None:
    """Brute force (gyrovib.core.numeric): the g² average is an exact quadrature, so the
    g² term equals the closed form; Δ_V agrees within its standard error."""
    catalog = load([write(tmp_path, TONES_AND_RANDOM)])
    exact = analyze(catalog)
    numeric = analyze(catalog, method="numeric", samples=20_000, seed=3)
    assert numeric.error.extra_terms[..., 0] == pytest.approx(exact.error.extra_terms[..., 0],
                                                              rel=1e-9, abs=1e-18, nan_ok=True)
    assert numeric.error.extra_terms[0, 0, 0] == pytest.approx(DELTA6, rel=1e-9)
    assert numeric.stderr is not None
    # no-g2 under lin: unknown (NaN) by either method, the rest known
    unknown = np.isnan(exact.error.total)
    assert unknown.tolist() == [[False, False], [True, False]]
    assert np.isnan(numeric.error.total).tolist() == unknown.tolist()
    diff = np.abs(numeric.error.total - exact.error.total)[~unknown]
    assert np.all(diff <= 5 * numeric.stderr[~unknown] + 1e-12)


def test_numeric_method_through_the_cli(tmp_path: Path) -> None:
    doc = cli_json("analyze", write(tmp_path, TONES_AND_RANDOM), "--method", "numeric",
                   "--samples", "5000")
    row = next(r for r in doc["results"] if (r["sensor"], r["profile"]) == ("aniso", "lin"))
    assert row["additive_terms"]["g2"] == pytest.approx(DELTA6, rel=1e-9)
    # Δ_V: brute force of eq. (2) plus the g² quadrature; the angular part is k2·<x3²> = 1e-4
    assert row["total"] == pytest.approx(DELTA6 + 1e-4, abs=5 * row["stderr"] + 1e-12)


# ------------------------------------------------------------------ paper refusal


def test_paper_method_refuses_linear_vibration_located(tmp_path: Path) -> None:
    path = write(tmp_path, TONES_AND_RANDOM)
    result = run("analyze", path, "--method", "paper")
    assert result.exit_code == 2
    # located at the profile's id: (line 11 of the file, the first line being empty)
    assert f"{path}:11:" in result.stderr
    assert "'lin'" in result.stderr and "linear vibration" in result.stderr
    assert "--method exact" in result.stderr
    assert "Traceback" not in result.output
    # the profile without linear vibration is still accepted by the paper's method
    assert run("analyze", path, "--method", "paper", "--profile", "angular-only").exit_code == 0
    assert run("bounds", path, "--method", "paper", "--budget", "0.01").exit_code == 2


# ------------------------------------------------------------------ unit changes


@settings(deadline=None, max_examples=25, derandomize=True)
@given(
    amp=st.floats(0.0, 20.0), phase=st.floats(-180.0, 180.0), sigma=st.floats(0.0, 10.0),
    rho=st.floats(-0.9, 0.9), g11=st.floats(-1e-2, 1e-2), g12=st.floats(-1e-2, 1e-2),
    psd=st.floats(1e-4, 1.0), unit=st.sampled_from(["deg/h", "rad/s", "rpm"]),
)
def test_unit_changes_change_nothing(amp: float, phase: float, sigma: float, rho: float,
                                     g11: float, g12: float, psd: float, unit: str) -> None:
    """The same catalogue in g and deg/s, and in m/s² and another rate unit, gives the same
    Δ0(6); asking for another output unit scales it as a rate."""
    from gyrovib import units

    def text(acc_unit: str, rate_unit: str) -> str:
        a = 1.0 if acc_unit == "g" else G0  # acceleration unit per g
        r = units.scale(rate_unit)  # deg/s per rate unit

        def gv(x: float) -> str:  # a g² sensitivity per (acceleration unit)², with its unit
            unit = f"{rate_unit}/(m/s^2)^2"
            return repr(x) if acc_unit == "g" else f"{{value: {x!r}, unit: '{unit}'}}"

        return f"""
gyrovib: 1
units: {{rate: {rate_unit}, acceleration: {acc_unit}}}
sensors:
  - id: s
    coefficients: {{k2: {1e-4 * r!r}}}
    g2_sensitivity: {{G11: {gv(g11 / r / a**2)}, G22: {gv(g11 / r / a**2)},
                      G33: {gv(-g11 / r / a**2)}, G12: {gv(g12 / r / a**2)}, G13: 0.0,
                      G23: {gv(g12 / r / a**2)}}}
profiles:
  - id: p
    rate: [0, 0, {5.0 / r!r}]
    random: {{rms: [0, 0, {1.0 / r!r}]}}
    acceleration:
      harmonic:
        - {{frequency: 80, amplitude: [{amp * a!r}, {amp * a!r}, 0], phase: [0, {phase!r}, 0]}}
      random:
        psd:
          x1: [[20, {psd * a * a!r}], [200, {psd * a * a!r}]]
        rms: null
        coherence: [{rho!r}, 0, 0]
      mount: [[20, 1.0], [100, 0.5], [200, 0.25]]
"""
    with tempfile.TemporaryDirectory() as tmp:
        base = analyze(load([write(Path(tmp), text("g", "deg/s"), "a.yaml")]))
        other = analyze(load([write(Path(tmp), text("m/s^2", unit), "b.yaml")]))
        scaled = analyze(load([write(Path(tmp), text("g", "deg/s"), "c.yaml")]), unit=unit)
    ref = base.error.extra_terms[..., 0]
    assert other.error.extra_terms[..., 0] == pytest.approx(ref, rel=1e-9, abs=1e-15)
    assert other.error.rms == pytest.approx(base.error.rms, rel=1e-9, abs=1e-15)
    assert scaled.error.extra_terms[..., 0] * units.scale(unit) == pytest.approx(
        ref, rel=1e-12, abs=1e-15)


# ------------------------------------------------------------------ bounds and select


def test_bounds_gives_the_vre_bound_by_hand(tmp_path: Path) -> None:
    # default allocation r = 1.5: c_A = 1.5/√3.25 = 0.832050; with w6 = 1 appended,
    # ‖w‖ = √(1 + 1 + 1 + 0.25 + 0.25 + 1) = √4.5, α6 = c_A/√4.5 = 0.392232;
    # vre = α6·Δ*/Σ⟨a_j²⟩ = 0.392232·0.01/12.25 = 3.20190e-4 deg/s/g² (docs/model.md section 8)
    alpha6 = (1.5 / math.sqrt(3.25)) / math.sqrt(4.5)
    doc = cli_json("bounds", write(tmp_path, TONES_AND_RANDOM), "--budget", "0.01")
    by_id = {p["profile"]: p for p in doc["profiles"]}
    assert by_id["lin"]["bounds"]["vre"] == pytest.approx(alpha6 * 0.01 / 12.25, rel=1e-12)
    assert by_id["angular-only"]["bounds"]["vre"] is None  # no linear vibration: unbounded
    # in deg/h per g²: a rate per g², so ×3600
    doc_h = cli_json("bounds", write(tmp_path, TONES_AND_RANDOM), "--budget", "36deg/h",
                     "--unit", "deg/h")
    assert doc_h["profiles"][0]["bounds"]["vre"] == pytest.approx(
        3600 * alpha6 * 0.01 / 12.25, rel=1e-12)
    # the sixth weight of --allocation: w6 = 2 -> α6 = 2·c_A/√(3.5 + 4)
    doc_w = cli_json("bounds", write(tmp_path, TONES_AND_RANDOM), "--budget", "0.01",
                     "--allocation", "1.5,1,1,1,0.5,0.5,2,1,0.5,0.5")
    alpha6_w = 2 * (1.5 / math.sqrt(3.25)) / math.sqrt(7.5)
    assert doc_w["profiles"][0]["bounds"]["vre"] == pytest.approx(alpha6_w * 0.01 / 12.25,
                                                                  rel=1e-12)


def test_a_catalogue_allocation_of_six_weights_sets_the_vre_share(tmp_path: Path) -> None:
    # α_p = w_p·c_A/‖w‖ (eq. 21; docs/model.md section 8 adds w6 for the g² term):
    # r = 1.5 -> c_A = 1.5/√3.25; w = (1, 1, 1, 0.5, 0.5, 2) -> ‖w‖ = √(3.5 + 4) = √7.5,
    # α6 = 2·c_A/√7.5 = 0.607625; vre = α6·Δ*/Σ⟨a_j²⟩ with Σ⟨a_j²⟩ = 12.25 g² (above)
    c_a = 1.5 / math.sqrt(3.25)
    alpha6 = 2 * c_a / math.sqrt(7.5)
    six = TONES_AND_RANDOM + "allocation: {r: 1.5, w: [1, 1, 1, 0.5, 0.5, 2], v: [1, 0.5, 0.5]}\n"
    five = TONES_AND_RANDOM + "allocation: {r: 1.5, w: [1, 1, 1, 0.5, 0.5], v: [1, 0.5, 0.5]}\n"
    doc6 = cli_json("bounds", write(tmp_path, six, "six.yaml"), "--budget", "0.01")
    doc5 = cli_json("bounds", write(tmp_path, five, "five.yaml"), "--budget", "0.01")
    by6 = {p["profile"]: p["bounds"] for p in doc6["profiles"]}
    by5 = {p["profile"]: p["bounds"] for p in doc5["profiles"]}
    assert by6["lin"]["vre"] == pytest.approx(alpha6 * 0.01 / 12.25, rel=1e-12)
    # five weights: w6 = 1 appended, α6 = c_A/√4.5 (test_bounds_gives_the_vre_bound_by_hand)
    assert by5["lin"]["vre"] == pytest.approx(c_a / math.sqrt(4.5) * 0.01 / 12.25, rel=1e-12)
    # the file's six weights are the --allocation's ten numbers r, w1..w6, v1..v3
    flag = cli_json("bounds", write(tmp_path, TONES_AND_RANDOM), "--budget", "0.01",
                    "--allocation", "1.5,1,1,1,0.5,0.5,2,1,0.5,0.5")
    assert flag["profiles"][0]["bounds"]["vre"] == pytest.approx(by6["lin"]["vre"], rel=1e-15)
    # w6 acts only where there is a linear vibration: the angular-only profile keeps
    # α_p = w_p·c_A/‖w1..w5‖ and so every bound of the five-weight file
    assert by6["angular-only"] == by5["angular-only"]
    # a seventh weight is refused by the loader and by the JSON Schema alike
    from gyrovib.catalog.loader import _parse
    from gyrovib.models.schema import catalog_schema

    jsonschema = pytest.importorskip("jsonschema")
    seven = six.replace("0.5, 2]", "0.5, 2, 1]")
    result = run("validate", write(tmp_path, seven, "seven.yaml"))
    assert result.exit_code == 2
    assert "too many values (7; expected 5 or 6)" in result.output
    validator = jsonschema.Draft7Validator(catalog_schema())
    assert validator.is_valid(_parse(six, "six.yaml"))
    assert not validator.is_valid(_parse(seven, "seven.yaml"))


def test_bounds_table_shows_vre_only_with_linear_vibration(tmp_path: Path) -> None:
    path = write(tmp_path, TONES_AND_RANDOM)
    text = run("bounds", path, "--budget", "0.01", "--format", "markdown").stdout
    lin, angular = text.split("**angular-only")
    assert "| vre" in lin and "deg/s/g^2" in lin and "α6" in lin
    assert "| vre" not in angular
    csv = run("bounds", path, "--budget", "0.01", "--format", "csv", "--profile",
              "angular-only").stdout
    assert "vre" not in csv.splitlines()[0]


def test_select_fails_a_part_whose_vre_exceeds_its_bound(tmp_path: Path) -> None:
    # Under 'lin' with Δ* = 0.01 deg/s the vre bound is 3.2019e-4 deg/s/g² (above);
    # 'good' (vre 3e-4) passes, 'bad' (vre 4e-4) fails on the vre check alone: its
    # other coefficients are 0. Effective VRE of a pure vre part is |v|.
    text = """
gyrovib: 1
sensors:
  - id: good
    vre: 3.0e-4
    coefficients: {k2: 0.0}
  - id: bad
    vre: -4.0e-4
    coefficients: {k2: 0.0}
profiles:
""" + LINEAR_PROFILE
    path = write(tmp_path, text)
    bound = (1.5 / math.sqrt(3.25)) / math.sqrt(4.5) * 0.01 / 12.25
    doc = cli_json("select", path, "--budget", "0.01")
    sensors = {s["sensor"]: s for s in doc["sensors"]}
    assert sensors["good"]["pass"] is True and sensors["bad"]["pass"] is False
    vre = sensors["bad"]["profiles"][0]["checks"]["vre"]
    assert vre["value"] == pytest.approx(4.0e-4, rel=1e-12)
    assert vre["bound"] == pytest.approx(bound, rel=1e-12)
    assert vre["pass"] is False
    assert sensors["good"]["profiles"][0]["checks"]["vre"]["pass"] is True
    # the human output says why
    table = run("select", path, "--budget", "0.01")
    assert table.exit_code == 0  # 'good' passes: the requirement (any) is met
    assert "effective VRE" in table.stdout and "bad" in table.stdout
    assert f"is {4.0e-4 / bound:.3g}× its bound" in " ".join(table.stdout.split())
    junit = run("select", path, "--budget", "0.01", "--format", "junit").stdout
    assert "effective VRE" in junit and "exceeds its bound" in junit
    # by the API: the limit is the vre check
    result = select(load([path]), budget=0.01)
    assert result.limits[1].name == "vre"
    assert result.limits[1].ratio == pytest.approx(4.0e-4 / bound, rel=1e-12)


def test_select_rms_includes_the_g2_term(tmp_path: Path) -> None:
    catalog = load([write(tmp_path, TONES_AND_RANDOM)])
    chosen = select(catalog, budget=0.01, criterion="rms")
    exact = analyze(catalog)
    # where analyze knows Δ_V(RMS) (no-g2 under lin it does not: NaN; select judges that
    # cell unverified, and its rms leaves the unknown term out)
    known = ~np.isnan(exact.error.rms)
    assert known.tolist() == [[True, True], [False, True]]
    assert chosen.rms[known] == pytest.approx(exact.error.rms[known], rel=1e-12)
    assert chosen.status(1, 0) == "unverified"


def test_sweep_carries_the_g2_term(tmp_path: Path) -> None:
    catalog = load([write(tmp_path, TONES_AND_RANDOM)])
    swept = sweep(catalog, [0.0, 10.0, 30.0])
    at10 = analyze(catalog)  # the profiles' own Ω_K3 = 10 deg/s
    known = ~np.isnan(at10.error.total)  # no-g2 under lin: unknown in analyze
    assert known.tolist() == [[True, True], [False, True]]
    assert swept.exact.total[:, :, 1][known] == pytest.approx(at10.error.total[known],
                                                              rel=1e-12)
    assert swept.exact.extra_terms[0, 0, :, 0] == pytest.approx([DELTA6] * 3, rel=1e-12)
    assert swept.paper_refused.keys() == {"lin"}
    assert "linear vibration" in swept.paper_refused["lin"]


# ------------------------------------------------------------------ bundled catalogues


def test_bundled_mems_parts_show_the_g2_term_under_the_new_profiles() -> None:
    # ADIS16460 vre 4e-4 deg/s/g² (data sheet) under its own test condition, 5 g rms on
    # the tested axis, as the data sheet's test: Δ0(6) = 4e-4·25 = 0.01 deg/s (36 deg/h);
    # ADXRS645 vre 6e-4 under 25 g rms on the tested axis: 6e-4·625 = 0.375 deg/s.
    # The PSD levels are rounded to 6 digits (1.26263e-2, 0.126263): rel 1e-5.
    result = analyze(load(), sensors=["adis16460", "adxrs645", "generic-tactical-fog"],
                     profiles=["adis16460-vre-test", "adxrs645-vre-test",
                               "hg4930-operating-random"])
    g2 = dict(zip(((s, p) for s in result.sensors for p in result.profiles),
                  result.error.extra_terms[..., 0].ravel().tolist(), strict=True))
    assert g2[("adis16460", "adis16460-vre-test")] == pytest.approx(0.01, rel=1e-5)
    assert g2[("adxrs645", "adxrs645-vre-test")] == pytest.approx(0.375, rel=1e-5)
    # HG4930 operating PSD 0.003 g²/Hz over 10–2000 Hz: σ² = 5.97 g² per axis
    assert g2[("adis16460", "hg4930-operating-random")] == pytest.approx(4e-4 * 3 * 5.97,
                                                                         rel=1e-12)
    assert math.isnan(g2[("generic-tactical-fog", "adis16460-vre-test")])  # no g² figure
    table = run("analyze", "--profile", "cruise-hard-mounted", "--sensor", "adis16460").stdout
    assert "Δ0 g²" in table


def test_bundled_isolation_mount_cuts_the_g2_term() -> None:
    # The same HG4930 PSD through the 50 Hz isolator of 'cruise-isolated': the
    # g² term falls by ∫ν²S df / ∫S df; that ratio is the mean square after the mount over
    # the one before, whatever the part (docs/model.md section 8)
    result = analyze(load(), sensors=["adis16460"],
                     profiles=["cruise-hard-mounted", "cruise-isolated"])
    hard, isolated = result.error.extra_terms[0, :, 0]
    assert hard == pytest.approx(4e-4 * 3 * 5.97, rel=1e-12)
    from gyrovib.api.study.linear import profile_linear

    entry = next(p for p in load().profiles if p.profile.id == "cruise-isolated")
    linear = profile_linear(entry)
    assert linear is not None
    assert isolated == pytest.approx(4e-4 * float(np.sum(linear.sigma**2)), rel=1e-12)
    assert 0.1 < isolated / hard < 0.2  # the profile's comment: 0.132


OLD_PROFILES = ("uav-blade-pass-tone", "engine-harmonics", "flat-random-hover",
                "shaped-random-isolated", "sine-on-random", "manoeuvre-random-rms",
                "manoeuvre-saturation")


def _without_linear(tmp: Path) -> list[str]:
    """The bundled catalogues with every vre line and linear-vibration profile removed
    (and the bundled mission, which flies some of those profiles)."""
    from gyrovib.catalog.loader import bundled_paths

    out = []
    for path in bundled_paths():
        if path.name.startswith("missions."):
            continue
        text = path.read_text(encoding="utf-8")
        if "sensors:" in text:
            text = "\n".join(line for line in text.splitlines()
                             if not line.strip().startswith("vre:"))
        else:
            text = text.split("  # ---------------------------------------------------------"
                              "------- linear vibration")[0]
        out.append(write(tmp, text, path.name))
    return out


def test_results_without_linear_vibration_are_unchanged(tmp_path: Path) -> None:
    """The old profiles give, bit for bit, what they give with no g² data at all."""
    plain = load(_without_linear(tmp_path))
    assert [p.profile.id for p in plain.profiles] == list(OLD_PROFILES)
    bundled = load()
    for method in ("exact", "numeric"):
        kwargs = {"samples": 2000} if method == "numeric" else {}
        a = analyze(bundled, profiles=OLD_PROFILES, method=method, **kwargs)
        b = analyze(plain, method=method, **kwargs)
        for name in ("additive_terms", "multiplicative_coefficients", "additive",
                     "multiplicative", "total", "rms", "extra_terms"):
            assert np.array_equal(getattr(a.error, name), getattr(b.error, name)), name
    a_b = bounds(bundled, profiles=OLD_PROFILES, budget=0.01)
    b_b = bounds(plain, budget=0.01)
    assert np.array_equal(a_b.bounds.stacked(), b_b.bounds.stacked())
    assert a_b.bounds.vre is None and b_b.bounds.vre is None
    a_s = select(bundled, profiles=OLD_PROFILES, budget=0.01, criterion="both")
    b_s = select(plain, budget=0.01, criterion="both")
    assert np.array_equal(a_s.passed, b_s.passed) and np.array_equal(a_s.rms, b_s.rms)
    # and the human outputs of the old profiles keep their columns
    args = ["--profile", "sine-on-random"]
    assert run("analyze", *args).stdout == run("analyze", *_without_linear(tmp_path),
                                               *args).stdout
    assert "Δ0 g²" not in run("analyze", *args).stdout
    assert "additive_g2" not in run("analyze", *args, "--format", "csv").stdout


def test_tables_show_the_g2_column_with_linear_vibration(tmp_path: Path) -> None:
    path = write(tmp_path, TONES_AND_RANDOM)
    markdown = run("analyze", path, "--format", "markdown").stdout
    assert "Δ0 g²" in markdown
    header = run("analyze", path, "--format", "csv").stdout.splitlines()[0].split(",")
    # Δ0(6) follows Δ0(5) (additive_m32); its value is the hand-worked 4.72e-3 deg/s
    assert header[header.index("additive_m32") + 1] == "additive_g2"
    row = run("analyze", path, "--format", "csv", "--sensor", "aniso", "--profile",
              "lin").stdout.splitlines()[1].split(",")
    assert float(row[header.index("additive_g2")]) == pytest.approx(DELTA6, rel=1e-12)


def test_impossible_coherences_are_refused_located(tmp_path: Path) -> None:
    # ρ12 = ρ13 = 0.9 force ρ23 ≥ 0.81 − √(0.19·0.19) = 0.62, not −0.9: the correlation
    # matrix [[1, .9, .9], [.9, 1, −.9], [.9, −.9, 1]] maps (1, −1, −1) to
    # (1 − 1.8, 0.9 − 1 + 0.9, 0.9 + 0.9 − 1) = −0.8·(1, −1, −1): eigenvalue −0.8 < 0
    text = """
gyrovib: 1
sensors:
  - id: s
    vre: 1.0e-3
    coefficients: {k2: 0.0}
profiles:
  - id: bad-rho
    rate: [0, 0, 0]
    acceleration:
      random: {rms: [1, 1, 1], coherence: [0.9, 0.9, -0.9]}
"""
    path = write(tmp_path, text)
    result = run("analyze", path)
    assert result.exit_code == 2
    # located at the coherence itself (line 11; the file's first line is empty)
    assert f"{path}:11:" in result.stderr and "correlation matrix" in result.stderr


def test_absurd_linear_magnitudes_are_refused_located(tmp_path: Path) -> None:
    # (1e200 g)²/2 overflows floating point, and 1e300 deg/s/g² × (1e10 g)² too: the
    # catalogue models refuse both magnitudes (at most 1e12, gyrovib.models._types) at
    # their place, for every command; a budget of 1e-300 deg/s over Σ⟨a²⟩ ≈ 1e20 g²
    # leaves a VRE bound below the smallest normal float: refused at the profile
    text = """
gyrovib: 1
sensors:
  - id: s
    vre: 1.0e+300
    coefficients: {k2: 0.0}
profiles:
  - id: big
    rate: [0, 0, 0]
    acceleration:
      harmonic:
        - {frequency: 10, amplitude: [1.0e+200, 0, 0]}
  - id: ok
    rate: [0, 0, 0]
    acceleration:
      random: {rms: [1.0e+10, 1, 1]}
"""
    path = write(tmp_path, text)
    for args in (["validate"], ["analyze"], ["select", "--budget", "1"],
                 ["bounds", "--budget", "1"]):
        result = run(args[0], path, *args[1:])
        assert result.exit_code == 2, args
        lines = result.stderr.splitlines()
        assert lines[0].startswith(f"{path}:5:10: sensor 's': vre: must not be greater "
                                   "than 1e+12"), lines
        assert lines[1].startswith(f"{path}:12:39: profile 'big': acceleration.harmonic[0]"
                                   ".amplitude[0]: must not be greater than 1e+12"), lines
    path = write(tmp_path, text.replace("1.0e+300", "1.0e-3").replace("1.0e+200", "1"))
    result = run("bounds", path, "--profile", "ok", "--budget", "1e-300")
    assert result.exit_code == 2
    assert f"{path}:13:" in result.stderr and "VRE bound" in result.stderr, result.stderr
    assert "overflows floating point" in result.stderr and "Traceback" not in result.output
