"""One pass over a recording's segments: the split, the sums of Δ_V,rec and the vibration
(docs/model.md section 13), a column and a block at a time.

The memory of a pass is the vibration it hands to the spectra — x (n, 3),
and a − A for the accelerations in a second pass once the angular spectra
are done — and one column being filtered; Ω_K3 for the carrier histogram is
filtered again at the end (:func:`carrier3`), when the vibration is gone.
Nothing else as long as the recording: each column is split
into the column of x that will hold its vibration (the carrier is written
there first), the sums are taken over blocks of :data:`BLOCK` samples read
again from the recording's store, and the vibration replaces the carrier
block by block. For a ``.npy`` the store reads the file, so the array itself
is never held whole.

Every sum is taken over the same blocks, in the same order, as
:func:`gyrovib.core.recording.recorded_moments` takes it over a whole
segment, so the moments are those numbers exactly.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from gyrovib.api.recordings.reading import Recording
from gyrovib.core import recording as core
from gyrovib.core._types import FloatArray, Table

#: Samples summed at once: core.recording's own chunk, so the sums are its sums.
BLOCK = 1 << 20


class RatePass:
    """What the angular pass measures, summed over every kept sample (an accumulator
    private to :func:`gyrovib.api.recordings.fit.fit_recording`, not a result)."""

    __slots__ = ("carrier_sum", "moments", "peak", "raw", "signal", "x")

    def __init__(self, responses: int) -> None:
        self.moments: dict[Any, FloatArray] = {key: np.zeros(len(core.MOMENTS))
                                               for key in (None, *range(responses))}
        self.peak = np.zeros(1 + responses)
        self.carrier_sum = np.zeros(3)
        self.raw = np.zeros((4, 3))
        self.signal = np.zeros(3)
        self.x: list[FloatArray] = []


def rate_pass(recording: Recording, kept: Sequence[tuple[int, int]], crossover: float,
              responses: Sequence[Table] = ()) -> RatePass:
    """The angular pass: moments (``None`` and one per response), peaks, carrier sums, the
    power sums of x and x itself per segment (Fortran order: a column is contiguous)."""
    out = RatePass(len(responses))
    for lo, hi in kept:
        x = _split(recording, "rate", lo, hi, crossover, out)
        seg = np.zeros(len(core.MOMENTS))
        for b in range(0, hi - lo, BLOCK):
            w = recording.store.block("rate", lo + b, min(hi, lo + b + BLOCK))
            c = x[b:b + BLOCK]
            seg += core.recorded_moments(w, c)
            np.subtract(w, c, out=c)  # the carrier becomes the vibration
        out.moments[None] += seg
        for i, table in enumerate(responses):
            _response(recording, x, lo, hi, table, i, out)
        out.raw += core.power_sums(x)
        out.x.append(x)
    return out


def _split(recording: Recording, kind: str, lo: int, hi: int, crossover: float,
           out: RatePass | None) -> FloatArray:
    """The carrier of each column of samples lo:hi, in a new (n, 3) Fortran-order array."""
    x = np.empty((hi - lo, 3), order="F")
    for j in range(3):
        w = recording.store.column(kind, j, lo, hi)
        core.lowpass(w, recording.fs, crossover, out=x[:, j])
        if out is not None:
            out.carrier_sum[j] += float(x[:, j].sum())
            out.signal[j] += float(w @ w)
            if j == 2:
                out.peak[0] = max(out.peak[0], float(np.max(np.abs(w))))
        del w
    return x


def _response(recording: Recording, x: FloatArray, lo: int, hi: int, table: Table, i: int,
              out: RatePass) -> None:
    """Moments and peak of Ω_K + ν·x, the rate at an input-side response's element."""
    xr = np.empty_like(x)
    for j in range(3):  # a column at a time: the transforms are one column long
        xr[:, j] = core.zero_phase_gain(x[:, j], recording.fs, table)
    seg = np.zeros(len(core.MOMENTS))
    for b in range(0, hi - lo, BLOCK):
        omega_k = recording.store.block("rate", lo + b, min(hi, lo + b + BLOCK)) - x[b:b + BLOCK]
        part = xr[b:b + BLOCK]
        part += omega_k
        seg += core.recorded_moments(part, omega_k)
        out.peak[i + 1] = max(out.peak[i + 1], float(np.max(np.abs(part[:, 2]))))
    out.moments[i] += seg


def accel_pass(recording: Recording, kept: Sequence[tuple[int, int]],
               crossover: float) -> tuple[FloatArray, list[FloatArray]]:
    """The linear pass: the sums of a_j·a_k − A_j·A_k (g²) and a − A per segment."""
    sums = np.zeros(len(core.G2_PAIRS))
    vibration: list[FloatArray] = []
    for lo, hi in kept:
        xa = _split(recording, "accel", lo, hi, crossover, None)
        seg = np.zeros(len(core.G2_PAIRS))
        for b in range(0, hi - lo, BLOCK):
            a = recording.store.block("accel", lo + b, min(hi, lo + b + BLOCK))
            big = xa[b:b + BLOCK]
            seg += core.recorded_g2_moments(a, big)
            np.subtract(a, big, out=big)
        sums += seg
        vibration.append(xa)
    return sums, vibration


def carrier3(recording: Recording, kept: Sequence[tuple[int, int]],
             crossover: float) -> FloatArray:
    """Ω_K3 over the kept segments, end to end (the same split as the rate pass's)."""
    out = np.empty(sum(hi - lo for lo, hi in kept))
    at = 0
    for lo, hi in kept:
        core.lowpass(recording.store.column("rate", 2, lo, hi), recording.fs, crossover,
                     out=out[at:at + hi - lo])
        at += hi - lo
    return out


def carrier(recording: Recording, kept: Sequence[tuple[int, int]], crossover: float,
            rate: FloatArray) -> FloatArray:
    """Ω_K on every axis over the kept segments, end to end, (samples, 3); an axis not
    recorded holds its mean ``rate`` (0 where that is not known either: the caller puts
    the axis's own value back)."""
    out = np.empty((sum(hi - lo for lo, hi in kept), 3))
    for j in range(3):
        if not recording.rate_axes[j]:
            out[:, j] = rate[j] if np.isfinite(rate[j]) else 0.0
            continue
        at = 0
        column = np.empty(out.shape[0])
        for lo, hi in kept:
            core.lowpass(recording.store.column("rate", j, lo, hi), recording.fs, crossover,
                         out=column[at:at + hi - lo])
            at += hi - lo
        out[:, j] = column
    return out


__all__ = ["BLOCK", "RatePass", "accel_pass", "carrier", "carrier3", "rate_pass"]
