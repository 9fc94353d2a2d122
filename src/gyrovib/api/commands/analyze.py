"""``analyze``: the direct problem, eq. (13)-(16) for every sensor × profile."""

from __future__ import annotations

import zlib
from collections.abc import Callable, Sequence

import numpy as np

from gyrovib import units
from gyrovib.api import specs
from gyrovib.api.convert import error_arrays, sensor_ranges, to_unit
from gyrovib.api.prepare import (
    Prepared,
    check_finite,
    float_guard,
    prepare,
    vibration_peak,
)
from gyrovib.api.results import AnalysisResult
from gyrovib.catalog.loader import Catalog
from gyrovib.core.analysis import EXTRA_TERMS, METHODS, VibrationError, vibration_error
from gyrovib.core.linear import LinearVibration
from gyrovib.core.statistics import Vibration
from gyrovib.core.transmissibility import FloatArray
from gyrovib.errors import OptionError

#: Every method of :func:`analyze`: the closed forms, and brute force.
ANALYZE_METHODS: tuple[str, ...] = (*METHODS, "numeric")
#: Defaults of the numeric method.
DEFAULT_SAMPLES = 200_000
DEFAULT_SEED = 0

ProgressCallback = Callable[[int, int], None]

_PARTS = ("additive_terms", "multiplicative_coefficients", "additive", "multiplicative",
          "total", "rms", "extra_terms")


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
    from gyrovib.core.numeric import MIN_SAMPLES

    if samples < MIN_SAMPLES:
        raise OptionError(f"--samples {samples}: give at least {MIN_SAMPLES}")
    if seed < 0:
        raise OptionError(f"--seed {seed}: the seed must be a non-negative integer")


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
    envelope (:mod:`gyrovib.api.specs`): under ``exact`` or ``paper`` that
    method's multipliers feed the programme; under ``numeric`` the worst
    polynomial (found with the exact multipliers) is averaged by brute force,
    and ``rms`` stays the per-term bound.
    """
    _check_options(method, samples, seed)
    unit = units.canonical_unit(unit)
    numeric = method == "numeric"
    with float_guard():
        prepared = prepare(catalog, sensors=sensors, profiles=profiles, rate=rate,
                           methods=() if numeric else (method,))
        n_s, n_p = len(prepared.sensors), len(prepared.profiles)
        coeffs, rates = prepared.coefficients, prepared.rates
        parts = {name: np.zeros((n_s, n_p, *tail)) for name, tail in
                 zip(_PARTS, ((5,), (3,), (), (), (), (), (len(EXTRA_TERMS),)), strict=True)}
        stderr = np.zeros((n_s, n_p)) if numeric else None
        tracker = _Tracker(progress, len(prepared.groups) * n_p * samples)
        spec = specs.spec_results(prepared, "exact" if numeric else method)
        for group in prepared.groups:
            idx = group.index
            if stderr is not None:
                for j, (p, v) in enumerate(zip(prepared.profiles, group.vibrations,
                                               strict=True)):
                    block = coeffs[idx] if spec is None else specs.numeric_rows(
                        coeffs, idx, j, spec)
                    err, stderr[idx, j] = _simulate(block, v, rates[j], samples,
                                                    profile_generator(seed, p.profile.id),
                                                    tracker, linear=prepared.linear[j],
                                                    g2=prepared.g2[idx])
                    for name, array in parts.items():
                        array[idx, j] = getattr(err, name)
            else:
                err = vibration_error(coeffs[idx], group.multipliers[method],
                                      g2_sensitivity=prepared.g2[idx])
                for name, array in parts.items():
                    array[idx] = getattr(err, name)
        if spec is not None:
            specs.place_analysis(parts, spec, numeric=numeric)
        warnings = specs.with_cross_axis(_saturation(prepared, unit), spec)
        error = to_unit(VibrationError(**parts), unit)
        out_scale = units.scale(unit)
        stderr_out = None if stderr is None else stderr / out_scale
        check_finite([*error_arrays(error), *([] if stderr_out is None else [stderr_out])],
                     prepared)
    return AnalysisResult(
        method=method,
        unit=unit,
        sensors=tuple(e.sensor.id for e in prepared.sensors),
        profiles=tuple(p.profile.id for p in prepared.profiles),
        rates=rates / out_scale,
        error=error,
        warnings=warnings,
        stderr=stderr_out,
        samples=samples if numeric else None,
        seed=seed if numeric else None,
        linear=tuple(v is not None for v in prepared.linear),
        **specs.analysis_fields(len(prepared.sensors), n_p, spec, unit),
    )


def _saturation(prepared: Prepared, unit: str) -> dict[tuple[int, int], tuple[str, ...]]:
    """Warnings where |Ω_K3| + the vibration's peak exceeds a sensor's range."""
    out_scale = units.scale(unit)
    ranges = sensor_ranges(prepared.sensors)
    rates = prepared.rates
    warnings: dict[tuple[int, int], tuple[str, ...]] = {}
    for group in prepared.groups:
        idx = group.index
        reach = np.abs(rates[:, 2]) + np.array([vibration_peak(v) for v in group.vibrations])
        over_s, over_p = np.nonzero(reach[None, :] > ranges[idx][:, None])
        messages: dict[tuple[int, float], tuple[str, ...]] = {}  # one text per value pair
        for sensor, j in zip(idx[over_s].tolist(), over_p.tolist(), strict=True):
            key = (j, float(ranges[sensor]))
            message = messages.get(key)
            if message is None:
                message = messages[key] = (
                    f"|Ω_K3| + vibration peak = {reach[j] / out_scale:.6g} {unit} exceeds "
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
              rng: np.random.Generator, tracker: _Tracker, *,
              linear: LinearVibration | None = None, g2: FloatArray | None = None,
              ) -> tuple[VibrationError, FloatArray]:
    """Brute force for one profile and one group of sensors (deg/s).

    ``linear`` (g) with ``g2`` (deg/s per g²): the profile's linear vibration,
    whose g² term the brute force averages too (MODEL.md section 8).
    """
    from gyrovib.core.numeric import simulate

    before = tracker.done
    estimate = simulate(coefficients, vibration, rate, samples=samples, rng=rng,
                        progress=tracker, linear=linear,
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
