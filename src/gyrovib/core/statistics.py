"""Statistics of the angular vibration reaching the sensor (docs/model.md).

The vibration about axis i is ``x_i(t)``: a sum of harmonic tones and at most
one Gaussian broadband part. Everything the error of eq. (13)-(15) needs from
it is

* ``M2 = <x3²>``, ``M4 = <x3⁴>`` and ``C3i = <x3·xi>`` (i = 1, 2), and
* ``E(Ω) = <|Ω + x3|> − |Ω|``, the rectified mean behind the asymmetry term.

Tones of different frequencies are averaged as if their phases were
independent and uniform (the brute force of docs/model.md); tones given at
the same frequency are coherent and are first added as phasors.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from gyrovib.core.transmissibility import FloatArray, Table, loglog_interp, psd_variance

SQRT_2_OVER_PI = math.sqrt(2.0 / math.pi)
#: The paper's printed multiplier of A1·a for a tone (eq. 14; docs/model.md).
PAPER_TONE_ASYMMETRY = 0.673
#: The paper's printed multiplier of A1·σ for random vibration (eq. 15).
PAPER_RANDOM_ASYMMETRY = 0.5

_MAX_GRID = 1 << 21  # phase-grid nodes per rate, for mixtures


@dataclass(frozen=True)
class Vibration:
    """The vibration at the sensor, after transmissibility.

    ``phasors``: complex amplitudes ``a_i·exp(jφ_i)`` of the tones, shape
    (K, 3), one row per distinct frequency. ``sigma``: RMS of the Gaussian part
    per axis, shape (3,). ``coherence``: ρ31, ρ32. ``has_random`` tells whether
    a random part was given at all (the paper's method needs to know).
    """

    phasors: NDArray[np.complex128]
    sigma: FloatArray
    coherence: FloatArray
    has_random: bool

    @property
    def tone_amplitudes(self) -> FloatArray:
        """Amplitude of each tone on the sensitive axis x3."""
        amps: FloatArray = np.abs(self.phasors[:, 2])
        return amps

    @property
    def m2(self) -> float:
        """``<x3²> = Σ a²/2 + σ²``."""
        a = self.tone_amplitudes
        return float(np.sum(a**2) / 2.0 + self.sigma[2] ** 2)

    @property
    def m4(self) -> float:
        """``<x3⁴> = Σ M4c + 3·[(Σ M2c)² − Σ M2c²]`` over independent components."""
        a = self.tone_amplitudes
        s2 = self.sigma[2] ** 2
        parts2 = np.append(a**2 / 2.0, s2)
        own4 = np.sum(3.0 * a**4 / 8.0) + 3.0 * s2**2
        return float(own4 + 3.0 * (np.sum(parts2) ** 2 - np.sum(parts2**2)))

    def cross(self, axis: int) -> float:
        """``C3i = <x3·xi> = Σ ½·a3·ai·cos(φ3 − φi) + ρ3i·σ3·σi`` for axis 1 or 2."""
        p = self.phasors
        tones = 0.5 * float(np.sum((p[:, 2] * np.conj(p[:, axis - 1])).real))
        return tones + float(self.coherence[axis - 1] * self.sigma[2] * self.sigma[axis - 1])


def vibration_at_sensor(
    tones: Sequence[tuple[float, ArrayLike, ArrayLike]] = (),
    *,
    psd: Sequence[Table | None] | None = None,
    rms: ArrayLike | None = None,
    coherence: ArrayLike = (1.0, 1.0),
    gains: Sequence[Table] = (),
) -> Vibration:
    """Build the vibration at the sensor from a profile's description.

    ``tones``: ``(frequency Hz, amplitude per axis, phase per axis in degrees)``.
    ``psd``: per axis a breakpoint table (rate²/Hz) or None; ``rms``: per-axis
    RMS at the sensor (no transmissibility applies); at most one of the two.
    ``gains``: the transmissibility tables ν_j(f) whose product scales a tone's
    amplitude by ν(f) and a PSD by ν(f)² (docs/model.md).
    """
    merged: dict[float, NDArray[np.complex128]] = {}
    for frequency, amplitude, phase in tones:
        amp = np.asarray(amplitude, dtype=float)
        ph = np.deg2rad(np.asarray(phase, dtype=float))
        nu = 1.0
        for gain in gains:
            nu *= float(loglog_interp(gain, frequency))
        phasor = (amp * nu) * np.exp(1j * ph)
        merged[float(frequency)] = merged.get(float(frequency), np.zeros(3, complex)) + phasor
    phasors = (
        np.array([merged[f] for f in sorted(merged)], dtype=complex)
        if merged
        else np.zeros((0, 3), dtype=complex)
    )
    if psd is not None and rms is not None:
        raise ValueError("give the random part as a PSD or as RMS values, not both")
    if psd is not None:
        sigma = np.array(
            [math.sqrt(psd_variance(t, tuple(gains))) if t is not None else 0.0 for t in psd]
        )
    elif rms is not None:
        sigma = np.asarray(rms, dtype=float).copy()
    else:
        sigma = np.zeros(3)
    return Vibration(
        phasors=phasors,
        sigma=sigma,
        coherence=np.asarray(coherence, dtype=float).copy(),
        has_random=psd is not None or rms is not None,
    )


# --------------------------------------------------------------------------- E(Ω)

_erfc_scalar = np.frompyfunc(math.erfc, 1, 1)


def _erfc(x: FloatArray) -> FloatArray:
    """math.erfc elementwise (numpy has no erf; scipy would slow start-up)."""
    out: FloatArray = np.asarray(_erfc_scalar(x), dtype=float)
    return out


def folded_normal_excess(omega: ArrayLike, sigma: float) -> FloatArray:
    """``E(Ω) = <|Ω + σZ|> − |Ω|`` for Gaussian Z (folded normal mean).

    ``<|Ω+σZ|> = σ·√(2/π)·exp(−Ω²/2σ²) + Ω·erf(Ω/(σ√2))``, written with erfc
    so that the difference keeps its precision for large |Ω|/σ.
    """
    w = np.abs(np.asarray(omega, dtype=float))
    if sigma <= 0:
        return np.zeros_like(w)
    u = w / (sigma * math.sqrt(2.0))
    out: FloatArray = sigma * SQRT_2_OVER_PI * np.exp(-(u**2)) - w * _erfc(u)
    return out


def arcsine_excess(omega: ArrayLike, a: float) -> FloatArray:
    """``E(Ω)`` for one tone ``a·sin θ``: ``(2/π)(Ω·asin(Ω/a) + √(a²−Ω²)) − |Ω|``, 0 if |Ω| ≥ a."""
    w = np.abs(np.asarray(omega, dtype=float))
    if a <= 0:
        return np.zeros_like(w)
    r = np.minimum(w / a, 1.0)
    inside = (2.0 / math.pi) * (w * np.arcsin(r) + a * np.sqrt(1.0 - r * r)) - w
    out: FloatArray = np.where(w < a, inside, 0.0)
    return out


def _phase_nodes(n: int) -> FloatArray:
    """``sin`` of ``n`` equally spaced phases (trapezoidal rule on a period).

    The values to average with equal weights: when 4 divides ``n`` each value
    occurs twice (θ and π − θ), so only the ``n/2`` distinct ones are returned,
    ``±sin θ_k`` for the first quarter period; the mean is the same.
    """
    if n % 4 == 0:
        quarter: FloatArray = np.sin(2.0 * math.pi * (np.arange(n // 4) + 0.5) / n)
        return np.concatenate([quarter, -quarter])
    nodes: FloatArray = np.sin(2.0 * math.pi * (np.arange(n) + 0.5) / n)
    return nodes


def _tone_grid(amplitudes: FloatArray, counts: Sequence[int]) -> FloatArray:
    """All sums ``Σ a_k·sin θ_k`` over the product grid of phases."""
    total = np.zeros(1)
    for a, n in zip(amplitudes, counts, strict=True):
        total = (total[:, None] + a * _phase_nodes(n)[None, :]).ravel()
    return total


def rectified_excess(omega: ArrayLike, amplitudes: ArrayLike, sigma: float) -> FloatArray:
    """``E(Ω) = <|Ω + x3|> − |Ω|`` for tones of ``amplitudes`` plus Gaussian ``sigma``.

    One component: the closed forms. Several: the mean over the tones' phases
    (trapezoidal rule, exact for trigonometric polynomials and spectrally
    convergent for the smooth integrands here) of

    * the folded-normal mean, when ``sigma > 0``: ``ceil(8a/σ) + 32`` nodes per
      tone make the error ~1e-12 of σ;
    * the one-tone arcsine mean of the largest tone, for tones alone.
    """
    w = np.abs(np.atleast_1d(np.asarray(omega, dtype=float)))
    a = np.asarray(amplitudes, dtype=float)
    a = np.sort(a[a > 0])[::-1]
    if a.size == 0:
        return folded_normal_excess(w, sigma)
    if sigma <= 0 and a.size == 1:
        return arcsine_excess(w, float(a[0]))
    if sigma > 0:
        counts = [math.ceil(8.0 * ak / sigma) + 32 for ak in a]
        grid_amps = a
    else:
        per_tone = {1: 4096, 2: 512}.get(a.size - 1, 96)
        counts = [per_tone] * (a.size - 1)
        grid_amps = a[1:]
    total = math.prod(counts)
    if total > _MAX_GRID:
        shrink = (_MAX_GRID / total) ** (1.0 / len(counts))
        counts = [max(16, int(n * shrink)) for n in counts]
    shifts = _tone_grid(grid_amps, counts)
    out = np.empty_like(w)
    chunk = max(1, (1 << 22) // shifts.size)
    for start in range(0, w.size, chunk):
        y = np.abs(w[start : start + chunk, None] + shifts[None, :])
        if sigma > 0:
            excess = folded_normal_excess(y, sigma) + y
        else:
            excess = arcsine_excess(y, float(a[0])) + y
        out[start : start + chunk] = excess.mean(axis=1) - w[start : start + chunk]
    result: FloatArray = out
    return result
