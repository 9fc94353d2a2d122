"""The run-up test's kernels (docs/model.md section 16, core/runup.py) and the library call
on simulated run-ups of known coefficients (tests/runup_sim.py) and on a real PX4 log.

Where each expected number comes from is said beside it: a closed form of the moments
(docs/model.md section 4), the variance of a mean of white noise (σ²/n), exact
least squares on noiseless data, or the coefficients a simulation was made with.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from gyrovib.api.recordings import read_recording
from gyrovib.api.runup import runup
from gyrovib.core import runup as kernel
from tests.runup_sim import simulate

DATA = Path(__file__).parent / "data"


# ----------------------------------------------------------------- regressors


def test_regressors_of_a_tone_are_the_closed_form_moments() -> None:
    # one tone of amplitude a over whole periods, carrier 0: ⟨x²⟩ = a²/2, ⟨x⁴⟩ = 3a⁴/8,
    # ⟨|x|⟩ = 2a/π (docs/model.md section 4), ⟨x1x3⟩ = ½·a1·a3 in phase; a tone A on
    # a_3 above gravity g: ⟨a3²⟩ − g² = A²/2, and ⟨a1 a3⟩ = ½·A1·A3 in phase
    fs, f, n = 1000.0, 1.0, 20_000                    # 1000 samples a period, 20 periods
    t = np.arange(n) / fs
    s = np.sin(2 * np.pi * f * t)
    a3, a1 = 2.0, 0.7
    rate = np.column_stack([a1 * s, np.zeros(n), a3 * s])
    accel = np.column_stack([0.5 * s, np.zeros(n), 1.0 + 3.0 * s])
    gravity = np.tile([0.0, 0.0, 1.0], (n, 1))
    phi = dict(zip(kernel.TERMS, kernel.step_regressors(rate, np.zeros((n, 3)), accel,
                                                        gravity), strict=True))
    assert phi["k2"] == pytest.approx(a3**2 / 2, rel=1e-9)
    assert phi["k4"] == pytest.approx(3 * a3**4 / 8, rel=1e-9)
    assert phi["A1"] == pytest.approx(0.5 * 2 * a3 / math.pi, rel=1e-5)   # sampled |sin|
    assert phi["m31"] == pytest.approx(a1 * a3 / 2, rel=1e-9)
    assert phi["m32"] == pytest.approx(0.0, abs=1e-12)
    assert phi["G33"] == pytest.approx(3.0**2 / 2, rel=1e-9)
    assert phi["G11"] == pytest.approx(0.5**2 / 2, rel=1e-9)
    assert phi["G13"] == pytest.approx(0.5 * 3.0 / 2, rel=1e-9)
    assert phi["vre"] == pytest.approx(phi["G11"] + phi["G22"] + phi["G33"], rel=1e-12)


def test_without_accelerations_the_g2_regressors_are_unknown_not_zero() -> None:
    rate = np.random.default_rng(1).standard_normal((100, 3))
    phi = kernel.step_regressors(rate, np.zeros((100, 3)))
    assert np.all(np.isnan(phi[5:]))
    assert np.all(np.isfinite(phi[:5]))


# ----------------------------------------------------------------- noise of a mean


def test_variance_of_a_step_mean_is_that_of_white_noise_on_average() -> None:
    # white noise of σ per sample: the variance of the mean of n samples is σ²/n; the
    # estimate over 200 records scatters around it, never an order off
    rng = np.random.default_rng(11)
    n, sigma, fs = 4000, 0.3, 200.0
    ratios = np.array([kernel.mean_variance(sigma * rng.standard_normal(n), fs)
                       / (sigma**2 / n) for _ in range(200)])
    assert 0.9 < float(np.mean(ratios)) < 1.4          # the largest of 5 reads: ≥ 1 on average
    assert float(np.min(ratios)) > 0.4


def test_the_drift_inside_a_step_is_not_read_as_noise() -> None:
    # a linear ramp (the drift term's own) adds nothing once the step's line is removed
    rng = np.random.default_rng(2)
    y = 0.1 * rng.standard_normal(5000)
    ramp = y + 1e-3 * np.arange(5000)
    assert kernel.mean_variance(ramp, 100.0) == pytest.approx(kernel.mean_variance(y, 100.0),
                                                              rel=1e-9)


# ----------------------------------------------------------------- steps


def test_steps_are_found_where_the_level_changes() -> None:
    # levels 0, 10, 20, 10 dB over 20 windows each: four steps, one window trimmed at
    # each inner edge (the change itself)
    levels = np.repeat([0.0, 10.0, 20.0, 10.0], 20)[:, None]
    steps = kernel.detect_steps(levels, window=100)
    assert steps.tolist() == [[0, 1900], [2100, 3900], [4100, 5900], [6100, 8000]]


def test_a_short_excursion_is_a_transition_not_a_step() -> None:
    levels = np.concatenate([np.zeros(20), [30.0, 30.0, 30.0], np.zeros(20)])[:, None]
    steps = kernel.detect_steps(levels, window=10)
    assert len(steps) == 2                             # the 3-window burst is dropped


# ----------------------------------------------------------------- the fit


def test_noiseless_steps_give_the_coefficients_exactly() -> None:
    # ȳ = c + d·t + θ·φ exactly: weighted least squares returns c, d and θ to rounding
    phi = np.array([[0, 0], [1, 0], [0, 2], [2, 1], [1, 1], [0, 0], [3, 2.0]])
    t = np.arange(7) * 60.0 + 30.0
    theta, c, d = np.array([0.02, -0.5]), 0.1, 1e-4
    y = c + d * t + phi @ theta
    fit = kernel.fit_steps(y, t, phi, np.full(7, 1e-6))
    assert fit.values == pytest.approx(theta, abs=1e-10)
    assert fit.drift == pytest.approx(d, abs=1e-12)
    assert fit.constant == pytest.approx(c, abs=1e-10)
    assert fit.chi2 == pytest.approx(0.0, abs=1e-8)
    assert fit.inflation == 1.0


def test_a_drift_is_estimated_only_when_the_order_separates_it() -> None:
    var = np.full(6, 1.0)
    t = np.arange(6) * 60.0
    up = np.array([[0.0], [1], [2], [3], [4], [5]])        # level grows with time: no
    assert not kernel.drift_separable(up, t, var)[0]
    updown = np.array([[0.0], [2], [4], [4], [2], [0]])    # up and down again: yes
    assert kernel.drift_separable(updown, t, var)[0]
    fit = kernel.fit_steps(np.zeros(6), t, up, var)
    assert math.isnan(fit.drift)
    fit = kernel.fit_steps(np.zeros(6), t, updown, var)
    assert math.isfinite(fit.drift)


def test_collinear_terms_are_not_identifiable_and_name_their_partner() -> None:
    # k2 and vre regressors in a fixed ratio over every step: the design cannot tell them
    phi = np.array([[0.0, 0.0], [1, 2], [2, 4], [1, 2], [0, 0], [3, 6]])
    fit = kernel.fit_steps(np.arange(6.0), np.arange(6) * 60.0, phi, np.ones(6), drift=False)
    assert not fit.separable.any()
    assert fit.partner.tolist() == [1, 0]
    # a regressor the same on every step (no vibration where it needs it): not estimated
    fit = kernel.fit_steps(np.arange(4.0), np.zeros(4), [[0.0, 1], [1, 1], [2, 1], [3, 1]],
                           np.ones(4), drift=False)
    assert fit.partner.tolist()[1] == -3 and math.isnan(fit.values[1])
    assert fit.values[0] == pytest.approx(1.0)
    # too few steps for the unknowns
    fit = kernel.fit_steps([0.0, 1.0], [0.0, 60.0], [[0.0], [1.0]], [1.0, 1.0], drift=False)
    assert fit.partner.tolist() == [-2]


def test_reduced_chi2_above_one_inflates_the_covariance() -> None:
    rng = np.random.default_rng(5)
    phi = np.arange(10.0)[:, None]
    y = 0.3 * phi[:, 0] + rng.standard_normal(10)        # scatter 1, declared 0.1²
    fit = kernel.fit_steps(y, np.zeros(10), phi, np.full(10, 0.01), drift=False)
    plain = math.sqrt(0.01 / np.sum((phi[:, 0] - phi[:, 0].mean()) ** 2))
    assert fit.inflation == pytest.approx(fit.chi2 / 8)
    assert fit.sigma[0] == pytest.approx(plain * math.sqrt(fit.inflation), rel=1e-9)


# ----------------------------------------------------------------- simulated run-ups


def _record(tmp_path: Path, rng: np.random.Generator, coefficients: dict[str, float],
            **kw: float) -> tuple[Path, list[tuple[float, float]]]:
    data, steps = simulate(rng, coefficients, **kw)
    path = tmp_path / "runup.npy"
    np.save(path, data)
    return path, steps


def _read(path: Path, fs: float = 200.0):  # type: ignore[no-untyped-def]
    return read_recording(str(path), fs=fs, rate_columns=(0, 1, 2), accel_columns=(3, 4, 5))


def test_simulated_runups_cover_the_truth_and_find_no_zero(tmp_path: Path) -> None:
    # 30 records (the 200 of the acceptance run: benchmarks/bench_runup_coverage.py):
    # k2 = 0.002 (deg/s)^-1, vre = 0.01 deg/s/g², A1 = 0; drift 1e-4 deg/s/s, noise
    # 0.01 deg/s/√Hz; the steps found from the record. Each 95 % interval (±1.96 u)
    # holds the simulated value in ≥ 26 of 30 (binomial: P(< 26 | 0.95) ≈ 1.6 %);
    # the zero A1 is "found" (|value| ≥ 2u) in at most 4 of 30 (P(> 4 | 0.05) ≈ 2 %)
    rng = np.random.default_rng(20261206)
    truth = {"A1": 0.0, "k2": 0.002, "vre": 0.01}
    covered = dict.fromkeys(truth, 0)
    found_zero = 0
    for _ in range(30):
        path, steps = _record(tmp_path, rng, truth, gap=2.0)
        result = runup(_read(path), estimate=list(truth))
        assert len(result.steps) == len(steps)
        for e in result.estimates:
            covered[e.name] += abs(e.value - truth[e.name]) <= 1.96 * e.uncertainty
        found_zero += result.estimates[0].status == "found"
    assert min(covered.values()) >= 26, covered
    assert found_zero <= 4


def test_found_steps_match_the_simulated_ones(tmp_path: Path) -> None:
    rng = np.random.default_rng(3)
    path, steps = _record(tmp_path, rng, {"k2": 0.002}, gap=2.0)
    result = runup(_read(path), estimate=["k2"])
    for s, (a, b) in zip(result.steps, steps, strict=True):
        assert a - 0.01 <= s.start and s.end <= b + 0.01      # inside the true step
        assert s.duration >= (b - a) - 2.0                   # less at most the trimmed edges
    assert [s.baseline for s in result.steps] == [x == 0 and a == 0 for x, a in
                                                  zip((0, 1, 2, 0, 2, 1, 0, 3, 0, 1),
                                                      (0, 1, 0, 2, 2, 0, 1, 1, 0, 2),
                                                      strict=True)]


def test_vre_and_k2_stepped_together_are_not_identifiable(tmp_path: Path) -> None:
    # angular and linear vibration in one ratio on every step: the regressors of k2 and
    # vre are (near) proportional; neither is reported as found, and the way out is named
    rng = np.random.default_rng(4)
    levels = (0.0, 1.0, 2.0, 3.0, 2.0, 1.0, 0.0)
    path, _ = _record(tmp_path, rng, {"k2": 0.002, "vre": 0.01}, angular=levels,
                      linear=levels)
    result = runup(_read(path), estimate=["k2", "vre"])
    for e in result.estimates:
        assert e.status == "not identifiable", e
        assert not e.identifiable
        assert e.separate is not None and "ratio" in e.separate


def test_steps_only_up_keep_the_drift_out_and_say_so(tmp_path: Path) -> None:
    rng = np.random.default_rng(6)
    # amplitudes √s: ⟨x3²⟩ grows in proportion to the step's index, as time does
    path, _ = _record(tmp_path, rng, {"k2": 0.002},
                      angular=tuple(math.sqrt(s) for s in range(5)), linear=(0.0,) * 5)
    result = runup(_read(path), estimate=["k2"])
    assert math.isnan(result.drift)
    assert any("step down again" in n for n in result.notes)


# ----------------------------------------------------------------- a real PX4 log


def test_a_rectification_injected_into_a_px4_log_is_recovered(tmp_path: Path) -> None:
    # tests/data/px4-sample.ulg (pyulog's test log; the vehicle on the ground): its gyro
    # and accelerometer samples, 250 Hz, the longest contiguous stretch. Injected on x3,
    # step by step: a 55 Hz tone of amplitude a_s and the rectification a k2 of
    # 0.01 (deg/s)^-1 makes of it, k2·v². The same log with the tone and without the
    # rectification is the reference: the injected estimate less the reference's must
    # be 0.01 within the injected estimate's 95 % interval.
    log = read_recording(str(DATA / "px4-sample.ulg"))
    lo, hi = max(log.segments.tolist(), key=lambda s: s[1] - s[0])
    rate, accel, fs = log.rate[lo:hi], log.accel[lo:hi], log.fs
    assert accel is not None
    t = np.arange(rate.shape[0]) / fs
    steps = [(0.2, 1.6), (1.8, 3.2), (3.4, 4.8), (5.0, 6.4), (6.6, 8.0)]
    amplitude = np.zeros(t.size)
    for (a, b), level in zip(steps, (0.0, 4.0, 8.0, 4.0, 0.0), strict=True):
        amplitude[(t >= a - 0.1) & (t < b + 0.1)] = level
    v = amplitude * np.sin(2 * np.pi * 55.0 * t)
    k2 = 0.01
    estimates = {}
    for name, extra in (("reference", v), ("injected", v + k2 * v**2)):
        data = np.column_stack([rate[:, :2], rate[:, 2] + extra, accel])
        path = tmp_path / f"{name}.npy"
        np.save(path, data)
        result = runup(_read(path, fs), steps=steps, estimate=["k2"])
        estimates[name] = result.estimates[0]
    injected, reference = estimates["injected"], estimates["reference"]
    assert injected.status == "found"
    assert abs(injected.value - reference.value - k2) <= 1.96 * injected.uncertainty
    assert abs(reference.value) < 0.1 * k2                   # the log itself: no such term


def test_the_ulog_reader_feeds_the_test_directly() -> None:
    # every recording gyrovib reads works: the ULog itself, steps given
    log = read_recording(str(DATA / "px4-sample.ulg"))
    result = runup(log, steps=[(1.2, 3.0), (3.2, 5.0), (5.2, 7.0), (7.2, 9.0)],
                   estimate=["k2"])
    assert len(result.steps) == 4
    assert all(math.isfinite(s.shift) for s in result.steps)


def test_a_step_where_the_vehicle_turned_is_flagged_moved(tmp_path: Path) -> None:
    # during step 4 (80–100 s) the vehicle rolls by 12.7° and back is not modelled: a
    # half-sine rate pulse of 20 deg/s peak over 1 s about x1 (∫ = 40/π deg); its mean
    # over the step, 0.64 deg/s, is far beyond the noise, and the carrier swings with it
    rng = np.random.default_rng(8)
    data, steps = simulate(rng, {"vre": 0.01})
    fs = 200.0
    a, _ = steps[4]
    k = np.arange(round(1.0 * fs))
    at = round((a + 5.0) * fs)
    data[at:at + k.size, 0] += 20.0 * np.sin(np.pi * k / k.size)
    path = tmp_path / "moved.npy"
    np.save(path, data)
    result = runup(_read(path), steps=steps, estimate=["vre"])
    assert [s.index for s in result.steps if s.moved] == [4]
    assert any("moving" in n for n in result.notes)


def test_regressors_many_decades_apart_are_solved_to_rounding() -> None:
    # ⟨x3⁴⟩ of 1e4 beside ½⟨|x3|⟩ of 1e-2: noiseless data, exact least squares
    rng = np.random.default_rng(10)
    phi = np.column_stack([1e-2 * rng.uniform(0, 1, 8), 1e4 * rng.uniform(0, 1, 8)])
    theta = np.array([0.3, 2e-7])
    y = 0.01 + phi @ theta
    fit = kernel.fit_steps(y, np.zeros(8), phi, np.full(8, 1e-8), drift=False)
    assert fit.values == pytest.approx(theta, rel=1e-9)
