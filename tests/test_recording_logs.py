"""Flight logs as recordings (docs/recordings.md): ArduPilot DataFlash
(IMU and the batch sampler), PX4 ULog high-rate FIFO with several instances, and the
CSV of Betaflight's blackbox_decode.

The longer logs are written by tests/logwriters.py with a known vibration (a tone and
white noise over slow manoeuvres; the files say they are synthetic). Each gives
Δ_V,rec equal to a float64 evaluation of docs/model.md section 13 from the values as
stored (tests/recording_oracle.py) to 1e-9, and a fitted profile whose tone is the
known one within 2 dB and whose random part lies within 2 dB of the known flat
spectrum, power-weighted. pymavlink's own test log (tests/data/test.BIN) checks the
parser on a real ArduPilot log.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from tests.conftest import invoke
from tests.logwriters import (
    ACCEL_SCALE,
    D2R,
    G0,
    GYRO_SCALE,
    SYNTHETIC,
    UlogWriter,
    batch_example,
    betaflight_csv,
    dataflash_imu,
    fifo_example,
    motion,
)
from tests.recording_oracle import recorded_error
from tests.test_recording import SENSOR

pytest.importorskip("scipy.signal")
DATA = Path(__file__).parent / "data"
TEST_BIN = DATA / "test.BIN"


def _sensor(tmp_path: Path) -> Path:
    path = tmp_path / "s.gyrovib.yaml"
    path.write_text(SENSOR)
    return path


def _check_fit(fit: object, fs: float, fc: float, tone: float, amp: float,
               sigma: float) -> None:
    """The fitted tone is the known one (frequency within a bin, amplitude within 2 dB);
    the fitted random PSD is within 2 dB of the known flat one (2σ²/fs), power-weighted
    over f_c … fs/2 (a flat PSD weights every frequency alike)."""
    tones = fit.angular.tones  # type: ignore[attr-defined]
    near = [t for t in tones if abs(t.frequency - tone) < 2.0]
    assert near, [t.frequency for t in tones]
    for axis in range(3):
        assert abs(20 * np.log10(near[0].amplitude[axis] / amp)) < 2.0
        f_bp, s_bp = fit.angular.psd[axis]  # type: ignore[attr-defined]
        f = np.linspace(max(fc * 2, f_bp[0]), min(fs / 2 * 0.9, f_bp[-1]), 400)
        fitted = np.exp(np.interp(np.log(f), np.log(f_bp), np.log(s_bp)))
        known = 2 * sigma**2 / fs
        assert float(np.mean(np.abs(10 * np.log10(fitted / known)))) < 2.0


def _fit_and_check(tmp_path: Path, recording: object, w: np.ndarray, g: np.ndarray | None,
                   t: np.ndarray, fc: float, resolution: float) -> object:
    from gyrovib.api import load
    from gyrovib.api.recordings.analysis import analyze_recording

    result = analyze_recording(recording, load([_sensor(tmp_path)]),  # type: ignore[arg-type]
                               crossover=fc, resolution=resolution)
    assert result.recorded[0] == pytest.approx(recorded_error(w, g, t, fc), rel=1e-9)
    return result.fit


# ----------------------------------------------------------------- DataFlash


def test_real_dataflash_log_is_parsed_and_named(tmp_path: Path) -> None:
    """pymavlink's tests/test.BIN (ArduPilot 2017, IMU and IMU2 at 50 Hz, 64 KiB: it
    ends inside a message). The samples are pymavlink's own values, promoted; two
    instances without --instance are refused with their rates and lengths."""
    pytest.importorskip("pymavlink")
    from pymavlink import DFReader

    from gyrovib.api.recordings.reading import read_recording

    r = invoke("profile", TEST_BIN)
    assert r.exit_code == 2 and "Traceback" not in r.stderr
    assert "IMU is logged by 2 instances: instance 0 (49.9401 Hz, 0.90108 s, 45 " \
           "samples), instance 1 (49.9401 Hz" in r.stderr
    assert "--instance N" in r.stderr
    rec = read_recording(str(TEST_BIN), instance=1)
    assert rec.source == "IMU instance 1" and rec.samples == 45
    assert any("cut short" in w for w in rec.warnings)
    log = DFReader.DFReader_binary(str(TEST_BIN))
    msgs = []
    while (m := log.recv_match(type="IMU2")) is not None:
        msgs.append(m)
    assert len(msgs) == 45
    expected = np.array([[m.GyrX, m.GyrY, m.GyrZ] for m in msgs]) * (180 / np.pi)
    np.testing.assert_array_equal(rec.rate, expected)
    np.testing.assert_allclose(rec.accel, np.array([[m.AccX, m.AccY, m.AccZ]
                                                    for m in msgs]) / G0, rtol=1e-15)
    strict = invoke("profile", TEST_BIN, "--instance", "1", "--strict")
    assert strict.exit_code == 2 and "refused under --strict" in strict.stderr


def test_dataflash_imu_two_instances(tmp_path: Path) -> None:
    """IMU at 400 Hz, two instances interleaved; instance 1 read and named everywhere;
    its VIBE clip count is damage."""
    pytest.importorskip("pymavlink")
    from gyrovib.api.recordings.reading import read_recording

    fs, n, fc = 400.0, 12000, 5.0
    t_us = np.round(np.arange(n) * 1e6 / fs) + 5e6
    w0, g0 = motion(n, fs, 1, 90.0, 4.0, 1.0)
    w1, g1 = motion(n, fs, 2, 130.0, 6.0, 2.0)
    gyro = [(w * D2R).astype(np.float32) for w in (w0, w1)]
    accel = [(g * G0).astype(np.float32) for g in (g0, g1)]
    path = dataflash_imu(tmp_path / "imu.bin", t_us, gyro, accel, clips=(0, 7))
    rec = read_recording(str(path), instance=1)
    w = gyro[1].astype(np.float64) * (180 / np.pi)
    g = accel[1].astype(np.float64) / G0
    fit = _fit_and_check(tmp_path, rec, w, g, t_us * 1e-6, fc, 0.5)
    _check_fit(fit, fs, fc, 130.0, 6.0, 2.0)
    assert any("VIBE counted 7 clipped sample(s) on IMU 1" in x for x in rec.warnings)
    r = invoke("analyze", "--recording", path, "--instance", "1", _sensor(tmp_path),
               "--format", "json")
    assert r.exit_code == 0, r.stderr
    doc = json.loads(r.stdout)
    assert doc["recording"]["topic"] == "IMU" and doc["recording"]["instance"] == 1
    r = invoke("profile", path, "--instance", "1", "--strict")
    assert r.exit_code == 2 and "VIBE counted 7" in r.stderr
    r = invoke("profile", path, "--instance", "0")
    assert r.exit_code == 0, r.stderr
    assert "# source: IMU instance 0" in r.stdout
    assert "recording imu.bin (IMU instance 0):" in r.stderr
    assert "IMU has no instance 3: instance 0 (400 Hz, 30 s, 12000 samples)" in \
        invoke("profile", path, "--instance", "3").stderr


def test_dataflash_batch_sampler(tmp_path: Path) -> None:
    """The batch sampler at 2 kHz, as ArduPilot logs it: an accelerometer batch of 2048
    samples, then the gyro batch of the same instance (never simultaneous: paired with
    the nearest in time, sample for sample); every batch is a segment of its own (gaps
    split them)."""
    pytest.importorskip("pymavlink")
    from gyrovib.api.recordings.reading import read_recording

    fs, count, fc, mul_g, mul_a = 2000.0, 2048, 8.0, 16384 / 35.0, 32767 / (16 * G0)
    truth_w, truth_g, times = [], [], []
    start = 1e6
    for b in range(12):  # the samples batch_example writes, as stored
        w, g = motion(count, fs, 10 + b, 310.0, 5.0, 1.5)
        raw_w = np.round(w * D2R * mul_g).astype(np.int16)
        raw_g = np.round(g * G0 * mul_a).astype(np.int16)
        truth_w.append(raw_w.astype(np.float64) / np.float64(int(mul_g)) * (180 / np.pi))
        truth_g.append(raw_g.astype(np.float64) / np.float64(int(mul_a)) / G0)
        times.append(start + 1.2e6 + np.arange(count) * 1e6 / fs)
        start += 3e6
    path = batch_example(tmp_path / "batch.BIN")
    rec = read_recording(str(path), topic="batch")
    assert rec.source == "batch instance 0" and rec.segments.shape[0] == 12
    w, g, t = np.concatenate(truth_w), np.concatenate(truth_g), np.concatenate(times) * 1e-6
    fit = _fit_and_check(tmp_path, rec, w, g, t, fc, 2.0)
    _check_fit(fit, fs, fc, 310.0, 5.0, 1.5)


# ----------------------------------------------------------------- PX4 FIFO


def _fifo(tmp_path: Path, **kw: object) -> tuple[Path, list[np.ndarray], list[np.ndarray]]:
    return fifo_example(tmp_path / "fifo.ulg", **kw)


def test_px4_fifo_two_instances(tmp_path: Path) -> None:
    """sensor_gyro_fifo at 4 kHz, 16 samples a message, two instances, each paired
    with sensor_accel_fifo; instance 1 (the noisier) read only when asked for."""
    pytest.importorskip("pyulog")
    from gyrovib.api.recordings.reading import read_recording

    path, gyro, accel = _fifo(tmp_path, clips=(0, 4))
    r = invoke("allan", path, "--topic", "sensor_gyro_fifo")
    assert r.exit_code == 2, r.stderr
    assert "sensor_gyro_fifo is logged by 2 instances: instance 0 (4000 Hz, 19.996 s, 80000 " \
           "samples), instance 1 (4000 Hz" in r.stderr and "--instance N" in r.stderr
    rec = read_recording(str(path), topic="sensor_gyro_fifo", instance=1)
    assert rec.samples == 80000 and rec.fs == pytest.approx(4000.0)
    w = gyro[1].astype(np.float64) * np.float64(np.float32(GYRO_SCALE)) * (180 / np.pi)
    g = accel[1].astype(np.float64) * np.float64(np.float32(ACCEL_SCALE)) / G0
    t = (1000 + np.arange(80000) * 250.0) * 1e-6
    fit = _fit_and_check(tmp_path, rec, w, g, t, 5.0, 2.0)
    _check_fit(fit, 4000.0, 5.0, 345.0, 8.0, 2.5)
    assert any("vehicle_imu_status instance 1 counted clipped gyro samples" in x
               and "X 4," in x for x in rec.warnings)
    # one run for the JSON on standard output and the noise block written with -o
    block = tmp_path / "noise.yaml"
    r = invoke("allan", path, "--topic", "sensor_gyro_fifo", "--instance", "0",
               "--format", "json", "-o", block)
    assert r.exit_code == 0, r.stderr
    doc = json.loads(r.stdout)
    assert doc["recording"]["topic"] == "sensor_gyro_fifo"
    assert doc["recording"]["instance"] == 0
    assert block.read_text(encoding="utf-8").startswith(
        "# from gyrovib allan fifo.ulg, sensor_gyro_fifo instance 0 ")
    table = invoke("allan", path, "--topic", "sensor_gyro_fifo", "--instance", "0")
    assert "recording fifo.ulg (sensor_gyro_fifo instance 0): " in table.stdout
    r = invoke("allan", path, "--topic", "sensor_gyro_fifo", "--instance", "1", "--strict")
    assert r.exit_code == 2 and "refused under --strict" in r.stderr


def test_library_prints_become_warnings_on_stderr(tmp_path: Path) -> None:
    """pyulog prints on standard output ("Warning: unknown file version…"): the JSON on
    standard output still parses, and the words come back as a warning naming the file."""
    pytest.importorskip("pyulog")
    path, _, _ = _fifo(tmp_path, version=2)
    r = invoke("profile", path, "--topic", "sensor_gyro_fifo", "--instance", "0",
               "--format", "json")
    assert r.exit_code == 0, r.stderr
    json.loads(r.stdout)
    assert "fifo.ulg: pyulog said: Warning: unknown file version" in r.stderr


def test_a_cut_or_corrupt_ulog_is_said_by_allan(tmp_path: Path) -> None:
    """allan warns about a log cut short as profile does, refuses it under --strict; a
    corrupt message in the middle of a whole log is corrupt data, not a cut."""
    pytest.importorskip("pyulog")
    path, _, _ = _fifo(tmp_path)
    whole = path.read_bytes()
    cut = tmp_path / "cut.ulg"
    cut.write_bytes(whole[:len(whole) - 100])
    args = ("--topic", "sensor_gyro_fifo", "--instance", "0")
    r = invoke("allan", cut, *args)
    assert r.exit_code == 0, r.stderr
    assert "cut.ulg: the log looks cut short" in r.stderr
    assert invoke("allan", cut, *args, "--strict").exit_code == 2
    middle = bytearray(whole)
    at = len(whole) // 2
    at = bytes(middle).index(b"D", at) - 2  # a data message's header
    middle[at:at + 3] = b"\xff\xff\x00"  # its size and type made nonsense
    bad = tmp_path / "middle.ulg"
    bad.write_bytes(bytes(middle))
    r = invoke("allan", bad, *args)
    assert "middle.ulg: pyulog found corrupt data inside the log" in r.stderr, r.stderr
    assert "cut short" not in r.stderr, r.stderr


def test_ulog_formats_that_multiply_are_refused_before_reading(tmp_path: Path) -> None:
    """A few nested formats, each array small, flatten to 10^8 fields a message: refused
    at the format, naming its byte, before pyulog parses it; a format that contains
    itself likewise."""
    pytest.importorskip("pyulog")
    w = UlogWriter()
    w.format("d", [("uint8_t", 100, "w")])
    w.format("c", [("d", 100, "z")])  # type: ignore[list-item]
    w.format("b", [("c", 100, "y")])  # type: ignore[list-item]
    w.format("sensor_combined", [("uint64_t", 0, "timestamp"), ("b", 100, "x")])
    w.subscribe("sensor_combined")
    path = w.save(tmp_path / "nested.ulg")
    r = invoke("profile", path)
    assert r.exit_code == 2
    assert "nested.ulg: format 'b' (byte" in r.stderr and "more than 16384 fields" in r.stderr
    loop = UlogWriter()
    loop.format("sensor_combined", [("uint64_t", 0, "timestamp"),
                                    ("sensor_combined", 2, "again")])
    r = invoke("profile", loop.save(tmp_path / "loop.ulg"))
    assert r.exit_code == 2 and "contains itself" in r.stderr


def test_synthetic_logs_say_so(tmp_path: Path) -> None:
    """Each writer's file carries the words in its own header."""
    path, _, _ = _fifo(tmp_path)
    assert SYNTHETIC.encode() in path.read_bytes()[:400]
    t = np.arange(100.0)
    bin_path = dataflash_imu(tmp_path / "s.bin", t, [np.zeros((100, 3), np.float32)],
                             [np.zeros((100, 3), np.float32)])
    assert SYNTHETIC.encode() in bin_path.read_bytes()[:400]


# ----------------------------------------------------------------- Betaflight


def test_betaflight_preset(tmp_path: Path) -> None:
    """blackbox_decode's CSV: time (us), gyroADC in deg/s (as Betaflight logs it), and
    accSmooth read only when --accel-unit says its unit."""
    from gyrovib.api.recordings.reading import read_recording

    fs, n, fc = 2000.0, 40000, 5.0
    w, g = motion(n, fs, 5, 260.0, 4.0, 1.2)
    w = np.round(w)  # blackbox_decode writes integers
    t_us = np.round(np.arange(n) * 1e6 / fs)
    path = betaflight_csv(tmp_path / "bb.csv", t_us, w, g)
    rec = read_recording(str(path), preset="betaflight", accel_unit="g")
    assert rec.accel_axes == (True, True, True)
    fit = _fit_and_check(tmp_path, rec, w, g, t_us * 1e-6, fc, 1.0)
    _check_fit(fit, fs, fc, 260.0, 4.0, 1.2)
    plain = read_recording(str(path), preset="betaflight")
    assert plain.accel is None
    assert any("accSmooth[0..2] not read" in x for x in plain.warnings)
    # the library's note names its argument; the command line's, the option
    assert any("give accel_unit='g' (or m/s^2)" in x for x in plain.warnings)
    assert not any("--accel-unit" in x for x in plain.warnings)
    r = invoke("profile", path, "--preset", "betaflight", "--format", "json")
    assert r.exit_code == 0, r.stderr
    assert "give --accel-unit g (or m/s^2)" in r.stderr
    assert invoke("profile", path).exit_code == 2  # no t/time column without the preset


@pytest.mark.parametrize(("junk", "said"), [
    (b"\x00" * 40, "40 byte(s) inside the log are not part of any message"),
    (b"\x00junk\xa3\x95\xee", "of the log, after byte 108208, were not read: pymavlink "
                              "found no message it knows there (corrupt data)"),
])
def test_a_corrupt_dataflash_log_is_said(tmp_path: Path, junk: bytes, said: str) -> None:
    """Bytes that are no message in the middle of a log: skipped and counted, or (a
    message type the log never declared) the end of what pymavlink indexes, said with
    where the reading stopped. pymavlink's own prints ("bad header…", from its compiled
    indexer too) come back as warnings on standard error, the JSON on standard output
    intact; --strict refuses the file."""
    pytest.importorskip("pymavlink")
    from gyrovib.api.recordings.reading import read_recording

    fs, n = 400.0, 4000
    w, g = motion(n, fs, 1, 90.0, 3.0, 1.0)
    path = dataflash_imu(tmp_path / "whole.bin", np.round(np.arange(n) * 1e6 / fs) + 1e6,
                         [(w * D2R).astype(np.float32)], [(g * G0).astype(np.float32)])
    data = path.read_bytes()
    at = data.index(b"\xa3\x95", len(data) // 2)
    bad = tmp_path / "bad.bin"
    bad.write_bytes(data[:at] + junk + data[at:])
    r = invoke("profile", bad, "--format", "json")
    assert r.exit_code == 0, r.stderr
    document = json.loads(r.stdout)
    assert said in r.stderr and "warning: bad.bin: " in r.stderr, r.stderr
    # the command line's warning and JSON name the option; the library's, its argument
    assert "(--strict refuses such a file)\n" in r.stderr
    assert any(said in w and w.endswith("(--strict refuses such a file)")
               for w in document["warnings"])
    assert any(said in w and w.endswith("(strict=True refuses such a file)")
               for w in read_recording(str(bad)).warnings)
    assert "bad.bin: pymavlink said: bad header" in r.stderr
    strict = invoke("profile", bad, "--strict")
    assert strict.exit_code == 2 and "refused under --strict" in strict.stderr


def test_log_options_are_refused_where_they_mean_nothing(tmp_path: Path) -> None:
    """--topic and --instance name a log's topic and instance, --preset a CSV's writer:
    given to another format they are refused, not ignored."""
    csv = tmp_path / "r.csv"
    csv.write_text("t,gx,gy,gz\n" + "".join(f"{k / 100},0,0,{k % 3}\n" for k in range(300)))
    r = invoke("profile", csv, "--instance", "1")
    assert r.exit_code == 2 and "--instance applies only to a PX4 ULog" in r.stderr
    r = invoke("profile", csv, "--topic", "IMU")
    assert r.exit_code == 2 and "--topic applies only to a PX4 ULog" in r.stderr
    pytest.importorskip("pymavlink")
    r = invoke("profile", TEST_BIN, "--preset", "betaflight")
    assert r.exit_code == 2 and "--preset betaflight" in r.stderr and "CSV" in r.stderr
    r = invoke("profile", TEST_BIN, "--topic", "GPS")
    assert r.exit_code == 2 and "a DataFlash log is read as IMU" in r.stderr


def test_a_log_is_known_by_its_first_bytes_whatever_its_name(tmp_path: Path) -> None:
    """docs/recordings.md: readers by content or extension. A ULog and a DataFlash log named
    .log are read as what they are."""
    pytest.importorskip("pyulog")
    pytest.importorskip("pymavlink")
    from gyrovib.api.recordings.reading import read_recording
    from tests.test_recording import ULOG

    ulog = tmp_path / "flight.log"
    ulog.write_bytes(ULOG.read_bytes())
    assert read_recording(str(ulog)).source == "sensor_combined instance 0"
    bin_log = tmp_path / "00000042.log"
    bin_log.write_bytes(TEST_BIN.read_bytes())
    assert read_recording(str(bin_log), instance=1).source == "IMU instance 1"
