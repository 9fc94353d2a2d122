"""``gyrovib allan``: the overlapping Allan deviation of a static recording, per axis,
each point with its confidence interval, and IEEE Std 952's five terms (and a
Gauss–Markov term where the curve shows one) fitted to it, each a value with its
interval or an upper bound (docs/model.md section 15; the kernels are core/allan.py,
core/allan_edf.py and core/allan_fit.py)."""

from __future__ import annotations

import importlib.util
import math
import os
import tempfile
from collections.abc import Callable

import numpy as np

from gyrovib import units
from gyrovib.api.noise.results import (
    FIGURE_UNITS,
    NOISE_TERMS,
    AllanResult,
    AxisAllan,
    Figure,
    GaussMarkov,
)
from gyrovib.api.recordings.reading import AXES, Recording, RecordingError
from gyrovib.core import allan as kernel
from gyrovib.core import allan_fit, allan_stream
from gyrovib.errors import OptionError, Problem

#: From the kernel's figures (deg, deg/s·√s, deg/s, deg/s/√s, deg/s²) to the reported
#: units (deg, deg/√h, deg/h, deg/h/√h, deg/h²).
TO_REPORTED = {"quantization": 1.0, "arw": 60.0, "bias_instability": 3600.0,
               "rrw": 216_000.0, "rate_ramp": 3600.0 ** 2}
#: The accelerometer's terms: from the kernel's (m/s², s) units to the reported ones
#: (velocity random walk in m/s/√h, bias instability in m/s², its random walk in
#: m/s²/√h), with their units.
ACCEL_REPORTED = {"quantization": (1.0, "m/s"), "arw": (60.0, "m/s/sqrt(h)"),
                  "bias_instability": (1.0, "m/s^2"), "rrw": (60.0, "m/s^2/sqrt(h)"),
                  "rate_ramp": (1.0, "m/s^3")}
#: Fewest samples an Allan deviation is computed from.
MIN_SAMPLES = 30
#: Fewest changes of a quantised record's level that carry a noise figure.
MIN_CHANGES = 30
#: Samples above which the curve is computed without holding the record
#: (core/allan_stream.py): 2²² samples are 100 MB of float64 over three axes.
STREAM_SAMPLES = 1 << 22


def _figure(term: allan_fit.Term, name: str, confidence: float,
            accel: bool = False) -> Figure:
    f, unit = ACCEL_REPORTED[name] if accel else (TO_REPORTED[name], FIGURE_UNITS[name])
    if term.bound is not None:
        return Figure(unit=unit, confidence=allan_fit.BOUND_CONFIDENCE, bound=term.bound * f)
    assert term.value is not None
    (lo, hi), (lo95, hi95) = term.intervals
    return Figure(unit=unit, confidence=confidence, value=term.value * f,
                  interval=(lo * f, hi * f), interval95=(lo95 * f, hi95 * f))


def longest_segment(recording: Recording) -> tuple[int, int]:
    """The longest contiguous segment (a gap breaks the record: σ needs even spacing)."""
    seg = recording.segments
    k = int(np.argmax(seg[:, 1] - seg[:, 0]))
    return int(seg[k, 0]), int(seg[k, 1])


def seen_noise(rate: np.ndarray, axis: str, file: str) -> None:
    """Refuses a record in which no noise is seen (:func:`refuse_unseen`)."""
    refuse_unseen(axis, float(np.min(rate)), float(np.max(rate)),
                  int(np.count_nonzero(np.diff(rate))), rate.size, file)


def refuse_unseen(axis: str, low: float, high: float, changes: int, n: int,
                  file: str) -> None:
    """Refuses a record in which no noise is seen: a constant, or a quantised output
    that changes level fewer than :data:`MIN_CHANGES` times. No noise seen is not zero
    noise (a stuck sensor, or noise below one step of its quantisation)."""
    if low == high:
        raise RecordingError(Problem(
            f"axis {axis} is constant ({low:.6g} deg/s in every sample): no noise is seen, "
            "which is not zero noise (a stuck output, or noise below one step of its "
            "quantisation); no figure is written", file))
    if changes < MIN_CHANGES:
        raise RecordingError(Problem(
            f"axis {axis} changes level only {changes} times in {n} samples (between "
            f"{low:.6g} and {high:.6g} deg/s): its noise is below one step of quantisation, "
            "which says nothing about its size; no figure is written", file))


def allan_axis(axis: str, rate: np.ndarray, fs: float, unit: str,
               per_decade: int = kernel.PER_DECADE, confidence: float = 0.68,
               seed: int = 0) -> AxisAllan:
    """One axis: ``rate`` in deg/s at ``fs`` Hz; σ(τ) reported in ``unit``."""
    tau0 = 1.0 / fs
    m = kernel.tau_grid(rate.size, per_decade)
    adev = kernel.oadev(rate, tau0, m)[1]
    return axis_from_curve(axis, m, adev, rate.size, fs, unit, confidence, seed)


def axis_from_curve(axis: str, m: np.ndarray, adev: np.ndarray, n: int, fs: float,
                    unit: str, confidence: float = 0.68, seed: int = 0,
                    accel: bool = False) -> AxisAllan:
    """One axis from its curve: σ(τ) (deg/s; m/s² for an ``accel`` axis, reported in
    m/s²) at cluster sizes ``m`` of ``n`` samples."""
    tau = m / fs  # as written: 3 / 10 is 0.3, where 3 · 0.1 is 0.30000000000000004
    keep = adev > 0
    tau, m, adev = tau[keep], m[keep], adev[keep]
    model = allan_fit.noise_model(tau, adev, m, n, 1.0 / fs, (confidence, 0.95), seed)
    figures = {name: _figure(term, name, confidence, accel)
               for name, term in zip(NOISE_TERMS, model.terms, strict=False)}
    unit, scale = ("m/s^2", 1.0) if accel else (unit, units.scale(unit))
    return AxisAllan(axis=axis, tau=tau, adev=adev / scale, unit=unit,
                     ci_lo=model.ci[0] / scale, ci_hi=model.ci[1] / scale,
                     edf=model.nu, figures=figures,
                     gauss_markov=_gauss_markov(model, 1.0 if accel else 3600.0,
                                                "m/s^2" if accel else "deg/h"),
                     model=np.sqrt(model.fit.model(tau)) / scale,
                     misfit=tuple(float(tau[i]) for i in model.misfit),
                     fitted_from=float(tau[model.start]))


def _gauss_markov(model: allan_fit.Model, factor: float, unit: str) -> GaussMarkov | None:
    if model.fit.tau_c is None:
        return None
    term = model.terms[5]
    sigma = math.sqrt(float(model.fit.coef[5])) * factor
    interval = None
    if term.value is not None:
        lo, hi = term.intervals[0]
        interval = (lo * factor, hi * factor)
    return GaussMarkov(sigma=sigma, tau_c=model.fit.tau_c, interval=interval, unit=unit)


def accel_axes(recording: Recording, lo: int, hi: int, per_decade: int,
               confidence: float) -> tuple[tuple[AxisAllan, ...], tuple[str, ...]]:
    """The accelerometer's noise model per recorded axis (specific force in m/s²), and
    the axes left out because no noise is seen on them (said, never zero)."""
    if not any(recording.accel_axes):
        return (), ()
    block = recording.store.block("accel", lo, hi) * units.STANDARD_GRAVITY
    out, notes = [], []
    for k, name in enumerate(AXES):
        if not recording.accel_axes[k]:
            continue
        y = block[:, k]
        try:
            seen_noise(y, name, recording.file)
        except RecordingError:
            notes.append(_no_accel_noise(name))
            continue
        m = kernel.tau_grid(y.size, per_decade)
        out.append(axis_from_curve(name, m, kernel.oadev(y, 1.0 / recording.fs, m)[1],
                                   y.size, recording.fs, "m/s^2", confidence, accel=True))
    return tuple(out), tuple(notes)


def roll_off_warning(ax: AxisAllan) -> str | None:
    """A warning when the curve's first points were left out of the fit (a roll-off)."""
    if ax.fitted_from <= ax.tau[0]:
        return None
    return (f"axis {ax.axis}: below τ = {ax.fitted_from:.4g} s the curve is flatter than "
            "white noise and below its line (a low-pass filter's roll-off): those points are "
            "left out of the fit, and N is read where the curve is white")


def misfit_warning(ax: AxisAllan) -> str | None:
    """A warning when more than a tenth of the curve lies outside the model's 99 % band."""
    if len(ax.misfit) <= max(1, ax.tau.size // 10):
        return None
    where = ", ".join(f"{t:.4g}" for t in ax.misfit[:6]) + ("…" if len(ax.misfit) > 6 else "")
    return (f"axis {ax.axis}: the noise model does not fit the curve at τ = {where} s "
            f"({len(ax.misfit)} of {ax.tau.size} points outside their 99 % interval): "
            "the record holds noise the five terms do not describe (a vibration, a "
            "temperature change, a filter), and the figures are only as good as the fit")


def _check_options(per_decade: int | None, confidence: float) -> None:
    if per_decade is not None and per_decade < 1:
        raise OptionError(argument="per_decade", value=str(per_decade), reason="give at least 1")
    if not (0.0 < confidence < 1.0):
        raise OptionError(f"confidence {confidence:g}: give a level between 0 and 1 "
                          "(0.68 for 68 %)")


def _need_scipy(recording: Recording) -> None:
    if importlib.util.find_spec("scipy") is None:
        raise RecordingError(Problem(
            "the noise model's fit and intervals need scipy: pip install "
            "'gyrovib[recording]'", recording.file))


def _streamed(recording: Recording, lo: int, hi: int, chosen: list[tuple[int, str]],
              unit: str, per_decade: int | None, confidence: float) -> tuple[AxisAllan, ...]:
    """The curves of a long record read a block at a time (core/allan_stream.py), the
    record never held: a pass checks that noise is seen, one takes the mean and writes
    the angle to a scratch file, one per τ reads it back."""
    read_rows = _block_reader(recording, "rate", lo, [k for k, _ in chosen], 1.0)
    n = hi - lo
    low, high, changes = _levels_blockwise(read_rows, n, len(chosen))
    for j, (_, name) in enumerate(chosen):
        refuse_unseen(name, float(low[j]), float(high[j]), int(changes[j]), n, recording.file)
    return _streamed_axes(recording, read_rows, n, chosen, unit, per_decade, confidence)


def _block_reader(recording: Recording, kind: str, lo: int, cols: list[int],
                  scale: float) -> Callable[[int, int], np.ndarray]:
    """Rows a:b of the segment from ``lo``, the ``cols`` of ``kind`` (rate or accel),
    times ``scale``, read from the store a block at a time."""
    def read_rows(a: int, b: int) -> np.ndarray:
        block = recording.store.block(kind, lo + a, lo + b)[:, cols]
        return block * scale if scale != 1.0 else block

    return read_rows


def _streamed_axes(recording: Recording, read_rows: Callable[[int, int], np.ndarray], n: int,
                   chosen: list[tuple[int, str]], unit: str, per_decade: int | None,
                   confidence: float, accel: bool = False) -> tuple[AxisAllan, ...]:
    """The angle of the ``chosen`` columns written to a scratch file, σ(τ) read back from
    it, and each axis's noise model (an ``accel`` axis in m/s²)."""
    m = allan_stream.octave_grid(n) if per_decade is None else kernel.tau_grid(n, per_decade)
    with tempfile.TemporaryFile(prefix="gyrovib-allan-") as scratch:
        allan_stream.write_angle(read_rows, n, len(chosen), 1.0 / recording.fs, scratch)
        curves = allan_stream.oadev_scratch(scratch, n, len(chosen), 1.0 / recording.fs, m)
    return tuple(axis_from_curve(name, m, curves[:, j], n, recording.fs, unit, confidence,
                                 accel=accel)
                 for j, (_, name) in enumerate(chosen))


def _streamed_accel(recording: Recording, lo: int, hi: int, per_decade: int | None,
                    confidence: float) -> tuple[tuple[AxisAllan, ...], tuple[str, ...]]:
    """:func:`accel_axes` for a long record: the specific force (m/s²) read a block at a
    time like the rate, its axes without noise left out and said."""
    cols = [k for k in range(3) if recording.accel_axes[k]]
    if not cols:
        return (), ()
    read_all = _block_reader(recording, "accel", lo, cols, units.STANDARD_GRAVITY)
    n = hi - lo
    low, high, changes = _levels_blockwise(read_all, n, len(cols))
    kept, notes = [], []
    for j, k in enumerate(cols):
        try:
            refuse_unseen(AXES[k], float(low[j]), float(high[j]), int(changes[j]), n,
                          recording.file)
            kept.append(k)
        except RecordingError:
            notes.append(_no_accel_noise(AXES[k]))
    if not kept:
        return (), tuple(notes)
    read_rows = _block_reader(recording, "accel", lo, kept, units.STANDARD_GRAVITY)
    chosen = [(k, AXES[k]) for k in kept]
    return (_streamed_axes(recording, read_rows, n, chosen, "m/s^2", per_decade, confidence,
                           accel=True), tuple(notes))


def _no_accel_noise(name: str) -> str:
    return (f"accelerometer axis {name}: no noise seen (a constant, or changes below one "
            "step of quantisation): its figures are not given")


def _levels_blockwise(read_rows: Callable[[int, int], np.ndarray], n: int,
                      cols: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Each column's least and greatest value and how often its level changes, a block
    at a time (changes counted across blocks): what :func:`refuse_unseen` judges."""
    low, high = np.full(cols, np.inf), np.full(cols, -np.inf)
    changes = np.zeros(cols, dtype=np.int64)
    last = None
    for a in range(0, n, allan_stream.ROWS):
        y = read_rows(a, min(n, a + allan_stream.ROWS))
        low, high = np.minimum(low, y.min(axis=0)), np.maximum(high, y.max(axis=0))
        changes += np.count_nonzero(np.diff(y, axis=0), axis=0)
        if last is not None:
            changes += y[0] != last
        last = y[-1].copy()
    return low, high, changes


def allan(recording: Recording, unit: str = "deg/h",
          per_decade: int | None = None, confidence: float = 0.68,
          stream_samples: int = STREAM_SAMPLES) -> AllanResult:
    """Every recorded axis of ``recording`` (read by :func:`gyrovib.api.recordings.
    read_recording`): σ(τ) in ``unit`` on a log grid (``per_decade`` points a decade)
    with its limits at ``confidence``, and the noise model's terms, from the record's
    longest contiguous segment. A segment longer than ``stream_samples`` is read a block
    at a time and never held, on the octave grid τ0·2^j unless ``per_decade`` is given
    (each τ costs a pass over the record); otherwise ``per_decade`` defaults to
    :data:`gyrovib.core.allan.PER_DECADE`."""
    unit = units.canonical_unit(unit)
    _check_options(per_decade, confidence)
    _need_scipy(recording)
    lo, hi = longest_segment(recording)
    if hi - lo < MIN_SAMPLES:
        raise RecordingError(Problem(
            f"{hi - lo} contiguous samples: an Allan deviation needs {MIN_SAMPLES} at least "
            "(and hours of a static record for the bias instability and rate random walk)",
            recording.file, None, None))
    chosen = [(k, name) for k, name in enumerate(AXES) if recording.rate_axes[k]]
    if hi - lo > stream_samples:
        axes = _streamed(recording, lo, hi, chosen, unit, per_decade, confidence)
    else:
        # only the recorded axes are read (never a column of zeros per axis not recorded)
        rate = {k: recording.axis(k, lo, hi) for k, _ in chosen}
        for k, name in chosen:
            seen_noise(rate[k], name, recording.file)
        axes = tuple(allan_axis(name, rate[k], recording.fs, unit,
                                per_decade or kernel.PER_DECADE, confidence)
                     for k, name in chosen)
    accel, notes = (_streamed_accel(recording, lo, hi, per_decade, confidence)
                    if hi - lo > stream_samples else
                    accel_axes(recording, lo, hi, per_decade or kernel.PER_DECADE, confidence))
    base = os.path.basename(recording.file)  # every warning names its file
    warnings = tuple(f"{base}: {w}" for ax in axes
                     for w in (roll_off_warning(ax), misfit_warning(ax)) if w is not None)
    warnings += tuple(f"{base}: {w}" for w in notes)
    return AllanResult(file=recording.file, sha256=recording.sha256, fs=recording.fs,
                       samples=hi - lo, segments=int(recording.segments.shape[0]), axes=axes,
                       topic=recording.topic, instance=recording.instance,
                       confidence=confidence, warnings=recording.warnings + warnings,
                       accel=accel)
