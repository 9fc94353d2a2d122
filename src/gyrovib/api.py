"""Library entry points: a catalogue in, immutable results out.

This layer joins the catalogue models to the numpy engines. It does all unit
handling: catalogue values are converted to deg/s on the way in, results to
the requested output unit on the way out.

>>> from gyrovib.api import load, analyze
>>> result = analyze(load())          # the bundled catalogues  # doctest: +SKIP
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import ParamSpec, TypeVar

import numpy as np

from gyrovib import units
from gyrovib.catalog.loader import (
    Catalog,
    ProfileEntry,
    SensorEntry,
    bundled_paths,
    load_catalog,
)
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
from gyrovib.core.transmissibility import FloatArray, Table, as_table
from gyrovib.errors import GyrovibError, ModelError, OptionError

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
    catalog: Catalog, sensors: Sequence[str] = (), profiles: Sequence[str] = ()
) -> tuple[tuple[SensorEntry, ...], tuple[ProfileEntry, ...]]:
    """The sensors and profiles named (all when none are named), in catalogue order."""

    def pick(entries: Sequence[SensorEntry] | Sequence[ProfileEntry], wanted: Sequence[str],
             what: str) -> tuple[int, ...]:
        ids = [e.sensor.id if isinstance(e, SensorEntry) else e.profile.id  # type: ignore[union-attr]
               for e in entries]
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


def coefficient_matrix(entries: Sequence[SensorEntry]) -> FloatArray:
    """Eq. (2) coefficients of every sensor in deg/s powers, shape (sensors, 11)."""
    raw = np.array(
        [[getattr(e.sensor.rate_coefficients, c) for c in COEFFICIENTS] for e in entries],
        dtype=float,
    ).reshape(len(entries), len(COEFFICIENTS))
    scales = np.array([units.scale(e.unit) for e in entries], dtype=float)
    out: FloatArray = raw * scales[:, None] ** _RATE_POWERS[None, :]
    return out


def sensor_ranges(entries: Sequence[SensorEntry]) -> FloatArray:
    """Full-scale range of each sensor in deg/s (inf where not given)."""
    return np.array(
        [e.sensor.range * units.scale(e.unit) if e.sensor.range is not None else np.inf
         for e in entries],
        dtype=float,
    )


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


def check_finite(error: VibrationError, what: str = "the vibration error") -> None:
    """Refuse results that overflowed (huge amplitudes or coefficients)."""
    for name in ("additive_terms", "multiplicative_coefficients", "total", "rms"):
        if not np.all(np.isfinite(getattr(error, name))):
            raise GyrovibError(
                f"{what} overflows floating point: check the amplitudes, PSD levels, "
                "rates and coefficients for absurd magnitudes"
            )


def _check_finite_located(error: VibrationError, s_entries: Sequence[SensorEntry],
                          p_entries: Sequence[ProfileEntry]) -> None:
    """Name the first sensor × profile whose error overflowed, at the profile's place."""
    bad = ~(np.isfinite(error.total) & np.isfinite(error.rms)
            & np.all(np.isfinite(error.additive_terms), axis=-1)
            & np.all(np.isfinite(error.multiplicative_coefficients), axis=-1))
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
) -> AnalysisResult:
    """Eq. (13)-(16) for every chosen sensor under every chosen profile.

    ``rate`` overrides Ω_K (in deg/s): one number for Ω_K3, or three.
    ``unit`` is the output unit.
    """
    if method not in METHODS:
        raise OptionError(f"unknown method {method!r}; use one of {', '.join(METHODS)}")
    unit = units.canonical_unit(unit)
    s_entries, p_entries = select_entries(catalog, sensors, profiles)
    coeffs = coefficient_matrix(s_entries)
    ranges = sensor_ranges(s_entries)
    rates = np.array([resolve_rate(p, rate) for p in p_entries], dtype=float).reshape(-1, 3)
    n_s, n_p = len(s_entries), len(p_entries)
    shape = (n_s, n_p)
    parts = {
        "additive_terms": np.zeros(shape + (5,)),
        "multiplicative_coefficients": np.zeros(shape + (3,)),
        "additive": np.zeros(shape),
        "multiplicative": np.zeros(shape),
        "total": np.zeros(shape),
        "rms": np.zeros(shape),
    }
    warnings: dict[tuple[int, int], tuple[str, ...]] = {}
    for response, idx in response_groups(s_entries) if n_p else []:
        vibrations = [profile_vibration(p, response) for p in p_entries]
        multipliers = stack_multipliers(
            [located_multipliers(p, v, r[2], method)
             for p, v, r in zip(p_entries, vibrations, rates, strict=True)]
        )
        err = vibration_error(coeffs[idx], multipliers)
        for name, array in parts.items():
            array[idx] = getattr(err, name)
        reach = np.abs(rates[:, 2]) + np.array([vibration_peak(v) for v in vibrations])
        over = reach[None, :] > ranges[idx][:, None]
        for i, j in zip(*np.nonzero(over), strict=True):
            sensor = int(idx[i])
            warnings[(sensor, int(j))] = (
                f"|Ω_K3| + vibration peak = {reach[j] / units.scale(unit):.6g} {unit} exceeds "
                f"the sensor's range {ranges[sensor] / units.scale(unit):.6g} {unit}: "
                "the static model does not hold in saturation",
            )
    error = to_unit(VibrationError(**parts), unit)
    _check_finite_located(error, s_entries, p_entries)
    check_finite(error)
    return AnalysisResult(
        method=method,
        unit=unit,
        sensors=tuple(e.sensor.id for e in s_entries),
        profiles=tuple(p.profile.id for p in p_entries),
        rates=rates / units.scale(unit),
        error=error,
        warnings=warnings,
    )
