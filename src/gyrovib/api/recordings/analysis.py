"""A recording's analysis (docs/model.md section 13): Δ_V,rec of every sensor beside the
closed form of the fitted profile.

:func:`analyze_recording` fits the recording (:mod:`gyrovib.api.recordings.fit`) and
adds every chosen sensor's Δ_V,rec on the recording itself beside the closed form of
the fitted profile over the carrier histogram (the fitted mission), their ratio and
the honesty warnings (:mod:`gyrovib.api.recordings.honesty`): ``analyze --recording``.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from gyrovib import units
from gyrovib.api.commands.analyze import analysis_of
from gyrovib.api.commands.mission import mission
from gyrovib.api.datasheet.specs import figures, g2_unknown, is_spec
from gyrovib.api.evaluation.unknown import depends_on, not_recorded
from gyrovib.api.recordings.fit import fit_recording
from gyrovib.api.recordings.honesty import (
    RATIO_RANGE,
    at_mean_warnings,
    g2_warnings,
    ratio_warnings,
    unknown_warnings,
)
from gyrovib.api.recordings.reading import Recording
from gyrovib.api.recordings.records import recording_columns
from gyrovib.api.recordings.results import RecordingFit
from gyrovib.api.recordings.yaml import mission_id, with_fitted_profile
from gyrovib.api.study.convert import coefficient_matrix, sensor_ranges
from gyrovib.api.study.entries import select_entries
from gyrovib.api.study.linear import g2_matrix
from gyrovib.api.study.prepare import input_response
from gyrovib.api.study.study import Study
from gyrovib.core._types import FloatArray, Table
from gyrovib.core.envelope import worst_case
from gyrovib.core.recording import recorded_error
from gyrovib.core.transmissibility import as_table
from gyrovib.frozen import Frozen
from gyrovib.limits import (
    DEFAULT_BREAKPOINTS,
    DEFAULT_CROSSOVER,
    DEFAULT_RESOLUTION,
    DEFAULT_THRESHOLD,
)
from gyrovib.records import Column, frame_of


@dataclass(frozen=True, eq=False, repr=False)
class RecordingAnalysis(Frozen):
    """Δ_V,rec of every sensor beside the fitted mission's closed form (output unit).

    ``recorded`` (N,) Δ_V,rec; ``terms`` (N, 7) its parts per coefficient
    (:data:`gyrovib.core.recording.MOMENTS`); ``g2`` (N,) the g² part;
    ``fitted`` (N,) the time-weighted closed form over the fitted mission,
    ``fitted_rms`` (N,); ``ratio`` (N,) fitted/recorded (NaN where either is 0);
    ``saturated`` (N,), ``peak_rate`` (N,) max |ω3| at the element;
    ``spec`` (N,) bool: a datasheet sensor (worst case over its envelope);
    ``at_mean`` (N,) the fitted profile's closed form at its own (mean) rate, the
    number ``analyze`` gives on the written file (NaN where a g² figure is not given
    under the recorded linear vibration, as Δ_V,rec is), and
    ``at_mean_ratio`` (N,) its ratio to Δ_V,rec (NaN where either is 0 or unknown),
    warned of outside :data:`RATIO_RANGE` (one mean rate hides the carrier's spread: the
    fitted mission keeps it).
    """

    unit: str
    sensors: tuple[str, ...]
    recorded: FloatArray
    terms: FloatArray
    g2: FloatArray
    fitted: FloatArray
    fitted_rms: FloatArray
    ratio: FloatArray
    saturated: NDArray[np.bool_]
    peak_rate: FloatArray
    spec: NDArray[np.bool_]
    fit: RecordingFit
    warnings: dict[int, tuple[str, ...]]
    at_mean: FloatArray = field(default_factory=lambda: np.zeros(0))
    at_mean_ratio: FloatArray = field(default_factory=lambda: np.zeros(0))

    @property
    def at_mean_outside(self) -> NDArray[np.bool_]:
        """Per sensor: the profile at its mean rate and the recording disagree by more
        than :data:`RATIO_RANGE` (False where the ratio is unknown)."""
        lo, hi = RATIO_RANGE
        r = self.at_mean_ratio
        out: NDArray[np.bool_] = np.isfinite(r) & ((r < lo) | (r > hi))
        return out

    def records(self) -> tuple[Column[int], ...]:
        """The columns of the CSV, the frame and the JSON's ``results``, one row per sensor
        (its index): :func:`~gyrovib.api.recordings.records.recording_columns`."""
        return recording_columns(self)

    def to_frame(self) -> Any:
        """One row per sensor (pandas DataFrame): the columns of :meth:`records`."""
        fit = self.fit
        return frame_of(self.records(), range(len(self.sensors)), {
            "unit": self.unit, "file": os.path.basename(fit.file), "topic": fit.topic,
            "instance": fit.instance, "sha256": fit.sha256, "samples": fit.samples, "fs": fit.fs,
            "crossover": fit.crossover, "segments": fit.segments, "duration": fit.duration})


def analyze_recording(recording: Recording, catalog: Any, *, sensors: Sequence[str] = (),
                      unit: str = "deg/s", crossover: float = DEFAULT_CROSSOVER,
                      resolution: float = DEFAULT_RESOLUTION,
                      tone_threshold: float = DEFAULT_THRESHOLD,
                      breakpoints: int = DEFAULT_BREAKPOINTS, independent_tones: bool = False,
                      profile_id: str | None = None) -> RecordingAnalysis:
    """Δ_V,rec (docs/model.md section 13) of every chosen sensor, and the fitted mission's
    closed form beside it.

    Coefficient-form sensors: the definition itself, vectorised; sensors whose
    response acts at the input see ν·x (a zero-phase gain). Spec-form
    sensors: the worst Δ_V,rec over their datasheet envelope (it is linear in
    the coefficients, docs/model.md section 11). The closed form is the fitted
    mission's mean error Δ̄_V (docs/model.md section 12): the fitted profile at
    each histogram bin of Ω_K3, the bins weighted by their time, exactly as
    ``gyrovib mission`` computes it on the written YAML.
    """
    unit = units.canonical_unit(unit)
    entries, tables = recording_responses(catalog, sensors)
    fit = fit_recording(recording, crossover=crossover, resolution=resolution,
                        tone_threshold=tone_threshold, breakpoints=breakpoints,
                        independent_tones=independent_tones, profile_id=profile_id,
                        responses=tables)
    return analysis_of_fit(fit, catalog, entries, unit=unit)


def recording_responses(catalog: Any, sensors: Sequence[str] = ()) -> tuple[Sequence[Any],
                                                                          tuple[Table, ...]]:
    """The chosen sensor entries, and the distinct input-side responses among them (in
    order of first use): what :func:`fit_recording` needs as ``responses`` for
    :func:`analysis_of_fit` to find each sensor's Δ_V,rec moments."""

    entries, _ = select_entries(catalog, sensors, (), need=("sensors",))
    keys = [input_response(e) for e in entries]
    distinct = [k for k in dict.fromkeys(keys) if k is not None]
    return entries, tuple(as_table(k) for k in distinct)


def analysis_of_fit(fit: RecordingFit, catalog: Any, entries: Sequence[Any], *,
                    unit: str = "deg/s") -> RecordingAnalysis:
    """:func:`analyze_recording` on a fit already made with the ``responses`` of
    :func:`recording_responses` for the same ``entries`` (the fit can come from another
    process: it holds the recording's moments, never its samples)."""

    unit = units.canonical_unit(unit)
    keys = [input_response(e) for e in entries]
    distinct = [k for k in dict.fromkeys(keys) if k is not None]
    n = len(entries)
    coeffs = coefficient_matrix(entries)
    g2 = g2_matrix(entries)
    group = [None if k is None else distinct.index(k) for k in keys]
    moments = np.array([fit.moments[g] for g in group]).reshape(n, -1)
    peak = np.array([fit.peak[0 if g is None else g + 1] for g in group])
    total, terms, g2_part = recorded_error(coeffs, moments, g2, fit.g2_moments)
    total, terms, g2_part = total.copy(), terms.copy(), g2_part.copy()
    spec = np.array([is_spec(e) for e in entries], dtype=bool)
    if spec.any():
        total, terms, g2_part = _spec_recorded(entries, spec, moments, fit.g2_moments, total,
                                               terms, g2_part, figures)
    ranges = sensor_ranges(entries)
    saturated = peak > ranges
    fitted, fitted_rms, at_mean = _fitted_mission(fit, catalog,
                                                  [e.sensor.id for e in entries])
    unknown = depends_on(entries, fit_missing(fit), spec_cross=False)
    no_g2 = g2_not_given(entries, fit)
    _unknown_rows(unknown, no_g2, (total, g2_part, fitted, fitted_rms, at_mean), terms)
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = np.where((total != 0) & (fitted != 0), fitted / total, np.nan)
        at_mean_ratio = np.where((total != 0) & (at_mean != 0), at_mean / total, np.nan)
    s = units.scale(unit)
    warnings = unknown_warnings(unknown, ratio_warnings(fit, ratio, saturated, peak / s,
                                                    ranges / s, unit))
    g2_warnings(no_g2, spec, warnings)
    at_mean_warnings(fit, at_mean_ratio, warnings)
    return RecordingAnalysis(
        unit=unit, sensors=tuple(e.sensor.id for e in entries), recorded=total / s,
        terms=terms / s, g2=g2_part / s, fitted=fitted / s, fitted_rms=fitted_rms / s,
        ratio=ratio, saturated=saturated, peak_rate=peak / s, spec=spec, fit=fit,
        warnings=warnings, at_mean=at_mean / s, at_mean_ratio=at_mean_ratio)


def _unknown_rows(unknown: Sequence[tuple[str, ...]], no_g2: Sequence[int],
                  sums: Sequence[FloatArray], terms: FloatArray) -> None:
    """NaN, in place, where a row is unknown (never 0; docs/model.md section 13): every
    number of a row that depends on a part the recording lacks (``unknown``), and the
    g² term and every sum holding it on a row whose g² figure is not given (``no_g2``;
    its other terms stay, known). ``sums``: Δ_V,rec, its g² part, the fitted Δ̄_V and
    mean RMS, the at-mean total."""
    for i, parts in enumerate(unknown):
        if parts:
            terms[i] = np.nan
            for a in sums:
                a[i] = np.nan
    for i in no_g2:
        for a in sums:
            a[i] = np.nan


def g2_not_given(entries: Sequence[Any], fit: RecordingFit) -> list[int]:
    """The rows whose g² term is unknown on this recording: it recorded the accelerations
    of a linear vibration, and the sensor gives no g² figure (a coefficient-form sensor
    without ``g2_sensitivity`` or ``vre``, a datasheet part that publishes no VRE;
    docs/model.md sections 8 and 13)."""
    shaken = (fit.linear is not None and bool(np.all(np.isfinite(fit.linear.variance)))
              and bool(np.any(np.asarray(fit.linear.variance) > 0)))
    if not shaken:
        return []
    return [i for i, e in enumerate(entries)
            if (e.sensor.specs.vre is None if is_spec(e) else g2_unknown(e.sensor))]


def fit_missing(fit: RecordingFit) -> tuple[str, ...]:
    """The parts the fitted recording did not record (rate axes, accelerations)."""
    accel = fit.linear is not None and bool(np.all(np.isfinite(fit.linear.variance)))
    return not_recorded(fit.rate_axes, accel)


def recorded_totals(entries: Sequence[Any], moments: FloatArray,
                    g2_moments: FloatArray | None) -> FloatArray:
    """Δ_V,rec (deg/s) of every sensor of ``entries`` from mean moments (N, 7) and the mean
    g² moments (6,) or None: the definition for coefficient-form sensors, the worst case
    over the envelope for spec-form ones (docs/model.md sections 11, 13). The run-up test
    takes it step by step."""
    total, terms, g2_part = recorded_error(coefficient_matrix(entries), moments,
                                           g2_matrix(entries), g2_moments)
    spec = np.array([is_spec(e) for e in entries], dtype=bool)
    if spec.any():
        total = _spec_recorded(entries, spec, moments, g2_moments, total, terms, g2_part,
                               figures)[0]
    return total


def _spec_recorded(entries: Sequence[Any], spec: NDArray[np.bool_], moments: FloatArray,
                   g2_moments: FloatArray | None, total: FloatArray, terms: FloatArray,
                   g2_part: FloatArray, figures: Any) -> tuple[FloatArray, FloatArray,
                                                               FloatArray]:
    """Spec-form rows: worst Δ_V,rec over the envelope (docs/model.md sections 11, 13).

    Δ_V,rec = cᵀx + Σ G_jj⟨a_j² − A_j²⟩ with c = (½⟨|ω3|−|Ω3|⟩, ⟨ω3ⁿ−Ω3ⁿ⟩),
    k1 = 1 and m31 = m32 = 0 (datasheets do not give them); each row of c is
    handed to :func:`gyrovib.core.envelope.worst_case` as a diagonal term matrix.
    """

    total, terms, g2_part = total.copy(), terms.copy(), g2_part.copy()
    idx = np.flatnonzero(spec)
    figs = figures([entries[i] for i in idx.tolist()])
    s_acc = 0.0 if g2_moments is None else float(np.sum(g2_moments[:3]))
    for k, i in enumerate(idx.tolist()):
        t = np.zeros((1, 8, 5))
        for c in range(5):
            t[0, c, c] = moments[i, c]
        wc = worst_case(t, s_acc, figs.range[k:k + 1], figs.limit[k:k + 1],
                        figs.fit[k:k + 1], figs.measure[k:k + 1],
                        asymmetry=figs.asymmetry[k:k + 1], vre=figs.vre[k:k + 1])
        x = wc.coefficients[0, 0]
        terms[i] = 0.0
        terms[i, :5] = x * moments[i, :5]
        g2_part[i] = float(wc.g2[0, 0])
        total[i] = float(wc.total[0, 0])
    return total, terms, g2_part


def _fitted_mission(fit: RecordingFit, catalog: Any, sensor_ids: Sequence[str]
                    ) -> tuple[FloatArray, FloatArray, FloatArray]:
    """The fitted mission's closed form, deg/s: :func:`gyrovib.api.mission` on the mission
    the written YAML holds (the same numbers as ``gyrovib mission`` on that file), and
    the fitted profile's at its own mean rate (as ``gyrovib analyze`` on that file).

    Δ̄ = Σ T_b·Δ_V(Ω_b)/ΣT over the carrier histogram's bins, and the mean RMS
    √(Σ T_b·Δ_V(RMS)_b²/ΣT) (docs/model.md section 12). A spec-form sensor's Δ̄
    is the worst case over its envelope of the whole mission — one conversion
    function for every bin.
    """

    combined = with_fitted_profile(catalog, fit)
    result = mission(combined, missions=(mission_id(fit),), sensors=sensor_ids, unit="deg/s")
    rows = {r.sensor: r for r in result.rows}
    total = np.array([rows[s].mean for s in sensor_ids], dtype=float)
    rms = np.array([rows[s].rms for s in sensor_ids], dtype=float)
    at_rate = analysis_of(Study.of(combined, sensors=sensor_ids, profiles=(fit.profile_id,)),
                          unit="deg/s")
    where = {s: i for i, s in enumerate(at_rate.sensors)}
    at_mean = np.array([at_rate.error.total[where[s], 0] for s in sensor_ids], dtype=float)
    return total, rms, at_mean
