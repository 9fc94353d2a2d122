"""The noise model of an Allan deviation curve (core/allan_edf.py, core/allan_fit.py,
core/allan_sim.py): EDF and χ² intervals against allantools, the five terms with their
intervals or bounds on records of known terms, a filter's roll-off, a curve the model
does not fit, and the intervals' coverage at a small scale (the full study is
benchmarks/bench_allan_coverage.py)."""

import math

import numpy as np
import pytest

from gyrovib.core.allan import oadev, tau_grid
from gyrovib.core.allan_edf import confidence_interval, edf_one
from gyrovib.core.allan_fit import (
    TERMS,
    Curve,
    bootstrap,
    fit,
    gm_basis,
    noise_model,
    pivot,
    resolution,
    roll_off,
    studentized,
)
from gyrovib.core.allan_levels import read_level
from gyrovib.core.allan_sim import Truth, simulate

ALPHAS = (2, 1, 0, -1, -2)


def test_edf_equals_allantools_greenhall() -> None:
    allantools = pytest.importorskip("allantools")
    checked = 0
    for points in (31, 101, 1001, 20_001, 1_000_001):
        for m in (1, 2, 3, 5, 10, 33, 34, 50, 100, 300, 1000, 3000, 100_000):
            if points - 2 * m < 2:
                continue
            for alpha in ALPHAS:
                try:
                    ref = allantools.edf_greenhall(alpha=alpha, d=2, m=m, N=points,
                                                   overlapping=True, modified=False)
                except NotImplementedError:    # α = 2 with M ≤ 2m: the paper's own gap
                    continue
                assert edf_one(alpha, m, points) == pytest.approx(max(ref, 1.0), rel=1e-9)
                checked += 1
    assert checked > 200


def test_chi2_interval_equals_allantools() -> None:
    allantools = pytest.importorskip("allantools")
    for dev, nu, c in ((1.0, 3.5, 0.68), (2.5, 40.0, 0.95), (0.1, 1e4, 0.5)):
        lo, hi = confidence_interval(np.array([dev]), np.array([nu]), c)
        ref = allantools.confidence_interval(dev, nu, ci=c)
        assert (lo[0], hi[0]) == pytest.approx(ref, rel=1e-12)


def test_gauss_markov_basis_limits() -> None:
    # x = τ/τ_c → 0: 2x/3 (a random walk, K² = 2σ²/τ_c); x → ∞: 2/x (white, N² = 2σ²τ_c)
    assert gm_basis(np.array([1e-6]), 1.0)[0] == pytest.approx(2e-6 / 3, rel=1e-6)
    assert gm_basis(np.array([1e-3]), 1.0)[0] == pytest.approx(
        2 * (1 - (1 - math.exp(-1e-3)) * (3 - math.exp(-1e-3)) / 2e-3) / 1e-3, rel=1e-6)
    assert gm_basis(np.array([1e6]), 1.0)[0] == pytest.approx(2e-6, rel=1e-5)


def _model(truth: Truth, n: int, tau0: float, seed: int, **kw: object):  # type: ignore[no-untyped-def]
    y = simulate(truth, n, tau0, np.random.default_rng(seed))
    m = tau_grid(n)
    tau, adev = oadev(y, tau0, m)
    return noise_model(tau, adev, m, n, tau0, **kw)  # type: ignore[arg-type]


def _covers(term, truth: float, level: int = 1) -> bool:  # type: ignore[no-untyped-def]
    lo, hi = term.intervals[level]
    return bool(lo <= truth <= hi)


def test_a_four_hour_log_with_flicker_gives_n_and_b_in_their_intervals() -> None:
    # 4 h at 10 Hz of N = 0.1 deg/√h and B = 1 deg/h (the case): 144 000 samples,
    # so the shortened bootstrap of long records (k = 5), on seeds 41–43. Over 100 seeds
    # (0–99) of this record the fit's B scatters by 6.2 % and N by 0.32 % (measured); N's
    # scatter is two populations: where the fit puts a little quantization (47 seeds)
    # N comes out 0.26 % low, where it puts none 0.13 % high, and the bootstrap of a fit
    # with none reproduces the first population in its replicates but not the second's
    # offset, so N's 95 % interval is a little narrow here (about 0.25 % a side at 68 %
    # against the 0.32 % scatter): on seed 42 it misses by 0.01 % of N
    # (docs/error-budget.md, section 5). B's holds on all three, N's on two of three.
    truth = Truth(arw=0.1 / 60, bias_instability=1 / 3600)
    n_held = 0
    for seed in (41, 42, 43):
        model = _model(truth, 144_000, 0.1, seed=seed)
        arw, bias = model.terms[1], model.terms[2]
        assert arw.resolved and bias.resolved
        assert _covers(bias, truth.bias_instability)
        n_held += _covers(arw, truth.arw)
        # and the terms the record does not hold are bounds, never values of 0
        for k in (3, 4):
            assert not model.terms[k].resolved and model.terms[k].bound > 0
    assert n_held >= 2


def test_white_noise_gives_k_as_a_bound_that_holds() -> None:
    truth = Truth(arw=0.2 / 60)
    model = _model(truth, 50_000, 0.1, seed=3)
    rrw = model.terms[TERMS.index("rrw")]
    assert not rrw.resolved and rrw.value is None
    # the bound is real: a K of twice the bound would show in the curve's last points
    assert rrw.bound is not None and 0 < rrw.bound < 5e-4


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_n_is_not_read_on_a_20_hz_roll_off(seed: int) -> None:
    scipy_signal = pytest.importorskip("scipy.signal")
    fs, n_true = 200.0, 0.1 / 60
    y = np.random.default_rng(seed).standard_normal(int(fs * 3600)) * n_true * math.sqrt(fs)
    y = scipy_signal.sosfilt(scipy_signal.butter(4, 20.0, fs=fs, output="sos"), y)
    m = tau_grid(y.size)
    tau, adev = oadev(y, 1 / fs, m)
    model = noise_model(tau, adev, m, y.size, 1 / fs)
    assert model.start > 0 and tau[model.start] > 1 / 20   # the roll-off left out
    arw = model.terms[1]
    # N within its 95 % interval. Past the roll-off the filter's tail is fitted beside N,
    # which costs N precision: over seeds 100–129 its fit scattered by 1.2 % about the
    # truth (mean +0.07 %; measured), against 0.09 % on the same noise unfiltered, so
    # the 68 % interval must be about that wide — the earlier bootstrap, whose
    # replicates held the filter's column at 0, gave a third of it and missed on seed 3
    assert arw.resolved and _covers(arw, n_true)
    lo, hi = arw.intervals[0]
    assert 0.006 < (hi - lo) / 2 / n_true < 0.02
    # read on the roll-off (the first point, N = σ·√τ) it would be far too small
    assert adev[0] * math.sqrt(tau[0]) < 0.5 * n_true


def test_a_vibration_the_model_cannot_hold_is_a_misfit() -> None:
    n, tau0 = 60_000, 0.1
    y = simulate(Truth(arw=0.1 / 60), n, tau0, np.random.default_rng(9))
    y += 0.05 * np.sin(2 * math.pi * 0.013 * tau0 * np.arange(n))   # a 77 s oscillation
    m = tau_grid(n)
    tau, adev = oadev(y, tau0, m)
    model = noise_model(tau, adev, m, n, tau0)
    assert model.misfit.size > tau.size // 10


@pytest.mark.parametrize("sim_cap", [1 << 15, 1 << 11])
def test_coverage_at_a_small_scale(sim_cap: int) -> None:
    # 12 records of white noise and flicker (seeds unseen by the benchmark): N's 95 %
    # interval must hold the truth in 10 of 12 at least (P ≈ 0.98 at 95 % coverage), its
    # 68 % interval in 4 to 11 (P ≈ 0.95 at 68 %); B's 95 % in 9 at least, over those
    # resolved. An interval of zero width, or one a mile wide, fails. With sim_cap 2¹¹
    # the 2¹⁴-sample records take the shortened bootstrap of long records (k = 8).
    truth = Truth(arw=0.1 / 60, bias_instability=1 / 3600)
    held = {"arw": [0, 0, 0], "bias_instability": [0, 0, 0]}
    for seed in range(500, 512):
        model = _model(truth, 1 << 14, 1.0, seed, replicates=100, sim_cap=sim_cap)
        for name in held:
            term = model.terms[TERMS.index(name)]
            if term.resolved:
                true = getattr(truth, name)
                held[name][0] += 1
                held[name][1] += _covers(term, true, 0)
                held[name][2] += _covers(term, true, 1)
                lo, hi = term.intervals[1]
                assert 0.001 < (hi - lo) / true < 5.0
    assert held["arw"][0] == 12 and held["arw"][2] >= 10 and 4 <= held["arw"][1] <= 11
    resolved, _, b95 = held["bias_instability"]
    assert resolved >= 8 and b95 >= resolved - 3


def test_a_term_alone_in_its_model_gets_the_pivot_interval() -> None:
    # White noise alone: the fit's information gives N² a standard error proportional to
    # N² (every weight is ν/(2·(N²/τ)²)), so inverting (ĉ − c)/s(c) between the
    # replicates' quantiles of (c* − ĉ)/s(ĉ) gives ĉ/r_hi … ĉ/r_lo, r = c*/ĉ: the ratio
    # pivot, by algebra. The same replicates (noise_model's: bootstrap seed 0) must give
    # the same interval from the studentized root itself (not its fallback to the pivot),
    # the pivot read at the levels the studentized root is read at (core/allan_levels).
    n, tau0 = 20_000, 0.1
    model = _model(Truth(arw=0.2 / 60), n, tau0, seed=4)
    y = simulate(Truth(arw=0.2 / 60), n, tau0, np.random.default_rng(4))
    m = tau_grid(n)
    tau, adev = oadev(y, tau0, m)
    assert roll_off(tau, adev) == 0
    fitted = fit(tau, adev ** 2, m, n + 1)
    coefs = bootstrap(fitted, tau, m, n, tau0)
    curve = Curve(tau, adev ** 2, m, n + 1, fitted)
    levels = (read_level(1, 0.68), read_level(1, 0.95))
    own = studentized(curve, 1, coefs, resolution(fitted, tau, coefs), levels)
    ratio = pivot(math.sqrt(fitted.coef[1]), 1, coefs, levels)
    assert model.terms[1].resolved and None not in own
    assert model.terms[1].intervals == tuple(own)
    for got, ref in zip(own, ratio, strict=True):
        assert got == pytest.approx(ref, rel=1e-6)
