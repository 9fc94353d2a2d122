"""A recording fitted (docs/model.md section 13): the profile and mission it writes.

:func:`fit_recording` splits a recording at the crossover, fits a catalogue
profile to its vibration (tones, phase-locked harmonics, a log-log PSD,
coherences, the carrier histogram, the linear vibration) and writes it as
catalogue YAML, with the honesty figures and warnings of the fit. The analysis
of every sensor on the recording is :mod:`gyrovib.api.recordings.analysis`.
"""

from __future__ import annotations

import dataclasses
import importlib.util
import math
import os
from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from gyrovib.api.recordings.passes import RatePass, accel_pass, carrier, rate_pass
from gyrovib.api.recordings.reading import PADDING, Recording, RecordingError, iter_segments
from gyrovib.api.recordings.results import (
    AxisHonesty,
    FittedHarmonics,
    FittedPart,
    FittedTone,
    RecordingFit,
)
from gyrovib.api.recordings.yaml import profile_yaml
from gyrovib.catalog.loader import parse_catalog
from gyrovib.core import recording as core
from gyrovib.core._types import FloatArray, Table
from gyrovib.core.breakpoints import fit_breakpoints, shape_figures
from gyrovib.core.transmissibility import psd_variance
from gyrovib.errors import GyrovibError, Note, OptionError, Problem, headed
from gyrovib.limits import (  # the options' defaults, shared with the command line
    DEFAULT_BREAKPOINTS,
    DEFAULT_CROSSOVER,
    DEFAULT_RESOLUTION,
    DEFAULT_THRESHOLD,
)
from gyrovib.progress import advance

#: A vibration whose rms is below this fraction of the signal's is rounding: none.
NEGLIGIBLE = 1e-10
#: Lines below this frequency (× f_c) are the crossover's skirt, not vibration.
LINE_FLOOR = 2.0
#: A fitted PSD worse than this (dB, power-weighted) or with more than this share of the
#: power off by 3 dB is warned of.
SHAPE_DB_LIMIT = 2.0
OFF_3DB_LIMIT = 0.2


def _check(crossover: float, resolution: float, threshold: float, breakpoints: int) -> None:
    if not (math.isfinite(crossover) and crossover > 0):
        raise OptionError(argument="crossover", value=f"{crossover:g}",
                          reason="give a positive frequency in Hz")
    if not (math.isfinite(resolution) and resolution > 0):
        raise OptionError(argument="resolution", value=f"{resolution:g}",
                          reason="give a positive frequency in Hz")
    if not math.isfinite(threshold) or threshold <= 0:
        raise OptionError(argument="tone_threshold", value=f"{threshold:g}",
                          reason="give a positive number of dB")
    if breakpoints < 2:
        raise OptionError(argument="breakpoints", value=str(breakpoints), reason="give at least 2")


def _kept(recording: Recording, crossover: float) -> tuple[list[tuple[int, int]], list[str]]:
    """The segments kept for f_c, and the warnings so far (the reader's, segments dropped)."""
    fs = recording.fs
    if crossover >= fs / 2:
        raise RecordingError(Problem.naming(
            f"fs = {fs:.6g} Hz is too low for the crossover {crossover:g} Hz (it must lie "
            f"below fs/2 = {fs / 2:.6g} Hz): lower {{crossover}}", ("crossover",),
            recording.file))
    kept = list(iter_segments(recording, crossover))
    warnings: list[str] = list(recording.warnings)
    dropped = len(recording.segments) - len(kept)
    if dropped:
        warnings.append(f"{dropped} segment(s) shorter than 4/f_c = {4 / crossover:g} s "
                        "dropped (docs/model.md section 13)")
    if not kept:
        longest = int(np.max(recording.segments[:, 1] - recording.segments[:, 0]))
        raise RecordingError(Problem.naming(
            f"the recording is shorter than one segment: its longest contiguous stretch "
            f"is {longest} samples = {longest / fs:.6g} s, and a segment needs 4/f_c = "
            f"{4 / crossover:g} s and more than {PADDING} samples (the filter's padding) "
            "(raise {crossover}, or record longer)", ("crossover",), recording.file))
    return kept, warnings


def _up(value: float) -> str:
    """``value`` rounded up to 3 significant figures (a --resolution that is enough)."""
    step = 10.0 ** (math.floor(math.log10(value)) - 2)
    return f"{math.ceil(value / step - 1e-9) * step:.3g}"


def _short_for_welch(kept: Sequence[tuple[int, int]], fs: float,
                     resolution: float) -> list[str]:
    """A warning when kept segments are shorter than one Welch window: they count in
    Δ_V,rec and the statistics, but hold no window of the spectra (docs/model.md
    section 13)."""
    nper = core.welch_length(fs, resolution)
    short = [hi - lo for lo, hi in kept if hi - lo < nper]
    if not short or len(short) == len(kept):  # none left for the spectra: an error later
        return []
    return [f"{len(short)} of {len(kept)} segment(s) shorter than one Welch window "
            f"(1/Δf = {1 / resolution:g} s, {nper} samples) are left out of the spectra "
            f"and the fitted profile; Δ_V,rec and the statistics use every sample"]


def _statistics(measured: RatePass, n_total: int, axes: tuple[bool, bool, bool],
                ) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Variance, skewness and excess kurtosis of x per axis (NaN on an axis not recorded)."""

    var, skew, kurt = core.central_moments(measured.raw, n_total)
    # a vibration below 1e-10 of the signal's rms is the filter's rounding, not a vibration
    quiet = var <= NEGLIGIBLE**2 * measured.signal / n_total
    var = np.where(quiet, 0.0, var)
    skew, kurt = (np.where(quiet, np.nan, v) for v in (skew, kurt))
    axes_on = np.array(axes)
    var, skew, kurt = (np.where(axes_on, v, np.nan) for v in (var, skew, kurt))
    return var, skew, kurt


def _linear_variance(segments: list[FloatArray], n_total: int,
                     axes: tuple[bool, bool, bool]) -> FloatArray:
    """The variance of a − A per axis (0 when it is rounding, NaN where not recorded)."""

    raw_a = np.zeros((2, 3))
    for xa in segments:
        raw_a += core.power_sums(xa, 2)
    var_a = raw_a[1] / n_total - (raw_a[0] / n_total) ** 2
    var_a = np.where(var_a <= NEGLIGIBLE**2 * np.abs(raw_a[1]) / n_total, 0.0, var_a)
    return np.where(np.array(axes), var_a, np.nan)


def _need_scipy(recording: Recording) -> None:
    """The split and the Welch spectra are scipy's, an optional dependency: without it,
    the user is told what to install (not a traceback)."""
    if importlib.util.find_spec("scipy") is None:
        raise RecordingError(Problem(
            "fitting a recording needs scipy (the zero-phase split and the Welch spectra): "
            "pip install 'gyrovib[recording]'", recording.file))


#: The progress label of :func:`fit_recording`.
_FITTING = "fitting the recording"


def fit_recording(recording: Recording, *, crossover: float = DEFAULT_CROSSOVER,
                  resolution: float = DEFAULT_RESOLUTION,
                  tone_threshold: float = DEFAULT_THRESHOLD,
                  breakpoints: int = DEFAULT_BREAKPOINTS, independent_tones: bool = False,
                  profile_id: str | None = None,
                  responses: Sequence[Table] = ()) -> RecordingFit:
    """Split, measure and fit a recording (docs/model.md section 13).

    ``responses``: input-side sensor responses for which Δ_V,rec moments are
    wanted besides the plain ones (``moments[None]``); each gets
    ``moments[i]`` and ``peak[i + 1]`` (``peak[0]``: max |ω3| as recorded).
    """

    _check(crossover, resolution, tone_threshold, breakpoints)
    _need_scipy(recording)
    fs = recording.fs
    kept, warnings = _kept(recording, crossover)
    warnings += _short_for_welch(kept, fs, resolution)
    n_total = sum(hi - lo for lo, hi in kept)
    advance(_FITTING, 0, 3)  # split, spectra, accelerations: a bar on a terminal
    measured = rate_pass(recording, kept, crossover, responses)
    advance(_FITTING, 1, 3)
    moments = {key: value / n_total for key, value in measured.moments.items()}
    var, skew, kurt = _statistics(measured, n_total, recording.rate_axes)
    angular = _fit_part(recording.file, measured.x, fs, resolution, tone_threshold, breakpoints,
                        independent_tones, crossover, var, rate=True)
    measured.x.clear()  # the angular vibration is done with before the linear one is made
    advance(_FITTING, 2, 3)
    g2_moments, linear = None, None
    if recording.store.has_accel:
        g2_sums, xa_segments = accel_pass(recording, kept, crossover)
        g2_moments = g2_sums / n_total
        var_a = _linear_variance(xa_segments, n_total, recording.accel_axes)
        linear = _fit_part(recording.file, xa_segments, fs, resolution, tone_threshold,
                           breakpoints, True, crossover, var_a, rate=False)
        del xa_segments
    advance(_FITTING, 3, 3)
    rate = measured.carrier_sum / n_total
    # the fitted mission keeps the carrier of every axis: the joint carrier in at most
    # 16 groups (a histogram of Ω_K3 alone left a triad's X and Y sensors no carrier)
    joint = carrier(recording, kept, crossover, rate)
    mission_rates, counts = core.carrier_clusters(joint)
    del joint
    for j in range(3):
        if not recording.rate_axes[j]:
            mission_rates[:, j] = rate[j]
    peak = measured.peak
    honesty = tuple(AxisHonesty(float(var[j]), float(angular.held[j]), float(skew[j]),
                                float(kurt[j]), float(angular.shape_db[j]),
                                float(angular.off_3db[j])) for j in range(3))
    warnings += fit_warnings(angular, linear, os.path.basename(recording.file))
    base = os.path.basename(recording.file)
    pid = profile_id or _default_id(base)
    fit = RecordingFit(
        file=recording.file, sha256=recording.sha256, samples=recording.samples, fs=fs,
        crossover=crossover, segments=len(kept), duration=n_total / fs, profile_id=pid,
        rate=rate, mission_rates=mission_rates, mission_durations=counts / fs,
        angular=angular, linear=linear,
        honesty=honesty,  # type: ignore[arg-type]
        rate_axes=recording.rate_axes, warnings=tuple(warnings), yaml="", peak=peak,
        moments=moments, g2_moments=g2_moments, topic=recording.topic,
        instance=recording.instance)

    text = profile_yaml(fit, independent_tones=independent_tones)
    try:  # what is written must validate: an --id the format refuses is said here
        parse_catalog(text, "<fitted profile>")
    except GyrovibError as exc:
        raise OptionError(argument="profile_id", value=repr(pid),
                          reason="the fitted profile does not validate: "
                                 f"{exc.problems[0].message}") from None
    return dataclasses.replace(fit, yaml=text)


def _default_id(base: str) -> str:
    stem = base.split(".")[0] or "recording"
    clean = "".join(ch if ch.isalnum() or ch in "-_" else "-" for ch in stem).strip("-_")
    return f"{clean or 'recording'}-fitted"


def _fit_part(file: str, segments: list[FloatArray], fs: float, resolution: float, threshold: float,
              breakpoints: int, independent: bool, crossover: float, variance: FloatArray,
              *, rate: bool) -> FittedPart:
    """Tones, harmonics, PSD breakpoints and coherences of one kind of vibration."""

    f, spectra, windows = core.welch_spectra(segments, fs, resolution)
    if windows == 0:
        longest = max(s.shape[0] for s in segments)
        raise RecordingError(Problem.naming(
            f"no contiguous segment holds one Welch window of 1/Δf = {1 / resolution:g} s "
            f"({core.welch_length(fs, resolution)} samples; the longest segment kept has "
            f"{longest} = {longest / fs:.6g} s): give {{resolution}} {_up(fs / longest)} or "
            "more (Hz)", ("resolution",), file))
    silent = ~(variance > 0)  # not recorded, or negligible: no spectrum to fit
    spectra[silent, :, :] = 0.0
    spectra[:, silent, :] = 0.0
    lines, median = core.find_lines(f, spectra, threshold, fmin=LINE_FLOOR * crossover)
    df = float(f[1] - f[0])
    psd = np.real(np.stack([spectra[i, i] for i in range(3)]))
    random = psd.copy()
    in_line = np.zeros(f.size, dtype=bool)
    for line in lines:
        random[:, line.lo:line.hi] = median[:, line.lo:line.hi]
        in_line[line.lo:line.hi] = True
    band = (f >= crossover) & (f < f[-1])
    tables, sigma2, shape = random_tables(f[band], random[:, band], variance, breakpoints)
    coh = _coherences(psd, spectra, band & ~in_line, df, rate)
    tones, harmonics, released = _tones(lines, grouped=not independent and rate)
    tone_var = sum((ln.amplitude**2 / 2 for ln in lines), np.zeros(3))
    with np.errstate(invalid="ignore", divide="ignore"):
        held = np.where(variance > 0, (tone_var + sigma2) / variance, np.nan)
    return FittedPart(tones, harmonics, tables, coh, f, psd, median, variance, held,
                      shape_db=shape[0], off_3db=shape[1], released=released)


def random_tables(f: FloatArray, random: FloatArray, variance: FloatArray,
                   breakpoints: int) -> tuple[tuple[Table | None, Table | None, Table | None],
                                              FloatArray, FloatArray]:
    """Per axis the fitted breakpoints of the random PSD over the band ``f`` (None where
    the axis has no vibration), their variances, and their shape figures (2, 3):
    shape_db and off_3db (docs/model.md section 13)."""

    tables: list[Table | None] = [None, None, None]
    sigma2 = np.zeros(3)
    shape = np.full((2, 3), np.nan)
    for j in range(3):
        if np.isfinite(variance[j]) and np.any(random[j] > 0):
            table = fit_breakpoints(f, random[j], breakpoints)
            tables[j] = table
            sigma2[j] = psd_variance(table)
            shape[:, j] = shape_figures(f, random[j], table)
    return (tables[0], tables[1], tables[2]), sigma2, shape


def _coherences(psd: FloatArray, spectra: NDArray[np.complex128], keep: NDArray[np.bool_],
                df: float, rate: bool) -> FloatArray:
    """ρ31, ρ32, ρ12 (rate) or ρ12, ρ13, ρ23 (acceleration) over the bins ``keep``."""
    coh = np.zeros(3)
    pairs = ((2, 0), (2, 1), (0, 1)) if rate else ((0, 1), (0, 2), (1, 2))
    for k, (i, j) in enumerate(pairs):
        si = float(np.sum(psd[i, keep]) * df)
        sj = float(np.sum(psd[j, keep]) * df)
        if si > 0 and sj > 0:
            coh[k] = float(np.clip(np.real(np.sum(spectra[i, j, keep])) * df
                                   / math.sqrt(si * sj), -1.0, 1.0))
    return coh


def _tones(lines: Sequence[Any], *, grouped: bool,
           ) -> tuple[tuple[FittedTone, ...], tuple[FittedHarmonics, ...], tuple[float, ...]]:
    """The lines as tones, those at integer multiples of a fundamental as phase-locked
    groups when ``grouped``, and the frequencies of the orders let go of their group to
    keep its search within budget (:func:`gyrovib.core.recording.fitted_groups`)."""

    harmonics: list[FittedHarmonics] = []
    taken: set[int] = set()
    released: list[int] = []
    if grouped:
        groups, released = core.fitted_groups([ln.frequency for ln in lines],
                                       [float(np.linalg.norm(ln.amplitude)) for ln in lines])
        for f0, members, orders in groups:
            order_sort = np.argsort(orders)
            mem = [members[k] for k in order_sort]
            harmonics.append(FittedHarmonics(
                f0, tuple(int(orders[k]) for k in order_sort),
                np.array([lines[m].amplitude for m in mem]),
                np.array([lines[m].phase for m in mem])))
            taken.update(members)
    tones = tuple(FittedTone(ln.frequency, ln.amplitude, ln.phase)
                  for k, ln in enumerate(lines) if k not in taken)
    return tones, tuple(harmonics), tuple(float(lines[k].frequency) for k in released)


def fit_warnings(angular: FittedPart, linear: FittedPart | None, head: str,
                 spectrum: str = "the recording's") -> list[str]:
    """What a fitted profile does not hold of its spectrum, each warning after ``head``
    (the file's name, or the envelope's): each axis whose fitted PSD is off the measured
    one (:func:`shape_warnings`; ``spectrum`` names what was measured), and the orders of a
    fundamental let go of their phase-locked group, written as independent tones so that
    the profile's ``phase: worst`` search stays within budget
    (:func:`gyrovib.core.recording.fitted_groups`)."""
    out = (shape_warnings(angular, "rate", spectrum)
           + shape_warnings(linear, "acceleration", spectrum))
    if angular.released:
        out.append("lines at " + ", ".join(f"{f:.4g}" for f in angular.released)
                   + " Hz, orders of a fundamental, are written as independent tones: a "
                   "phase: worst search over every order would exceed its budget")
    return [headed(f"{head}: ", w) for w in out]


def shape_warnings(part: FittedPart | None, kind: str,
                   spectrum: str = "the recording's") -> list[str]:
    """A warning per axis whose fitted PSD is off the measured one (``spectrum``'s) by
    more than :data:`SHAPE_DB_LIMIT` dB power-weighted, or with more than
    :data:`OFF_3DB_LIMIT` of the power in bins off by 3 dB (docs/model.md section 13);
    none for no part."""
    out: list[str] = []
    if part is None:
        return out
    for axis, db, off in zip("XYZ", part.shape_db, part.off_3db, strict=True):
        if db > SHAPE_DB_LIMIT or off > OFF_3DB_LIMIT:
            out.append(Note(f"the fitted {kind} PSD of axis {axis} is off the measured one "
                            f"by {db:.2g} dB (power-weighted), {100 * off:.0f} % of the power "
                            f"by more than 3 dB: its shape is not {spectrum} (raise "
                            "{breakpoints}, or read the plot)", ("breakpoints", None)))
    return out
