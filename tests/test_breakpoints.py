"""The breakpoint fit of a recording's random PSD and its shape figures (docs/model.md
section 13, gyrovib.core.breakpoints): optimal knots, the variance held, the shape held
on spectra of every kind (plateaus, resonances, roll-offs, random shapes, a real log)."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gyrovib.core.breakpoints import (
    anchor_levels,
    candidate_knots,
    fit_breakpoints,
    optimal_knots,
    pair_costs,
    shape_figures,
)
from gyrovib.core.transmissibility import loglog_interp, psd_variance

#: The acceptance figures of a breakpoint fit: within 2 dB power-weighted, at most 20 % of the
#: power off by more than 3 dB.
SHAPE_DB, OFF_3DB = 2.0, 0.2


def _anchored_error(x: np.ndarray, z: np.ndarray, w: np.ndarray, cand: np.ndarray,
                    anchors: np.ndarray, knots: tuple[int, ...]) -> float:
    """E of the chain of anchored lines through ``knots``, written out with np.interp."""
    line = np.interp(x, x[cand[list(knots)]], anchors[list(knots)])
    return float(np.sum(w * (line - z) ** 2))


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_the_programme_is_the_brute_force_optimum(seed: int) -> None:
    """On a tiny grid (12 candidates) the dynamic programme's knots and error equal those
    of a brute-force search over every subset of candidates with both ends kept."""
    rng = np.random.default_rng(seed)
    f = np.arange(1.0, 61.0)
    psd = np.exp(rng.normal(0.0, 1.5, f.size)) * (1 + 30 * np.exp(-((f - 25) / 3) ** 2))
    x, z = np.log(f), np.log(psd)
    w = psd / psd.sum() + 1e-3 / f.size
    cand = candidate_knots(f, psd, count=12)
    anchors = anchor_levels(x, z, cand)
    cost = pair_costs(x, z, w, cand, anchors)
    last = w[-1] * (anchors[-1] - z[-1]) ** 2  # the last bin: in no pair's half-open span
    k = cand.size
    for count in (2, 3, 4, 5):
        chosen, value = optimal_knots(cost, count)
        brute = min(((0, *inner, k - 1) for inner in itertools.combinations(range(1, k - 1),
                                                                            count - 2)),
                    key=lambda knots: _anchored_error(x, z, w, cand, anchors, knots))
        assert tuple(chosen.tolist()) == brute
        assert value + last == pytest.approx(
            _anchored_error(x, z, w, cand, anchors, brute), rel=1e-9)


def test_shape_figures_by_hand() -> None:
    """Four bins of equal power; the fit doubles two of them (+3.0103 dB) and is exact on
    the others: shape_db = 3.0103/2, off_3db = 1/2. A fit of 1.9× is not off by 3 dB."""
    f = np.array([10.0, 20.0, 40.0, 80.0])
    s = np.ones(4)
    table = (f, np.array([1.0, 1.0, 2.0, 2.0]))
    db, off = shape_figures(f[[0, 1, 3]], s[[0, 1, 3]], table)
    assert (db, off) == pytest.approx((10 * np.log10(2) / 3, 1 / 3))
    table = (f, np.array([1.0, 1.0, 1.0, 1.9]))
    assert shape_figures(f, s, table) == pytest.approx((10 * np.log10(1.9) / 4, 0.0))
    assert all(np.isnan(shape_figures(f, s, None)))


def _welch_like(rng: np.random.Generator, true: np.ndarray, windows: int = 60) -> np.ndarray:
    """A Welch estimate's scatter: the true PSD times χ²(2·windows)/(2·windows)."""
    return true * rng.chisquare(2 * windows, true.size) / (2 * windows)


def _plateau_resonance(f: np.ndarray, fs: float) -> np.ndarray:
    """The synthetic reference spectrum: a plateau 2–150 Hz, a resonance at 80 Hz that holds
    most of the power, and an anti-alias roll-off from 0.42·fs."""
    plateau = 0.01 / (1 + (2 / f) ** 8) / (1 + (f / 150) ** 8)
    resonance = 0.3 / (1 + ((f - 80) / 2) ** 2)
    return (plateau + resonance) / (1 + (f / (0.42 * fs)) ** 16)


@pytest.mark.parametrize("fs", [1000.0, 250.0])
def test_plateau_resonance_and_roll_off(fs: float) -> None:
    """The shape holds (SHAPE_DB, OFF_3DB), the resonance is a peak of the random PSD with
    knots on both sides, the roll-off (≈ 1e-6 of the power) takes no knot but the band's
    end, and the variance is held exactly (Σ S·Δf of the bins)."""
    rng = np.random.default_rng(int(fs))
    df = 0.5
    f = np.arange(5.0, fs / 2, df)  # f_c = 5 Hz … below the Nyquist bin
    psd = _welch_like(rng, _plateau_resonance(f, fs))
    table = fit_breakpoints(f, psd, 12)
    db, off = shape_figures(f, psd, table)
    assert db <= SHAPE_DB and off <= OFF_3DB
    knots = table[0]
    assert knots[0] == f[0] and knots[-1] == f[-1]
    assert np.any((knots > 70) & (knots < 80)) and np.any((knots > 80) & (knots < 90))
    peak = float(loglog_interp(table, np.array([80.0]), hold=False)[0])
    assert 10 * np.log10(peak / _plateau_resonance(np.array([80.0]), fs)[0]) == \
        pytest.approx(0.0, abs=3.0)
    assert np.sum(knots > 0.42 * fs) <= 2
    assert psd_variance(table) == pytest.approx(float(np.sum(psd) * df), rel=1e-9)


@settings(max_examples=8)
@given(st.integers(min_value=0, max_value=2**32 - 1))
def test_random_shapes_hold(seed: int) -> None:
    """Spectra drawn at random from a seeded generator: a log-log outline of 2–8 levels over
    60 dB, 0–3 resonances (Q 3–100, up to 30 dB), an anti-alias roll-off of order 4–32,
    sampled at 200–2000 Hz and scattered as a 60-window Welch estimate: 12 breakpoints
    hold the shape within SHAPE_DB and OFF_3DB and the variance exactly."""
    rng = np.random.default_rng(seed)
    fs = float(rng.choice([200.0, 250.0, 500.0, 1000.0, 2000.0]))
    f = np.arange(2.0, fs / 2, 0.5)
    outline = np.sort(np.exp(rng.uniform(np.log(2.0), np.log(fs / 2), rng.integers(2, 9))))
    true = 10 ** np.interp(np.log(f), np.log(outline), rng.uniform(-6, 0, outline.size))
    for _ in range(rng.integers(0, 4)):
        fr = np.exp(rng.uniform(np.log(8.0), np.log(0.45 * fs)))
        q = 10 ** rng.uniform(0.5, 2.0)
        true += np.median(true) * 10 ** rng.uniform(0, 3) / (1 + ((f - fr) / (fr / q / 2)) ** 2)
    true /= 1 + (f / (rng.uniform(0.3, 0.49) * fs)) ** int(rng.choice([4, 8, 16, 32]))
    psd = _welch_like(rng, true)
    table = fit_breakpoints(f, psd, 12)
    db, off = shape_figures(f, psd, table)
    assert db <= SHAPE_DB and off <= OFF_3DB, (db, off)
    assert psd_variance(table) == pytest.approx(float(np.sum(psd) * 0.5), rel=1e-9)


def test_zero_bins_are_left_out_and_two_bins_are_needed() -> None:
    """Bins with S ≤ 0 carry nothing and are not fitted (the fit ends at the last positive
    bin, 10 Hz, and holds Σ S·Δf = 10 of the ten positive bins); fewer than two positive
    bins is a model error."""
    from gyrovib.errors import ModelError

    f = np.arange(1.0, 21.0)
    psd = np.where(f > 10, 0.0, 1.0)
    table = fit_breakpoints(f, psd, 4)
    assert table[0][0] == 1.0 and table[0][-1] == 10.0
    assert psd_variance(table) == pytest.approx(10.0, rel=1e-9)
    with pytest.raises(ModelError, match="fewer than two positive"):
        fit_breakpoints(f, np.where(f == 3, 1.0, 0.0), 4)
