"""A mission: segments of a flight, each under its own profile and carrier rate (docs/model.md §12).

Given each segment's vibration error Δ_V,s and RMS error Δ_V(RMS),s (the
section 4–11 results) and its duration T_s (s):

    mean error        Δ̄_V   = Σ T_s·Δ_V,s / Σ T_s
    accumulated angle θ_V   = Σ T_s·Δ_V,s            (rate × s → angle)
    mean RMS          Δ̄_RMS = √(Σ T_s·Δ_V(RMS),s² / Σ T_s)
    worst segment     argmax_s |Δ_V,s|

Every function takes the segment axis last and works on any leading shape
(sensors, axes, ...), in one vectorised expression.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from gyrovib.core._types import FloatArray

#: An angle accumulated from each rate unit over seconds, and its factor:
#: θ[angle unit] = factor · Σ T_s[s] · Δ_s[rate unit].
ANGLE_UNITS: dict[str, tuple[str, float]] = {
    "deg/s": ("deg", 1.0),
    "deg/h": ("deg", 1.0 / 3600.0),
    "rad/s": ("rad", 1.0),
    "rpm": ("rev", 1.0 / 60.0),
}
#: Angle units an angle budget may be written in, as radians.
ANGLE_IN_RAD: dict[str, float] = {
    "deg": math.pi / 180.0,
    "rad": 1.0,
    "mrad": 1e-3,
    "urad": 1e-6,
    "µrad": 1e-6,
    "arcmin": math.pi / 180.0 / 60.0,
    "arcsec": math.pi / 180.0 / 3600.0,
    "rev": 2.0 * math.pi,
}


@dataclass(frozen=True, slots=True)
class MissionTotals:
    """Per leading index: the mission's mean error, angle, mean RMS and worst segment."""

    mean: FloatArray
    angle: FloatArray
    rms: FloatArray
    worst_index: NDArray[np.intp]
    worst_total: FloatArray
    duration: float


def weights(durations: ArrayLike) -> FloatArray:
    """Durations T_s (s), checked: finite, positive, at least one."""
    t = np.asarray(durations, dtype=float).reshape(-1)
    if t.size == 0:
        raise ValueError("a mission needs at least one segment")
    if not np.all(np.isfinite(t)) or np.any(t <= 0.0):
        raise ValueError("segment durations must be finite and positive")
    return t


def totals(durations: ArrayLike, total: ArrayLike, rms: ArrayLike,
           angle_factor: float = 1.0) -> MissionTotals:
    """The mission's aggregates of docs/model.md §12 (segment axis last).

    ``total``, ``rms``: (..., S) in a rate unit; ``angle_factor`` turns
    rate × seconds into the angle unit (:data:`ANGLE_UNITS`).
    """
    t = weights(durations)
    d = np.asarray(total, dtype=float)
    r = np.asarray(rms, dtype=float)
    if d.shape[-1] != t.size or r.shape[-1] != t.size:
        raise ValueError("one value per segment is needed")
    span = float(np.sum(t))
    theta = d @ t
    mean = theta / span
    mean_rms = np.sqrt((r * r) @ t / span)
    worst = np.argmax(np.abs(d), axis=-1)
    worst_total = np.take_along_axis(d, worst[..., None], axis=-1)[..., 0]
    return MissionTotals(mean=mean, angle=theta * angle_factor, rms=mean_rms,
                         worst_index=worst, worst_total=worst_total, duration=span)


def combined_functional(durations: ArrayLike, terms: ArrayLike) -> FloatArray:
    """The mission's mean error as one linear functional of the conversion function.

    Each segment's error is linear in the coefficients x: Δ_s = c_s · x. The
    mission mean is then ``(Σ T_s c_s / Σ T_s) · x`` — one functional, so the
    worst case over a datasheet envelope is one programme (section 11), not a
    sum of per-segment worst cases. ``terms``: (S, ...), segment axis first
    (e.g. (S, 8, 5) from :func:`gyrovib.core.envelope.term_functionals`, or
    (S,) of g² moments).
    """
    t = weights(durations)
    c = np.asarray(terms, dtype=float)
    if c.shape[:1] != t.shape:
        raise ValueError("one functional per segment is needed")
    out: FloatArray = np.tensordot(t / np.sum(t), c, axes=(0, 0))
    return out
