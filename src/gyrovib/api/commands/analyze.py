"""``analyze``: the direct problem, eq. (13)-(16) for every sensor × profile."""

from __future__ import annotations

import zlib
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from gyrovib import units
from gyrovib.api.datasheet import specs
from gyrovib.api.evaluation.evaluate import (
    ERROR_PARTS,
    errors,
    numeric_done,
    numeric_polynomials,
    phase_bound,
    phase_worst,
    saturation,
    worst_case,
)
from gyrovib.api.evaluation.results import AnalysisResult
from gyrovib.api.evaluation.unknown import unknown_cells, unknown_g2
from gyrovib.api.lots.uncertainty import distributions, with_uncertainty
from gyrovib.api.study.convert import catalog_unit, error_arrays, to_unit
from gyrovib.api.study.prepare import (
    Group,
    Prepared,
    check_finite,
    float_guard,
    profile_problem,
)
from gyrovib.api.study.study import Study, check_peak_factor
from gyrovib.catalog.loader import Catalog
from gyrovib.core._types import FloatArray
from gyrovib.core.analysis import METHODS, VibrationError, vibration_error
from gyrovib.core.harmonics import LockedGroup
from gyrovib.core.linear import LinearVibration
from gyrovib.core.saturation import DEFAULT_PEAK_FACTOR
from gyrovib.core.statistics import Vibration
from gyrovib.errors import ModelError, OptionError, literal
from gyrovib.limits import MAX_SAMPLES, MIN_SAMPLES

#: Every method of :func:`analyze`: the closed forms, and brute force.
ANALYZE_METHODS: tuple[str, ...] = (*METHODS, "numeric")
#: Defaults of the numeric method.
DEFAULT_SAMPLES = 200_000
DEFAULT_SEED = 0

ProgressCallback = Callable[[int, int], None]

def profile_generator(seed: int, profile_id: str) -> np.random.Generator:
    """The random stream of one profile: a function of the seed and the profile id only.

    So a profile's numbers do not change when other profiles or sensors are
    selected or deselected.
    """
    return np.random.default_rng([seed, zlib.crc32(profile_id.encode("utf-8"))])


def _check_options(method: str, samples: int, seed: int) -> None:
    if method not in ANALYZE_METHODS:
        raise OptionError(f"unknown method {method!r}; use one of {', '.join(ANALYZE_METHODS)}")
    if method != "numeric":
        return
    if samples < MIN_SAMPLES:
        raise OptionError(argument="samples", value=str(samples),
                          reason=f"give at least {MIN_SAMPLES}")
    if samples > MAX_SAMPLES:
        raise OptionError(argument="samples", value=str(samples),
                          reason=f"give at most {MAX_SAMPLES:,} (10^8 evaluations of eq. 2 "
                                 "already take minutes)")
    if seed < 0:
        raise OptionError(argument="seed", value=str(seed),
                          reason="the seed must be a non-negative integer")


def analyze(
    catalog: Catalog,
    *,
    sensors: Sequence[str] = (),
    profiles: Sequence[str] = (),
    method: str = "exact",
    rate: Sequence[float] | None = None,
    unit: str = "deg/s",
    samples: int = DEFAULT_SAMPLES,
    seed: int = DEFAULT_SEED,
    progress: ProgressCallback | None = None,
    peak_factor: float = DEFAULT_PEAK_FACTOR,
) -> AnalysisResult:
    """Eq. (13)-(16) for every chosen sensor under every chosen profile.

    ``rate`` overrides Ω_K (in deg/s): one number for Ω_K3, or three.
    ``unit`` is the output unit.

    ``method="numeric"`` averages eq. (2) itself over the vibration
    (:func:`gyrovib.core.numeric.simulate`, ``samples`` evaluations per sensor
    × profile, random streams from ``seed``): ``error.total`` is that
    brute-force Δ_V and :attr:`AnalysisResult.stderr` its standard error. The
    other fields of ``error`` come from the closed-form term formulas applied
    to the sample moments (<x3²>, <x3⁴>, <x3·xi>, <|Ω+x3|>) of the same
    samples, so they are brute-force estimates too, without their own stderr.
    ``progress(done, total)`` is called as samples are evaluated.

    A spec-form sensor (``specs:``) gets the worst case over its datasheet
    envelope (:mod:`gyrovib.api.datasheet.specs`): under ``exact`` or ``paper`` that
    method's multipliers feed the programme; under ``numeric`` the worst
    polynomial (found with the exact multipliers) is averaged by brute force,
    and ``rms`` stays the per-term bound.

    Phase-locked harmonics (docs/model.md section 10) add the terms k3·M3 and k5·M5
    (``error.extra_terms``); a profile with ``phase: worst`` orders is
    evaluated at the phases that maximise |Δ_V| for each sensor
    (:attr:`AnalysisResult.worst_phases`; a spec-form sensor's worst case there
    takes each multiplier at its largest over the phases, and reports none).
    :attr:`AnalysisResult.saturated`
    flags where |Ω_K3| + Σ tone amplitudes + Σ locked peaks + κσ3 at the
    nonlinear element exceeds the sensor's range (κ = ``peak_factor``,
    docs/model.md section 9).
    """
    _check_options(method, samples, seed)
    check_peak_factor(peak_factor)
    study = Study.of(catalog, sensors=sensors, profiles=profiles, rate=rate)
    return analysis_of(study, method=method, unit=unit, samples=samples, seed=seed,
                       progress=progress, peak_factor=peak_factor)


def analysis_of(study: Study, *, method: str = "exact", unit: str = "deg/s",
                samples: int = DEFAULT_SAMPLES, seed: int = DEFAULT_SEED,
                progress: ProgressCallback | None = None,
                peak_factor: float = DEFAULT_PEAK_FACTOR,
                g2_unknown_as_zero: bool = False) -> AnalysisResult:
    """:func:`analyze` as a view of a :class:`~gyrovib.api.study.study.Study`.
    ``g2_unknown_as_zero``: a g² term whose figure is unknown is left out of the numbers
    (a mission's totals, whose rows name the figure themselves); by default that term,
    Δ_VA, Δ_V and Δ_V(RMS) are NaN there (unknown)."""
    _check_options(method, samples, seed)
    unit = units.canonical_unit(unit)
    numeric = method == "numeric"
    with float_guard():
        prepared = study.prepare(methods=() if numeric else (method,),
                                 peak_factor=peak_factor, phase_search=False)
        n_p = len(prepared.profiles)
        stderr = None
        if numeric:
            _refuse_unknown_phases(prepared)
        datasheet = phase_bound(study, prepared, method, peak_factor)
        spec = worst_case(study, datasheet, "exact" if numeric else method)
        worst: dict[tuple[int, int], tuple[dict[str, float], ...]] = {}
        if numeric:
            parts, stderr = _numeric(prepared, spec, samples, seed, progress)
        else:
            parts, worst = _closed_form(study, prepared, datasheet, method)
        warnings = specs.with_unknown_g2(
            specs.with_cross_axis(_saturation(prepared, unit), spec, _shaken(prepared)),
            prepared.sensors, _shaken(prepared))
        saturated = saturation(prepared).saturated
        error = to_unit(VibrationError(**parts), unit)
        out_scale = units.scale(unit)
        stderr_out = None if stderr is None else stderr / out_scale
        check_finite([*error_arrays(error), *([] if stderr_out is None else [stderr_out])],
                     prepared)
        unknown_cells(prepared, error, warnings)
        fields = _spec_fields(prepared, spec, unit, error, g2_unknown_as_zero)
        locked = tuple(any(bool(g.locked[j]) for g in prepared.groups) for j in range(n_p))
        spread = _spread(study, prepared, method, unit, peak_factor, error.total)
    return AnalysisResult(
        method=method,
        unit=unit,
        sensors=tuple(e.sensor.id for e in prepared.sensors),
        profiles=tuple(p.profile.id for p in prepared.profiles),
        rates=prepared.rates / out_scale,
        error=error,
        warnings=warnings,
        stderr=stderr_out,
        samples=samples if numeric else None,
        seed=seed if numeric else None,
        linear=tuple(_shaken(prepared)),
        **fields,
        saturated=saturated,
        peak_factor=peak_factor,
        locked=locked,
        worst_phases=worst,
        rate_unit=catalog_unit([p.unit for p in prepared.profiles]),
        **spread,
    )


def _spec_fields(prepared: Prepared, spec: Any, unit: str, error: VibrationError,
                 g2_unknown_as_zero: bool) -> dict[str, Any]:
    """The spec-form fields of the result; unless ``g2_unknown_as_zero``, the numbers that
    hold a g² term whose figure is unknown made NaN, in ``error`` and the RMS bound."""
    fields = specs.analysis_fields(len(prepared.sensors), len(prepared.profiles), spec, unit)
    if not g2_unknown_as_zero:
        unknown_g2(error, fields.get("rms_bound"),
                   specs.unknown_g2_cells(prepared.sensors, spec, _shaken(prepared)))
    return fields


def _spread(study: Study, prepared: Prepared, method: str, unit: str,
            peak_factor: float, total: FloatArray) -> dict[str, Any]:
    """The uncertainty fields of the result
    (:func:`~gyrovib.api.lots.uncertainty.with_uncertainty`); under ``numeric``, g comes
    from the Study's exact multipliers (the closed form's). The uncertainty of an unknown
    Δ_V (NaN in ``total``) is unknown too."""
    if method == "numeric" and any(d is not None for d in distributions(prepared)):
        prepared = study.prepare(methods=("exact",), peak_factor=peak_factor,
                                 phase_search=False)
    spread = with_uncertainty(prepared, method, unit)
    if "uncertainty" in spread:
        spread["uncertainty"] = np.where(np.isnan(total), np.nan, spread["uncertainty"])
    return spread


def _shaken(prepared: Prepared) -> list[bool]:
    """Per profile, whether it has a linear vibration (docs/model.md section 8)."""
    return [v is not None for v in prepared.linear]


def _closed_form(study: Study, prepared: Prepared, datasheet: Prepared, method: str,
                 ) -> tuple[dict[str, FloatArray],
                            dict[tuple[int, int], tuple[dict[str, float], ...]]]:
    """Eq. (13)-(16) by ``method`` (deg/s); under ``exact``, profiles with ``phase:
    worst`` orders at the phases found for each coefficient sensor, and those phases."""
    parts = errors(study, prepared, method, datasheet=datasheet)
    worst: dict[tuple[int, int], tuple[dict[str, float], ...]] = {}
    if method == "exact":
        for group in prepared.groups:
            worst.update(_worst_phases(prepared, group, parts))
    return parts, worst


def _numeric(prepared: Prepared, spec: specs.SpecResults | None, samples: int, seed: int,
             progress: ProgressCallback | None,
             ) -> tuple[dict[str, FloatArray], FloatArray]:
    """Brute force of eq. (2) for every sensor group × profile (deg/s), and its stderr.

    A datasheet sensor averages its worst polynomial; its ``total`` gets the g²
    part |v|·S and its ``rms`` stays the per-term bound (:func:`specs.place_analysis`).
    """
    n_s, n_p = len(prepared.sensors), len(prepared.profiles)
    parts = {name: np.zeros((n_s, n_p, *tail)) for name, tail in ERROR_PARTS.items()}
    stderr = np.zeros((n_s, n_p))
    tracker = _Tracker(progress, len(prepared.groups) * n_p * samples)
    for group in prepared.groups:
        idx = group.index
        for j, (p, v) in enumerate(zip(prepared.profiles, group.vibrations, strict=True)):
            block = numeric_polynomials(prepared, idx, j, spec)
            err, stderr[idx, j] = _simulate(block, v, prepared.rates[j], samples,
                                            profile_generator(seed, p.profile.id),
                                            tracker, group.locked[j],
                                            linear=prepared.linear[j], g2=prepared.g2[idx])
            for name, array in parts.items():
                array[idx, j] = getattr(err, name)
    numeric_done(prepared, parts, spec)
    return parts, stderr


def _refuse_unknown_phases(prepared: Prepared) -> None:
    """Brute force averages one waveform: it needs every phase of a locked group."""
    problems = [
        profile_problem(p, f"profile {literal(repr(p.profile.id))}: the numeric method averages "
                           "one waveform and needs the phases of every order; 'phase: worst' "
                           "is searched by {method} exact (its worst_phases give phases "
                           "to write in)", ("method",))
        for j, p in enumerate(prepared.profiles)
        if any(g.worst.any() for group in prepared.groups for g in group.locked[j])]
    if problems:
        raise ModelError(problems, reason="phase: worst with the numeric method")


def _worst_phases(prepared: Prepared, group: Group, parts: dict[str, FloatArray],
                  ) -> dict[tuple[int, int], tuple[dict[str, float], ...]]:
    """Profiles with ``phase: worst`` orders: the phases maximising |Δ_V| per sensor.

    Overwrites those profiles' columns of ``parts`` (deg/s) with the error at
    the phases found (:func:`~gyrovib.api.evaluation.evaluate.phase_worst`: each
    form searches its own rows, or none); returns, per (sensor, profile), per
    locked group, the phase (degrees, common to the axes) of each order written
    ``worst``.
    """
    out: dict[tuple[int, int], tuple[dict[str, float], ...]] = {}
    for j, idx, found in phase_worst(prepared, group):
        locked = group.locked[j]
        for name, array in parts.items():
            array[idx, j] = getattr(found.error, name)
        for k, sensor in enumerate(idx.tolist()):
            per_group: list[dict[str, float]] = [{} for _ in locked]
            for gi, g in enumerate(locked):
                for oi in np.flatnonzero(g.worst).tolist():
                    per_group[gi][str(int(g.orders[oi]))] = 0.0
            for (gi, oi), psi in zip(found.free, found.offsets[k], strict=True):
                phase = float(np.rad2deg(psi)) % 360.0
                per_group[gi][str(int(locked[gi].orders[oi]))] = phase
            out[(sensor, j)] = tuple(per_group)
    return out


def _saturation(prepared: Prepared, unit: str) -> dict[tuple[int, int], tuple[str, ...]]:
    """Warnings where the saturation reach (|Ω_K3| + the vibration's peak) exceeds a range."""
    out_scale = units.scale(unit)
    found = saturation(prepared)
    reach, ranges = found.reach, found.ranges
    warnings: dict[tuple[int, int], tuple[str, ...]] = {}
    messages: dict[tuple[float, float], tuple[str, ...]] = {}  # one text per value pair
    for sensor, j in zip(*(a.tolist() for a in np.nonzero(found.saturated)), strict=True):
        key = (float(reach[sensor, j]), float(ranges[sensor]))
        message = messages.get(key)
        if message is None:
            message = messages[key] = (
                f"|Ω_K3| + vibration peak = {reach[sensor, j] / out_scale:.6g} {unit} exceeds "
                f"the sensor's range {ranges[sensor] / out_scale:.6g} {unit}: "
                "the static model does not hold in saturation",
            )
        warnings[(sensor, j)] = message
    return warnings


class _Tracker:
    """Turns per-block sample counts into ``progress(done, total)`` calls."""

    def __init__(self, callback: ProgressCallback | None, total: int) -> None:
        self.callback = callback
        self.total = total
        self.done = 0

    def __call__(self, advance: int) -> None:
        self.done += advance
        if self.callback is not None:
            self.callback(min(self.done, self.total), self.total)

    def finish_block(self, planned: int, used: int) -> None:
        """Account for a scheme that evaluated fewer points than planned."""
        if planned > used:
            self(planned - used)


def _simulate(coefficients: FloatArray, vibration: Vibration, rate: FloatArray, samples: int,
              rng: np.random.Generator, tracker: _Tracker,
              locked: Sequence[LockedGroup] = (), *,
              linear: LinearVibration | None = None, g2: FloatArray | None = None,
              ) -> tuple[VibrationError, FloatArray]:
    """Brute force for one profile and one group of sensors (deg/s).

    ``locked``: the profile's phase-locked groups (docs/model.md section 10).
    ``linear`` (g) with ``g2`` (deg/s per g²): the profile's linear vibration,
    whose g² term the brute force averages too (docs/model.md section 8).
    """
    # lazy: the brute force only with --method numeric
    from gyrovib.core.numeric import simulate

    before = tracker.done
    estimate = simulate(coefficients, vibration, rate, samples=samples, rng=rng,
                        progress=tracker, locked=locked, linear=linear,
                        g2_sensitivity=None if linear is None else g2)
    tracker.finish_block(samples, tracker.done - before)
    terms = vibration_error(coefficients, estimate.multipliers,
                            g2_sensitivity=None if linear is None else g2)
    error = VibrationError(
        additive_terms=terms.additive_terms,
        multiplicative_coefficients=terms.multiplicative_coefficients,
        additive=terms.additive,
        multiplicative=terms.multiplicative,
        total=estimate.total,
        rms=terms.rms,
        extra_terms=terms.extra_terms,
    )
    return error, estimate.stderr
