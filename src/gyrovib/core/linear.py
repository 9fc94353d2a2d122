"""Linear vibration and the g² rectification term Δ0(6) (docs/model.md section 8).

The specific force along the sensor axes, ``a_j(t)`` (j = 1, 2, 3, unit g),
is a sum of tones of distinct frequencies (per-axis amplitude A_j and phase
φ_j) and a Gaussian part (per-axis σ_j, coherences ρ12, ρ13, ρ23). The
quadratic acceleration terms of the conversion function rectify:

    Δ0(6) = Σ_j G_jj·⟨a_j²⟩ + Σ_{j<k} G_jk·⟨a_j·a_k⟩

    ⟨a_j²⟩    = Σ_tones A_j²/2 + σ_j²
    ⟨a_j·a_k⟩ = Σ_tones ½·A_j·A_k·cos(φ_j − φ_k) + ρ_jk·σ_j·σ_k

Both the six second moments and the six sensitivities are ordered as
:data:`G2_TERMS`: (11, 22, 33, 12, 13, 23). G is in rate/g², so Δ0(6) is in
rate units.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from gyrovib.core._types import FloatArray
from gyrovib.frozen import Frozen

#: Order of the g²-sensitivities G_jk and of the second moments ⟨a_j·a_k⟩.
G2_TERMS: tuple[str, ...] = ("G11", "G22", "G33", "G12", "G13", "G23")
#: Axis pairs (0-based) of :data:`G2_TERMS`.
PAIRS: tuple[tuple[int, int], ...] = ((0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2))


def acceleration_moments(
    amplitudes: ArrayLike,
    phases: ArrayLike,
    sigma: ArrayLike,
    coherence: ArrayLike = (0.0, 0.0, 0.0),
) -> FloatArray:
    """The six second moments ⟨a_j·a_k⟩ of a linear vibration (docs/model.md section 8).

    ``amplitudes``: (..., K, 3) tone amplitudes per axis in g (K may be 0);
    ``phases``: (..., K, 3) in degrees; ``sigma``: (..., 3) Gaussian RMS per
    axis in g; ``coherence``: (..., 3) ρ12, ρ13, ρ23 (default 0: independent
    axes). Leading dimensions (profiles, ...) broadcast. Returns (..., 6) in g²,
    ordered as :data:`G2_TERMS`.
    """
    amp = np.asarray(amplitudes, dtype=float)
    ph = np.deg2rad(np.asarray(phases, dtype=float))
    s = np.asarray(sigma, dtype=float)
    rho = np.asarray(coherence, dtype=float)
    if amp.shape[-1:] != (3,) or amp.ndim < 2 or ph.shape[-1:] != (3,) or ph.ndim < 2:
        raise ValueError("tone amplitudes and phases must have shape (..., K, 3)")
    if s.shape[-1:] != (3,) or rho.shape[-1:] != (3,):
        raise ValueError("sigma and coherence must have shape (..., 3)")
    if not (np.all(np.isfinite(amp)) and np.all(np.isfinite(ph)) and np.all(np.isfinite(s))
            and np.all(np.isfinite(rho))):
        raise ValueError("linear-vibration values must be finite")
    if np.any(s < 0) or np.any(np.abs(rho) > 1):
        raise ValueError("sigma must be ≥ 0 and every coherence within [-1, 1]")
    amp, ph = np.broadcast_arrays(amp, ph)
    p = amp * np.exp(1j * ph)  # (..., K, 3) phasors
    rho_of = {(0, 1): rho[..., 0], (0, 2): rho[..., 1], (1, 2): rho[..., 2]}
    out = []
    for j, k in PAIRS:
        tones = 0.5 * np.sum((p[..., j] * np.conj(p[..., k])).real, axis=-1)
        coh = 1.0 if j == k else rho_of[(j, k)]
        out.append(tones + coh * s[..., j] * s[..., k])
    moments: FloatArray = np.stack(np.broadcast_arrays(*out), axis=-1)
    return moments


def g2_term(sensitivity: ArrayLike, moments: ArrayLike) -> FloatArray:
    """Δ0(6) = Σ G_jk·⟨a_j·a_k⟩ for every sensor × profile (docs/model.md section 8).

    ``sensitivity``: (sensors, 6) G in rate/g², order :data:`G2_TERMS`;
    ``moments``: (..., 6) in g² from :func:`acceleration_moments` (profiles,
    or profiles × rates). Returns (sensors, ...) in rate units.
    """
    g = np.asarray(sensitivity, dtype=float)
    m = np.asarray(moments, dtype=float)
    if g.ndim != 2 or g.shape[1] != 6 or m.shape[-1:] != (6,):
        raise ValueError("sensitivity must be (sensors, 6) and moments (..., 6)")
    expand = (slice(None),) + (None,) * (m.ndim - 1) + (slice(None),)
    out: FloatArray = np.sum(g[expand] * m[None], axis=-1)
    return out


def mean_square(moments: ArrayLike) -> FloatArray:
    """Σ_j ⟨a_j²⟩ (g²), the denominator of the effective VRE: shape (...,) of (..., 6)."""
    m = np.asarray(moments, dtype=float)
    out: FloatArray = m[..., 0] + m[..., 1] + m[..., 2]
    return out


def effective_vre(sensitivity: ArrayLike, moments: ArrayLike) -> FloatArray:
    """|Δ0(6)| / Σ_j⟨a_j²⟩ (rate/g²), (sensors, ...); 0 where there is no linear vibration."""
    num = np.abs(g2_term(sensitivity, moments))
    den = np.broadcast_to(mean_square(moments)[None], num.shape)
    out: FloatArray = np.zeros(num.shape)
    np.divide(num, den, out=out, where=den > 0)
    return out


@dataclass(frozen=True, eq=False, repr=False)
class LinearVibration(Frozen):
    """A linear vibration at the sensor's axes, in g (docs/model.md section 8).

    ``amplitudes`` (K, 3) and ``phases`` (K, 3, degrees) of tones of distinct
    frequencies; ``sigma`` (3,) Gaussian RMS per axis; ``coherence`` (3,)
    ρ12, ρ13, ρ23. Build it with :func:`linear_vibration`.
    """

    amplitudes: FloatArray
    phases: FloatArray
    sigma: FloatArray
    coherence: FloatArray

    def moments(self) -> FloatArray:
        """The six ⟨a_j·a_k⟩ (g²), :func:`acceleration_moments`."""
        return acceleration_moments(self.amplitudes, self.phases, self.sigma, self.coherence)

    def covariance(self) -> FloatArray:
        """(3, 3) covariance of the Gaussian part, ρ_jk·σ_j·σ_k (g²)."""
        rho = np.eye(3)
        rho[0, 1] = rho[1, 0] = self.coherence[0]
        rho[0, 2] = rho[2, 0] = self.coherence[1]
        rho[1, 2] = rho[2, 1] = self.coherence[2]
        out: FloatArray = rho * np.outer(self.sigma, self.sigma)
        return out


def linear_vibration(
    amplitudes: ArrayLike = (),
    phases: ArrayLike | None = None,
    sigma: ArrayLike = (0.0, 0.0, 0.0),
    coherence: ArrayLike = (0.0, 0.0, 0.0),
) -> LinearVibration:
    """Check and build a :class:`LinearVibration` (shapes and units as there)."""
    amp = np.array(amplitudes, dtype=float).reshape(-1, 3)
    ph = np.zeros(amp.shape) if phases is None else np.array(phases, dtype=float).reshape(-1, 3)
    out = LinearVibration(amp, ph, np.array(sigma, dtype=float).reshape(3),
                          np.array(coherence, dtype=float).reshape(3))
    out.moments()  # validates
    return out
