"""The measuring half of the run-up test (docs/model.md section 16): the recording split at
the crossover segment by segment, its steps found or placed, and per step what the fit
and the prediction need.

Rates in deg/s, accelerations in g, times in s counted from the first sample at the
recording's sample rate.
"""

from __future__ import annotations

import importlib.util
import math
from collections.abc import Sequence

import numpy as np

from gyrovib.api.recordings.reading import Recording, RecordingError, iter_segments
from gyrovib.core import recording as rec
from gyrovib.core import runup as kernel
from gyrovib.core.transmissibility import FloatArray, Table
from gyrovib.errors import OptionError, Problem

#: Window of the running variance that finds the steps, s (at least 16 samples).
WINDOW_SECONDS = 0.5
#: A step is part of the baseline when its vibration is within this many dB of the
#: quietest step's, on the angular and on the linear level.
BASELINE_DB = 3.0
#: A vibration whose rms is below this fraction of the signal's is the split's rounding
#: and filter tails (a millionth of 1 g is below any accelerometer's noise): none.
NEGLIGIBLE = 1e-6


class Measured:
    """What one step gives (an accumulator private to :mod:`gyrovib.api.runup`)."""

    __slots__ = ("accel_rms", "end", "excursion", "g2_moments", "lo", "mean", "moments",
                 "phi", "start", "variance", "x3_rms")

    def __init__(self, lo: int, hi: int, fs: float) -> None:
        self.lo = lo
        self.start, self.end = lo / fs, hi / fs
        self.mean = math.nan
        self.variance = math.nan
        self.x3_rms = math.nan
        self.accel_rms = math.nan
        self.phi = np.full(len(kernel.TERMS), np.nan)
        self.excursion = np.zeros(3)
        self.moments: list[FloatArray] = []
        self.g2_moments: FloatArray | None = None


def need_scipy(recording: Recording) -> None:
    """The split is scipy's (an optional dependency): without it, say what to install."""
    if importlib.util.find_spec("scipy") is None:
        raise RecordingError(Problem(
            "a run-up test needs scipy (the zero-phase split at the crossover): "
            "pip install 'gyrovib[recording]'", recording.file))


def _place(recording: Recording, kept: Sequence[tuple[int, int]],
           steps: Sequence[tuple[float, float]]) -> list[tuple[int, int, int]]:
    """Given steps (s) as (segment, lo, hi) sample indices; each must lie in one segment."""
    fs = recording.fs
    out = []
    for a, b in steps:
        if not (math.isfinite(a) and math.isfinite(b) and 0 <= a < b):
            raise OptionError(f"step {a:g}:{b:g}: give a start and a later end, in s from "
                              "the recording's first sample")
        lo, hi = math.ceil(a * fs - 1e-9), math.floor(b * fs + 1e-9)
        where = [k for k, (s0, s1) in enumerate(kept) if s0 <= lo and hi <= s1]
        if not where or hi - lo < 4:
            raise RecordingError(Problem(
                f"step {a:g}:{b:g} s does not lie within one contiguous stretch of the "
                f"recording ({recording.samples / fs:.6g} s at {fs:.6g} Hz, "
                f"{len(kept)} segment(s) kept) or holds fewer than 4 samples",
                recording.file))
        out.append((where[0], lo, hi))
    return out


def _detect(x3: FloatArray, xa: FloatArray | None, fs: float, s0: int) -> list[tuple[int, int]]:
    window = max(16, round(WINDOW_SECONDS * fs))
    levels = kernel.window_levels(x3, window, xa)
    found = kernel.detect_steps(levels, window)
    return [(s0 + int(lo), s0 + int(hi)) for lo, hi in found.tolist()]


def measure(recording: Recording, crossover: float,
            steps: Sequence[tuple[float, float]] | None,
            responses: Sequence[Table] | None = None) -> list[Measured]:
    """Split each kept segment at ``crossover``, find (or place) the steps, and measure
    each: its mean and the variance of that mean, its regressors, its vibration levels,
    the carrier's mean and spread per axis, and — when ``responses`` is given, for a
    prediction — the Δ_V,rec moments (plain, and for each input-side response)."""
    fs = recording.fs
    if not 0 < crossover < fs / 2:
        raise OptionError(f"the crossover {crossover:g} Hz must lie in (0, fs/2 = "
                          f"{fs / 2:.6g} Hz)")
    kept = list(iter_segments(recording, crossover))
    if not kept:
        raise RecordingError(Problem(
            f"no contiguous stretch of the recording is 4/f_c = {4 / crossover:g} s long",
            recording.file))
    placed = None if steps is None else _place(recording, kept, steps)
    out: list[Measured] = []
    for k, (s0, s1) in enumerate(kept):
        wanted = (None if placed is None
                  else [(lo, hi) for seg, lo, hi in placed if seg == k])
        if wanted != []:
            out += _segment(recording, s0, s1, crossover, wanted, responses)
    if placed is not None:  # in the order given
        order = {lo: n for n, (_, lo, _) in enumerate(placed)}
        out.sort(key=lambda m: order[m.lo])
    return out


def _segment(recording: Recording, s0: int, s1: int, crossover: float,
             wanted: list[tuple[int, int]] | None,
             responses: Sequence[Table] | None) -> list[Measured]:
    """One contiguous segment split at the crossover, its steps found (``wanted`` None)
    or placed, and each measured."""
    fs = recording.fs
    w = recording.store.block("rate", s0, s1)
    c = rec.lowpass(w, fs, crossover)
    a = low = None
    if recording.store.has_accel:
        a = recording.store.block("accel", s0, s1)
        low = rec.lowpass(a, fs, crossover)
    if wanted is None:
        wanted = _detect(w[:, 2] - c[:, 2], None if a is None or low is None else a - low,
                         fs, s0)
    out = []
    for lo, hi in wanted:
        i, j = lo - s0, hi - s0
        out.append(_one(fs, lo, hi, w[i:j], c[i:j], None if a is None else a[i:j],
                        None if low is None else low[i:j], responses))
    return out


def _one(fs: float, lo: int, hi: int, w: FloatArray, c: FloatArray, a: FloatArray | None,
         low: FloatArray | None, responses: Sequence[Table] | None) -> Measured:
    m = Measured(lo, hi, fs)
    n = hi - lo
    m.mean = float(np.mean(w[:, 2]))
    m.variance = kernel.mean_variance(w[:, 2], fs)
    m.phi = kernel.step_regressors(w, c, a, low)
    x = w - c
    m.x3_rms = _rms(x[:, 2:], w[:, 2:])
    m.excursion = kernel.angle_excursion(c, fs)
    if a is not None and low is not None:
        m.accel_rms = _rms(a - low, a)
    if responses is None:
        return m
    m.moments = [rec.recorded_moments(w, c) / n]
    for table in responses:
        xr = np.column_stack([rec.zero_phase_gain(x[:, j], fs, table) for j in range(3)])
        m.moments.append(rec.recorded_moments(c + xr, c) / n)
    if a is not None and low is not None:  # columns contiguous for the dot products
        m.g2_moments = rec.recorded_g2_moments(np.asfortranarray(a),
                                               np.asfortranarray(low)) / n
    return m


def _rms(vibration: FloatArray, signal: FloatArray) -> float:
    """√(Σ_axes ⟨v²⟩); 0 where that is below :data:`NEGLIGIBLE` of the signal's rms (the
    split's rounding and tails, not a vibration)."""
    power = float(np.sum(np.mean(vibration**2, axis=0)))
    floor = NEGLIGIBLE**2 * float(np.sum(np.mean(signal**2, axis=0)))
    return math.sqrt(power) if power > floor else 0.0


def baseline(steps: Sequence[Measured]) -> np.ndarray:
    """The steps without vibration: within :data:`BASELINE_DB` of the quietest step's
    angular level (and linear level, where recorded)."""
    def db(values: list[float]) -> FloatArray:  # floored as the step finder's levels are
        v = np.asarray(values, dtype=float)
        floor = max(float(v.max()) * 10.0 ** (-kernel.LEVEL_FLOOR_DB / 10.0), 1e-30)
        return np.asarray(10.0 * np.log10(np.maximum(v, floor)), dtype=float)

    ang = db([s.x3_rms ** 2 for s in steps])
    keep = ang <= ang.min() + BASELINE_DB
    lin_values = [s.accel_rms ** 2 for s in steps]
    if all(math.isfinite(v) for v in lin_values):
        lin = db(lin_values)
        keep &= lin <= lin.min() + BASELINE_DB
    if not keep.any():  # the quietest angularly is not the quietest linearly
        keep[int(np.argmin(ang))] = True
    out: np.ndarray = keep
    return out


__all__ = ["BASELINE_DB", "WINDOW_SECONDS", "Measured", "baseline", "measure", "need_scipy"]
