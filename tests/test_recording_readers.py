"""The recording readers: float64 before any arithmetic, a ULog cut short is said (and
refused under --strict), a .npy is read from the file a block at a time, and the
block-wise zero-phase filter gives scipy's numbers."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from tests.conftest import invoke
from tests.recording_oracle import recorded_error
from tests.test_recording import SENSOR, ULOG

scipy_signal = pytest.importorskip("scipy.signal")


def test_ulog_recorded_error_is_float64_from_the_raw_samples(tmp_path: Path) -> None:
    """Δ_V,rec on the public PX4 log (tests/data/README.md) equals docs/model.md section 13
    evaluated here in float64 from pyulog's own float32 arrays: promoted first, then
    rad/s → deg/s and m/s² → g, split at gaps of 1.5 median intervals, segments shorter
    than 4/f_c dropped, scipy's butter/sosfiltfilt. Converting in float32 instead is
    2e-6 away, far outside 1e-9."""
    pyulog = pytest.importorskip("pyulog", reason="the ULog path needs gyrovib[ulog]")
    from gyrovib.api import load
    from gyrovib.api.recordings.analysis import analyze_recording
    from gyrovib.api.recordings.reading import read_recording

    fc = 2.0
    (tmp_path / "s.gyrovib.yaml").write_text(SENSOR)
    result = analyze_recording(read_recording(str(ULOG)), load([tmp_path / "s.gyrovib.yaml"]),
                               crossover=fc, resolution=1.0)

    log = pyulog.ULog(str(ULOG), ["sensor_combined"])
    data = next(d for d in log.data_list if d.name == "sensor_combined").data
    assert data["gyro_rad[0]"].dtype == np.float32  # a float32 log, as PX4 writes it
    w = np.column_stack([data[f"gyro_rad[{j}]"].astype(np.float64) for j in range(3)])
    w *= 180.0 / np.pi
    g = np.column_stack([data[f"accelerometer_m_s2[{j}]"].astype(np.float64)
                         for j in range(3)]) / 9.80665
    t = data["timestamp"].astype(np.float64) * 1e-6
    assert result.recorded[0] == pytest.approx(recorded_error(w, g, t, fc), rel=1e-9)


@pytest.mark.parametrize("dtype", ["<f4", ">f8", "<i2"])
def test_npy_of_any_dtype_is_promoted_before_scaling(tmp_path: Path, dtype: str) -> None:
    """The samples are float64(stored value) × scale, exactly, whatever the stored dtype and
    byte order, in C and in Fortran order."""
    from gyrovib.api.recordings.reading import read_recording

    rng = np.random.default_rng(3)
    raw = (rng.normal(0, 300, (500, 4))).astype(dtype)
    scale = np.pi / 180.0  # rad/s → deg/s is 1/scale: converting in float32 would lose digits
    for name, arr in (("c.npy", raw), ("f.npy", np.asfortranarray(raw))):
        np.save(tmp_path / name, arr)
        rec = read_recording(str(tmp_path / name), fs=100.0, rate_columns=(2, None, 0),
                             accel_columns=(1, 3, None), rate_unit="rad/s")
        expected = raw[:, 2].astype(np.float64) * (180.0 / np.pi)
        np.testing.assert_array_equal(rec.rate[:, 0], expected)
        np.testing.assert_array_equal(rec.rate[:, 1], 0.0)
        np.testing.assert_array_equal(rec.store.column("rate", 2, 7, 311),
                                      raw[7:311, 0].astype(np.float64) * (180.0 / np.pi))
        np.testing.assert_array_equal(rec.accel[:, 1], raw[:, 3].astype(np.float64))
        assert rec.rate.dtype == np.float64 and scale > 0


def test_npy_read_by_blocks_reports_the_first_bad_sample(tmp_path: Path,
                                                         monkeypatch: pytest.MonkeyPatch) -> None:
    """A non-finite sample is found wherever it lies among the blocks read."""
    from gyrovib.api.recordings import readers

    monkeypatch.setattr(readers, "NPY_BLOCK", 3 * 8 * 10)  # 10 rows per block
    arr = np.ones((95, 3))
    arr[57, 2] = np.inf
    arr[81, 0] = np.nan
    np.save(tmp_path / "bad.npy", arr)
    r = invoke("profile", tmp_path / "bad.npy", "--fs", "100")
    assert r.exit_code == 2
    assert "bad.npy: column '0', sample 81: not a finite number" in r.stderr, r.stderr


def _cut(tmp_path: Path, size: int, name: str = "cut.ulg") -> Path:
    path = tmp_path / name
    path.write_bytes(ULOG.read_bytes()[:size])
    return path


@pytest.mark.parametrize("share", [None, 0.5, 0.9])
def test_a_cut_ulog_is_said_and_refused_under_strict(tmp_path: Path,
                                                     share: float | None) -> None:
    """A log cut short as `head -c 405336` cuts it, and at 50 % and 90 % of the file, each
    end inside a message: a warning names the file, its bytes and the seconds read;
    --strict makes it exit status 2 on profile and analyze --recording."""
    pytest.importorskip("pyulog", reason="the ULog path needs gyrovib[ulog]")
    size = 405336 if share is None else int(share * ULOG.stat().st_size)
    path = _cut(tmp_path, size)
    args = ("--crossover", "2", "--resolution", "1")
    r = invoke("profile", path, *args, "-o", tmp_path / "p.yaml")
    assert r.exit_code == 0, r.stderr
    warning = next(ln for ln in r.stderr.splitlines() if "cut short" in ln)
    assert "cut.ulg" in warning and f"after {size} bytes" in warning, warning
    assert " s of sensor_combined read" in warning and "--strict" in warning
    for command in (("profile", path), ("analyze", "--recording", path)):
        r = invoke(*command, *args, "--strict")
        assert r.exit_code == 2
        assert f"cut.ulg: the log looks cut short: it ends inside a message after {size} " \
               "bytes" in r.stderr and "refused under --strict" in r.stderr, r.stderr
        assert "Traceback" not in r.stderr


def test_a_whole_ulog_gives_no_cut_warning() -> None:
    pytest.importorskip("pyulog", reason="the ULog path needs gyrovib[ulog]")
    r = invoke("profile", ULOG, "--crossover", "2", "--resolution", "1", "--strict")
    assert r.exit_code == 0, r.stderr
    assert "cut short" not in r.stderr


@pytest.mark.parametrize(("n", "block"), [(16, 4), (100, 7), (5000, 333), (5000, 1 << 18)])
def test_the_block_wise_filter_is_scipys_sosfiltfilt(n: int, block: int) -> None:
    """Bit for bit: the recursion carried across blocks is the same recursion."""
    from gyrovib.core.filtfilt import sosfiltfilt_into

    x = np.random.default_rng(n).normal(3.0, 10.0, (n, 2))
    sos = scipy_signal.butter(4, 5.0, fs=250.0, output="sos")
    out = np.empty((n, 3))
    sosfiltfilt_into(sos, x[:, 1], out[:, 2], block=block)
    np.testing.assert_array_equal(out[:, 2], scipy_signal.sosfiltfilt(sos, x[:, 1]))


def test_a_npy_read_from_the_file_fits_as_the_same_samples_in_memory(tmp_path: Path) -> None:
    """The .npy store (read from the file a block at a time, samples never held whole) and the
    .npz store (arrays in memory) give the same sums bit for bit, over two segments."""
    from gyrovib.api.recordings import readers
    from gyrovib.api.recordings.fit import fit_recording
    from gyrovib.api.recordings.reading import read_recording

    rng = np.random.default_rng(5)
    data = rng.normal(0.0, 2.0, (6000, 6)) + np.array([0, 0, 3.0, 0, 0, 1.0])
    np.save(tmp_path / "r.npy", data)
    np.savez(tmp_path / "r.npz", data)
    fits = []
    for name in ("r.npy", "r.npz"):
        rec = read_recording(str(tmp_path / name), fs=400.0, accel_columns=(3, 4, 5))
        assert isinstance(rec.store, readers.NpyStore) == name.endswith(".npy")
        fits.append(fit_recording(rec, crossover=5.0))
    a, b = fits
    for key in a.moments:
        np.testing.assert_array_equal(a.moments[key], b.moments[key])
    np.testing.assert_array_equal(a.g2_moments, b.g2_moments)
    np.testing.assert_array_equal(a.angular.psd, b.angular.psd)
    def text(fit: object) -> list[str]:  # the YAML but for the file's name and digest
        return [ln for ln in fit.yaml.splitlines()  # type: ignore[attr-defined]
                if "r.np" not in ln and "sha256" not in ln]

    assert text(a) == text(b)


def test_a_recording_without_scipy_says_what_to_install(tmp_path: Path,
                                                       monkeypatch: pytest.MonkeyPatch) -> None:
    # scipy is an optional extra (gyrovib[recording]); the README's first command installs
    # gyrovib without it, and `profile` must then say so at the file, exit 2, no traceback
    import importlib.util

    from gyrovib.api.recordings import fit as recording

    real = importlib.util.find_spec
    monkeypatch.setattr(recording.importlib.util, "find_spec",
                        lambda name, *a: None if name == "scipy" else real(name, *a))
    path = tmp_path / "rec.npy"
    np.save(path, np.random.default_rng(0).normal(size=(4000, 3)))
    result = invoke("profile", path, "--fs", "250")
    assert result.exit_code == 2
    assert "needs scipy" in result.stderr and "gyrovib[recording]" in result.stderr
    assert result.stderr.startswith(str(path))
