"""`gyrovib bounds` and `gyrovib select` from the command line: verdicts, exit codes, formats."""

from __future__ import annotations

import csv
import io
import json
import re
import textwrap
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any

import pytest

from tests.conftest import TONE_AND_NOISE
from tests.conftest import invoke as run

BUDGET = 0.01  # deg/s

# One tone a3 = 2 deg/s (a1 = 1, a2 = ½) at 100 Hz, Ω̄ = 0.5 deg/s, and Gaussian
# σ = (0.5, 0.5, 1) deg/s at Ω̄ = 2 deg/s (conftest.TONE_AND_NOISE).
PROFILES = TONE_AND_NOISE
# k2 bounds (exact, Δ* = 0.01): α2·Δ*/M2 with α2 = 0.4447496 —
#   tone: M2 = a²/2 = 2 → 0.0022237;  noise: M2 = σ² = 1 → 0.0044475.
# good: k2 = 1e-4 is far inside both; its only term k2·M2 ≤ 2e-4 deg/s ≪ Δ*.
# bad: k2 = 3e-3 > 0.0022237 (tone bound) but < 0.0044475 (noise bound);
#   its RMS error is k2·M2 = 6e-3 (tone) and 3e-3 (noise), both < Δ* = 0.01.
# awful: A1 = 0.5: tone bound α1·Δ*/g_A = 0.0109377 (g_A = ½E(0.5) = 0.4066198),
#   error A1·g_A = 0.2033 deg/s > Δ* (margin 0.0492).
SENSORS = """
sensors:
  - id: good
    coefficients: {k2: 1.0e-4}
  - id: bad
    coefficients: {k2: 3.0e-3}
  - id: awful
    coefficients: {A1: 0.5}
"""


def write(tmp_path: Path, body: str, name: str = "cat.yaml") -> str:
    path = tmp_path / name
    path.write_text("gyrovib: 1\n" + textwrap.dedent(body))
    return str(path)


def strict_json(text: str) -> Any:
    def refuse(name: str) -> None:
        raise AssertionError(f"{name} in JSON output")

    return json.loads(text, parse_constant=refuse)


@pytest.fixture
def catalog(tmp_path: Path) -> str:
    return write(tmp_path, PROFILES + SENSORS)


# ---------------------------------------------------------------- select verdicts


def test_select_json_verdicts(catalog: str) -> None:
    result = run("select", catalog, "--budget", "0.01", "--format", "json")
    assert result.exit_code == 0, result.stderr          # "good" passes: any is met
    doc = strict_json(result.stdout)
    assert set(doc) == {"tool", "version", "method", "unit", "budget", "profiles",
                        "criterion", "require", "assume_unknown", "sensors"}
    assert doc["tool"] == "gyrovib" and doc["method"] == "exact" and doc["unit"] == "deg/s"
    assert doc["budget"] == 0.01 and doc["criterion"] == "bounds" and doc["require"] == "any"
    assert [p["profile"] for p in doc["profiles"]] == ["tone", "noise"]
    assert set(doc["profiles"][0]) == {"profile", "rate", "bounds", "parts"}
    # vre (docs/model.md section 8): null, these profiles have no linear vibration
    assert set(doc["profiles"][0]["bounds"]) == {"A1", "k2", "k3", "k4", "k5", "m31", "m32",
                                                 "vre"}
    assert doc["profiles"][0]["bounds"]["vre"] is None
    assert set(doc["profiles"][0]["parts"]) == {"k4_additive", "k4_multiplicative",
                                                "k5_linear", "k5_cubic"}
    sensors = {s["sensor"]: s for s in doc["sensors"]}
    assert [s["sensor"] for s in doc["sensors"]] == ["good", "bad", "awful"]
    assert sensors["good"]["pass"] is True
    assert sensors["bad"]["pass"] is False
    assert sensors["awful"]["pass"] is False
    bad_tone, bad_noise = sensors["bad"]["profiles"]
    # total (|Δ_V|), saturated and reason: docs/output.md, select
    assert set(bad_tone) == {"profile", "pass", "status", "unknown", "rms", "margin",
                             "criterion_margin", "disagrees", "checks", "total", "saturated",
                             "reason"}
    # a coefficient-form part states its coefficients: nothing unknown (README)
    assert (bad_tone["status"], bad_noise["status"], bad_tone["unknown"]) == ("fail", "pass", [])
    assert (sensors["bad"]["status"], sensors["good"]["status"]) == ("fail", "pass")
    assert sensors["bad"]["source"] == "coefficients"
    assert bad_tone["saturated"] is False and "exceeds its bound" in bad_tone["reason"]
    assert bad_tone["pass"] is False and bad_noise["pass"] is True
    assert bad_tone["reason"].startswith("|k2| = 0.003 exceeds its bound")
    assert bad_noise["reason"] is None
    k2 = bad_tone["checks"]["k2"]
    assert k2["value"] == 3.0e-3 and k2["pass"] is False
    # eq. (23): |k2| ≤ α2·Δ*/M2, α2 = c_A/‖w‖ = 0.83205/√3.5 = 0.4447496;
    # tone a3 = 2: M2 = a²/2 = 2; noise σ3 = 1: M2 = 1
    assert k2["bound"] == pytest.approx(0.4447496 * BUDGET / 2, rel=1e-6)
    assert bad_noise["checks"]["k2"]["bound"] == pytest.approx(0.4447496 * BUDGET, rel=1e-6)
    # rms = k2·M2 = 3e-3·2 = 6e-3, margin = 0.01/6e-3 = 1.6667
    assert bad_tone["rms"] == pytest.approx(6e-3, rel=1e-12)
    assert bad_tone["margin"] == pytest.approx(0.01 / 6e-3, rel=1e-12)
    # The cell is decided by the bounds (the criterion): its margin is the least
    # bound/value, k2's 0.4447496·0.01/2 / 3e-3 = 0.7412 (< 1: it fails), and the direct
    # tests Δ_V(RMS) = |Δ_V| = 6e-3 ≤ 0.01 would pass it: they disagree, and say so.
    assert bad_tone["criterion_margin"] == pytest.approx(0.4447496 * BUDGET / 2 / 3e-3,
                                                         rel=1e-6)
    assert bad_tone["disagrees"] == ["rms", "worst"] and bad_noise["disagrees"] == []
    # k3 under Ω̄ = 0.5: bound finite; a coefficient the sensor does not have: value 0, pass.
    # Its share is β1/2 = 0.2264554 (docs/model.md section 6): (β1/2)·Δ*/(|Ω̄|·3M2), |Ω̄|·3M2 = 3
    assert bad_tone["checks"]["k3"] == {"value": 0.0, "bound": pytest.approx(
        0.2264554 * BUDGET / 3, rel=1e-6), "pass": True}


def test_margin_is_null_when_the_error_is_zero(tmp_path: Path) -> None:
    path = write(tmp_path, PROFILES + "sensors:\n  - id: ideal\n    coefficients: {}\n")
    doc = strict_json(run("select", path, "--budget", "0.01", "--format", "json").stdout)
    cell = doc["sensors"][0]["profiles"][0]
    assert cell["rms"] == 0.0 and cell["margin"] is None and cell["pass"] is True


def test_unconstrained_bound_is_null(tmp_path: Path) -> None:
    # Ω̄ = 0 → k3 and k5 unconstrained (zero denominators)
    path = write(tmp_path, PROFILES + SENSORS)
    doc = strict_json(run("bounds", path, "--budget", "0.01", "--rate", "0",
                          "--format", "json").stdout)
    for p in doc["profiles"]:
        assert p["bounds"]["k3"] is None and p["bounds"]["k5"] is None
        assert p["parts"]["k4_multiplicative"] is None
        assert p["rate"] == [0.0, 0.0, 0.0]
        assert p["bounds"]["k2"] is not None


@pytest.mark.parametrize(("sensors", "require", "code"), [
    (["good", "bad"], "any", 0),
    (["good", "bad"], "all", 1),
    (["good"], "all", 0),
    (["bad", "awful"], "any", 1),
])
def test_require_any_all_exit_codes(catalog: str, sensors: list[str], require: str,
                                    code: int) -> None:
    args = ["select", catalog, "--budget", "0.01", "--require", require]
    for s in sensors:
        args += ["--sensor", s]
    result = run(*args)
    assert result.exit_code == code, result.stdout + result.stderr
    assert result.stdout  # the report is written whether or not the requirement is met


@pytest.mark.parametrize(("criterion", "verdicts"), [
    ("bounds", {"good": True, "bad": False, "awful": False}),
    # bad's RMS error (6e-3, 3e-3) is within Δ*: it passes eq. (17) though it breaks a bound
    ("rms", {"good": True, "bad": True, "awful": False}),
    ("both", {"good": True, "bad": False, "awful": False}),
])
def test_criterion(catalog: str, criterion: str, verdicts: dict[str, bool]) -> None:
    doc = strict_json(run("select", catalog, "--budget", "0.01", "--criterion", criterion,
                          "--format", "json").stdout)
    assert {s["sensor"]: s["pass"] for s in doc["sensors"]} == verdicts
    assert doc["criterion"] == criterion


def test_input_response_gets_credit(tmp_path: Path) -> None:
    # a sensor whose response acts at its input (README, "Catalogue files", `at: input`)
    # and is 0.1 at the 100 Hz tone sees a3 = 0.2: M2 = 0.02, so its k2 bound is
    # α2·Δ*/0.02 = 100× the profile-alone bound 0.0022237.
    body = PROFILES + """
sensors:
  - id: damped
    coefficients: {k2: 3.0e-3}
    response: {at: input, table: [[1, 0.1], [1000, 0.1]]}
"""
    doc = strict_json(run("select", write(tmp_path, body), "--budget", "0.01",
                          "--profile", "tone", "--format", "json").stdout)
    alone = doc["profiles"][0]["bounds"]["k2"]
    own = doc["sensors"][0]["profiles"][0]["checks"]["k2"]["bound"]
    assert alone == pytest.approx(0.4447496 * BUDGET / 2, rel=1e-6)
    assert own == pytest.approx(100 * alone, rel=1e-9)
    assert doc["sensors"][0]["pass"] is True       # 3e-3 < 0.22237


@pytest.mark.parametrize("response", ["[[1, 0.1], [1000, 0.1]]",
                                      "{at: output, table: [[1, 0.1], [1000, 0.1]]}"])
def test_output_response_earns_no_credit(tmp_path: Path, response: str) -> None:
    # an output filter acts after the error is rectified (docs/model.md section 9): the
    # sensor's bounds are the profile's own, 0.0022237 < 3e-3, so it fails.
    body = PROFILES + f"""
sensors:
  - id: filtered
    coefficients: {{k2: 3.0e-3}}
    response: {response}
"""
    doc = strict_json(run("select", write(tmp_path, body), "--budget", "0.01",
                          "--profile", "tone", "--format", "json").stdout)
    alone = doc["profiles"][0]["bounds"]["k2"]
    own = doc["sensors"][0]["profiles"][0]["checks"]["k2"]["bound"]
    assert own == alone
    assert doc["sensors"][0]["pass"] is False


def test_table_output(catalog: str) -> None:
    result = run("select", catalog, "--budget", "0.01")
    out = result.stdout
    assert result.exit_code == 0
    assert "✓" in out and "✗" in out
    assert "Passing sensors, ranked by worst margin" in out
    # the limiting coefficient of each failing sensor, with its profile
    assert "bad" in out and "k2: |k2| = 0.003 is 1.35× its bound 0.002224" in out
    assert "A1: |A1| = 0.5 is 45.7× its bound 0.01094" in out
    assert "1 of 3 sensor(s) pass" in out


def test_table_ranks_by_worst_margin(tmp_path: Path) -> None:
    # k2 = 1e-4 → rms 2e-4 (tone, M2 = 2), margin 50; k2 = 1e-5 → margin 500
    body = PROFILES + """
sensors:
  - id: fair
    coefficients: {k2: 1.0e-4}
  - id: best
    coefficients: {k2: 1.0e-5}
"""
    out = run("select", write(tmp_path, body), "--budget", "0.01",
              "--format", "markdown").stdout
    ranking = out.split("Passing sensors, ranked by worst margin")[1]
    assert ranking.index("best") < ranking.index("fair")
    assert "| 1 | best | 500 | tone |" in ranking
    assert "| 2 | fair | 50 | tone |" in ranking


def test_junit(catalog: str) -> None:
    result = run("select", catalog, "--budget", "0.01", "--format", "junit")
    assert result.exit_code == 0
    root = ET.fromstring(result.stdout.encode("utf-8"))
    cases = root.findall(".//testcase")
    assert len(cases) == 6                                      # 3 sensors × 2 profiles
    assert {(c.get("classname"), c.get("name")) for c in cases} == {
        (s, p) for s in ("good", "bad", "awful") for p in ("tone", "noise")}
    failed = {(c.get("classname"), c.get("name")): c.find("failure") for c in cases
              if c.find("failure") is not None}
    # awful under noise: its A1 bound is α1·Δ*/g_A = 0.523808 (g_A = ½E(2) = 0.00849070)
    # ≥ 0.5, so it passes there
    assert set(failed) == {("bad", "tone"), ("awful", "tone")}
    assert "|k2| = 0.003 exceeds its bound 0.002224" in failed[("bad", "tone")].get("message")
    assert root.get("failures") == "2" and root.get("tests") == "6"
    rms = run("select", catalog, "--budget", "0.01", "--format", "junit", "--criterion", "rms")
    root = ET.fromstring(rms.stdout.encode("utf-8"))
    messages = [f.get("message") for f in root.iter("failure")]
    assert messages and all("Δ_V(RMS)" in m and "exceeds the budget" in m for m in messages)


def test_csv_and_markdown(catalog: str) -> None:
    text = run("select", catalog, "--budget", "0.01", "--format", "csv").stdout
    rows = list(csv.DictReader(io.StringIO(text)))
    assert len(rows) == 6
    bad_tone = next(r for r in rows if r["sensor"] == "bad" and r["profile"] == "tone")
    # the verdict column is "passed" (as in the DataFrame; "pass" is a Python keyword)
    assert bad_tone["passed"] == "False" and bad_tone["pass_k2"] == "False"
    assert float(bad_tone["value_k2"]) == 3e-3
    md = run("select", catalog, "--budget", "0.01", "--format", "markdown").stdout
    assert md.count("**FAIL**") == 2 and md.count("**PASS**") == 1
    bounds_csv = run("bounds", catalog, "--budget", "0.01", "--rate", "0",
                     "--format", "csv").stdout
    first = next(csv.DictReader(io.StringIO(bounds_csv)))
    assert first["profile"] == "tone" and first["k3"] == "inf"


def test_bounds_table_one_per_profile(catalog: str) -> None:
    result = run("bounds", catalog, "--budget", "0.01", "--rate", "0")
    assert result.exit_code == 0
    out = result.stdout
    assert out.count("Δ* = 0.01 deg/s") == 2 and "tone  (Ω_K3 = 0" in out and "noise  (" in out
    # an unconstrained bound (k3 at Ω̄ = 0) reads "unbounded", never inf or a huge number
    assert "unbounded" in out and "inf" not in out and "nan" not in out


def test_output_file(catalog: str, tmp_path: Path) -> None:
    target = tmp_path / "out.json"
    result = run("bounds", catalog, "--budget", "0.01", "--format", "json",
                 "--output", str(target))
    assert result.exit_code == 0 and result.stdout == ""
    assert strict_json(target.read_text())["budget"] == 0.01


# ---------------------------------------------------------------- units and budget


def test_budget_with_unit_equals_plain_number(catalog: str) -> None:
    a = strict_json(run("bounds", catalog, "--budget", "36deg/h", "--unit", "deg/s",
                        "--format", "json").stdout)
    b = strict_json(run("bounds", catalog, "--budget", "0.01", "--format", "json").stdout)
    c = strict_json(run("bounds", catalog, "--budget", "0.01 deg/s", "--format", "json").stdout)
    assert a["budget"] == pytest.approx(0.01, rel=1e-15)
    for x, y in ((a, b), (c, b)):
        for p, q in zip(x["profiles"], y["profiles"], strict=True):
            for name, value in q["bounds"].items():
                if value is None:  # vre without linear vibration
                    assert p["bounds"][name] is None
                    continue
                assert p["bounds"][name] == pytest.approx(value, rel=1e-12)


@pytest.mark.parametrize("command", ["bounds", "select"])
def test_output_follows_the_budget_unit(catalog: str, command: str) -> None:
    # README, "Units": --unit defaults to the unit --budget carries; 36deg/h stays 36 deg/h,
    # and the bounds equal those of an explicit --unit deg/h
    got = strict_json(run(command, catalog, "--budget", "36deg/h", "--format", "json").stdout)
    explicit = strict_json(run(command, catalog, "--budget", "36", "--unit", "deg/h",
                               "--format", "json").stdout)
    assert got["unit"] == "deg/h" and got["budget"] == pytest.approx(36.0, rel=1e-15)
    assert got["profiles"] == explicit["profiles"]


def test_bounds_unit_invariance(catalog: str) -> None:
    s = strict_json(run("bounds", catalog, "--budget", "0.01", "--format", "json").stdout)
    h = strict_json(run("bounds", catalog, "--budget", "36", "--unit", "deg/h",
                        "--format", "json").stdout)
    assert h["unit"] == "deg/h" and h["budget"] == pytest.approx(36.0)
    # kn[deg/h] = kn[deg/s]·(1/3600)^(n−1); m3i·(1/3600); A1 unchanged
    power = {"A1": 0, "k2": 1, "k3": 2, "k4": 3, "k5": 4, "m31": 1, "m32": 1}
    for ps, ph in zip(s["profiles"], h["profiles"], strict=True):
        assert ph["rate"][2] == pytest.approx(ps["rate"][2] * 3600)
        for name, n in power.items():
            assert ph["bounds"][name] == pytest.approx(ps["bounds"][name] / 3600**n,
                                                       rel=1e-12)
    # select verdicts do not depend on the output unit, checks convert like bounds
    vs = strict_json(run("select", catalog, "--budget", "0.01", "--format", "json").stdout)
    vh = strict_json(run("select", catalog, "--budget", "36deg/h", "--unit", "deg/h",
                         "--format", "json").stdout)
    for a, b in zip(vs["sensors"], vh["sensors"], strict=True):
        assert a["pass"] == b["pass"]
        for pa, pb in zip(a["profiles"], b["profiles"], strict=True):
            assert pa["pass"] == pb["pass"]
            assert pb["rms"] == pytest.approx(pa["rms"] * 3600, rel=1e-12)
            assert pb["checks"]["k2"]["value"] == pytest.approx(
                pa["checks"]["k2"]["value"] / 3600, rel=1e-12)


@pytest.mark.parametrize("budget", ["0", "-1", "nan", "3 furlongs", "inf", "", "0 deg/h"])
@pytest.mark.parametrize("command", ["bounds", "select"])
def test_bad_budget_exits_2(catalog: str, command: str, budget: str) -> None:
    result = run(command, catalog, "--budget", budget)
    assert result.exit_code == 2
    assert "--budget" in result.stderr
    assert "Traceback" not in result.stderr and result.stdout == ""


@pytest.mark.parametrize("command", ["bounds", "select"])
def test_budget_is_required(catalog: str, command: str) -> None:
    result = run(command, catalog)
    assert result.exit_code == 2 and "--budget" in result.stderr


# ---------------------------------------------------------------- method and allocation


@pytest.mark.parametrize("command", ["bounds", "select"])
def test_paper_with_custom_allocation_is_refused(catalog: str, command: str) -> None:
    result = run(command, catalog, "--budget", "0.01", "--method", "paper",
                 "--allocation", "2")
    assert result.exit_code == 2
    assert "paper" in result.stderr and "allocation" in result.stderr
    narrow = ["--sensor", "good"] if command == "select" else []
    ok = run(command, catalog, "--budget", "0.01", "--method", "paper", *narrow)
    assert ok.exit_code == 0, ok.stderr


def test_paper_with_catalogue_allocation_is_refused(tmp_path: Path) -> None:
    path = write(tmp_path, "allocation: {r: 2.0}\n" + PROFILES)
    result = run("bounds", path, "--budget", "0.01", "--method", "paper")
    assert result.exit_code == 2 and "allocation" in result.stderr
    exact = run("bounds", path, "--budget", "0.01", "--format", "json")
    assert exact.exit_code == 0, exact.stderr
    # the exact method honours the catalogue's r = 2: c_A = 2/√5, α2 = c_A/‖w‖ = 0.8944272/√3.5
    # = 0.4780914; tone M2 = a²/2 = 2
    k2 = strict_json(exact.stdout)["profiles"][0]["bounds"]["k2"]
    assert k2 == pytest.approx(0.4780914 * BUDGET / 2, rel=1e-6)


def test_paper_bounds_from_the_command_line(catalog: str) -> None:
    doc = strict_json(run("bounds", catalog, "--budget", "0.01", "--method", "paper",
                          "--format", "json").stdout)
    tone, noise = doc["profiles"]
    # tone: 0.44·Δ*/(0.673·2) = 0.00326895; noise: 0.24·Δ*/(Ω̄²·6σ²) = 0.0024/24 = 1e-4
    assert tone["bounds"]["A1"] == pytest.approx(0.0044 / 1.346, rel=1e-12)
    assert noise["bounds"]["k4"] == pytest.approx(1e-4, rel=1e-12)
    assert doc["method"] == "paper"


def test_custom_allocation_option(catalog: str) -> None:
    doc = strict_json(run("bounds", catalog, "--budget", "0.01", "--allocation",
                          "3,1,1,1,1,1,1,1,1", "--format", "json").stdout)
    # r = 3 → c_A = 3/√10, ‖w‖ = √5: α2 = 0.9486833/2.2360680 = 0.4242641; M2 = 2 (tone)
    assert doc["profiles"][0]["bounds"]["k2"] == pytest.approx(0.4242641 * BUDGET / 2,
                                                               rel=1e-6)


@pytest.mark.parametrize("allocation", ["0", "1,2", "1,a", "nan", "-1,1,1,1,1,1,1,1,1"])
def test_bad_allocation_exits_2(catalog: str, allocation: str) -> None:
    result = run("bounds", catalog, "--budget", "0.01", "--allocation", allocation)
    assert result.exit_code == 2 and "--allocation" in result.stderr


def test_paper_refuses_a_mixed_profile(tmp_path: Path) -> None:
    path = write(tmp_path, """
        profiles:
          - id: mixed
            harmonic:
              - frequency: 50
                amplitude: [0, 0, 1]
            random:
              rms: [0, 0, 1]
        """)
    result = run("bounds", path, "--budget", "0.01", "--method", "paper")
    assert result.exit_code == 2 and "mixed" in result.stderr


def test_unknown_ids_exit_2(catalog: str) -> None:
    result = run("bounds", catalog, "--budget", "0.01", "--profile", "nope")
    assert result.exit_code == 2 and result.stdout == ""
    assert result.stderr == ("gyrovib: error: unknown profile id 'nope'; the catalogue has: "
                             "tone, noise\n")
    result = run("select", catalog, "--budget", "0.01", "--sensor", "nope")
    assert result.exit_code == 2 and result.stdout == ""
    assert result.stderr == ("gyrovib: error: unknown sensor id 'nope'; the catalogue has: "
                             "good, bad, awful\n")


def test_help_lists_the_commands() -> None:
    result = run("--help")
    assert result.exit_code == 0
    # the Commands section lists each command with the first line of its help
    commands = result.stdout.split("Commands:")[1]
    assert re.search(r"^\s+bounds\s+The inverse problem", commands, re.MULTILINE)
    assert re.search(r"^\s+select\s+Check every sensor against a budget", commands,
                     re.MULTILINE)
