"""The overlapping Allan deviation kernel (core/allan.py), its streamed form for records
too long to hold (core/allan_stream.py), and published reference values."""

import io
import math

import numpy as np
import pytest

from gyrovib.core.allan import oadev, tau_grid
from gyrovib.core.allan_stream import oadev_scratch, octave_grid, write_angle


def naive_oadev(y: np.ndarray, tau0: float, m: int) -> float:
    """IEEE 952 overlapping Allan deviation from cluster averages, written out directly:
    σ² = Σ_k (ȳ_{k+m} − ȳ_k)² / (2(n + 1 − 2m)), ȳ_k the mean of y[k:k+m]."""
    n = y.size
    means = np.array([y[k:k + m].mean() for k in range(n - m + 1)])
    d = means[m:] - means[:-m]
    return math.sqrt(float(np.sum(d * d)) / (2.0 * (n + 1 - 2 * m)))


def test_grid_spans_tau0_to_a_third_with_ten_per_decade() -> None:
    m = tau_grid(30_000)
    assert m[0] == 1 and m[-1] == 10_000          # τ0 … n·τ0/3
    assert np.all(np.diff(m) > 0)
    assert np.sum(m >= 10) >= 30                   # three decades above m = 10: ≥ 10 each


@pytest.mark.parametrize("seed", [1, 2])
def test_equals_an_independent_estimator_at_every_tau(seed: int) -> None:
    g = np.random.default_rng(seed)
    n = 1500
    # white noise + a random walk + a large offset: the offset must not cost digits
    y = 40.0 + g.standard_normal(n) + np.cumsum(g.standard_normal(n)) * 0.05
    tau, adev = oadev(y, 0.02, block=97)           # a small block: several blocks per τ
    assert tau[0] == 0.02
    for t, a in zip(tau, adev, strict=True):
        m = round(t / 0.02)
        assert a == pytest.approx(naive_oadev(y, 0.02, m), rel=1e-6)


def test_equals_allantools() -> None:
    allantools = pytest.importorskip("allantools")
    y = np.random.default_rng(5).standard_normal(4000)
    tau, adev = oadev(y, 0.01)
    taus, ad, _, _ = allantools.oadev(y, rate=100.0, data_type="freq",
                                      taus=tau)
    assert np.allclose(taus, tau) and np.allclose(ad, adev, rtol=1e-6, atol=0)


# NIST SP 1065 (Riley, Handbook of Frequency Stability Analysis), tables 30 and 31: the
# overlapping Allan deviation of the NBS14 data sets, to the digits printed there.
NBS9 = [892.0, 809.0, 823.0, 798.0, 671.0, 644.0, 883.0, 903.0, 677.0]
NBS9_OADEV = {1: 91.22945, 2: 85.95287}
NBS1000_OADEV = {1: 2.922319e-01, 10: 9.159953e-02, 100: 3.241343e-02}


def nbs1000() -> np.ndarray:
    """The 1000-point NBS14 frequency series: the Lehmer generator n_{i+1} = 16807·n_i
    mod (2³¹ − 1) from n_1 = 1234567890, each divided by 2³¹ − 1 (SP 1065 section 12.3)."""
    n = [1234567890]
    for _ in range(999):
        n.append(16807 * n[-1] % 2147483647)
    return np.array(n, dtype=float) / 2147483647.0


@pytest.mark.parametrize(("data", "table"), [(NBS9, NBS9_OADEV), (None, NBS1000_OADEV)])
def test_nbs14_to_the_printed_digits(data: list[float] | None,
                                     table: dict[int, float]) -> None:
    y = np.array(data) if data is not None else nbs1000()
    m = np.array(sorted(table), dtype=np.int64)
    _, adev = oadev(y, 1.0, m)
    for mm, a in zip(m.tolist(), adev, strict=True):
        printed = table[mm]
        digits = 7 if printed < 1 else 7 - len(str(int(printed)))  # 7 significant figures
        assert round(float(a), digits) == pytest.approx(printed, abs=0.5 * 10.0 ** -digits)
    allantools = pytest.importorskip("allantools")   # and allantools on the same samples
    _, ad, _, _ = allantools.oadev(y, rate=1.0, data_type="freq", taus=m.astype(float))
    assert np.allclose(ad, adev, rtol=1e-12, atol=0)


def _streamed(y: np.ndarray, tau0: float, m: np.ndarray, rows: int) -> np.ndarray:
    scratch = io.BytesIO()
    write_angle(lambda a, b: y[a:b].astype(np.float64), y.shape[0], y.shape[1], tau0,
                scratch, rows)
    return oadev_scratch(scratch, y.shape[0], y.shape[1], tau0, m, rows)


@pytest.mark.parametrize("rows", [64, 1000])
def test_streamed_equals_allantools_to_1e9(rows: int) -> None:
    # small blocks so that every path runs several times: the sliding window (2m < rows)
    # and the chains k, k + m, k + 2m (m ≥ rows/2, m a multiple of the block or not)
    allantools = pytest.importorskip("allantools")
    g = np.random.default_rng(8)
    n = 20_001
    y = (g.standard_normal((n, 3)) + np.cumsum(g.standard_normal((n, 3)), axis=0) * 0.02
         ).astype(np.float32)                         # a float32 log, as a day-long .npy
    m = np.unique(np.concatenate([tau_grid(n, 7), octave_grid(n)]))
    curves = _streamed(y, 0.001, m, rows)
    for k in range(3):
        _, ad, _, _ = allantools.oadev(y[:, k].astype(np.float64), rate=1000.0,
                                       data_type="freq", taus=m * 0.001)
        assert np.max(np.abs(curves[:, k] / ad - 1.0)) < 1e-9


def test_octave_grid_is_powers_of_two_to_a_third() -> None:
    assert octave_grid(100).tolist() == [1, 2, 4, 8, 16, 32]
    assert octave_grid(86_400_000)[-1] == 1 << 24        # 16.8 M ≤ 28.8 M < 2²⁵
