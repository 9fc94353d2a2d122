"""Records of known noise terms (docs/model.md section 15): the rate
(deg/s) of a gyro at rest whose Allan variance is IEEE Std 952's five terms and a
first-order Gauss–Markov bias. The parametric bootstrap of :mod:`gyrovib.core.allan_fit`
draws from it; the coverage study (benchmarks/bench_allan_coverage.py) and the tests
simulate their truths with it. Each part, at interval τ0 (s):

* quantization Q (deg): angle white noise e_k of standard deviation Q, the rate
  (e_{k+1} − e_k)/τ0, so σ²(τ) = 3Q²/τ²;
* angle random walk N (deg/√s): white rate noise of standard deviation N/√τ0,
  σ²(τ) = N²/τ;
* bias instability B (deg/s): flicker rate noise, white noise of standard deviation B
  through the fractional-integration filter h_0 = 1, h_j = h_{j−1}·(j − ½)/j (Kasdin
  1995), whose one-sided spectrum B²/(π f) far below 1/τ0 gives the floor
  σ² = (2 ln 2/π)·B²;
* rate random walk K (deg/s/√s): the sum of steps of standard deviation K·√τ0,
  σ²(τ) = K²τ/3;
* rate ramp R (deg/s²): the line R·t, σ²(τ) = R²τ²/2;
* Gauss–Markov (σ_GM deg/s, τ_c s): y_k = φ·y_{k−1} + √(1 − φ²)·σ_GM·w_k,
  φ = exp(−τ0/τ_c), started in its stationary state.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from gyrovib.core._types import FloatArray


@dataclass(frozen=True, slots=True)
class Truth:
    """The terms of a simulated record, in the kernel's units (deg, deg/√s, deg/s,
    deg/s/√s, deg/s², and σ_GM deg/s with τ_c s); 0 leaves a term out."""

    quantization: float = 0.0
    arw: float = 0.0
    bias_instability: float = 0.0
    rrw: float = 0.0
    rate_ramp: float = 0.0
    gm_sigma: float = 0.0
    gm_tau: float = 0.0


@functools.lru_cache(maxsize=4)
def _flicker_filter(n: int) -> tuple[int, NDArray[np.complex128]]:
    """The FFT size and the transform of h_0 … h_{n−1} (one per length: the bootstrap
    draws many records of one length)."""
    j = np.arange(1, n, dtype=float)
    h = np.empty(n)
    h[0] = 1.0
    h[1:] = np.cumprod((j - 0.5) / j)
    size = 1 << (2 * n - 1).bit_length()
    return size, np.fft.rfft(h, size)


def flicker(n: int, scale: float, rng: np.random.Generator) -> FloatArray:
    """n samples of flicker noise: white noise of standard deviation ``scale`` through
    the filter h_j (linear convolution by FFT, zero-padded to twice the length)."""
    size, h = _flicker_filter(n)
    w = rng.standard_normal(n) * scale
    out: FloatArray = np.fft.irfft(np.fft.rfft(w, size) * h, size)[:n]
    return out


def gauss_markov(n: int, sigma: float, tau_c: float, tau0: float,
                 rng: np.random.Generator) -> FloatArray:
    """A stationary first-order Gauss–Markov sequence (see the module docstring)."""
    # lazy: scipy only where a Gauss–Markov term is simulated
    from scipy.signal import lfilter

    phi = math.exp(-tau0 / tau_c)
    w = rng.standard_normal(n) * sigma * math.sqrt(1.0 - phi * phi)
    w[0] = rng.standard_normal() * sigma
    out: FloatArray = lfilter([1.0], [1.0, -phi], w)
    return out


def simulate(truth: Truth, n: int, tau0: float, rng: np.random.Generator) -> FloatArray:
    """n rate samples (deg/s) at interval ``tau0`` of a record with ``truth``'s terms."""
    y = np.zeros(n)
    if truth.quantization > 0:
        e = rng.standard_normal(n + 1) * truth.quantization
        y += np.diff(e) / tau0
    if truth.arw > 0:
        y += rng.standard_normal(n) * (truth.arw / math.sqrt(tau0))
    if truth.bias_instability > 0:
        y += flicker(n, truth.bias_instability, rng)
    if truth.rrw > 0:
        y += np.cumsum(rng.standard_normal(n)) * (truth.rrw * math.sqrt(tau0))
    if truth.rate_ramp > 0:
        y += truth.rate_ramp * tau0 * np.arange(n)
    if truth.gm_sigma > 0 and truth.gm_tau > 0:
        y += gauss_markov(n, truth.gm_sigma, truth.gm_tau, tau0, rng)
    return y


__all__ = ["Truth", "flicker", "gauss_markov", "simulate"]
