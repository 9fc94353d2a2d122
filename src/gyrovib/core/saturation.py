"""Saturation: how far the nonlinear element is driven (docs/model.md section 9).

    reach = |Ω_K3| + Σ_tones a3 + Σ_groups max_t |x3,group(t)| + κ·σ3

with the vibration as it reaches the element (after the mount, and after the
sensor's response only where it acts at the input). Independent tones drift
through every relative phase, so their sum of amplitudes is the supremum of
|Σ x3|; a phase-locked group keeps its waveform, so its true peak
(:func:`group_peak`) is used — Σ a3 over its orders is only an upper bound,
reached when the orders happen to align. A sensor saturates under a profile
when reach > R (R in the same rate unit); R = None or +inf never saturates.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike

from gyrovib.core._types import BoolArray, FloatArray
from gyrovib.core.harmonics import LockedGroup, locked_peak
from gyrovib.limits import DEFAULT_PEAK_FACTOR as DEFAULT_PEAK_FACTOR


def group_peak(group: LockedGroup) -> float:
    """``max_t |x3(t)|`` of a locked group (rate units), exact.

    Orders whose phase is unknown (``worst``) are aligned with the peak of
    the rest, which is attainable: peak(rest) + Σ a3 of those orders.
    """
    fixed = ~group.worst
    rest = locked_peak(group.orders[fixed], group.phasors[fixed, 2])
    return rest + float(np.sum(np.abs(group.phasors[group.worst, 2])))


def saturation_reach(
    omega3: ArrayLike,
    tone_amplitudes: ArrayLike,
    sigma3: ArrayLike,
    *,
    locked_peaks: ArrayLike = 0.0,
    kappa: float = DEFAULT_PEAK_FACTOR,
) -> FloatArray:
    """``|Ω_K3| + Σ a3 + Σ peaks + κ·σ3`` (rate units), broadcast over sensors × profiles.

    ``omega3``: Ω_K3, shape broadcastable to the result (e.g. (profiles,) or
    (sensors, profiles)); ``tone_amplitudes``: (..., K) x3 amplitudes of the
    independent tones at the element, summed over the last axis (K may be 0);
    ``sigma3``: (...) Gaussian σ3 at the element; ``locked_peaks``: (..., G)
    true peaks of the locked groups (:func:`group_peak`), summed over the last
    axis, or a scalar; ``kappa``: κ ≥ 0.
    """
    if not (np.isfinite(kappa) and kappa >= 0):
        raise ValueError("the peak factor κ must be finite and ≥ 0")
    a = np.asarray(tone_amplitudes, dtype=float)
    peaks = np.asarray(locked_peaks, dtype=float)
    tones = a.sum(axis=-1) if a.ndim else a
    locked = peaks.sum(axis=-1) if peaks.ndim else peaks
    out: FloatArray = (np.abs(np.asarray(omega3, dtype=float)) + tones + locked
                       + kappa * np.asarray(sigma3, dtype=float))
    return out


def saturated(reach: ArrayLike, ranges: Sequence[float | None] | ArrayLike) -> BoolArray:
    """Boolean (sensors, ...) array: reach > R, for ``reach`` (sensors, ...) or (...).

    ``ranges``: (sensors,) R per sensor in the rate unit of ``reach``; None,
    NaN or +inf mean no range (never saturates). A reach equal to R does not
    saturate.
    """
    r = np.array([np.inf if v is None else v for v in np.asarray(ranges, dtype=object).ravel()],
                 dtype=float)
    r = np.where(np.isnan(r), np.inf, r)
    x = np.asarray(reach, dtype=float)
    if x.ndim == 0 or x.shape[0] != r.size:
        x = np.broadcast_to(x, (r.size, *x.shape))
    out: BoolArray = x > r.reshape((r.size,) + (1,) * (x.ndim - 1))
    return out
