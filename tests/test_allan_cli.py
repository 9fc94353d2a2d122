"""`gyrovib allan`: JSON keys of docs/output.md, the noise block it
writes, Kalibr's imu.yaml, the reader options it shares with `profile`, and its
refusals."""

import json
import math
from pathlib import Path

import numpy as np
import pytest
import yaml

from gyrovib.core.allan import oadev
from gyrovib.models import Sensor
from tests.conftest import invoke

FS = 50.0
# white rate noise of N = 0.3 deg/√h (0.005 deg/√s): σ_y = N·√fs per sample
N_DEG_SQRT_S = 0.3 / 60.0
TERMS = ("quantization", "arw", "bias_instability", "rrw", "rate_ramp")


def _record(tmp_path: Path, gap: bool = False) -> tuple[Path, np.ndarray]:
    g = np.random.default_rng(7)
    rate = g.standard_normal((20_000, 2)) * N_DEG_SQRT_S * math.sqrt(FS)
    t = np.arange(rate.shape[0]) / FS
    if gap:
        t[15_000:] += 5.0                                       # a 5 s gap
    path = tmp_path / "static.csv"
    np.savetxt(path, np.column_stack([t, rate]), delimiter=",", header="t,gx,gz",
               comments="", fmt="%.10g")
    return path, rate


def test_json_per_axis_with_the_interface_keys(tmp_path: Path) -> None:
    path, rate = _record(tmp_path)
    out = invoke("allan", path, "--rate-columns", "gx,-,gz", "--unit", "deg/s",
                 "--format", "json")
    assert out.exit_code == 0, out.stderr
    doc = json.loads(out.stdout)
    assert doc["confidence"] == 0.68
    assert [a["axis"] for a in doc["axes"]] == ["X", "Z"]          # Y not recorded
    z = doc["axes"][1]
    assert {"axis", "tau", "adev", "ci", "gauss_markov", *TERMS} <= set(z)
    for key in TERMS:
        assert set(z[key]) in ({"value", "unit", "interval"}, {"bound", "unit", "confidence"})
    # the curve is the kernel's on the column read from the CSV (written to 10 digits)
    expected = oadev(np.round(rate[:, 1], 12), 1 / FS)[1]
    assert np.allclose(z["adev"], expected, rtol=1e-6)
    # every σ lies inside its own interval, which narrows as the EDF grows
    ci = np.array(z["ci"])
    assert np.all((ci[:, 0] < z["adev"]) & (z["adev"] < ci[:, 1]))
    width = (ci[:, 1] - ci[:, 0]) / np.array(z["adev"])
    assert width[0] < 0.05 < width[-1]
    # the simulated N within its 68 % interval's width of the truth (the interval's
    # own coverage is the benchmark's business), and pure white noise: K, R, B bounds
    lo, hi = z["arw"]["interval"]
    assert lo <= z["arw"]["value"] <= hi and abs(z["arw"]["value"] - 0.3) <= 3 * (hi - lo)
    assert z["arw"]["unit"] == "deg/sqrt(h)"
    for key in ("rrw", "rate_ramp"):
        assert z[key]["confidence"] == 0.95 and z[key]["bound"] > 0   # never a value of 0


def test_output_is_one_noise_block_with_bounds_a_sensor_accepts(tmp_path: Path) -> None:
    path, _ = _record(tmp_path)
    block = tmp_path / "noise.yaml"
    out = invoke("allan", path, "--rate-columns", "gx,-,gz", "-o", block)
    assert out.exit_code == 0, out.stderr
    text = block.read_text(encoding="utf-8")
    doc = yaml.safe_load(text)
    assert set(doc["noise"]) == {"x", "z"}                       # a sub-block per axis
    sensor = Sensor(id="s", coefficients={}, noise=doc["noise"])
    assert sensor.noise is not None and sensor.noise.z is not None
    assert sensor.noise.z.arw is not None and not sensor.noise.z.arw.is_bound
    assert sensor.noise.z.rrw is not None and sensor.noise.z.rrw.is_bound   # white noise
    assert "rrw: \"≤ " in text
    assert "only the longest" not in text


def test_a_record_with_gaps_says_in_the_block_that_one_segment_was_used(tmp_path: Path
                                                                         ) -> None:
    path, _ = _record(tmp_path, gap=True)
    out = invoke("allan", path, "--rate-columns", "gx,-,-", "-o", "-")
    assert out.exit_code == 0, out.stderr
    assert "# only the longest of 2 contiguous segments was used" in out.stdout
    assert "15000 samples" in out.stdout
    assert yaml.safe_load(out.stdout)["noise"]["arw"]


def test_plot_writes_a_png_with_no_library_warnings(tmp_path: Path) -> None:
    path, _ = _record(tmp_path)
    png = tmp_path / "a.png"
    out = invoke("allan", path, "--rate-columns", "gx,-,gz", "--plot", png, "--format", "json")
    assert out.exit_code == 0, out.stderr
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "Warning" not in out.stderr and ".py:" not in out.stderr


@pytest.mark.parametrize("values", ["constant", "quantised"])
def test_a_record_without_visible_noise_is_refused_never_zero(tmp_path: Path,
                                                              values: str) -> None:
    n = 2000
    if values == "constant":
        rate = np.full(n, 0.25)
    else:                                    # one LSB flip now and then: 5 changes in 2000
        rate = np.zeros(n)
        rate[[100, 101, 900, 1500, 1501]] = 0.01
    path = tmp_path / "flat.csv"
    np.savetxt(path, np.column_stack([np.arange(n) / 10.0, rate]), delimiter=",",
               header="t,gz", comments="", fmt="%.10g")
    for extra in ((), ("-o", "-"), ("--plot", str(tmp_path / "p.png"))):
        out = invoke("allan", path, "--rate-columns", "-,-,gz", *extra)
        assert out.exit_code == 2 and out.stdout == ""
        assert out.stderr.startswith(f"{path}: ") and "Traceback" not in out.stderr
        assert ("constant" if values == "constant" else "changes level only") in out.stderr
        assert "Warning" not in out.stderr


def test_kalibr_yaml_round_trips_with_the_hand_conversion(tmp_path: Path) -> None:
    path, _ = _record(tmp_path)
    doc = json.loads(invoke("allan", path, "--rate-columns", "gx,-,gz", "--format", "json").stdout)
    out = invoke("allan", path, "--rate-columns", "gx,-,gz", "--format", "kalibr")
    assert out.exit_code == 0, out.stderr
    imu = yaml.safe_load(out.stdout)
    # by hand: N [deg/√h] / 60 = deg/√s = deg/s/√Hz, × π/180 → rad/s/√Hz; K [deg/h/√h]
    # / 216 000 = deg/s/√s = deg/s²/√Hz, × π/180 → rad/s²/√Hz; the largest axis
    n_hand = max(a["arw"]["value"] for a in doc["axes"]) / 60.0 * math.pi / 180.0
    k_hand = max(a["rrw"].get("value", a["rrw"].get("bound")) for a in doc["axes"]) \
        / 216_000.0 * math.pi / 180.0
    assert imu["gyroscope_noise_density"] == pytest.approx(n_hand, rel=1e-5)
    assert imu["gyroscope_random_walk"] == pytest.approx(k_hand, rel=1e-5)
    assert imu["update_rate"] == FS
    assert "upper bound" in out.stdout                          # K of white noise: a bound
    assert "σ_d = density·√update_rate" in out.stdout           # the conversion, stated


def test_a_short_record_is_refused_with_the_file_named(tmp_path: Path) -> None:
    path = tmp_path / "short.csv"
    path.write_text("t,g\n" + "".join(f"{i / 10},{i % 3}\n" for i in range(10)),
                    encoding="utf-8")
    out = invoke("allan", path, "--rate-columns", "-,-,g")
    assert out.exit_code == 2
    assert "short.csv" in out.stderr and "needs 30" in out.stderr


def test_confidence_option(tmp_path: Path) -> None:
    path, _ = _record(tmp_path)
    docs = {c: json.loads(invoke("allan", path, "--rate-columns", "gx,-,gz", "--confidence",
                                 c, "--format", "json").stdout) for c in ("68%", "0.95")}
    assert docs["0.95"]["confidence"] == 0.95
    narrow, wide = (np.array(docs[c]["axes"][0]["ci"]) for c in ("68%", "0.95"))
    assert np.all(wide[:, 0] < narrow[:, 0]) and np.all(wide[:, 1] > narrow[:, 1])
    bad = invoke("allan", path, "--rate-columns", "gx,-,gz", "--confidence", "150%")
    assert bad.exit_code == 2 and "--confidence" in bad.stderr


def test_the_accelerometer_where_recorded_in_json_table_and_kalibr(tmp_path: Path) -> None:
    # white specific-force noise of VRW 0.05 m/s/√h = 0.05/60 m/s²·√s, logged in g
    g = np.random.default_rng(11)
    n, fs, vrw = 30_000, 100.0, 0.05 / 60.0
    gyro = g.standard_normal(n) * N_DEG_SQRT_S * math.sqrt(fs)
    accel = 1.0 + g.standard_normal(n) * vrw * math.sqrt(fs) / 9.80665
    path = tmp_path / "imu.csv"
    np.savetxt(path, np.column_stack([np.arange(n) / fs, gyro, accel]), delimiter=",",
               header="t,gz,az", comments="", fmt="%.12g")
    cols = ("--rate-columns", "-,-,gz", "--accel-columns", "-,-,az")
    doc = json.loads(invoke("allan", path, *cols, "--format", "json").stdout)
    (az,) = doc["accelerometer"]
    assert az["axis"] == "Z" and az["arw"]["unit"] == "m/s/sqrt(h)"
    lo, hi = az["arw"]["interval"]
    assert abs(az["arw"]["value"] - 0.05) <= 3 * (hi - lo)
    assert "velocity random walk" in invoke("allan", path, *cols).stdout
    imu = yaml.safe_load(invoke("allan", path, *cols, "--format", "kalibr").stdout)
    # by hand: VRW [m/s/√h] / 60 = m/s/√s = m/s²/√Hz
    assert imu["accelerometer_noise_density"] == pytest.approx(az["arw"]["value"] / 60.0,
                                                               rel=1e-5)
    assert imu["accelerometer_random_walk"] > 0            # a bound here, said in a comment


def test_the_accelerometer_on_the_streamed_path_equals_the_held_one(tmp_path: Path) -> None:
    # A record read a block at a time (forced by a small stream_samples) gives the
    # accelerometer's figures too, and on the same τ grid the same ones as the record
    # held in memory: the streamed curve equals the held one to rounding (tests/
    # test_allan.py checks it against allantools), and the fit and bootstrap are the same.
    from gyrovib.api.noise import allan
    from gyrovib.api.recordings import read_recording

    g = np.random.default_rng(12)
    n, fs, vrw = 6_000, 100.0, 0.05 / 60.0
    gyro = g.standard_normal(n) * N_DEG_SQRT_S * math.sqrt(fs)
    accel = 1.0 + g.standard_normal((n, 2)) * vrw * math.sqrt(fs) / 9.80665
    accel[:, 1] = 1.0                                  # a constant axis: no noise seen
    path = tmp_path / "imu.csv"
    np.savetxt(path, np.column_stack([np.arange(n) / fs, gyro, accel]), delimiter=",",
               header="t,gz,ax,ay", comments="", fmt="%.12g")
    rec = read_recording(str(path), rate_columns=[None, None, "gz"],
                         accel_columns=["ax", "ay", None])
    held = allan(rec, per_decade=5)
    streamed = allan(rec, per_decade=5, stream_samples=1_000)
    assert [a.axis for a in held.accel] == [a.axis for a in streamed.accel] == ["X"]
    # every warning names its file, as a reader's do
    assert "imu.csv: accelerometer axis Y: no noise seen" in "\n".join(streamed.warnings)
    assert "imu.csv: accelerometer axis Y: no noise seen" in "\n".join(held.warnings)
    h, s = held.accel[0], streamed.accel[0]
    assert s.unit == "m/s^2" and np.allclose(s.adev, h.adev, rtol=1e-9)
    assert s.arw.value == pytest.approx(h.arw.value, rel=1e-6)
    # VRW read back in its reported unit, m/s/√h, within three widths of the truth
    lo, hi = s.arw.interval
    assert abs(s.arw.value - 0.05) <= 3 * (hi - lo)
    assert s.figures["bias_instability"].unit == "m/s^2"
