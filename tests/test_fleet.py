"""Many recordings (docs/fleet.md): the envelope profile, --jobs, analyze on several
recordings, and the same reduction on Dask."""

from __future__ import annotations

import functools
import json
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from tests.conftest import invoke

pytest.importorskip("scipy.signal")

FS = 250.0


def _write(path: Path, rng: np.random.Generator, *, sigma: float, tones: list[tuple[float, float]],
           fs: float = FS, seconds: float = 30.0, carrier: float = 2.0) -> Path:
    """Gaussian noise σ (deg/s) on each axis, tones (f, amplitude on x3; half on x1, x2),
    a carrier Ω_K3 = carrier + sin(2π·0.05·t) deg/s; saved as .npy columns."""
    n = int(fs * seconds)
    t = np.arange(n) / fs
    rate = rng.normal(0.0, sigma, (n, 3))
    for f, a in tones:
        rate += np.outer(np.sin(2 * np.pi * f * t), (a / 2, a / 2, a))
    rate[:, 2] += carrier + np.sin(2 * np.pi * 0.05 * t)
    np.save(path, rate)
    return path


@pytest.fixture(scope="module")
def logs(tmp_path_factory: pytest.TempPathFactory) -> list[Path]:
    """Three recordings: quiet with a 31.3 Hz tone of 0.4; loud with the same tone at 1.2
    and a 71.7 Hz one; a third like the first (other noise)."""
    d = tmp_path_factory.mktemp("logs")
    rng = np.random.default_rng(30)
    return [_write(d / "a.npy", rng, sigma=0.2, tones=[(31.3, 0.4)]),
            _write(d / "b.npy", rng, sigma=0.5, tones=[(31.3, 1.2), (71.7, 0.6)], carrier=-4.0),
            _write(d / "c.npy", rng, sigma=0.2, tones=[(31.3, 0.4)])]


def test_envelope_of_one_recording_is_its_own_profile(logs: list[Path]) -> None:
    """The envelope reduction on a recording and a twin of it (the same samples under
    another identity: the same file itself is refused) gives back the one-recording fit
    (profile body identical but for the id and name; its mission's time twice)."""
    import dataclasses

    from gyrovib.api.fleet.envelope import envelope
    from gyrovib.api.fleet.run import RecordingOptions, profile_one

    options = RecordingOptions(fs=FS)
    fit = profile_one(str(logs[0]), options)
    twin = dataclasses.replace(fit, sha256="0" * 64)
    env = envelope([fit, twin], options)
    one, both = fit.yaml, env.fit.yaml
    body = one[one.index("profiles:"):one.index("missions:")]
    assert both[both.index("profiles:"):both.index("missions:")] == body.replace(
        fit.profile_id, "envelope-fitted").replace("Fitted from a.npy",
                                                   "Fitted from envelope of 2 recordings")
    # the joined mission, re-binned: its time and its time-weighted mean rate kept
    assert env.fit.mission_durations.sum() == pytest.approx(2 * fit.mission_durations.sum())
    np.testing.assert_allclose(env.fit.mission_durations @ env.fit.mission_rates,
                               2 * fit.mission_durations @ fit.mission_rates, rtol=1e-12)


def test_the_fleet_mission_is_a_carrier_histogram() -> None:
    """At most 16 segments are written as they are; more become at most 16 bins of Ω_K3,
    each with its segments' total time at their time-weighted mean rate (worked here by
    hand: 20 segments at Ω_K3 = 0…19 deg/s, 1 s each, except 3 s at 19)."""
    from gyrovib.api.fleet.envelope import fleet_mission

    rates = np.zeros((20, 3))
    rates[:, 2] = np.arange(20.0)
    rates[:, 0] = 1.0
    durations = np.ones(20)
    durations[-1] = 3.0
    same = fleet_mission(rates[:16], durations[:16])
    assert np.array_equal(same[0], rates[:16]) and np.array_equal(same[1], durations[:16])
    binned, time = fleet_mission(rates, durations)
    # edges 0, 19/16, 2·19/16, …: bins of width 1.1875 take one or two of the integers
    assert time.sum() == 22.0 and len(time) == 16
    assert time[0] == 2.0 and binned[0, 2] == 0.5  # 0 and 1 (1 < 1.1875)
    assert time[-1] == 4.0 and binned[-1, 2] == (18 + 3 * 19) / 4  # 18 and 19 (3 s)
    np.testing.assert_allclose(binned[:, 0], 1.0)


def test_envelope_takes_the_largest_psd_and_the_loudest_tones(logs: list[Path]) -> None:
    """Per bin the largest random PSD; the shared tone at the amplitude of the recording
    where it is largest, the other tone kept; the missions joined."""
    from gyrovib.api.fleet.envelope import combine, envelope, envelope_part
    from gyrovib.api.fleet.run import RecordingOptions, profile_one

    options = RecordingOptions(fs=FS)
    fits = [profile_one(str(p), options) for p in logs]
    env = envelope(fits, options)
    parts = [envelope_part(f, options) for f in fits]
    largest = np.max([p.angular.random for p in parts], axis=0)
    joined = parts[0]
    for p in parts[1:]:
        joined = combine(joined, p)
    np.testing.assert_array_equal(joined.angular.random, largest)
    # the balanced tree of envelope() joins in the order a left fold does
    from gyrovib.api.fleet.envelope import reduce_parts

    five = [*parts, *parts[:2]]
    tree, fold = reduce_parts(five), functools.reduce(combine, five)
    for name in ("mission_rates", "mission_durations"):
        np.testing.assert_array_equal(getattr(tree, name), getattr(fold, name))
    np.testing.assert_array_equal(tree.angular.lines, fold.angular.lines)
    assert tree.recordings == fold.recordings
    tones = {round(t.frequency): t for t in env.fit.angular.tones}
    assert sorted(tones) == [31, 72]
    loud = {round(t.frequency): t for t in fits[1].angular.tones}
    np.testing.assert_array_equal(tones[31].amplitude, np.max(
        [next(t.amplitude for t in f.angular.tones if round(t.frequency) == 31) for f in fits],
        axis=0))
    np.testing.assert_array_equal(tones[72].amplitude, loud[72].amplitude)
    assert env.fit.mission_durations.sum() == pytest.approx(sum(f.duration for f in fits))
    # the random part of the loud recording decides: its fitted variance, within the 1 %
    # the breakpoint fit holds a band's variance to (docs/model.md section 13)
    from gyrovib.core.transmissibility import psd_variance

    for j in range(3):
        assert psd_variance(env.fit.angular.psd[j]) == pytest.approx(
            psd_variance(fits[1].angular.psd[j]), rel=0.05)


def test_recordings_on_different_grids(tmp_path: Path) -> None:
    """A 500 Hz and a 250.3 Hz recording: the common grid is the coarser Δf up to the
    higher Nyquist frequency, and above 125 Hz only the 500 Hz recording is known."""
    from gyrovib.api.fleet.envelope import combine, envelope_part
    from gyrovib.api.fleet.run import RecordingOptions, profile_one

    rng = np.random.default_rng(5)
    fast = _write(tmp_path / "fast.npy", rng, sigma=0.1, tones=[], fs=500.0, seconds=20.0)
    slow = _write(tmp_path / "slow.npy", rng, sigma=1.0, tones=[], fs=250.3, seconds=20.0)
    a = envelope_part(profile_one(str(fast), RecordingOptions(fs=500.0)))
    b = envelope_part(profile_one(str(slow), RecordingOptions(fs=250.3)))
    joined = combine(a, b).angular
    f = joined.frequencies
    # Welch's Δf = fs / round(fs / 0.5): 0.5 Hz at 500 Hz, 250.3/501 Hz at 250.3 Hz
    assert f[1] - f[0] == pytest.approx(0.5) and f[-1] == pytest.approx(250.0)
    above = f > 125.2
    np.testing.assert_array_equal(joined.random[:, above], a.angular.random[:, above])
    below = (f > 10) & (f < 120)
    assert np.all(joined.random[:, below] > a.angular.random[:, below])


def test_jobs_give_the_same_bytes_and_errors_stay_located(logs: list[Path],
                                                          tmp_path: Path) -> None:
    """--jobs 2 writes what --jobs 1 writes (profile YAML and tables; analyze --recording
    runs the same run_recordings); a bad recording is reported as FILE: message, exit 2,
    the first in input order."""
    args = ("profile", *logs, "--fs", FS)
    one, two = invoke(*args), invoke(*args, "--jobs", 2)
    assert one.exit_code == 0, one.stderr
    assert (one.stdout, one.stderr) == (two.stdout, two.stderr)
    assert one.stdout.startswith("# Envelope of 3 recordings")
    assert one.stderr.count("recording ") >= 3 and "envelope of 3 recordings" in one.stderr
    out = tmp_path / "env.gyrovib.yaml"
    out.write_text(one.stdout)
    assert invoke("validate", out).exit_code == 0
    doc = json.loads(invoke(*args, "--format", "json").stdout)
    assert [r["file"] for r in doc["recordings"]] == ["a.npy", "b.npy", "c.npy"]
    assert doc["envelope"]["recordings"] == 3 and doc["profile"] == one.stdout
    bad = tmp_path / "bad.xyz"
    bad.write_text("x")
    r = invoke("profile", logs[0], bad, tmp_path / "missing.npy", "--fs", FS, "--jobs", 2)
    assert r.exit_code == 2 and r.stdout == ""
    assert r.stderr.startswith(f"{bad}: unknown recording format"), r.stderr


def test_analyze_several_recordings_reports_each_and_the_worst(logs: list[Path]) -> None:
    """JSON: one entry per recording as analyze --recording writes one, and per sensor the
    recording with the largest |Δ_V,rec| (the loud one, b.npy, whose vibration is larger
    on every axis). The sensors state no g² term, so the recordings' missing accelerations
    do not leave their Δ_V,rec unknown (tests/test_recording_unknown.py)."""
    r = invoke("analyze", "--recording", logs[0], "--recording", logs[1], "--fs", FS,
               "--sensor", "generic-rate-mems", "--sensor", "adxrs453", "--format", "json")
    assert r.exit_code == 0, r.stderr
    doc = json.loads(r.stdout)
    single = json.loads(invoke("analyze", "--recording", logs[1], "--fs", FS, "--sensor",
                               "generic-rate-mems", "--sensor", "adxrs453",
                               "--format", "json").stdout)
    assert [e["recording"]["file"] for e in doc["recordings"]] == ["a.npy", "b.npy"]
    assert doc["recordings"][1]["results"] == single["results"]
    for k, worst in enumerate(doc["worst"]):
        assert worst["recording"] == "b.npy" and worst["index"] == 1
        assert worst["recorded"] == single["results"][k]["recorded"]
    table = invoke("analyze", "--recording", logs[0], "--recording", logs[1], "--fs", FS,
                   "--sensor", "generic-rate-mems")
    assert "worst recording per sensor" in table.stdout
    refused = invoke("analyze", "--jobs", 2)
    assert refused.exit_code == 2 and "--jobs" in refused.stderr


def test_the_envelope_on_dask(logs: list[Path]) -> None:
    """docs/fleet.md's pipeline on Dask's synchronous scheduler gives the CLI's profile."""
    bag = pytest.importorskip("dask.bag")
    from gyrovib.api.fleet.envelope import (
        combine,
        envelope_step,
        fit_envelope,
        profile_recordings,
    )
    from gyrovib.api.fleet.pool import one_thread
    from gyrovib.api.fleet.run import RecordingOptions

    def one_log(path: str, options: RecordingOptions) -> Any:  # the recipe's, one thread
        with one_thread():
            return envelope_step(path, options)

    options = RecordingOptions(fs=FS)
    paths = [str(p) for p in logs]
    part = bag.from_sequence(paths, npartitions=2).map(one_log, options).fold(
        combine).compute(scheduler="synchronous")
    assert fit_envelope(part, options).fit.yaml == profile_recordings(paths, options).fit.yaml


def test_progress_counts_the_recordings_in_order(logs: list[Path]) -> None:
    """run_recordings reports each recording done through gyrovib.progress (the bar a
    terminal draws), and its results come in input order."""
    from gyrovib.api.fleet.run import RecordingOptions, run_recordings
    from gyrovib.progress import receiving

    calls: list[tuple[str, int, int]] = []
    with receiving(lambda *call: calls.append(call)):
        fits = run_recordings([str(p) for p in logs[:2]], RecordingOptions(fs=FS))
    # (each fit reports its own stages too, under its own label)
    assert [c for c in calls if c[0] == "recordings"] == [("recordings", 1, 2),
                                                          ("recordings", 2, 2)]
    assert [Path(f.file).name for f in fits] == ["a.npy", "b.npy"]


def test_a_sensor_without_a_g2_figure_has_no_worst_recording(tmp_path: Path) -> None:
    """Two recordings with accelerations (synthetic: noise of 0.5 g on each axis beside
    the rates of _write): generic-rate-mems gives no g² figure, so its Δ_V,rec is unknown
    on each (docs/output.md), its worst recording unknown (`recording` null), and the
    summary table writes every figure of its row '?' (the ratio too), never '—' or 0;
    adxrs645 (a datasheet VRE) keeps its worst recording."""
    rng = np.random.default_rng(31)
    paths = []
    for name, sigma in (("a.npy", 0.2), ("b.npy", 0.5)):
        rate = np.load(_write(tmp_path / name, rng, sigma=sigma, tones=[(31.3, 0.4)]))
        np.save(tmp_path / name, np.column_stack([rate, rng.normal(0.0, 0.5, rate.shape)]))
        paths.append(tmp_path / name)
    read = ("--fs", FS, "--rate-columns", "0,1,2", "--accel-columns", "3,4,5",
            "--sensor", "generic-rate-mems", "--sensor", "adxrs645")
    r = invoke("analyze", "--recording", paths[0], "--recording", paths[1], *read,
               "--format", "json")
    assert r.exit_code == 0, r.stderr
    worst = {w["sensor"]: w for w in json.loads(r.stdout)["worst"]}
    assert worst["generic-rate-mems"]["recording"] is None
    assert worst["adxrs645"]["recording"] in ("a.npy", "b.npy")
    table = invoke("analyze", "--recording", paths[0], "--recording", paths[1], *read)
    summary = table.stdout[table.stdout.index("worst recording per sensor"):]
    row = next(line for line in summary.splitlines() if line.startswith("generic-rate-mems"))
    assert row.split()[1:5] == ["?", "—", "?", "?"]  # Δ_V,rec, recording, fitted, ratio
