"""`gyrovib runup`: JSON keys of docs/output.md, CSV and table, the sensor entry
`-o` writes (read back by `analyze`), `--require`, `--plot`, and the refusals."""

from __future__ import annotations

import csv
import io
import json
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import yaml

from tests.conftest import invoke
from tests.runup_sim import simulate

READ = ("--fs", "200", "--rate-columns", "0,1,2", "--accel-columns", "3,4,5")


@pytest.fixture(scope="module")
def record(tmp_path_factory: pytest.TempPathFactory) -> Path:
    # a simulated run-up (synthetic numbers): vre 0.01 deg/s/g², k2 0.01 (deg/s)^-1,
    # 20 s steps at 200 Hz, up and down with angular and linear vibration stepped apart
    data, _ = simulate(np.random.default_rng(42), {"k2": 0.01, "vre": 0.01}, gap=2.0)
    path = tmp_path_factory.mktemp("runup") / "runup.npy"
    np.save(path, data)
    return path


def test_json_has_the_interface_keys(record: Path) -> None:
    out = invoke("runup", record, *READ, "--estimate", "k2,vre", "--format", "json")
    assert out.exit_code == 0, out.stderr
    doc = json.loads(out.stdout)
    assert {"steps", "estimates", "drift", "chi2"} <= set(doc)
    assert len(doc["steps"]) == 10
    for step in doc["steps"]:
        assert {"start", "end", "shift", "uncertainty", "regressors", "predicted",
                "residual"} <= set(step)
        assert set(step["regressors"]) == {"k2", "vre"}
        assert step["predicted"] is None                 # no sensor: no prediction, not 0
    for name in ("k2", "vre"):
        e = doc["estimates"][name]
        assert {"value", "uncertainty", "unit", "identifiable"} <= set(e)
        assert e["identifiable"] is True
    assert doc["estimates"]["vre"]["unit"] == "deg/s/g^2"
    assert doc["estimates"]["k2"]["unit"] == "(deg/s)^-1"
    # the simulated coefficients, within 2 standard uncertainties (synthetic truth)
    assert abs(doc["estimates"]["vre"]["value"] - 0.01) <= 2 * doc["estimates"]["vre"][
        "uncertainty"]
    assert abs(doc["estimates"]["k2"]["value"] - 0.01) <= 2 * doc["estimates"]["k2"][
        "uncertainty"]
    assert doc["drift"]["estimated"] is True             # up and down: separable
    assert abs(doc["drift"]["value"] - 1e-4) <= 3 * doc["drift"]["uncertainty"]


def test_csv_rows_per_step_and_estimate(record: Path) -> None:
    out = invoke("runup", record, *READ, "--estimate", "k2,vre", "--format", "csv")
    assert out.exit_code == 0, out.stderr
    steps_text, estimates_text = out.stdout.split("\n\n")
    steps = list(csv.DictReader(io.StringIO(steps_text)))
    estimates = list(csv.DictReader(io.StringIO(estimates_text)))
    assert len(steps) == 10 and [e["name"] for e in estimates] == ["k2", "vre"]
    assert all(s["predicted"] == "" for s in steps)      # unknown: empty, not 0
    assert float(estimates[1]["value"]) > 0


def test_table_shows_steps_estimates_and_the_limits(record: Path) -> None:
    out = invoke("runup", record, *READ, "--estimate", "k2,vre")
    assert out.exit_code == 0, out.stderr
    for word in ("shift ± u", "in-situ ± u", "found", "limit: the log sees vibration only "
                 "below fs/2 = 100 Hz"):
        assert word in out.stdout
    assert "predicted" not in out.stdout                # no sensor: no prediction column
    md = invoke("runup", record, *READ, "--estimate", "k2,vre", "--format", "markdown")
    assert md.exit_code == 0, md.stderr
    assert "| step | time, s |" in md.stdout and "| vre |" in md.stdout


def test_against_a_datasheet_vre_the_shifts_fall_outside(record: Path, tmp_path: Path
                                                         ) -> None:
    # ADIS16460's datasheet VRE bound is 0.0004 deg/s/g² (DATASHEETS.md); the record
    # rectifies 0.01: the steps with linear vibration lie outside its worst case
    png = tmp_path / "runup.png"
    out = invoke("runup", record, *READ, "--estimate", "k2,vre", "--sensor", "adis16460",
                 "--require", "--format", "json", "--plot", png)
    assert out.exit_code == 1, out.stderr
    doc = json.loads(out.stdout)
    assert doc["requirement_met"] is False
    assert any(s["status"] == "outside" for s in doc["steps"])
    assert all(s["predicted"] is not None and s["predicted_bound"] for s in doc["steps"])
    assert doc["estimates"]["vre"]["catalogue"] == pytest.approx(0.0004)
    assert doc["estimates"]["vre"]["catalogue_bound"] is True
    assert "in-situ vre" in out.stderr                  # the comparison, named
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_within_its_own_in_situ_entry_the_requirement_is_met(record: Path,
                                                              tmp_path: Path) -> None:
    # -o writes the in-situ sensor; the run-up against it passes (each prediction is
    # its own fit, to within the measurement's 2u), and analyze reads it like any sensor
    entry = tmp_path / "insitu.yaml"
    out = invoke("runup", record, *READ, "--estimate", "k2,vre", "-o", entry)
    assert out.exit_code == 0, out.stderr
    doc = yaml.safe_load(entry.read_text(encoding="utf-8"))
    sensor = doc["sensors"][0]
    assert set(sensor["coefficients"]) == {"k2"}
    assert set(sensor["uncertainty"]["sigma"]) == {"k2"}
    assert 0.005 < sensor["vre"] < 0.02
    check = invoke("runup", record, *READ, entry, "--estimate", "k2,vre", "--sensor",
                   sensor["id"], "--require", "--format", "json")
    assert check.exit_code == 0, check.stdout
    analyzed = invoke("analyze", entry, "--bundled", "profiles", "--profile",
                      "adis16460-vre-test", "--format", "json")
    assert analyzed.exit_code == 0, analyzed.stderr


def test_the_entry_on_standard_output_replaces_the_report(record: Path) -> None:
    out = invoke("runup", record, *READ, "--estimate", "vre", "-o", "-")
    assert out.exit_code == 0, out.stderr
    assert out.stdout.startswith("# Written by gyrovib")
    assert yaml.safe_load(out.stdout)["sensors"][0]["id"] == "runup-insitu"


@pytest.mark.parametrize(("args", "message"), [
    (("--steps", "0:10,20"), "start:end pairs"),
    (("--require",), "--sensor"),
    (("--estimate", "k9"), "cannot estimate 'k9'"),
    (("--estimate", "vre,G11"), "not both"),
    (("--steps", "0:10,12:20", "--estimate", "k2,vre"), "at least 3 steps"),
    (("--steps", "0:5000"), "does not lie within"),
])
def test_refusals_say_what_is_wrong(record: Path, args: tuple[str, ...],
                                    message: str) -> None:
    out = invoke("runup", record, *READ, *args)
    assert out.exit_code == 2
    assert message in out.stderr


def test_a_g2_term_needs_the_accelerations(record: Path) -> None:
    out = invoke("runup", record, "--fs", "200", "--rate-columns", "0,1,2", "--estimate",
                 "vre")
    assert out.exit_code == 2
    assert "accelerations" in out.stderr


def test_without_the_z_rate_there_is_no_test(record: Path) -> None:
    out = invoke("runup", record, "--fs", "200", "--rate-columns", "0,1,-",
                 "--accel-columns", "3,4,5")
    assert out.exit_code == 2
    assert "rate about x3 (Z)" in out.stderr


def test_without_x_and_y_the_z_terms_are_still_measured(record: Path) -> None:
    # an axis not recorded is unknown: m31 cannot be asked for, k2 and vre can, and the
    # "moved" test (which reads x1 and x2) says nothing rather than guessing
    out = invoke("runup", record, "--fs", "200", "--rate-columns", "-,-,2",
                 "--accel-columns", "3,4,5", "--estimate", "k2,vre", "--format", "json")
    assert out.exit_code == 0, out.stderr
    doc = json.loads(out.stdout)
    assert not any(s["moved"] for s in doc["steps"])
    assert doc["estimates"]["vre"]["status"] == "found"
    refused = invoke("runup", record, "--fs", "200", "--rate-columns", "-,-,2",
                     "--estimate", "m31")
    assert refused.exit_code == 2 and "rate about X" in refused.stderr


def test_a_datasheet_without_a_vre_leaves_the_verdict_unverified(record: Path) -> None:
    # SCH16T's datasheet publishes no VRE (DATASHEETS.md): on a recording with linear
    # vibration its prediction is unknown — null, not 0 — and every vibrating step
    # unverified; --require fails only on a step found outside, so it passes here
    out = invoke("runup", record, *READ, "--estimate", "vre", "--sensor", "sch16t",
                 "--require", "--format", "json")
    assert out.exit_code == 0, out.stderr
    doc = json.loads(out.stdout)
    assert all(s["predicted"] is None for s in doc["steps"])
    assert {s["status"] for s in doc["steps"]} == {"unverified"}
    assert doc["estimates"]["vre"]["catalogue"] is None
    table = invoke("runup", record, *READ, "--estimate", "vre", "--sensor", "sch16t")
    assert "verdict: unverified" in table.stdout and "│ unverified │" in table.stdout


def _steps(record: Path, catalogue: Path, sensor: str) -> list[dict[str, Any]]:
    """The JSON steps of the run-up estimating k2 and the VRE against ``sensor``."""
    out = invoke("runup", record, *READ, catalogue, "--estimate", "k2,vre", "--sensor", sensor,
                 "--format", "json")
    assert out.exit_code == 0, out.stderr
    steps: list[dict[str, Any]] = json.loads(out.stdout)["steps"]
    return steps


def test_a_sensor_without_a_g2_figure_predicts_unknown_under_linear_vibration(
        record: Path, tmp_path: Path) -> None:
    # 'bare' gives k2 but no g² figure (neither g2_sensitivity nor vre): on a recording with
    # linear vibration its prediction's g² part is unknown, so each prediction is null and
    # every vibrating step unverified, as for a datasheet without a VRE; 'stated' is the
    # same sensor with `vre: 0`, a known zero, and predicts numbers (not all 0: k2 acts)
    catalogue = tmp_path / "bare.yaml"
    catalogue.write_text(
        "gyrovib: 1\nunits: {rate: deg/s}\nsensors:\n"
        "  - id: bare\n    coefficients: {k2: 0.002}\n"
        "  - id: stated\n    coefficients: {k2: 0.002}\n    vre: 0\n", encoding="utf-8")
    bare, stated = (_steps(record, catalogue, sensor) for sensor in ("bare", "stated"))
    assert all(s["predicted"] is None for s in bare)
    assert "unverified" in {s["status"] for s in bare}
    assert all(s["predicted"] is not None for s in stated)
    assert max(abs(s["predicted"]) for s in stated) > 0


def test_an_input_response_of_unit_gain_predicts_as_none(record: Path,
                                                         tmp_path: Path) -> None:
    # the same coefficients with a response acting at the input whose gain is 1 at every
    # frequency: the vibration the element sees is the recorded one, so each step's
    # prediction is the same to rounding (the FFT's round trip)
    catalogue = tmp_path / "pair.yaml"
    catalogue.write_text(
        "gyrovib: 1\nunits: {rate: deg/s}\nsensors:\n"
        "  - id: plain\n    coefficients: {k2: 0.002}\n    vre: 0.01\n"
        "  - id: filtered\n    coefficients: {k2: 0.002}\n    vre: 0.01\n"
        "    response: {at: input, table: [[1, 1.0], [1000, 1.0]]}\n", encoding="utf-8")
    shifts = {sensor: [s["predicted"] for s in _steps(record, catalogue, sensor)]
              for sensor in ("plain", "filtered")}
    assert np.allclose(shifts["plain"], shifts["filtered"], rtol=1e-9, atol=1e-12)
    assert max(shifts["plain"]) > 0.01                  # a real prediction, not zeros


def test_a_csv_with_a_time_column_reads_as_the_npy_does(tmp_path: Path) -> None:
    # every reader feeds the test: the same synthetic run-up as CSV with t in s, the
    # sample rate from the timestamps, the columns by name
    data, steps = simulate(np.random.default_rng(9), {"vre": 0.01}, seconds=8.0, gap=1.0)
    t = np.arange(data.shape[0]) / 200.0
    path = tmp_path / "runup.csv"
    np.savetxt(path, np.column_stack([t, data]), delimiter=",", comments="", fmt="%.9g",
               header="t,gx,gy,gz,ax,ay,az")
    out = invoke("runup", path, "--accel-columns", "ax,ay,az", "--format", "json")
    assert out.exit_code == 0, out.stderr
    doc = json.loads(out.stdout)
    assert doc["recording"]["fs"] == pytest.approx(200.0)
    assert len(doc["steps"]) == len(steps)
    assert list(doc["estimates"]) == ["vre"]                 # the default with accelerations
    vre = doc["estimates"]["vre"]
    assert abs(vre["value"] - 0.01) <= 2 * vre["uncertainty"]  # the simulated value


def test_the_entry_keeps_the_catalogue_sensors_other_terms(record: Path,
                                                           tmp_path: Path) -> None:
    # a coefficient-form sensor: what the test did not estimate is the catalogue's (as
    # written there), what it estimated is the test's
    catalogue = tmp_path / "unit.yaml"
    catalogue.write_text("gyrovib: 1\nunits: {rate: deg/s}\nsensors:\n  - id: unit-7\n"
                         "    coefficients: {A1: 0.001, k4: 1.0e-6}\n    vre: 0.5\n",
                         encoding="utf-8")
    out = invoke("runup", record, *READ, catalogue, "--sensor", "unit-7", "--estimate",
                 "vre", "-o", "-")
    assert out.exit_code == 0, out.stderr
    sensor = yaml.safe_load(out.stdout)["sensors"][0]
    assert sensor["id"] == "unit-7-insitu"
    assert sensor["coefficients"] == {"A1": 0.001, "k4": 1.0e-6}
    assert abs(sensor["vre"] - 0.01) < 0.005                 # measured, not the 0.5 written
    assert "g2_sensitivity" not in sensor


def test_an_ardupilot_dataflash_log_feeds_the_test_and_is_named(tmp_path: Path) -> None:
    # the synthetic run-up written as DataFlash IMU messages (tests/logwriters.py: rad/s
    # and m/s² as float32, its header says synthetic): read by its own reader, the
    # output names the message and instance read, and vre comes back (simulated 0.01)
    pytest.importorskip("pymavlink")
    from tests.logwriters import D2R, G0, dataflash_imu

    data, steps = simulate(np.random.default_rng(12), {"vre": 0.01}, seconds=8.0, gap=1.0)
    t_us = np.round(np.arange(data.shape[0]) / 200.0 * 1e6)
    path = dataflash_imu(tmp_path / "runup.bin", t_us, [data[:, :3] * D2R],
                         [data[:, 3:] * G0])
    out = invoke("runup", path, "--format", "json")
    assert out.exit_code == 0, out.stderr
    doc = json.loads(out.stdout)
    assert (doc["recording"]["topic"], doc["recording"]["instance"]) == ("IMU", 0)
    assert len(doc["steps"]) == len(steps)
    vre = doc["estimates"]["vre"]
    assert abs(vre["value"] - 0.01) <= 2 * vre["uncertainty"]
    table = invoke("runup", path)
    assert "runup.bin (IMU instance 0)" in table.stdout


def test_the_ulog_topic_read_is_named() -> None:
    out = invoke("runup", Path(__file__).parent / "data" / "px4-sample.ulg", "--steps",
                 "1.2:3,3.2:5,5.2:7,7.2:9", "--format", "json")
    assert out.exit_code == 0, out.stderr
    doc = json.loads(out.stdout)
    assert doc["recording"]["topic"] == "sensor_combined"
