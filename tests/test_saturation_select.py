"""Saturation through `analyze` and `select` (docs/model.md section 9, docs/output.md).

The reach at the nonlinear element is |Ω_K3| + Σ tone amplitudes + κ·σ3. The
profile below has Ω_K3 = 10 deg/s, one 100 Hz tone of a3 = 5 deg/s and a
Gaussian part of σ3 = 2 deg/s, so with the default κ = 3 the reach is
10 + 5 + 3·2 = 21 deg/s, and with κ = 2 it is 10 + 5 + 2·2 = 19 deg/s.
"""

from __future__ import annotations

import json
import textwrap
from pathlib import Path
from typing import Any

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import gyrovib
from tests.conftest import invoke as run

PROFILE = """
profiles:
  - id: shake
    rate: [0, 0, 10]
    harmonic:
      - frequency: 100
        amplitude: [0, 0, 5.0]
    random:
      rms: [0, 0, 2.0]
"""
REACH = 10.0 + 5.0 + 3.0 * 2.0  # κ = 3
# k2 = 1e-6: k2·M2 = 1e-6·(5²/2 + 2²) = 1.65e-5 deg/s, far inside Δ* = 0.01 and its bound
# α2·Δ*/M2 = 0.4447·0.01/16.5 = 2.7e-4: the sensor passes every criterion unless it saturates.
BUDGET = "0.01"


def catalog(tmp_path: Path, ranges: dict[str, float | None], profile: str = PROFILE,
            extra: str = "") -> str:
    sensors = "\nsensors:\n"
    for name, r in ranges.items():
        sensors += f"  - id: {name}\n    coefficients: {{k2: 1.0e-6}}\n"
        if r is not None:
            sensors += f"    range: {r!r}\n"
    path = tmp_path / "cat.yaml"
    path.write_text("gyrovib: 1\n" + textwrap.dedent(profile) + sensors + extra)
    return str(path)


def analyze_rows(path: str, *args: str) -> dict[str, Any]:
    result = run("analyze", path, "--format", "json", *args)
    assert result.exit_code == 0, result.stderr
    return {row["sensor"]: row for row in json.loads(result.stdout)["results"]}


def select_doc(path: str, *args: str) -> tuple[int, Any]:
    result = run("select", path, "--budget", BUDGET, "--format", "json", *args)
    assert result.exit_code in (0, 1), result.stderr
    return result.exit_code, json.loads(result.stdout)


def test_reach_just_below_and_above_the_range(tmp_path: Path) -> None:
    # R just above the reach (wide), equal, just below (narrow); a reach equal to R does
    # not saturate (core.saturation.saturated: reach > R)
    path = catalog(tmp_path, {"wide": REACH * (1 + 1e-9), "equal": REACH,
                              "narrow": REACH * (1 - 1e-9), "none": None})
    rows = analyze_rows(path)
    assert {k: r["saturated"] for k, r in rows.items()} == {
        "wide": False, "equal": False, "narrow": True, "none": False}
    assert rows["narrow"]["warnings"] and not rows["wide"]["warnings"]
    code, doc = select_doc(path)
    verdict = {s["sensor"]: s["pass"] for s in doc["sensors"]}
    assert verdict == {"wide": True, "equal": True, "narrow": False, "none": True}
    cell = doc["sensors"][2]["profiles"][0]
    assert cell["saturated"] is True and cell["pass"] is False
    assert cell["reason"].startswith("saturated:") and "\n" not in cell["reason"]
    assert code == 0  # --require any: others pass


def test_peak_factor_moves_the_edge(tmp_path: Path) -> None:
    # R = 20: κ = 3 gives 21 > 20 (saturated), κ = 2 gives 19 < 20 (not)
    path = catalog(tmp_path, {"r20": 20.0})
    assert analyze_rows(path)["r20"]["saturated"] is True
    assert analyze_rows(path, "--peak-factor", "2")["r20"]["saturated"] is False
    assert select_doc(path)[1]["sensors"][0]["pass"] is False
    assert select_doc(path, "--peak-factor", "2")[1]["sensors"][0]["pass"] is True
    # κ = 0: |Ω| + a = 15 < 20
    assert analyze_rows(path, "--peak-factor", "0")["r20"]["saturated"] is False


def test_negative_peak_factor_is_refused(tmp_path: Path) -> None:
    result = run("analyze", catalog(tmp_path, {"r20": 20.0}), "--peak-factor", "-1")
    assert result.exit_code == 2


@pytest.mark.parametrize("criterion", ["bounds", "rms", "worst", "both"])
def test_saturating_part_never_ranks_as_passing(tmp_path: Path, criterion: str) -> None:
    # 'tiny' has the smallest error of all (no coefficient) but saturates (R = 12 < 21)
    path = catalog(tmp_path, {"ok": 100.0}, extra=(
        "  - id: tiny\n    range: 12\n    coefficients: {k1: 1.0}\n"))
    result = gyrovib.select(path, budget=0.01, criterion=criterion)
    tiny = result.sensors.index("tiny")
    assert not result.sensor_pass[tiny]
    assert result.saturated[tiny, 0]
    passing = [result.sensors[i] for i in result.ranking if result.sensor_pass[i]]
    assert passing == ["ok"]
    assert result.limits[tiny].name == "saturated"
    table = run("select", path, "--budget", BUDGET, "--criterion", criterion).stdout
    ranked = table.split("Passing sensors", 1)[1].split("Failing sensors", 1)[0]
    assert "tiny" not in ranked and "ok" in ranked
    assert "SAT" in table


def test_require_all_counts_a_saturating_part_as_failing(tmp_path: Path) -> None:
    # R = 18: κ = 3 gives reach 21 > 18 (fails), κ = 0 gives 10 + 5 = 15 < 18 (passes)
    path = catalog(tmp_path, {"ok": 100.0, "small": 18.0})
    assert run("select", path, "--budget", BUDGET, "--require", "all").exit_code == 1
    assert run("select", path, "--budget", BUDGET, "--require", "all",
               "--peak-factor", "0").exit_code == 0


def test_input_response_keeps_a_part_out_of_saturation(tmp_path: Path) -> None:
    # a 100 Hz tone of 50 deg/s at Ω = 0 against R = 30: as an output filter (bare
    # table or at: output) the response does not act on the element, reach 50 > 30;
    # at the input its gain 0.1 leaves a3 = 5 deg/s, reach 5 < 30 (docs/model.md section 9).
    profile = """
    profiles:
      - id: big
        rate: [0, 0, 0]
        harmonic:
          - frequency: 100
            amplitude: [0, 0, 50.0]
    """
    table = "[[1, 0.1], [1000, 0.1]]"
    extra = (f"  - id: output\n    range: 30\n    coefficients: {{k2: 1.0e-6}}\n"
             f"    response: {table}\n"
             f"  - id: output-marked\n    range: 30\n    coefficients: {{k2: 1.0e-6}}\n"
             f"    response: {{at: output, table: {table}}}\n"
             f"  - id: input\n    range: 30\n    coefficients: {{k2: 1.0e-6}}\n"
             f"    response: {{at: input, table: {table}}}\n")
    path = catalog(tmp_path, {}, profile=profile, extra=extra)
    rows = analyze_rows(path)
    assert {k: r["saturated"] for k, r in rows.items()} == {
        "output": True, "output-marked": True, "input": False}
    # the input-side response also scales the error: k2·a²/2 = 1e-6·25/2 vs 1e-6·2500/2
    assert rows["input"]["additive_terms"]["k2"] == pytest.approx(1.25e-5, rel=1e-12)
    assert rows["output"]["additive_terms"]["k2"] == pytest.approx(1.25e-3, rel=1e-12)
    _, doc = select_doc(path)
    assert {s["sensor"]: s["pass"] for s in doc["sensors"]} == {
        "output": False, "output-marked": False, "input": True}


def test_sweep_flags_the_rates_that_saturate(tmp_path: Path) -> None:
    # R = 20 against |Ω_K3| + 5 + 3·2 = |Ω_K3| + 11: saturated where |Ω_K3| > 9
    # (equal does not saturate); with κ = 1, |Ω_K3| + 7 > 20 only past 13
    profile = PROFILE.replace("rate: [0, 0, 10]", "rate: [0, 0, 0]")
    path = catalog(tmp_path, {"r20": 20.0}, profile=profile)
    result = run("sweep", path, "--rate-range=-10:10:5", "--format", "json")
    assert result.exit_code == 0, result.stderr
    (series,) = json.loads(result.stdout)["series"]
    assert series["saturated"] == [True, False, False, False, True]  # -10, -5, 0, 5, 10
    edge = json.loads(run("sweep", path, "--rate-range=9:9:1", "--format", "json").stdout)
    assert edge["series"][0]["saturated"] == [False]
    loose = json.loads(run("sweep", path, "--rate-range=-10:10:5", "--peak-factor", "1",
                           "--format", "json").stdout)
    assert loose["series"][0]["saturated"] == [False] * 5
    assert "SAT" in run("sweep", path, "--rate-range=-10:10:5").stdout


@settings(deadline=None, max_examples=30, derandomize=True)
@given(rate=st.floats(0, 50), amplitude=st.floats(0, 50), sigma=st.floats(0, 10),
       margin=st.floats(-0.5, 0.5).filter(lambda m: abs(m) > 1e-6),
       unit=st.sampled_from(["deg/h", "rad/s", "rpm"]))
def test_saturation_does_not_depend_on_the_file_unit(rate: float, amplitude: float,
                                                     sigma: float, margin: float,
                                                     unit: str) -> None:
    # the same catalogue written in deg/s and in another rate unit: the same verdict,
    # reach = |Ω| + a + 3σ against R = reach·(1 + margin) (saturated iff margin < 0)
    from gyrovib import units
    from gyrovib.api import analyze
    from gyrovib.catalog.loader import merge, parse_catalog

    reach = rate + amplitude + 3.0 * sigma
    r = max(reach * (1.0 + margin), 1e-3)

    def text(u: str) -> str:
        k = 1.0 / units.scale(u)  # deg/s → u
        return (f"gyrovib: 1\nunits: {{rate: {u}}}\n"
                f"profiles:\n  - id: p\n    rate: [0, 0, {rate * k!r}]\n"
                f"    harmonic:\n      - {{frequency: 50, amplitude: [0, 0, {amplitude * k!r}]}}\n"
                f"    random:\n      rms: [0, 0, {sigma * k!r}]\n"
                f"sensors:\n  - id: s\n    range: {r * k!r}\n    coefficients: {{k2: 1.0e-6}}\n")

    verdicts = [bool(analyze(merge([parse_catalog(text(u))])).saturated[0, 0])
                for u in ("deg/s", unit)]
    assert verdicts[0] == verdicts[1] == (reach > r * (1 + 1e-9) and margin < 0)


@pytest.mark.parametrize("criterion", ["bounds", "rms", "worst", "both"])
def test_saturating_datasheet_part_never_ranks_as_passing(tmp_path: Path,
                                                          criterion: str) -> None:
    # a spec-form (datasheet) part saturates against its specs.range (docs/model.md sections 9,
    # 11): R = 12 deg/s < reach 21 deg/s. Its nonlinearity, 1e-9 %FS of 12 deg/s, makes
    # its worst case ~1e-9 deg/s, far inside Δ* = 0.01, so only saturation can fail it.
    path = catalog(tmp_path, {"ok": 100.0}, extra=(
        "  - id: sheet\n    specs:\n      range: 12\n"
        "      nonlinearity: {value: 1.0e-9, unit: '%FS', fit: least-squares, measure: max}\n"))
    result = gyrovib.select(path, budget=0.01, criterion=criterion)
    sheet = result.sensors.index("sheet")
    assert result.source(sheet) == "specs"
    assert result.saturated[sheet, 0] and not result.sensor_pass[sheet]
    assert result.limits[sheet].name == "saturated"
    assert result.limits[sheet].ratio == pytest.approx(REACH / 12.0, rel=1e-12)
    passing = [result.sensors[i] for i in result.ranking if result.sensor_pass[i]]
    assert passing == ["ok"]
    # the reason is worded by gyrovib.reasons, in the output unit (here the budget's,
    # deg/h: 21 deg/s = 75600 deg/h, 12 deg/s = 43200 deg/h)
    code, doc = select_doc(path, "--criterion", criterion, "--budget", "36deg/h")
    cell = next(s for s in doc["sensors"] if s["sensor"] == "sheet")["profiles"][0]
    assert code == 0 and doc["unit"] == "deg/h"
    assert cell["saturated"] is True and cell["pass"] is False
    assert cell["reason"].startswith("saturated: ")
    assert "75600 deg/h exceeds the range 43200 deg/h" in cell["reason"]
    table = run("select", path, "--budget", BUDGET, "--criterion", criterion).stdout
    ranked = table.split("Passing sensors", 1)[1].split("Failing sensors", 1)[0]
    assert "sheet" not in ranked and "ok" in ranked
    assert "SAT" in table
    # analyze flags it too
    assert analyze_rows(path)["sheet"]["saturated"] is True
