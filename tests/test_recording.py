"""Recordings (docs/model.md section 13): Δ_V,rec, the fitted profile, reading and refusing
input."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np
import pytest

from tests.conftest import invoke

scipy_signal = pytest.importorskip("scipy.signal")

DATA = Path(__file__).parent / "data"
ULOG = DATA / "px4-sample.ulg"

#: A coefficient-form sensor with every term of eq. (2) and of docs/model.md section 8
#: (values chosen so that each term contributes at the rates used below).
SENSOR = """\
gyrovib: 1
units: {rate: deg/s, acceleration: g}
sensors:
  - id: every-term
    range: 500
    coefficients: {k0: 0.3, k1: 1.02, A1: 2.0e-2, k2: 8.0e-4, k3: -6.4e-5, k4: 1.28e-5,
                   k5: -7.8e-7, m1: 1.0e-2, m2: -2.0e-2, m31: 4.0e-3, m32: -3.0e-3}
    g2_sensitivity: {G11: 0.01, G22: 0.02, G33: 0.03, G12: 0.004, G13: 0.005, G23: 0.006}
  - id: k4-only
    range: 500
    coefficients: {k4: 1.0e-3}
  - id: linear-only
    coefficients: {k0: 5.0, k1: 1.3, m1: 0.2, m2: -0.1}
"""


def _sensor_file(tmp_path: Path) -> Path:
    path = tmp_path / "sensors.gyrovib.yaml"
    path.write_text(SENSOR)
    return path


def _synthetic(rng: np.random.Generator, fs: float = 1000.0,
               seconds: float = 120.0) -> tuple[np.ndarray, float]:
    """Two tones (37.23 and 83.71 Hz, between Welch bins, not harmonics), Gaussian noise
    σ = 0.7 deg/s, a slow carrier Ω_K3 = 3 + 2·sin(2π·0.05·t) deg/s."""
    n = int(fs * seconds)
    t = np.arange(n) / fs
    rate = np.zeros((n, 3))
    for f, a, ph in TONES:
        for j in range(3):
            rate[:, j] += a[j] * np.sin(2 * np.pi * f * t + np.deg2rad(ph[j]))
    rate += rng.normal(0.0, SIGMA, (n, 3))
    rate[:, 2] += 3.0 + 2.0 * np.sin(2 * np.pi * 0.05 * t)
    return rate, fs


def _still_accel(rate: np.ndarray) -> np.ndarray:
    """``rate`` with three accelerometer columns that read 0 g: a known zero, so the g²
    terms of SENSOR are known (0) and Δ_V,rec is the rate part alone; without them the
    accelerations are not recorded and a sensor with a g² term has an unknown Δ_V,rec
    (docs/model.md section 13, tests/test_recording_unknown.py)."""
    return np.column_stack([rate, np.zeros_like(rate)])


STILL = ("--rate-columns", "0,1,2", "--accel-columns", "3,4,5")

TONES = [(37.23, (0.5, 0.3, 1.5), (0.0, 40.0, 0.0)), (83.71, (0.2, 0.4, 0.8), (0.0, 0.0, 90.0))]
SIGMA = 0.7


def _eq2(c: dict[str, float], w: np.ndarray) -> np.ndarray:
    """Eq. (2) written out, with k0: the independent reference of Δ_V,rec."""
    w1, w2, w3 = w[:, 0], w[:, 1], w[:, 2]
    return (c["k0"] + c["k1"] * (1 + 0.5 * c["A1"] * np.sign(w3)) * w3 + c["k2"] * w3**2
            + c["k3"] * w3**3 + c["k4"] * w3**4 + c["k5"] * w3**5 + c["m1"] * w1
            + c["m2"] * w2 + c["m31"] * w3 * w1 + c["m32"] * w3 * w2)


def test_recorded_error_matches_the_definition(tmp_path: Path) -> None:
    """Δ_V,rec of docs/model.md section 13, evaluated here sample by sample with scipy's own
    butter/sosfiltfilt, over two segments split by a gap, with accelerations in m/s²."""
    from gyrovib.api import load
    from gyrovib.api.recordings.analysis import analyze_recording
    from gyrovib.api.recordings.reading import read_recording

    rng = np.random.default_rng(7)
    fs, fc = 400.0, 5.0
    t = np.concatenate([np.arange(4000), np.arange(6000, 9000)]) / fs  # a gap of 5 s
    n = t.size
    w = rng.normal(0, 3.0, (n, 3)) + np.array([1.0, -2.0, 4.0]) + 5 * np.sin(0.3 * t)[:, None]
    a = rng.normal(0, 4.0, (n, 3)) + np.array([0.0, 0.0, 9.80665])
    np.savez(tmp_path / "rec.npz", t=t, wx=w[:, 0], wy=w[:, 1], wz=w[:, 2],
             ax=a[:, 0], ay=a[:, 1], az=a[:, 2])
    rec = read_recording(str(tmp_path / "rec.npz"), rate_columns=("wx", "wy", "wz"),
                         accel_columns=("ax", "ay", "az"), accel_unit="m/s^2")
    assert rec.segments.tolist() == [[0, 4000], [4000, 7000]]
    result = analyze_recording(rec, load([_sensor_file(tmp_path)]), crossover=fc)

    c = {"k0": 0.3, "k1": 1.02, "A1": 2.0e-2, "k2": 8.0e-4, "k3": -6.4e-5, "k4": 1.28e-5,
         "k5": -7.8e-7, "m1": 1.0e-2, "m2": -2.0e-2, "m31": 4.0e-3, "m32": -3.0e-3}
    g = [0.01, 0.02, 0.03, 0.004, 0.005, 0.006]
    pairs = [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)]
    sos = scipy_signal.butter(4, fc, fs=fs, output="sos")
    total, count = 0.0, 0
    for lo, hi in ((0, 4000), (4000, 7000)):
        ws = w[lo:hi]
        ks = scipy_signal.sosfiltfilt(sos, ws, axis=0)
        x = ws - ks
        gs = a[lo:hi] / 9.80665
        big = scipy_signal.sosfiltfilt(sos, gs, axis=0)
        per = (_eq2(c, ws) - _eq2(c, ks) - c["k1"] * x[:, 2] - c["m1"] * x[:, 0]
               - c["m2"] * x[:, 1])
        per += sum(gj * (gs[:, j] * gs[:, k] - big[:, j] * big[:, k])
                   for gj, (j, k) in zip(g, pairs, strict=True))
        total += float(per.sum())
        count += hi - lo
    expected = total / count
    assert result.recorded[0] == pytest.approx(expected, rel=1e-9)
    assert result.terms[0].sum() + result.g2[0] == pytest.approx(expected, rel=1e-9)
    assert abs(result.g2[0]) > 0.1 * abs(expected)  # the g² term is really exercised
    # eq. (2)'s linear terms are the measured rate itself: nothing rectifies; but the
    # sensor gives no g² figure and the log holds a linear vibration, so its g² term, and
    # Δ_V,rec with it, is unknown (docs/model.md section 8), never the rate part alone
    assert result.sensors[2] == "linear-only" and not result.terms[2].any()
    assert np.isnan(result.recorded[2]) and np.isnan(result.g2[2])
    assert np.isnan(result.fitted[2]) and np.isnan(result.ratio[2])
    assert result.warnings[2][0].startswith("Δ_V,rec unknown: the sensor gives no g² ")
    # stated as a known zero (`vre: 0`), the same sensor rectifies nothing: exactly 0
    stated = tmp_path / "stated.gyrovib.yaml"
    stated.write_text(SENSOR.replace("m2: -0.1}", "m2: -0.1}\n    vre: 0"))
    again = analyze_recording(rec, load([str(stated)]), crossover=fc)
    assert again.sensors[2] == "linear-only" and again.recorded[2] == 0.0
    assert again.recorded[0] == result.recorded[0]
    assert not any(w.startswith("Δ_V,rec unknown") for w in again.warnings.get(2, ()))


def test_fit_recovers_tones_noise_and_the_ratio(tmp_path: Path) -> None:
    """Known tones + Gaussian noise: tones within 3 % amplitude and 0.5 % frequency,
    the random rms within 10 %, and the fitted mission's closed form within [0.8, 1.25]
    of Δ_V,rec for a sensor with every term."""
    rate, fs = _synthetic(np.random.default_rng(1))
    np.save(tmp_path / "syn.npy", rate)
    out = tmp_path / "fit.gyrovib.yaml"
    r = invoke("profile", tmp_path / "syn.npy", "--fs", fs, "-o", out)
    assert r.exit_code == 0, r.stderr
    assert "held" in r.stderr and "excess kurtosis" in r.stderr
    assert invoke("validate", out).exit_code == 0
    from gyrovib.api import load

    profile = load([out]).profiles[0].profile
    assert len(profile.harmonic) == 2 and not profile.harmonics
    for tone, (f, amp, phase) in zip(profile.harmonic, TONES, strict=True):
        assert tone.frequency == pytest.approx(f, rel=5e-3)
        assert np.asarray(tone.amplitude) == pytest.approx(np.asarray(amp), rel=0.03)
        # phases relative to the largest axis (x3), as docs/model.md section 13 writes them
        relative = (np.asarray(phase) - phase[2] - np.asarray(tone.phase) + 180) % 360 - 180
        assert np.abs(relative) == pytest.approx(np.zeros(3), abs=3.0)
    from gyrovib.core.transmissibility import as_table, psd_variance

    psd = profile.random.psd
    for axis in ("x1", "x2", "x3"):
        sigma = np.sqrt(psd_variance(as_table(getattr(psd, axis))))
        # the fitted band starts at f_c: white noise loses the part below it (5/500)
        assert sigma == pytest.approx(SIGMA * np.sqrt(1 - 5 / 500), rel=0.10)
    np.save(tmp_path / "syn6.npy", _still_accel(rate))
    r = invoke("analyze", "--recording", tmp_path / "syn6.npy", "--fs", fs, *STILL,
               _sensor_file(tmp_path), "--format", "json")
    assert r.exit_code == 0, r.stderr
    doc = json.loads(r.stdout)
    *rectifying, linear = doc["results"]
    for row in rectifying:
        assert 0.8 <= row["ratio"] <= 1.25, row
        # the profile at its one mean rate (3 deg/s) misses the carrier's swing of ±2 deg/s,
        # which the fitted mission keeps: that comparison is reported, and warned of
        # exactly when outside [0.8, 1.25] (docs/model.md section 13)
        at_mean = row["at_mean_rate"]
        assert at_mean["ratio"] == pytest.approx(
            at_mean["total"] / row["recorded"]["total"], rel=1e-12)
        outside = not 0.8 <= at_mean["ratio"] <= 1.25
        assert at_mean["outside"] is outside
        assert row["warnings"] == ([w for w in row["warnings"] if "at its mean rate" in w]
                                   if outside else [])
        assert len(row["warnings"]) == int(outside)
    # nothing rectifies, so there is no ratio: unknown (null), not 0
    assert linear["sensor"] == "linear-only" and linear["ratio"] is None
    # nor at the mean rate: no verdict on a ratio that is not there (null, not false)
    assert linear["at_mean_rate"]["ratio"] is None and linear["at_mean_rate"]["outside"] is None
    assert linear["recorded"]["total"] == 0.0 and linear["fitted"]["total"] == 0.0


def test_non_gaussian_recording_is_flagged(tmp_path: Path) -> None:
    """Uniform noise (excess kurtosis −1.2): for k4 alone at Ω ≈ 0 the closed form takes
    ⟨x⁴⟩ = 3σ⁴ where the recording has 1.8σ⁴, a ratio near 3/1.8 — outside [0.8, 1.25]."""
    rng = np.random.default_rng(3)
    n, fs = 120_000, 1000.0
    half = 2.0 * np.sqrt(3.0)
    rate = rng.uniform(-half, half, (n, 3))
    np.save(tmp_path / "uni.npy", rate)
    r = invoke("analyze", "--recording", tmp_path / "uni.npy", "--fs", fs,
               _sensor_file(tmp_path), "--sensor", "k4-only", "--format", "json")
    assert r.exit_code == 0, r.stderr
    doc = json.loads(r.stdout)
    row = doc["results"][0]
    assert row["ratio"] > 1.25
    assert any("not Gaussian-plus-tones" in w for w in row["warnings"])
    assert doc["recording"]["axes"]["Z"]["excess_kurtosis"] == pytest.approx(-1.2, abs=0.05)


def test_json_keys_are_the_contract(tmp_path: Path) -> None:
    rate, fs = _synthetic(np.random.default_rng(2), seconds=20.0)
    np.save(tmp_path / "syn.npy", rate)
    r = invoke("analyze", "--recording", tmp_path / "syn.npy", "--fs", fs,
               _sensor_file(tmp_path), "--format", "json")
    doc = json.loads(r.stdout)
    row = doc["results"][0]
    assert {"sensor", "recorded", "fitted", "ratio", "saturated", "peak_rate"} <= set(row)
    assert {"total", "additive_terms", "g2"} == set(row["recorded"])
    assert {"total", "rms"} == set(row["fitted"])
    assert set(doc["recording"]) == {"file", "topic", "instance", "sha256", "samples", "fs",
                                     "crossover", "segments", "duration", "axes"}
    assert doc["recording"]["topic"] is None and doc["recording"]["instance"] is None
    assert set(doc["recording"]["axes"]["X"]) == {"variance", "held", "skewness",
                                                  "excess_kurtosis", "shape_db", "off_3db"}
    import hashlib

    assert doc["recording"]["sha256"] == hashlib.sha256(
        (tmp_path / "syn.npy").read_bytes()).hexdigest()
    for fmt in ("csv", "markdown", "table"):
        assert invoke("analyze", "--recording", tmp_path / "syn.npy", "--fs", fs,
                      _sensor_file(tmp_path), "--format", fmt).exit_code == 0
    from gyrovib.api import load
    from gyrovib.api.recordings.analysis import analyze_recording
    from gyrovib.api.recordings.reading import read_recording

    frame = analyze_recording(read_recording(str(tmp_path / "syn.npy"), fs=fs),
                              load([_sensor_file(tmp_path)])).to_frame()
    assert list(frame["sensor"]) == ["every-term", "k4-only", "linear-only"]
    # every-term states a g² term and no acceleration was recorded: unknown (NaN, null)
    assert doc["results"][0]["recorded"]["total"] is None
    assert np.isnan(frame["recorded"][0])
    assert frame["recorded"].tolist()[1:] == pytest.approx(
        [r["recorded"]["total"] for r in doc["results"][1:]], rel=1e-12)


def test_gaps_split_and_short_segments_are_dropped(tmp_path: Path) -> None:
    """An interval > 1.5 median intervals splits; a segment < 4/f_c s is dropped, warned."""
    from gyrovib.api.recordings.reading import read_recording

    fs = 200.0
    t = np.concatenate([np.arange(0, 2000), np.arange(2003, 2100), np.arange(2200, 4200)]) / fs
    rng = np.random.default_rng(0)
    rows = ["t,gx,gy,gz", *(f"{float(ti)!r},{a!r},{b!r},{c!r}" for ti, (a, b, c)
                             in zip(t, rng.normal(size=(t.size, 3)).tolist(), strict=True))]
    path = tmp_path / "gaps.csv"
    path.write_text("\n".join(rows) + "\n")
    rec = read_recording(str(path))
    assert rec.segments.tolist() == [[0, 2000], [2000, 2097], [2097, 4097]]
    assert rec.fs == pytest.approx(fs)
    r = invoke("profile", path)
    assert r.exit_code == 0, r.stderr
    assert "1 segment(s) shorter than 4/f_c = 0.8 s dropped" in r.stderr
    assert "segments: 2" in r.stdout


def _csv(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "bad.csv"
    path.write_text(text)
    return path


def _long_csv(tmp_path: Path, n: int = 4000, fs: float = 200.0) -> Path:
    rows = ["time,gx,gy,gz"] + [f"{k / fs!r},0.1,0.2,{float(np.sin(k))!r}" for k in range(n)]
    return _csv(tmp_path, "\n".join(rows) + "\n")


@pytest.mark.parametrize(("args", "text", "message"), [
    (("--rate-columns", "gx,gy,nope"), None, "no column named 'nope'"),
    (("--rate-columns", "0,1,9"), None, "column 9 does not exist"),
    ((), "t,gx,gy,gz\n0,1,2,3\n0.01,1,x,3\n", "bad.csv:3:8: column 'gy': 'x' is not a number"),
    ((), "t,gx,gy,gz\n0,1,2,3\n0.01,1,2,3\n0.005,1,2,3\n",
         "bad.csv:4:1: sample 2: the time stamp goes back"),
    (("--crossover", "150"), None, "too low for the crossover 150 Hz"),
    ((), "t,gx,gy,gz\n0,1,2,3\n0.01,1,2,3\n0.02,1,2,3\n", "shorter than one segment"),
    ((), "gx,gy,gz\n1,2,3\n1,2,3\n", "give the sample rate with --fs"),
    (("--id", "bad id"), None, "--id 'bad id': the fitted profile does not validate"),
])
def test_bad_input_is_refused(tmp_path: Path, args: tuple[str, ...], text: str | None,
                              message: str) -> None:
    path = _long_csv(tmp_path) if text is None else _csv(tmp_path, text)
    r = invoke("profile", path, *args)
    assert r.exit_code == 2
    assert message in r.stderr, r.stderr
    assert str(path) in r.stderr or message.startswith("--id")


def test_ulog_without_pyulog_names_the_extra(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "pyulog", None)
    r = invoke("profile", ULOG)
    assert r.exit_code == 2
    assert "gyrovib[ulog]" in r.stderr and "px4-sample.ulg" in r.stderr


def test_ulog_end_to_end(tmp_path: Path) -> None:
    """A public PX4 log (tests/data/README.md): fit, validate, analyze."""
    pytest.importorskip("pyulog", reason="the ULog path needs the extra gyrovib[ulog]")
    out = tmp_path / "px4.gyrovib.yaml"
    r = invoke("profile", ULOG, "--crossover", "2", "--resolution", "1", "-o", out)
    assert r.exit_code == 0, r.stderr
    assert invoke("validate", out).exit_code == 0
    text = out.read_text()
    assert "# file: px4-sample.ulg" in text and "acceleration:" in text
    r = invoke("analyze", "--recording", ULOG, "--crossover", "2", "--resolution", "1",
               "--format", "json")
    assert r.exit_code == 0, r.stderr
    doc = json.loads(r.stdout)
    assert doc["recording"]["samples"] == 2373
    assert doc["recording"]["fs"] == pytest.approx(250.0, rel=1e-6)
    for axis in doc["recording"]["axes"].values():  # the breakpoint fit's figures on a real log
        assert axis["shape_db"] <= 2.0 and axis["off_3db"] <= 0.2, axis
    r = invoke("profile", ULOG, "--topic", "no_such_topic")
    assert r.exit_code == 2 and "no topic 'no_such_topic'" in r.stderr


def test_input_response_is_a_zero_phase_gain(tmp_path: Path) -> None:
    """A sensor whose response acts at the input sees ν·x (docs/model.md section 13): checked
    against the gain applied here bin by bin (log-log interpolation written out)."""
    from gyrovib.api import load
    from gyrovib.api.recordings.analysis import analyze_recording
    from gyrovib.api.recordings.reading import read_recording

    rng = np.random.default_rng(11)
    fs, fc, n = 500.0, 5.0, 6000
    w = rng.normal(0, 4.0, (n, 3)) + np.array([0.0, 0.0, 2.0])
    np.save(tmp_path / "r.npy", w)
    (tmp_path / "s.gyrovib.yaml").write_text(
        "gyrovib: 1\nunits: {rate: deg/s}\nsensors:\n"
        "  - id: pre-filtered\n    coefficients: {A1: 0.01, k2: 1.0e-3, k3: 2.0e-4}\n"
        "    response: {at: input, table: [[10, 1.0], [50, 0.5], [100, 0.1]]}\n")
    rec = read_recording(str(tmp_path / "r.npy"), fs=fs)
    result = analyze_recording(rec, load([tmp_path / "s.gyrovib.yaml"]), crossover=fc)
    sos = scipy_signal.butter(4, fc, fs=fs, output="sos")
    big = scipy_signal.sosfiltfilt(sos, w, axis=0)
    f = np.fft.rfftfreq(n, 1 / fs)
    tf, tg = np.log([10.0, 50.0, 100.0]), np.log([1.0, 0.5, 0.1])
    gain = np.exp(np.interp(np.log(np.maximum(f, f[1])), tf, tg))  # held past the ends
    x = np.fft.irfft(np.fft.rfft(w - big, axis=0) * gain[:, None], n=n, axis=0)
    om, ok3 = big[:, 2] + x[:, 2], big[:, 2]
    expected = np.mean(0.5 * 0.01 * (np.abs(om) - np.abs(ok3)) + 1e-3 * (om**2 - ok3**2)
                       + 2e-4 * (om**3 - ok3**3))
    assert result.recorded[0] == pytest.approx(expected, rel=1e-9)
    assert result.peak_rate[0] == pytest.approx(np.max(np.abs(om)), rel=1e-12)


def test_spec_form_worst_case_scales_with_the_nonlinearity(tmp_path: Path) -> None:
    """The worst Δ_V,rec over a datasheet envelope is proportional to the limit b
    (docs/model.md section 11): doubling NL doubles it; with no VRE nothing else adds."""
    from gyrovib.api import load
    from gyrovib.api.recordings.analysis import analyze_recording
    from gyrovib.api.recordings.reading import read_recording

    rate, fs = _synthetic(np.random.default_rng(5), seconds=20.0)
    np.save(tmp_path / "s.npy", rate)
    (tmp_path / "c.gyrovib.yaml").write_text(
        "gyrovib: 1\nunits: {rate: deg/s}\nsensors:\n"
        "  - id: nl1\n    specs: {range: 100, nonlinearity: {value: 0.1, unit: '%FS'}}\n"
        "  - id: nl2\n    specs: {range: 100, nonlinearity: {value: 0.2, unit: '%FS'}}\n")
    result = analyze_recording(read_recording(str(tmp_path / "s.npy"), fs=fs),
                               load([tmp_path / "c.gyrovib.yaml"]))
    assert result.spec.all()
    assert result.recorded[0] > 0
    assert result.recorded[1] == pytest.approx(2 * result.recorded[0], rel=1e-6)
    assert result.terms[0, :5].sum() == pytest.approx(result.recorded[0], rel=1e-6)


def test_harmonics_are_grouped_unless_independent(tmp_path: Path) -> None:
    """Lines at 40, 80 and 120 Hz form one group (phase: worst); a line at 57 Hz stays a
    tone; --independent-tones writes all four as tones."""
    rng = np.random.default_rng(9)
    fs, n = 1000.0, 60_000
    t = np.arange(n) / fs
    rate = rng.normal(0, 0.3, (n, 3))
    for f, a in ((40.0, 1.0), (80.0, 0.6), (120.0, 0.4), (57.0, 0.8)):
        rate += a * np.sin(2 * np.pi * f * t)[:, None]
    np.save(tmp_path / "h.npy", rate)
    out = tmp_path / "h.gyrovib.yaml"
    png = tmp_path / "h.png"
    assert invoke("profile", tmp_path / "h.npy", "--fs", fs, "-o", out, "--plot",
                  png).exit_code == 0
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert invoke("validate", out).exit_code == 0
    from gyrovib.api import load

    p = load([out]).profiles[0].profile
    (group,) = p.harmonics if isinstance(p.harmonics, tuple | list) else (p.harmonics,)
    assert group.fundamental == pytest.approx(40.0, rel=5e-3)
    assert [o.order for o in group.orders] == [1, 2, 3]
    assert all(o.worst_phase for o in group.orders)
    assert [h.frequency for h in p.harmonic] == pytest.approx([57.0], rel=5e-3)
    assert invoke("profile", tmp_path / "h.npy", "--fs", fs, "-o", out,
                  "--independent-tones").exit_code == 0
    p = load([out]).profiles[0].profile
    assert not p.harmonics and len(p.harmonic) == 4


def test_worst_phases_bound_what_independent_tones_estimate(tmp_path: Path) -> None:
    """Two locked orders (40, 80 Hz) on noise, with a carrier so that odd moments act:
    the group's worst phases give a larger closed form than independent tones, which
    agree with Δ_V,rec within [0.8, 1.25]."""
    rng = np.random.default_rng(9)
    fs, n = 1000.0, 60_000
    t = np.arange(n) / fs
    rate = rng.normal(0, 0.3, (n, 3))
    for f, a in ((40.0, 1.0), (80.0, 0.6)):
        rate += a * np.sin(2 * np.pi * f * t)[:, None]
    rate[:, 2] += 2.0
    np.save(tmp_path / "h.npy", rate)
    ratios = []
    for extra in ((), ("--independent-tones",)):
        r = invoke("analyze", "--recording", tmp_path / "h.npy", "--fs", fs, "--sensor",
                   "generic-rate-mems", "--format", "json", *extra)
        assert r.exit_code == 0, r.stderr
        ratios.append(json.loads(r.stdout)["results"][0]["ratio"])
    assert ratios[0] > ratios[1]
    assert 0.8 <= ratios[1] <= 1.25


def test_analyze_options_without_meaning_are_refused(tmp_path: Path) -> None:
    np.save(tmp_path / "r.npy", np.zeros((10, 3)))
    r = invoke("analyze", "--recording", tmp_path / "r.npy", "--fs", 100, "--rate", "3")
    assert r.exit_code == 2 and "--recording does not take --rate" in r.stderr


def test_welch_spectra_are_scipys_csd() -> None:
    """The cross-spectral matrix equals scipy.signal.csd (Hann, 50 %, no detrend) pair by
    pair, and two segments average their windows alike (weights = window counts)."""
    from gyrovib.core.recording import welch_spectra

    rng = np.random.default_rng(4)
    a, b = rng.normal(size=(5000, 3)), rng.normal(size=(2300, 3))
    f, s, count = welch_spectra([a, b], 200.0, 0.5)
    kw = {"fs": 200.0, "window": "hann", "nperseg": 400, "noverlap": 200, "detrend": False}
    for i in range(3):
        for j in range(3):
            fa, sa = scipy_signal.csd(a[:, i], a[:, j], **kw)
            _, sb = scipy_signal.csd(b[:, i], b[:, j], **kw)
            na, nb = 1 + (5000 - 400) // 200, 1 + (2300 - 400) // 200
            assert f == pytest.approx(fa)
            np.testing.assert_allclose(s[i, j], (na * sa + nb * sb) / (na + nb), rtol=1e-10,
                                       atol=1e-14)
    assert count == 24 + 10


def test_honesty_moments_are_scipys() -> None:
    """Chunked power sums → variance, skewness, excess kurtosis as scipy.stats computes them."""
    stats = pytest.importorskip("scipy.stats")
    from gyrovib.core import recording as core

    rng = np.random.default_rng(8)
    x = np.column_stack([rng.exponential(size=1_500_000), rng.normal(size=1_500_000) + 5.0,
                         rng.standard_t(6, size=1_500_000)])
    var, skew, kurt = core.central_moments(core.power_sums(x), x.shape[0])
    np.testing.assert_allclose(var, np.var(x, axis=0), rtol=1e-9)
    np.testing.assert_allclose(skew, stats.skew(x, axis=0), rtol=1e-7)
    np.testing.assert_allclose(kurt, stats.kurtosis(x, axis=0), rtol=1e-7)


def test_csv_with_bom_crlf_blank_lines_and_short_rows(tmp_path: Path) -> None:
    """A spreadsheet's CSV (UTF-8 BOM, CRLF, blank lines) reads; a short row is named."""
    from gyrovib.api.recordings.reading import read_recording

    rows = ["\ufefftime,gx,gy,gz", *(f"{k / 100!r},0.1,0.2,{k!r}" for k in range(50)), ""]
    path = tmp_path / "sheet.csv"
    path.write_bytes("\r\n".join(rows).encode("utf-8"))
    rec = read_recording(str(path))
    assert rec.samples == 50 and rec.fs == pytest.approx(100.0)
    assert rec.rate[:, 2].tolist() == list(range(50))
    path.write_text("t,gx,gy,gz\n0,1,2,3\n\n0.01,1,2\n")
    r = invoke("profile", path)
    assert r.exit_code == 2 and "sheet.csv:4:1: 3 cells where the header has 4" in r.stderr


def test_report_with_a_recording(tmp_path: Path) -> None:
    """report --recording: the recording's section (PSD charts, honesty, Δ_V,rec beside
    the closed form) and the fitted profile among the study's profiles."""
    rate, fs = _synthetic(np.random.default_rng(6), seconds=20.0)
    np.save(tmp_path / "s.npy", rate)
    out = tmp_path / "r.html"
    r = invoke("report", "--recording", tmp_path / "s.npy", "--fs", fs, "--budget", "0.01",
               "--profile", "uav-blade-pass-tone", "-o", out)
    assert r.exit_code == 0, r.stderr
    html = out.read_text(encoding="utf-8")
    section = html[html.index('<section class="recording"'):]
    section = section[:section.index("</section>")]
    assert section.count("<svg") == 3 and "Honesty of the fit" in section
    assert "adxrs453" in section and "s-fitted" in section
    assert 'id="p1"' in html and "s-fitted" in html[html.index('id="p1"'):]


def test_a_recording_without_vibration(tmp_path: Path) -> None:
    """A constant rate: no vibration (the filter's rounding is not one), one carrier bin,
    and a profile that validates with the rate alone."""
    np.save(tmp_path / "c.npy", np.full((5000, 3), 2.5))
    out = tmp_path / "c.gyrovib.yaml"
    r = invoke("profile", tmp_path / "c.npy", "--fs", 1000, "-o", out)
    assert r.exit_code == 0, r.stderr
    assert invoke("validate", out).exit_code == 0
    text = out.read_text()
    assert "random:" not in text and "harmonic" not in text.split("profiles:")[1]
    assert text.count("{profile: c-fitted, duration: 5, rate: [2.5, 2.5, 2.5]}") == 1


def test_npz_with_one_2d_array(tmp_path: Path) -> None:
    """An .npz holding one 2-D array reads like an .npy: columns by index, --fs."""
    from gyrovib.api.recordings.reading import read_recording

    a = np.arange(300.0).reshape(100, 3)
    np.savez_compressed(tmp_path / "a.npz", data=a)
    rec = read_recording(str(tmp_path / "a.npz"), fs=50.0, rate_columns=(2, None, 0),
                         rate_unit="rad/s")
    assert rec.rate_axes == (True, False, True)
    np.testing.assert_allclose(rec.rate[:, 0], a[:, 2] * 180 / np.pi, rtol=1e-15)
    np.testing.assert_array_equal(rec.rate[:, 1], 0.0)
    assert rec.segments.tolist() == [[0, 100]] and not rec.time_given


def test_ulog_another_topic_by_column_names() -> None:
    """--topic with --rate-columns: vehicle_attitude's body rates (rad/s), timestamps in µs."""
    pyulog = pytest.importorskip("pyulog", reason="the ULog path needs gyrovib[ulog]")
    from gyrovib.api.recordings.reading import read_recording

    rec = read_recording(str(ULOG), topic="vehicle_attitude",
                         rate_columns=("rollspeed", "pitchspeed", "yawspeed"))
    data = pyulog.ULog(str(ULOG), ["vehicle_attitude"]).data_list[0].data
    assert rec.samples == data["timestamp"].size and rec.accel is None
    np.testing.assert_allclose(rec.rate[:, 2], np.rad2deg(data["yawspeed"].astype(float)),
                               rtol=1e-6)
    assert rec.fs == pytest.approx(1e6 / np.median(np.diff(data["timestamp"])), rel=1e-9)


def test_the_written_mission_and_coherences_are_catalogue_data(tmp_path: Path) -> None:
    """`profile` writes the carrier histogram as a real `missions:` entry and the random
    part's coherences as [ρ31, ρ32, ρ12]; the file validates, `gyrovib mission` runs on it,
    and `analyze --recording`'s fitted closed form is that mission's, number for number.

    The noise is white (σ = 0.7 deg/s per axis) with the correlation matrix ρ31 = 0.3,
    ρ32 = 0.2, ρ12 = -0.5 (Cholesky factor applied to independent normals; its
    determinant 1 + 2·(-0.5)(0.3)(0.2) - 0.25 - 0.09 - 0.04 = 0.56 > 0): white noise is
    correlated alike in every band, so the measured coherences are these, and ρ12 is
    not the default ρ31·ρ32 = 0.06."""
    import yaml

    rng = np.random.default_rng(11)
    fs, n = 1000.0, 60_000
    corr = np.array([[1.0, -0.5, 0.3], [-0.5, 1.0, 0.2], [0.3, 0.2, 1.0]])
    rate = SIGMA * rng.normal(size=(n, 3)) @ np.linalg.cholesky(corr).T
    rate[:, 2] += 3.0 + 2.0 * np.sin(2 * np.pi * 0.05 * np.arange(n) / fs)  # slow carrier
    np.save(tmp_path / "w.npy", rate)
    out = tmp_path / "w.gyrovib.yaml"
    r = invoke("profile", tmp_path / "w.npy", "--fs", fs, "-o", out)
    assert r.exit_code == 0, r.stderr
    assert invoke("validate", out).exit_code == 0
    text = out.read_text(encoding="utf-8")
    assert "#   mission:" not in text and "a comment until" not in text
    doc = yaml.safe_load(text)
    (mission,) = doc["missions"]
    assert mission["id"] == "w-fitted-mission"
    segments = mission["segments"]
    assert len(segments) > 1  # the carrier sweeps 1..5 deg/s: several bins
    assert {s["profile"] for s in segments} == {"w-fitted"}
    assert sum(s["duration"] for s in segments) == pytest.approx(n / fs, rel=1e-5)
    assert [min(s["rate"][2] for s in segments), max(s["rate"][2] for s in segments)] \
        == pytest.approx([1.0, 5.0], abs=0.25)
    coherence = doc["profiles"][0]["random"]["coherence"]
    assert coherence == pytest.approx([0.3, 0.2, -0.5], abs=0.04)

    flown = invoke("mission", out, "--bundled", "sensors", "--format", "json")
    assert flown.exit_code == 0, flown.stderr
    rows = {row["sensor"]: row for row in json.loads(flown.stdout)["mission"]}
    analyzed = invoke("analyze", "--recording", tmp_path / "w.npy", "--fs", fs,
                      "--format", "json")
    assert analyzed.exit_code == 0, analyzed.stderr
    results = json.loads(analyzed.stdout)["results"]
    assert {row["sensor"] for row in results} == set(rows)
    for row in results:
        if row["fitted"]["total"] is None:  # a VRE part: w.npy records no acceleration
            assert "acceleration" in rows[row["sensor"]]["unknown"]
            continue
        assert row["fitted"]["total"] == pytest.approx(rows[row["sensor"]]["mean"], rel=1e-12)
        assert row["fitted"]["rms"] == pytest.approx(rows[row["sensor"]]["rms"], rel=1e-12)
    assert sum(row["fitted"]["total"] is not None for row in results) >= 5


def test_rounded_coherences_stay_a_correlation_matrix() -> None:
    """Nearly singular coherences (x1 = x3 and x2 = x3 but for a trace of noise) round to
    6 figures into a matrix that would not be positive semi-definite; the written ρ12 is
    held inside ρ31·ρ32 ± √((1-ρ31²)(1-ρ32²)), so the file still validates."""
    from gyrovib.api.recordings.yaml import _coherence
    from gyrovib.models.profile import correlation_problem

    r31, r32 = 0.99999949, 0.99999951
    r12 = r31 * r32 + 0.999999 * np.sqrt((1 - r31**2) * (1 - r32**2))  # just inside
    text = _coherence((r31, r32, r12))
    a, b, c = (float(v) for v in text.strip("[]").split(","))
    naive = [float(f"{v:.6g}") for v in (r31, r32, r12)]
    assert correlation_problem(naive[2], naive[0], naive[1]) is not None  # rounding breaks it
    assert correlation_problem(c, a, b) is None


def _shaped_noise(rng: np.random.Generator, fs: float, seconds: float) -> np.ndarray:
    """Three axes of white noise shaped in the frequency domain to the reference spectrum:
    a plateau 2–150 Hz, a resonance at 80 Hz holding most of the power, an anti-alias
    roll-off from 0.42·fs (tests/test_breakpoints.py has the same outline)."""
    from tests.test_breakpoints import _plateau_resonance

    n = int(fs * seconds)
    f = np.fft.rfftfreq(n, 1 / fs)
    gain = np.sqrt(_plateau_resonance(np.maximum(f, 1e-3), fs))
    return np.fft.irfft(np.fft.rfft(rng.normal(size=(n, 3)), axis=0) * gain[:, None], n=n,
                        axis=0)


def test_the_fitted_shape_is_reported_and_warned(tmp_path: Path,
                                                 monkeypatch: pytest.MonkeyPatch) -> None:
    """End to end on a synthetic recording: every axis within the breakpoint fit's figures (≤ 2 dB,
    ≤ 20 % of the power off by 3 dB), the resonance left in the random PSD (no tone),
    the figures in the YAML's comments, the plot's titles and the honesty table; with
    only 2 breakpoints
    the straight line misses the resonance and the warning says so."""
    from gyrovib.api.recordings.fit import fit_recording
    from gyrovib.api.recordings.reading import read_recording

    np.save(tmp_path / "res.npy", _shaped_noise(np.random.default_rng(30), 1000.0, 30.0))
    fit = fit_recording(read_recording(str(tmp_path / "res.npy"), fs=1000.0))
    assert not fit.angular.tones and not fit.angular.harmonics
    for h in fit.honesty:
        assert h.shape_db <= 2.0 and h.off_3db <= 0.2, h
    assert not any("is off the measured one" in w for w in fit.warnings)
    assert "#   rate: X " in fit.yaml and "shape dB" not in fit.yaml
    plt = pytest.importorskip("matplotlib.pyplot")
    from gyrovib.render.recording import plot_fit

    shown: list[str] = []
    monkeypatch.setattr(plt, "close", lambda fig: shown.extend(
        [fig.texts[0].get_text(), *(ax.get_title() for ax in fig.axes)]))
    plot_fit(fit, str(tmp_path / "res.png"))
    h = fit.honesty[0]
    assert f"axis X: shape {h.shape_db:.2f} dB, {100 * h.off_3db:.1f} % of power" in shown[1]
    assert f"worst shape {max(a.shape_db for a in fit.honesty):.2f} dB" in shown[0]
    r = invoke("profile", tmp_path / "res.npy", "--fs", 1000, "--breakpoints", 2)
    assert r.exit_code == 0, r.stderr
    assert "shape dB" in r.stderr and "off 3 dB" in r.stderr
    # the warning names its file, as a reader's do (raise --breakpoints: the option)
    assert ("res.npy: the fitted rate PSD of axis X is off the measured one" in r.stderr
            and "its shape is not the recording's (raise --breakpoints" in r.stderr)
    r = invoke("analyze", "--recording", tmp_path / "res.npy", "--fs", 1000, "--breakpoints",
               2, "--sensor", "generic-rate-mems", "--format", "json")
    assert r.exit_code == 0, r.stderr
    assert "gyrovib: warning: res.npy: the fitted rate PSD of axis X is off" in r.stderr
    assert json.loads(r.stdout)["recording"]["axes"]["X"]["shape_db"] > 2.0


def test_analyze_recording_warnings_name_their_file(tmp_path: Path) -> None:
    """With the JSON on standard output, each warning on standard error names the log it
    is about (the bundled ULog has a segment too short for f_c = 5 Hz: one warning)."""
    pytest.importorskip("pyulog")
    r = invoke("analyze", "--recording", ULOG, _sensor_file(tmp_path), "--format", "json")
    assert r.exit_code == 0, r.stderr
    json.loads(r.stdout)  # the document alone
    warnings = [w for w in r.stderr.splitlines() if w.startswith("gyrovib: warning: ")]
    assert warnings and all(w.startswith("gyrovib: warning: px4-sample.ulg: ")
                            for w in warnings), r.stderr
