"""The envelope profile of several recordings (docs/fleet.md).

The envelope is a reduction: :func:`envelope_part` turns a fit into an
:class:`EnvelopePart`, :func:`combine` joins two parts (associative and, but for
the order of the joined mission segments and recordings, commutative: maxima and
concatenations), and :func:`fit_envelope` fits the catalogue profile to the joined
part as :func:`fit_recording` fits one recording. What each part of the profile is over
the recordings (per bin the largest random PSD on the coarsest grid, lines within
max(Δf, 1 % of f) merged at their largest amplitude, the coherences of the recording with
the largest vibration variance, the joined mission re-binned past 16 segments by
:func:`fleet_mission`) is docs/fleet.md's table.
"""

from __future__ import annotations

import dataclasses
import hashlib
import math
import os
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from gyrovib.api.fleet.duplicates import refuse_same_contents, refuse_same_paths
from gyrovib.api.fleet.run import DEFAULTS, RecordingOptions, profile_one, run_recordings
from gyrovib.api.recordings.fit import LINE_FLOOR, fit_warnings, random_tables
from gyrovib.api.recordings.results import (
    AxisHonesty,
    FittedHarmonics,
    FittedPart,
    FittedTone,
    RecordingFit,
)
from gyrovib.api.recordings.yaml import missing_comments, missing_parts, profile_yaml
from gyrovib.catalog.loader import parse_catalog
from gyrovib.catalog.writer import measured
from gyrovib.core import recording as core
from gyrovib.core._types import FloatArray
from gyrovib.core.recording import HARMONIC_TOLERANCE, MISSION_BINS, find_lines
from gyrovib.errors import GyrovibError, OptionError
from gyrovib.frozen import Frozen

#: Default id of an envelope profile (``--id`` chooses another).
ENVELOPE_ID = "envelope-fitted"


def _read_only(result: Any) -> None:
    for f in dataclasses.fields(result):
        value = getattr(result, f.name)
        if isinstance(value, np.ndarray):
            value.setflags(write=False)


@dataclass(frozen=True, eq=False, repr=False)
class Provenance(Frozen):
    """One recording of an envelope: its file (base name), SHA-256, size and rate."""

    file: str
    sha256: str
    samples: int
    fs: float
    duration: float


@dataclass(frozen=True, eq=False, repr=False)
class SpectrumEnvelope(Frozen):
    """One kind of vibration over several recordings, before its fit.

    ``random``, ``measured``, ``median`` (3, F) on ``frequencies``: per bin the
    largest over the recordings (NaN: no recording knows that axis at that bin);
    ``lines`` (L,), ``amplitudes`` (L, 3), ``phases`` (L, 3): every recording's
    spectral lines; ``coherence`` of the recording with the largest ``weight``.
    """

    frequencies: FloatArray
    random: FloatArray
    measured: FloatArray
    median: FloatArray
    lines: FloatArray
    amplitudes: FloatArray
    phases: FloatArray
    coherence: FloatArray
    weight: float

    def __post_init__(self) -> None:
        _read_only(self)


@dataclass(frozen=True, eq=False, repr=False)
class EnvelopePart(Frozen):
    """What :func:`fit_envelope` needs of a set of recordings (see the module docstring);
    :func:`combine` joins two, :func:`envelope_part` makes one from a fit."""

    crossover: float
    recordings: tuple[Provenance, ...]
    angular: SpectrumEnvelope
    linear: SpectrumEnvelope | None
    rate_time: FloatArray  # Σ (mean Ω_K · duration), deg
    mission_rates: FloatArray
    mission_durations: FloatArray
    rate_axes: tuple[bool, bool, bool]
    segments: int
    #: Whether every recording recorded the accelerations (else they are unknown).
    accel_everywhere: bool = True

    def __post_init__(self) -> None:
        _read_only(self)


def _lines_of(part: FittedPart) -> tuple[FloatArray, FloatArray, FloatArray]:
    freq = [t.frequency for t in part.tones]
    amp = [t.amplitude for t in part.tones]
    phase = [t.phase for t in part.tones]
    for h in part.harmonics:
        for k, order in enumerate(h.orders):
            freq.append(h.fundamental * order)
            amp.append(h.amplitude[k])
            phase.append(h.phase[k])
    return (np.array(freq, dtype=float), np.array(amp, dtype=float).reshape(-1, 3),
            np.array(phase, dtype=float).reshape(-1, 3))


def _spectrum(part: FittedPart, crossover: float, tone_threshold: float, *,
              rate: bool) -> SpectrumEnvelope:
    """The random PSD the fit's breakpoints were fitted to, found again as the fit finds
    it: its lines' lobes (:func:`gyrovib.core.recording.find_lines` on the measured PSD,
    which alone decides them) replaced by the running median."""

    f = part.frequencies
    measured = np.array(part.measured, dtype=float)
    diagonal = np.zeros((3, 3, f.size), dtype=complex)
    for j in range(3):
        diagonal[j, j] = measured[j]
    found, median = find_lines(f, diagonal, tone_threshold, fmin=LINE_FLOOR * crossover)
    random = measured.copy()
    for line in found:
        random[:, line.lo:line.hi] = median[:, line.lo:line.hi]
    lines, amps, phases = _lines_of(part)
    unknown = ~np.isfinite(np.asarray(part.variance, dtype=float))
    for array in (random, measured, median):
        array[unknown] = np.nan
    variance = np.asarray(part.variance, dtype=float)
    weight = variance[2] if rate else float(np.nansum(variance))
    return SpectrumEnvelope(f, random, measured, median, lines, amps, phases,
                            np.array(part.coherence, dtype=float),
                            float(weight) if math.isfinite(weight) else -math.inf)


def envelope_part(fit: RecordingFit, options: RecordingOptions = DEFAULTS
                  ) -> EnvelopePart:
    """One recording's fit as the start of an envelope (``options``: those it was fitted
    with; the tone threshold tells its lines' lobes again)."""
    threshold = options.tone_threshold
    durations = np.asarray(fit.mission_durations, dtype=float)
    return EnvelopePart(
        crossover=fit.crossover,
        recordings=(Provenance(os.path.basename(fit.file), fit.sha256, fit.samples, fit.fs,
                               fit.duration),),
        angular=_spectrum(fit.angular, fit.crossover, threshold, rate=True),
        linear=(None if fit.linear is None
                else _spectrum(fit.linear, fit.crossover, threshold, rate=False)),
        rate_time=np.asarray(fit.rate, dtype=float) * fit.duration,
        mission_rates=np.asarray(fit.mission_rates, dtype=float).reshape(-1, 3),
        mission_durations=durations, rate_axes=fit.rate_axes, segments=fit.segments,
        accel_everywhere="acceleration" not in missing_parts(fit))


def _on_grid(s: SpectrumEnvelope, grid: FloatArray) -> tuple[FloatArray, ...]:
    f = s.frequencies
    if f.shape == grid.shape and np.array_equal(f, grid):
        return s.random, s.measured, s.median
    out = []
    for array in (s.random, s.measured, s.median):
        out.append(np.stack([np.interp(grid, f, row, left=np.nan, right=np.nan)
                             for row in array]))
    return tuple(out)


def _common_grid(a: FloatArray, b: FloatArray) -> FloatArray:
    if a.shape == b.shape and np.array_equal(a, b):
        return a
    df = max(float(a[1] - a[0]), float(b[1] - b[0]))
    top = max(float(a[-1]), float(b[-1]))
    return df * np.arange(math.floor(top / df * (1 + 1e-12)) + 1, dtype=float)


def _join_spectra(a: SpectrumEnvelope | None,
                  b: SpectrumEnvelope | None) -> SpectrumEnvelope | None:
    if a is None or b is None:
        return a if b is None else b
    grid = _common_grid(a.frequencies, b.frequencies)
    ra, ma, da = _on_grid(a, grid)
    rb, mb, db = _on_grid(b, grid)
    coherence, weight = (a.coherence, a.weight) if a.weight >= b.weight else (b.coherence,
                                                                             b.weight)
    return SpectrumEnvelope(grid, np.fmax(ra, rb), np.fmax(ma, mb), np.fmax(da, db),
                            np.concatenate([a.lines, b.lines]),
                            np.concatenate([a.amplitudes, b.amplitudes]),
                            np.concatenate([a.phases, b.phases]), coherence, weight)


def combine(a: EnvelopePart, b: EnvelopePart) -> EnvelopePart:
    """The envelope of the recordings of ``a`` and of ``b`` (``a``'s first)."""
    if a.crossover != b.crossover:
        raise OptionError(f"recordings fitted with different crossovers ({a.crossover:g} and "
                          f"{b.crossover:g} Hz) have no common envelope")
    angular = _join_spectra(a.angular, b.angular)
    assert angular is not None
    return EnvelopePart(
        crossover=a.crossover, recordings=a.recordings + b.recordings, angular=angular,
        linear=_join_spectra(a.linear, b.linear), rate_time=a.rate_time + b.rate_time,
        mission_rates=np.concatenate([a.mission_rates, b.mission_rates]),
        mission_durations=np.concatenate([a.mission_durations, b.mission_durations]),
        # an axis is known in the envelope only where every recording recorded it
        rate_axes=(a.rate_axes[0] and b.rate_axes[0], a.rate_axes[1] and b.rate_axes[1],
                   a.rate_axes[2] and b.rate_axes[2]),
        segments=a.segments + b.segments,
        accel_everywhere=a.accel_everywhere and b.accel_everywhere)


def _merged_lines(s: SpectrumEnvelope) -> list[tuple[float, FloatArray, FloatArray]]:
    """Lines within max(Δf, 1 % of f) of the first of a run are one line: per axis its
    largest amplitude; frequency and phases where its amplitude is largest."""

    df = float(s.frequencies[1] - s.frequencies[0])
    order = np.argsort(s.lines, kind="stable").tolist()
    merged: list[tuple[float, FloatArray, FloatArray]] = []
    k = 0
    while k < len(order):
        anchor = float(s.lines[order[k]])
        run = [order[k]]
        k += 1
        while k < len(order) and s.lines[order[k]] - anchor <= max(df, HARMONIC_TOLERANCE
                                                                   * anchor):
            run.append(order[k])
            k += 1
        amps = s.amplitudes[run]
        strongest = run[int(np.argmax(np.linalg.norm(amps, axis=1)))]
        merged.append((float(s.lines[strongest]), amps.max(axis=0),
                       s.phases[strongest].copy()))
    return merged


def _fitted(s: SpectrumEnvelope, crossover: float, breakpoints: int, independent: bool,
            *, rate: bool) -> FittedPart:

    f = s.frequencies
    df = float(f[1] - f[0])
    band = (f >= crossover) & (f < f[-1])
    known = np.any(np.isfinite(s.random[:, band]), axis=1)
    random = np.nan_to_num(s.random[:, band], nan=0.0)
    spectrum_var = np.where(known, random.sum(axis=1) * df, np.nan)
    tables, sigma2, shape = random_tables(f[band], random, spectrum_var, breakpoints)
    lines = _merged_lines(s)
    tones: list[FittedTone] = []
    harmonics: list[FittedHarmonics] = []
    grouped: set[int] = set()
    released: list[int] = []
    if rate and not independent:
        groups, released = core.fitted_groups([ln[0] for ln in lines],
                                       [float(np.linalg.norm(ln[1])) for ln in lines])
        for f0, members, orders in groups:
            ranked = sorted(range(len(members)), key=lambda m: orders[m])
            harmonics.append(FittedHarmonics(
                f0, tuple(int(orders[m]) for m in ranked),
                np.array([lines[members[m]][1] for m in ranked]),
                np.array([lines[members[m]][2] for m in ranked])))
            grouped.update(members)
    tones = [FittedTone(*line) for k, line in enumerate(lines) if k not in grouped]
    tone_var = sum((amp**2 / 2 for _, amp, _ in lines), np.zeros(3))
    variance = spectrum_var + tone_var
    with np.errstate(invalid="ignore", divide="ignore"):
        held = np.where(variance > 0, (tone_var + sigma2) / variance, np.nan)
    return FittedPart(tones=tuple(tones), harmonics=tuple(harmonics),
                      psd=(tables[0], tables[1], tables[2]), coherence=s.coherence,
                      frequencies=f, measured=s.measured, median=s.median,
                      variance=variance, held=held, shape_db=shape[0], off_3db=shape[1],
                      released=tuple(lines[k][0] for k in released))


def fleet_mission(rates: FloatArray, durations: FloatArray) -> tuple[FloatArray, FloatArray]:
    """The joined missions' segments (rates (k, 3) deg/s, durations (k,) s) as written:
    unchanged while k ≤ 16, else their carrier histogram — at most 16 bins of Ω_K3 of
    equal width over the joined range (the one-recording rule), each bin the total time
    of the segments it takes at their time-weighted mean rate."""

    if durations.size <= MISSION_BINS:
        return rates, durations
    c = rates[:, 2]
    lo, hi = float(c.min()), float(c.max())
    if hi - lo <= 1e-9 * max(abs(lo), abs(hi)):  # one carrier rate, up to rounding
        idx = np.zeros(c.size, dtype=np.intp)
    else:
        edges = np.linspace(lo, hi, MISSION_BINS + 1)
        idx = np.clip(np.searchsorted(edges, c, side="right") - 1, 0, MISSION_BINS - 1)
    time = np.bincount(idx, weights=durations, minlength=MISSION_BINS)
    keep = time > 0
    mean = np.column_stack([np.bincount(idx, weights=durations * rates[:, j],
                                        minlength=MISSION_BINS)[keep] / time[keep]
                            for j in range(3)])
    return mean, np.asarray(time[keep], dtype=float)


@dataclass(frozen=True, eq=False, repr=False)
class Envelope(Frozen):
    """Several recordings and their envelope profile: ``fits`` in input order (empty when
    the envelope was reduced elsewhere, e.g. on Dask), ``fit`` the envelope as a
    :class:`RecordingFit` (``yaml`` its catalogue text, ``honesty`` per axis its
    variance and the share the fitted profile holds of its own spectrum's variance)."""

    fit: RecordingFit
    recordings: tuple[Provenance, ...]
    fits: tuple[RecordingFit, ...] = field(default=())


def _honesty(part: FittedPart, j: int) -> AxisHonesty:
    """Axis ``j`` of the envelope: its variance, the share held and the shape figures of
    the fit against the envelope spectrum; the skewness and kurtosis of a time series
    the envelope is not (NaN: unknown)."""
    values: dict[str, Any] = {f.name: math.nan for f in dataclasses.fields(AxisHonesty)}
    values.update(variance=float(part.variance[j]), held=float(part.held[j]),
                  shape_db=float(part.shape_db[j]), off_3db=float(part.off_3db[j]))
    return AxisHonesty(**values)


def fit_envelope(part: EnvelopePart, options: RecordingOptions = DEFAULTS
                 ) -> Envelope:
    """The catalogue profile of an envelope (see the module docstring), YAML included:
    ``options.breakpoints``, ``independent_tones`` and ``profile_id`` as for one."""
    breakpoints, independent_tones = options.breakpoints, options.independent_tones
    profile_id = options.profile_id
    # one recording twice would count its time twice (here too for a reduction made
    # elsewhere, e.g. Dask's)
    refuse_same_contents((r.file, r.sha256) for r in part.recordings)

    angular = _known_axes(_fitted(part.angular, part.crossover, breakpoints,
                                  independent_tones, rate=True), part.rate_axes)
    linear = None if part.linear is None or not part.accel_everywhere else _fitted(
        part.linear, part.crossover, breakpoints, True, rate=False)
    duration = float(np.sum([r.duration for r in part.recordings]))
    pid = profile_id or ENVELOPE_ID
    mission_rates, mission_durations = fleet_mission(part.mission_rates,
                                                     part.mission_durations)
    identity = hashlib.sha256("\n".join(r.sha256 for r in part.recordings).encode())
    n = len(part.recordings)
    fit = RecordingFit(
        file=f"envelope of {n} recordings", sha256=identity.hexdigest(),
        samples=sum(r.samples for r in part.recordings),
        fs=max(r.fs for r in part.recordings), crossover=part.crossover,
        segments=part.segments, duration=duration, profile_id=pid,
        rate=part.rate_time / duration if duration > 0 else np.zeros(3),
        mission_rates=mission_rates, mission_durations=mission_durations,
        angular=angular, linear=linear,
        honesty=tuple(_honesty(angular, j)
                      for j in range(3)),  # type: ignore[arg-type]
        rate_axes=part.rate_axes, warnings=tuple(fit_warnings(
            angular, linear, f"envelope of {n} recordings", "the envelope spectrum's")),
        yaml="")
    body = profile_yaml(fit, independent_tones=independent_tones)
    text = (_envelope_header(part) + "".join(f"{c}\n" for c in missing_comments(
        missing_parts(fit))) + body[body.index("\ngyrovib: 1\n"):])
    try:
        parse_catalog(text, "<envelope profile>")
    except GyrovibError as exc:
        raise OptionError(argument="profile_id", value=repr(pid),
                          reason="the envelope profile does not validate: "
                                 f"{exc.problems[0].message}") from None
    return Envelope(dataclasses.replace(fit, yaml=text), part.recordings)


def _known_axes(part: FittedPart, axes: tuple[bool, bool, bool]) -> FittedPart:
    """The envelope's part without a random PSD on an axis some recording did not record
    (its envelope is unknown there, not the others' largest)."""
    off = ~np.array(axes)
    if not off.any():
        return part
    nan = np.where(off, np.nan, 1.0)
    return dataclasses.replace(
        part, psd=tuple(None if off[j] else part.psd[j] for j in range(3)),  # type: ignore[arg-type]
        variance=part.variance * nan, held=part.held * nan, shape_db=part.shape_db * nan,
        off_3db=part.off_3db * nan)


def _envelope_header(part: EnvelopePart) -> str:

    lines = [
        f"# Envelope of {len(part.recordings)} recordings, fitted by `gyrovib profile` "
        "(docs/fleet.md):",
        "# per frequency bin the largest PSD of the recordings, each line at its largest "
        "amplitude,",
        "# the mission every recording's carrier histogram joined (re-binned to at most 16 "
        "bins of Omega_K3).",
        f"# crossover f_c: {measured(part.crossover)} Hz; segments: {part.segments}; duration "
        f"analysed: {measured(sum(r.duration for r in part.recordings))} s",
        "# Rates in deg/s (PSD in (deg/s)^2/Hz), accelerations in g (PSD in g^2/Hz).",
        "# recordings (file, sha256, samples, fs Hz, duration s):",
    ]
    lines += [f"#   {r.file}  {r.sha256}  {r.samples}  {measured(r.fs)}  {measured(r.duration)}"
              for r in part.recordings]
    return "\n".join(lines) + "\n"


def envelope(fits: Iterable[RecordingFit], options: RecordingOptions = DEFAULTS
             ) -> Envelope:
    """The envelope profile of several recordings fitted with ``options``, in their order
    (``options.profile_id`` names it)."""
    fits = tuple(fits)
    if not fits:
        raise OptionError("an envelope needs at least one recording")
    result = fit_envelope(reduce_parts(envelope_part(fit, options) for fit in fits), options)
    return dataclasses.replace(result, fits=fits)


def reduce_parts(parts: Iterable[EnvelopePart]) -> EnvelopePart:
    """:func:`combine` over ``parts`` in order, as a balanced tree (two of one size are
    joined as soon as both are there): the joined missions and lines are copied
    O(n log n) times, not O(n²), and at most log₂ n parts are held at once."""
    stack: list[tuple[int, EnvelopePart]] = []
    for part in parts:
        level = 0
        while stack and stack[-1][0] == level:
            part, level = combine(stack.pop()[1], part), level + 1
        stack.append((level, part))
    if not stack:
        raise OptionError("an envelope needs at least one recording")
    part = stack.pop()[1]
    while stack:
        part = combine(stack.pop()[1], part)
    return part


def envelope_step(path: str, options: RecordingOptions = DEFAULTS) -> EnvelopePart:
    """:func:`profile_one` then :func:`envelope_part`: what a fleet's worker returns when
    only the envelope is wanted (docs/fleet.md)."""
    return envelope_part(profile_one(path, dataclasses.replace(options, profile_id=None)),
                         options)


def profile_recordings(paths: Sequence[str], options: RecordingOptions = DEFAULTS,
                       *, jobs: int = 1) -> Envelope:
    """``gyrovib profile A B …``: every recording fitted (``jobs`` processes), then the
    envelope profile (``options.profile_id`` names it; the recordings keep their own)."""
    refuse_same_paths(paths)
    fits = run_recordings(paths, dataclasses.replace(options, profile_id=None), jobs=jobs)
    refuse_same_contents((fit.file, fit.sha256) for fit in fits)
    return envelope(fits, options)
