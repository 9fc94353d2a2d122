"""Library entry points: a catalogue in, immutable results out.

This layer joins the catalogue models to the numpy engines. It does all unit
handling: catalogue values are converted to deg/s on the way in, results to
the requested output unit on the way out.

>>> from gyrovib.api import load, analyze
>>> result = analyze(load())          # the bundled catalogues  # doctest: +SKIP
"""

from __future__ import annotations

import functools
import math
import operator
import zlib
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, ParamSpec, TypeVar, cast

import numpy as np
from numpy.typing import NDArray

from gyrovib import units
from gyrovib.catalog.loader import (
    Catalog,
    ProfileEntry,
    SensorEntry,
    bundled_paths,
    load_catalog,
)
from gyrovib.catalog.records import Allocation
from gyrovib.core.analysis import (
    COEFFICIENTS,
    METHODS,
    Multipliers,
    VibrationError,
    profile_multipliers,
    stack_multipliers,
    vibration_error,
)
from gyrovib.core.statistics import Vibration, vibration_at_sensor
from gyrovib.core.synthesis import (
    BOUNDED,
    DEFAULT_R,
    DEFAULT_V,
    DEFAULT_W,
    PAPER_CONSTANTS,
    AllocationConstants,
    CoefficientBounds,
    allocation_constants,
    coefficient_bounds,
)
from gyrovib.core.transmissibility import FloatArray, Table, as_table
from gyrovib.errors import GyrovibError, ModelError, OptionError, Problem

P = ParamSpec("P")
R = TypeVar("R")

_RATE_POWERS = np.array([units.COEFFICIENT_RATE_POWER[c] for c in COEFFICIENTS], dtype=float)


def load(paths: Sequence[str | Path] = ()) -> Catalog:
    """Load and merge catalogue files; no paths means the bundled catalogues."""
    return load_catalog(list(paths) if paths else bundled_paths())


def sensor_location(catalog: Catalog, sensor_id: str) -> tuple[str | None, int | None]:
    """The file and 1-based line where a sensor is defined (its ``id:``).

    ``(None, None)`` for an id the catalogue does not have; the line is None
    when it cannot be found.
    """
    for entry in catalog.sensors:
        if entry.sensor.id == sensor_id:
            place = catalog.sensor_line(entry)
            return entry.source.name, (place[0] if place else None)
    return None, None


def profile_location(catalog: Catalog, profile_id: str) -> tuple[str | None, int | None]:
    """The file and 1-based line where a profile is defined (its ``id:``)."""
    for entry in catalog.profiles:
        if entry.profile.id == profile_id:
            place = entry.source.locate(("profiles", entry.index, "id"))
            return entry.source.name, (place[0] if place else None)
    return None, None


def quiet_float(function: Callable[P, R]) -> Callable[P, R]:
    """Run ``function`` with numpy's floating-point warnings off.

    Absurd magnitudes (amplitudes of 1e200) overflow on the way; the result
    is checked with :func:`check_finite`, which reports that once, instead of
    numpy printing a RuntimeWarning per operation.
    """

    @functools.wraps(function)
    def wrapper(*args: P.args, **kwargs: P.kwargs) -> R:
        with np.errstate(over="ignore", invalid="ignore", divide="ignore", under="ignore"):
            return function(*args, **kwargs)

    return wrapper


# ----------------------------------------------------------------- selection


def select_entries(
    catalog: Catalog, sensors: Sequence[str] = (), profiles: Sequence[str] = (),
    need: Sequence[str] = ("sensors", "profiles"),
) -> tuple[tuple[SensorEntry, ...], tuple[ProfileEntry, ...]]:
    """The sensors and profiles named (all when none are named), in catalogue order.

    A catalogue without any of the kinds in ``need`` is an error: a check run
    on nothing would pass vacuously (a CI gate given only the sensors file).
    """
    missing = [kind for kind in need if not getattr(catalog, kind)]
    if missing:
        files = ", ".join(s.name for s in catalog.sources) or "the catalogue"
        raise OptionError(
            f"no {' and no '.join(missing)} in {files}: give a file that has them too "
            "(or no FILE at all for the bundled catalogues)"
        )

    def pick(entries: Sequence[SensorEntry] | Sequence[ProfileEntry], wanted: Sequence[str],
             what: str) -> tuple[int, ...]:
        ids = [e.sensor.id if isinstance(e, SensorEntry) else e.profile.id for e in entries]
        if not wanted:
            return tuple(range(len(ids)))
        unknown = [w for w in dict.fromkeys(wanted) if w not in ids]
        if unknown:
            known = ", ".join(ids) if len(ids) <= 20 else ", ".join(ids[:20]) + ", ..."
            raise OptionError(
                f"unknown {what} id {', '.join(map(repr, unknown))}; the catalogue has: {known}"
            )
        chosen = set(wanted)
        return tuple(i for i, x in enumerate(ids) if x in chosen)

    s_idx = pick(catalog.sensors, sensors, "sensor")
    p_idx = pick(catalog.profiles, profiles, "profile")
    return (tuple(catalog.sensors[i] for i in s_idx), tuple(catalog.profiles[i] for i in p_idx))


# ----------------------------------------------------------------- conversion


_GET_COEFFICIENTS = operator.attrgetter(*COEFFICIENTS)


def _unit_scales(entries: Sequence[SensorEntry]) -> FloatArray:
    """deg/s per rate unit of each entry's file."""
    known: dict[str, float] = {}
    out = []
    for e in entries:
        unit = e.unit
        s = known.get(unit)
        if s is None:
            s = known[unit] = units.scale(unit)
        out.append(s)
    return np.array(out, dtype=float)


def coefficient_matrix(entries: Sequence[SensorEntry]) -> FloatArray:
    """Eq. (2) coefficients of every sensor in deg/s powers, shape (sensors, 11)."""
    raw = np.array(
        [_GET_COEFFICIENTS(e.sensor.rate_coefficients) for e in entries], dtype=float
    ).reshape(len(entries), len(COEFFICIENTS))
    scales = _unit_scales(entries)
    if np.all(scales == 1.0):
        return raw
    out: FloatArray = raw * scales[:, None] ** _RATE_POWERS[None, :]
    return out


def sensor_ranges(entries: Sequence[SensorEntry]) -> FloatArray:
    """Full-scale range of each sensor in deg/s (inf where not given)."""
    ranges = np.array(
        [np.inf if e.sensor.range is None else e.sensor.range for e in entries], dtype=float
    )
    out: FloatArray = ranges * _unit_scales(entries)
    return out


def response_table(entry: SensorEntry) -> Table | None:
    """The sensor's own transmissibility ν_sensor(f), or None for ν ≡ 1."""
    return None if entry.sensor.response is None else as_table(entry.sensor.response)


def response_groups(entries: Sequence[SensorEntry]) -> list[tuple[Table | None, FloatArray]]:
    """Sensors grouped by identical response tables: ``(table, indices)`` pairs.

    Profile statistics depend on the sensor only through ν_sensor(f), so they
    are computed once per group, not once per sensor.
    """
    groups: dict[tuple[tuple[float, float], ...] | None, list[int]] = {}
    for i, e in enumerate(entries):
        key = None if e.sensor.response is None else tuple(e.sensor.response)
        groups.setdefault(key, []).append(i)
    return [
        (None if key is None else as_table(key), np.array(idx, dtype=int))
        for key, idx in groups.items()
    ]


def profile_rate(entry: ProfileEntry) -> FloatArray:
    """The profile's carrier rate Ω_K about x1, x2, x3 in deg/s."""
    return np.asarray(entry.profile.rate, dtype=float) * units.scale(entry.unit)


def profile_vibration(entry: ProfileEntry, response: Table | None = None) -> Vibration:
    """The vibration of a profile reaching a sensor of the given response, in deg/s."""
    p = entry.profile
    s = units.scale(entry.unit)
    gains: list[Table] = []
    if p.mount is not None:
        gains.append(as_table(p.mount))
    if response is not None:
        gains.append(response)
    tones = [(t.frequency, np.asarray(t.amplitude) * s, t.phase) for t in p.harmonic]
    psd: list[Table | None] | None = None
    rms = None
    coherence: tuple[float, float] = (1.0, 1.0)
    if p.random is not None:
        coherence = p.random.coherence
        if p.random.psd is not None:
            psd = []
            for axis in ("x1", "x2", "x3"):
                table = getattr(p.random.psd, axis)
                if table is None:
                    psd.append(None)
                else:
                    f, g = as_table(table)
                    psd.append((f, g * s * s))
        else:
            assert p.random.rms is not None
            rms = np.asarray(p.random.rms, dtype=float) * s
    return vibration_at_sensor(tones, psd=psd, rms=rms, coherence=coherence, gains=gains)


def vibration_peak(vibration: Vibration) -> float:
    """Peak of x3 for the saturation check: Σ tone amplitudes + 3σ."""
    return float(np.sum(vibration.tone_amplitudes) + 3.0 * vibration.sigma[2])


def resolve_rate(entry: ProfileEntry, override: Sequence[float] | None) -> FloatArray:
    """Ω_K in deg/s: the profile's, or an override (one number: Ω_K3 only; three: all)."""
    rate = profile_rate(entry)
    if override is None:
        return rate
    values = np.asarray(override, dtype=float)
    if values.size == 1:
        rate = rate.copy()
        rate[2] = float(values[0])
        return rate
    if values.size == 3:
        out: FloatArray = values.astype(float)
        return out
    raise OptionError("a rate is one number (Ω_K3) or three (Ω_K1, Ω_K2, Ω_K3)")


def located_multipliers(
    entry: ProfileEntry, vibration: Vibration, omega: float | FloatArray, method: str
) -> Multipliers:
    """:func:`profile_multipliers`, with a method's refusal placed at the profile's line."""
    try:
        return profile_multipliers(vibration, omega, method)
    except ModelError as exc:
        message = f"profile {entry.profile.id!r}: {exc.problems[0].message}"
        raise ModelError(entry.source.problem(message, ("profiles", entry.index, "id"))) from None


def profiles_multipliers(
    p_entries: Sequence[ProfileEntry], vibrations: Sequence[Vibration], rates: FloatArray,
    method: str,
) -> Multipliers:
    """The multipliers of every profile, stacked; every profile the method refuses
    is reported (one problem each), not only the first."""
    items: list[Multipliers] = []
    problems: list[Problem] = []
    for p, v, r in zip(p_entries, vibrations, rates, strict=True):
        try:
            items.append(located_multipliers(p, v, r[2], method))
        except ModelError as exc:
            problems.extend(exc.problems)
    if problems:
        raise ModelError(problems)
    return stack_multipliers(items)


# ----------------------------------------------------------------- analysis


@dataclass(frozen=True)
class AnalysisResult:
    """The direct problem for every chosen sensor × profile.

    Arrays of :attr:`error` have shape (sensors, profiles) and are in
    :attr:`unit`; ``rates`` is Ω_K per profile, shape (profiles, 3).
    ``warnings`` maps ``(sensor index, profile index)`` to messages.
    """

    method: str
    unit: str
    sensors: tuple[str, ...]
    profiles: tuple[str, ...]
    rates: FloatArray
    error: VibrationError
    warnings: dict[tuple[int, int], tuple[str, ...]] = field(default_factory=dict)
    #: ``numeric`` only: standard error of ``error.total`` (0 where exact), else None.
    stderr: FloatArray | None = None
    #: ``numeric`` only: evaluations of eq. (2) per sensor × profile, and the seed.
    samples: int | None = None
    seed: int | None = None

    def to_frame(self) -> Any:
        """Tidy pandas DataFrame, columns as the JSON keys (:mod:`gyrovib.frames`)."""
        from gyrovib.frames import to_frame

        return to_frame(self)


def _error_arrays(error: VibrationError) -> list[FloatArray]:
    return [error.additive_terms, error.multiplicative_coefficients, error.total, error.rms]


def to_unit(error: VibrationError, unit: str) -> VibrationError:
    """Convert an error computed in deg/s to ``unit`` (Δ(q) carries rate^(1−q))."""
    s = units.scale(unit)
    q_factor = np.array([1.0, s, s * s])
    return VibrationError(
        additive_terms=error.additive_terms / s,
        multiplicative_coefficients=error.multiplicative_coefficients * q_factor,
        additive=error.additive / s,
        multiplicative=error.multiplicative / s,
        total=error.total / s,
        rms=error.rms / s,
    )


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


def _check_numeric_options(samples: int, seed: int) -> None:
    from gyrovib.core.numeric import MIN_SAMPLES

    if samples < MIN_SAMPLES:
        raise OptionError(f"--samples {samples}: give at least {MIN_SAMPLES}")
    if seed < 0:
        raise OptionError(f"--seed {seed}: the seed must be a non-negative integer")


def check_finite(arrays: Sequence[FloatArray], s_entries: Sequence[SensorEntry],
                 p_entries: Sequence[ProfileEntry]) -> None:
    """Refuse results that overflowed (absurd amplitudes or coefficients).

    Each array is indexed (sensor, profile, ...); the first sensor × profile
    with a non-finite value is named, at the profile's place in its file.
    """
    bad = np.zeros((len(s_entries), len(p_entries)), dtype=bool)
    if bad.size == 0:
        return
    for array in arrays:
        finite = np.isfinite(array).reshape((*bad.shape, -1))
        bad |= ~np.all(finite, axis=-1)
    if not bad.any():
        return
    i, j = (int(k) for k in np.argwhere(bad)[0])
    sensor, profile = s_entries[i], p_entries[j]
    count = int(bad.sum())
    more = f" ({count - 1} more sensor/profile pairs too)" if count > 1 else ""
    raise GyrovibError(profile.source.problem(
        f"sensor {sensor.sensor.id!r} under profile {profile.profile.id!r}: the vibration "
        "error overflows floating point; check the amplitudes, PSD levels, rates and "
        f"coefficients for absurd magnitudes{more}",
        ("profiles", profile.index, "id"),
    ))


@quiet_float
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
    """
    if method not in ANALYZE_METHODS:
        raise OptionError(f"unknown method {method!r}; use one of {', '.join(ANALYZE_METHODS)}")
    if method == "numeric":
        _check_numeric_options(samples, seed)
    unit = units.canonical_unit(unit)
    s_entries, p_entries = select_entries(catalog, sensors, profiles)
    coeffs = coefficient_matrix(s_entries)
    ranges = sensor_ranges(s_entries)
    rates = np.array([resolve_rate(p, rate) for p in p_entries], dtype=float).reshape(-1, 3)
    n_s, n_p = len(s_entries), len(p_entries)
    shape = (n_s, n_p)
    parts = {
        "additive_terms": np.zeros((*shape, 5)),
        "multiplicative_coefficients": np.zeros((*shape, 3)),
        "additive": np.zeros(shape),
        "multiplicative": np.zeros(shape),
        "total": np.zeros(shape),
        "rms": np.zeros(shape),
    }
    warnings: dict[tuple[int, int], tuple[str, ...]] = {}
    out_scale = units.scale(unit)
    stderr = np.zeros(shape) if method == "numeric" else None
    groups = response_groups(s_entries) if n_p and n_s else []
    tracker = _Tracker(progress, len(groups) * n_p * samples)
    for response, idx in groups:
        vibrations = [profile_vibration(p, response) for p in p_entries]
        if stderr is not None:
            for j, (p, v) in enumerate(zip(p_entries, vibrations, strict=True)):
                err, stderr[idx, j] = _simulate(coeffs[idx], v, rates[j], samples,
                                                profile_generator(seed, p.profile.id), tracker)
                for name, array in parts.items():
                    array[idx, j] = getattr(err, name)
        else:
            multipliers = profiles_multipliers(p_entries, vibrations, rates, method)
            err = vibration_error(coeffs[idx], multipliers)
            for name, array in parts.items():
                array[idx] = getattr(err, name)
        reach = np.abs(rates[:, 2]) + np.array([vibration_peak(v) for v in vibrations])
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
    error = to_unit(VibrationError(**parts), unit)
    check_finite(_error_arrays(error), s_entries, p_entries)
    stderr_out = None if stderr is None else stderr / out_scale
    numeric = stderr is not None
    return AnalysisResult(
        method=method,
        unit=unit,
        sensors=tuple(e.sensor.id for e in s_entries),
        profiles=tuple(p.profile.id for p in p_entries),
        rates=rates / units.scale(unit),
        error=error,
        warnings=warnings,
        stderr=stderr_out,
        samples=samples if numeric else None,
        seed=seed if numeric else None,
    )


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
              rng: np.random.Generator, tracker: _Tracker) -> tuple[VibrationError, FloatArray]:
    """Brute force for one profile and one group of sensors (deg/s)."""
    from gyrovib.core.numeric import simulate

    before = tracker.done
    estimate = simulate(coefficients, vibration, rate, samples=samples, rng=rng,
                        progress=tracker)
    tracker.finish_block(samples, tracker.done - before)
    terms = vibration_error(coefficients, estimate.multipliers)
    error = VibrationError(
        additive_terms=terms.additive_terms,
        multiplicative_coefficients=terms.multiplicative_coefficients,
        additive=terms.additive,
        multiplicative=terms.multiplicative,
        total=estimate.total,
        rms=terms.rms,
    )
    return error, estimate.stderr


# ----------------------------------------------------------------- rate sweeps


@dataclass(frozen=True)
class SweepResult:
    """Δ_V and Δ_V(RMS) over a range of Ω_K3, by the exact and the paper's method.

    ``rates`` (R,): the Ω_K3 values in :attr:`unit`; Ω_K1, Ω_K2 stay the
    profile's. ``exact`` and ``paper`` hold arrays of shape (sensors,
    profiles, rates) in :attr:`unit`; ``paper``'s are NaN for the profiles in
    :attr:`paper_refused` (profile id → why the paper's formulas do not apply).
    """

    unit: str
    sensors: tuple[str, ...]
    profiles: tuple[str, ...]
    rates: FloatArray
    exact: VibrationError
    paper: VibrationError
    paper_refused: dict[str, str] = field(default_factory=dict)

    def to_frame(self) -> Any:
        """Tidy pandas DataFrame, columns as the JSON keys (:mod:`gyrovib.frames`)."""
        from gyrovib.frames import to_frame

        return to_frame(self)


#: Most rates in one sweep: several tones cost about 10^4 kernel values per rate.
MAX_SWEEP_POINTS = 20_000


def rate_range(start: float, stop: float, count: int) -> FloatArray:
    """``count`` evenly spaced rates from ``start`` to ``stop`` inclusive (deg/s)."""
    if count < 1:
        raise OptionError("a rate range needs a count of at least 1")
    if count > MAX_SWEEP_POINTS:
        raise OptionError(
            f"a rate range of {count} points is too many (at most {MAX_SWEEP_POINTS})"
        )
    if not (np.isfinite(start) and np.isfinite(stop) and np.isfinite(stop - start)):
        raise OptionError("a rate range needs finite start and stop, and a finite span")
    out: FloatArray = np.linspace(start, stop, count)
    return out


def _nan_multipliers(omega: FloatArray) -> Multipliers:
    nan = np.full(omega.shape, np.nan)
    return Multipliers(asymmetry=nan, m2=nan, m4=nan, c31=nan, c32=nan, omega=omega.copy())


def sweep(
    catalog: Catalog,
    rates: Sequence[float] | FloatArray,
    *,
    sensors: Sequence[str] = (),
    profiles: Sequence[str] = (),
    unit: str = "deg/s",
) -> SweepResult:
    """Eq. (13) and (16) at every Ω_K3 of ``rates`` (deg/s), exact and paper.

    One vectorised evaluation per profile and sensor-response group: the
    multipliers of :func:`profile_multipliers` are computed for the whole rate
    array at once. A value at a rate equals :func:`analyze` with that ``rate``.
    """
    unit = units.canonical_unit(unit)
    omega = np.asarray(rates, dtype=float).reshape(-1)
    if omega.size == 0 or not np.all(np.isfinite(omega)):
        raise OptionError("the swept rates must be finite, and at least one")
    s_entries, p_entries = select_entries(catalog, sensors, profiles)
    coeffs = coefficient_matrix(s_entries)
    shape = (len(s_entries), len(p_entries), omega.size)
    results: dict[str, dict[str, FloatArray]] = {
        m: {
            "additive_terms": np.zeros((*shape, 5)),
            "multiplicative_coefficients": np.zeros((*shape, 3)),
            "additive": np.zeros(shape),
            "multiplicative": np.zeros(shape),
            "total": np.zeros(shape),
            "rms": np.zeros(shape),
        }
        for m in METHODS
    }
    refused: dict[str, str] = {}
    groups = response_groups(s_entries) if p_entries and s_entries else []
    for response, idx in groups:
        vibrations = [profile_vibration(p, response) for p in p_entries]
        for method in METHODS:
            per_profile = []
            for p, v in zip(p_entries, vibrations, strict=True):
                try:
                    per_profile.append(profile_multipliers(v, omega, method))
                except ModelError as exc:
                    refused[p.profile.id] = exc.problems[0].message.split("; use --method")[0]
                    per_profile.append(_nan_multipliers(omega))
            err = vibration_error(coeffs[idx], stack_multipliers(per_profile))
            for name, array in results[method].items():
                array[idx] = getattr(err, name)
    exact = to_unit(VibrationError(**results["exact"]), unit)
    check_finite(_error_arrays(exact), s_entries, p_entries)
    paper = to_unit(VibrationError(**results["paper"]), unit)
    return SweepResult(
        unit=unit,
        sensors=tuple(e.sensor.id for e in s_entries),
        profiles=tuple(p.profile.id for p in p_entries),
        rates=omega / units.scale(unit),
        exact=exact,
        paper=paper,
        paper_refused={p.profile.id: refused[p.profile.id] for p in p_entries
                       if p.profile.id in refused},
    )


# ----------------------------------------------------------------- synthesis


def _bound_factors(unit: str) -> dict[str, float]:
    """deg/s → ``unit`` factors of each bounded coefficient: ``s**(-p)`` for rate power p."""
    s = units.scale(unit)
    return {name: s ** (-units.COEFFICIENT_RATE_POWER[name]) for name in BOUNDED}


def _is_default(allocation: Allocation) -> bool:
    return (allocation.r == DEFAULT_R and tuple(allocation.w) == DEFAULT_W
            and tuple(allocation.v) == DEFAULT_V)


def resolve_allocation(
    catalog: Catalog, method: str, allocation: Allocation | Sequence[float] | None = None
) -> AllocationConstants:
    """The shares of the budget for ``method``.

    ``allocation`` (an :class:`Allocation`, or 1 number r, or 9 numbers
    r, w1..w5, v1..v3) wins over the catalogue's ``allocation:`` section; the
    paper's r = 1.5, w = (1, 1, 1, ½, ½), v = (1, ½, ½) is the default.
    ``exact`` derives the shares (eq. 20, 21, 24); ``paper`` uses the printed
    constants and therefore refuses any other allocation.
    """
    where = "--allocation"
    if allocation is None:
        chosen = catalog.allocation
        if catalog.allocation is not None:
            source = next((s for s in catalog.sources if s.model.allocation is not None), None)
            where = f"the 'allocation:' section of {source.name}" if source else "the catalogue"
    elif isinstance(allocation, Allocation) or hasattr(allocation, "r"):
        chosen = cast(Allocation, allocation)  # the record, or the pydantic model alike
    else:
        values = [float(x) for x in allocation]
        if not all(math.isfinite(x) and x > 0 for x in values):
            raise OptionError("an allocation's r, w and v must be positive and finite")
        if len(values) == 1:
            chosen = Allocation(r=values[0])
        elif len(values) == 9:
            chosen = Allocation(r=values[0], w=tuple(values[1:6]), v=tuple(values[6:9]))
        else:
            raise OptionError(
                f"an allocation is r alone or 9 numbers r,w1,...,w5,v1,v2,v3; got {len(values)}"
            )
    if chosen is None:
        chosen = Allocation()
    if method == "paper":
        if not _is_default(chosen):
            raise OptionError(
                f"--method paper uses the paper's printed shares (0.44, 0.22, 0.49, 0.24, 0.35) "
                f"and cannot honour the custom allocation given by {where}; "
                "use --method exact, or drop the allocation"
            )
        return PAPER_CONSTANTS
    try:
        return allocation_constants(chosen.r, chosen.w, chosen.v)
    except ValueError as exc:
        raise OptionError(f"allocation: {exc}") from None


@dataclass(frozen=True)
class BoundsResult:
    """Allowable coefficients of eq. (23), (25) for every chosen profile.

    ``bounds`` arrays have shape (profiles,), each in its coefficient's unit
    built on :attr:`unit`; +inf means unconstrained. ``rates`` is Ω_K per
    profile in :attr:`unit`, shape (profiles, 3); ``budget`` Δ* in :attr:`unit`.
    The profile alone is taken: the sensor's own response is 1.
    """

    method: str
    unit: str
    budget: float
    profiles: tuple[str, ...]
    rates: FloatArray
    bounds: CoefficientBounds
    allocation: AllocationConstants

    def to_frame(self) -> Any:
        """Tidy pandas DataFrame, columns as the JSON keys (:mod:`gyrovib.frames`)."""
        from gyrovib.frames import to_frame

        return to_frame(self)


def _check_method_budget(method: str, budget: float) -> None:
    if method not in METHODS:
        raise OptionError(f"unknown method {method!r}; use one of {', '.join(METHODS)}")
    if not (math.isfinite(budget) and budget > 0):
        raise OptionError(f"the budget must be positive and finite, not {budget!r}")


def _group_multipliers(
    p_entries: Sequence[ProfileEntry], rates: FloatArray, method: str, response: Table | None
) -> Multipliers:
    vibrations = [profile_vibration(p, response) for p in p_entries]
    return profiles_multipliers(p_entries, vibrations, rates, method)


def bounds(
    catalog: Catalog,
    *,
    profiles: Sequence[str] = (),
    method: str = "exact",
    rate: Sequence[float] | None = None,
    budget: float,
    unit: str = "deg/s",
    allocation: Allocation | Sequence[float] | None = None,
) -> BoundsResult:
    """The inverse problem: allowable coefficients per profile, eq. (23), (25).

    ``budget`` is Δ*_V in deg/s; ``rate`` overrides Ω_K (deg/s) as in
    :func:`analyze`; ``unit`` is the output unit.
    """
    _check_method_budget(method, budget)
    unit = units.canonical_unit(unit)
    constants = resolve_allocation(catalog, method, allocation)
    _, p_entries = select_entries(catalog, (), profiles, need=("profiles",))
    rates = np.array([resolve_rate(p, rate) for p in p_entries], dtype=float).reshape(-1, 3)
    multipliers = _group_multipliers(p_entries, rates, method, None) if p_entries else None
    if multipliers is None:
        empty = np.zeros(0)
        raw = CoefficientBounds(**{n: empty for n in CoefficientBounds.__dataclass_fields__})
    else:
        raw = coefficient_bounds(multipliers, budget, constants)
    return BoundsResult(
        method=method,
        unit=unit,
        budget=budget / units.scale(unit),
        profiles=tuple(p.profile.id for p in p_entries),
        rates=rates / units.scale(unit),
        bounds=raw.scaled(_bound_factors(unit)),
        allocation=constants,
    )


CRITERIA = ("bounds", "rms", "both")
REQUIREMENTS = ("any", "all")
#: Relative slack of every ≤ comparison: a value at its bound, up to rounding
#: (e.g. a bound printed in deg/h and read back), passes.
PASS_RTOL = 1e-9


@dataclass(frozen=True)
class Limit:
    """What stops a failing sensor: the worst coefficient (or ``"rms"``) and where."""

    name: str
    profile: int
    ratio: float


@dataclass(frozen=True)
class SelectionResult:
    """Every chosen sensor checked against the budget under every chosen profile.

    Arrays are indexed (sensor, profile[, coefficient of :data:`BOUNDED`]) and
    are in :attr:`unit`. ``values`` are the sensors' |coefficients| (k1 taken
    as 1); ``bounds`` each sensor's own bounds (its response ν_sensor included);
    ``profile_bounds`` those of the profiles alone. ``margin`` is Δ*/Δ_V(RMS)
    (+inf when Δ_V(RMS) = 0). ``passed`` is the verdict under
    :attr:`criterion`; ``ranking`` orders the sensors by worst margin, best
    first; ``limits`` names, per failing sensor, the largest value/bound ratio
    (or Δ_V(RMS)/Δ*) among the criteria checked.
    """

    method: str
    unit: str
    budget: float
    criterion: str
    require: str
    sensors: tuple[str, ...]
    profiles: tuple[str, ...]
    rates: FloatArray
    profile_bounds: CoefficientBounds
    values: FloatArray
    bounds: FloatArray
    check_pass: NDArray[np.bool_]
    rms: FloatArray
    margin: FloatArray
    bounds_pass: NDArray[np.bool_]
    rms_pass: NDArray[np.bool_]
    passed: NDArray[np.bool_]
    sensor_pass: NDArray[np.bool_]
    worst_margin: FloatArray
    ranking: tuple[int, ...]
    limits: dict[int, Limit]
    requirement_met: bool
    allocation: AllocationConstants

    def to_frame(self) -> Any:
        """Tidy pandas DataFrame, columns as the JSON keys (:mod:`gyrovib.frames`)."""
        from gyrovib.frames import to_frame

        return to_frame(self)


def _at_most(value: FloatArray, bound: FloatArray | float) -> NDArray[np.bool_]:
    out: NDArray[np.bool_] = value <= np.asarray(bound) * (1.0 + PASS_RTOL)
    return out


def _ratio(value: FloatArray, bound: FloatArray) -> FloatArray:
    """value/bound: 0 for a zero value or an infinite bound, +inf for a zero bound."""
    out: FloatArray = np.zeros(np.broadcast_shapes(value.shape, bound.shape))
    v = np.broadcast_to(value, out.shape)
    b = np.broadcast_to(bound, out.shape)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        q = v / b
    return np.where(v == 0, 0.0, np.where(b == 0, np.inf, np.where(np.isinf(b), 0.0, q)))


def select(
    catalog: Catalog,
    *,
    sensors: Sequence[str] = (),
    profiles: Sequence[str] = (),
    method: str = "exact",
    rate: Sequence[float] | None = None,
    budget: float,
    unit: str = "deg/s",
    criterion: str = "bounds",
    require: str = "any",
    allocation: Allocation | Sequence[float] | None = None,
) -> SelectionResult:
    """Which sensors meet the budget: the bound checks and eq. (17), per profile.

    Each sensor's bounds include its own response ν_sensor(f) (computed once
    per distinct response). ``criterion``: ``bounds`` (every |coefficient| at
    most its bound), ``rms`` (Δ_V(RMS) ≤ Δ*, eq. 17) or ``both``. A sensor
    passes when it passes under every chosen profile; ``require`` ``any``
    (at least one sensor passes) or ``all`` decides :attr:`requirement_met`.
    ``budget`` and ``rate`` are in deg/s; ``unit`` is the output unit.
    """
    _check_method_budget(method, budget)
    if criterion not in CRITERIA:
        raise OptionError(f"unknown criterion {criterion!r}; use one of {', '.join(CRITERIA)}")
    if require not in REQUIREMENTS:
        raise OptionError(f"unknown requirement {require!r}; use one of {', '.join(REQUIREMENTS)}")
    unit = units.canonical_unit(unit)
    constants = resolve_allocation(catalog, method, allocation)
    alone = bounds(catalog, profiles=profiles, method=method, rate=rate, budget=budget,
                   unit=unit, allocation=allocation)
    s_entries, p_entries = select_entries(catalog, sensors, profiles)
    coeffs = coefficient_matrix(s_entries)
    rates = np.array([resolve_rate(p, rate) for p in p_entries], dtype=float).reshape(-1, 3)
    n_s, n_p, n_b = len(s_entries), len(p_entries), len(BOUNDED)
    limits_deg = np.full((n_s, n_p, n_b), np.inf)
    rms = np.zeros((n_s, n_p))
    for response, idx in response_groups(s_entries) if n_p else []:
        multipliers = _group_multipliers(p_entries, rates, method, response)
        limits_deg[idx] = coefficient_bounds(multipliers, budget, constants).stacked()[None]
        rms[idx] = vibration_error(coeffs[idx], multipliers).rms
    check_finite([rms], s_entries, p_entries)
    values_deg = np.abs(coeffs[:, [COEFFICIENTS.index(c) for c in BOUNDED]])[:, None, :]
    values_deg = np.broadcast_to(values_deg, (n_s, n_p, n_b))
    check_pass = _at_most(values_deg, limits_deg)
    bounds_pass = np.all(check_pass, axis=-1)
    rms_pass = _at_most(rms, budget)
    passed = {"bounds": bounds_pass, "rms": rms_pass,
              "both": bounds_pass & rms_pass}[criterion]
    sensor_pass = np.all(passed, axis=1)
    with np.errstate(divide="ignore"):
        margin = np.where(rms > 0, budget / np.where(rms > 0, rms, 1.0), np.inf)
    worst = margin.min(axis=1) if n_p else np.full(n_s, np.inf)
    ranking = tuple(int(i) for i in sorted(range(n_s), key=lambda i: (-worst[i], i)))
    limits: dict[int, Limit] = {}
    ratios = _ratio(values_deg, limits_deg)
    for i in np.nonzero(~sensor_pass)[0]:
        candidates: list[Limit] = []
        if criterion in ("bounds", "both"):
            jb = np.unravel_index(int(np.argmax(ratios[i])), ratios[i].shape)
            j, b = int(jb[0]), int(jb[1])
            candidates.append(Limit(BOUNDED[b], j, float(ratios[i, j, b])))
        if criterion in ("rms", "both"):
            jr = int(np.argmax(rms[i]))
            candidates.append(Limit("rms", jr, float(rms[i, jr] / budget)))
        limits[int(i)] = max(candidates, key=lambda c: c.ratio)
    met = bool(np.any(sensor_pass)) if require == "any" else bool(np.all(sensor_pass))
    factors = np.array([_bound_factors(unit)[c] for c in BOUNDED])
    s = units.scale(unit)
    return SelectionResult(
        method=method,
        unit=unit,
        budget=budget / s,
        criterion=criterion,
        require=require,
        sensors=tuple(e.sensor.id for e in s_entries),
        profiles=tuple(p.profile.id for p in p_entries),
        rates=rates / s,
        profile_bounds=alone.bounds,
        values=values_deg * factors,
        bounds=limits_deg * factors,
        check_pass=check_pass,
        rms=rms / s,
        margin=margin,
        bounds_pass=bounds_pass,
        rms_pass=rms_pass,
        passed=passed,
        sensor_pass=sensor_pass,
        worst_margin=worst,
        ranking=ranking,
        limits=limits,
        requirement_met=met,
        allocation=constants,
    )
