"""The one preparation pipeline every command runs.

entries → deg/s (coefficients, rates) → vibrations at each sensor response →
multipliers of the chosen methods → finite checks, all under
:func:`float_guard`. A value that leaves floating-point range (an amplitude of
1e200, a rate of 1e308) or a profile a method cannot handle is reported here,
once, at the profile's place in its file (:class:`~gyrovib.errors.RangeError`,
:class:`~gyrovib.errors.ModelError`, exit status 2), never as NaN or null in
the output nor as an OverflowError.

The commands then evaluate the model (eq. 13-16, 23, 25) on a
:class:`Prepared` and check what they computed with :func:`check_finite` /
:func:`check_bounds`, which word their refusals the same way.
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import ParamSpec, TypeVar

import numpy as np
from numpy.typing import NDArray

from gyrovib import units
from gyrovib.api.convert import coefficient_matrix, resolve_rate
from gyrovib.api.entries import select_entries
from gyrovib.catalog.loader import Catalog, ProfileEntry, SensorEntry
from gyrovib.core.analysis import Multipliers, profile_multipliers, stack_multipliers
from gyrovib.core.statistics import Vibration, vibration_at_sensor
from gyrovib.core.synthesis import BOUNDED
from gyrovib.core.transmissibility import FloatArray, Table, as_table
from gyrovib.errors import ModelError, Problem, RangeError

P = ParamSpec("P")
R = TypeVar("R")

#: Python's and numpy's ways of saying a number left floating-point range.
FLOAT_FAILURES = (OverflowError, FloatingPointError, ZeroDivisionError)
#: The smallest positive normal float: below it a share or a bound has lost its digits.
TINY = float(np.finfo(float).tiny)
_MULTIPLIER_FIELDS = ("asymmetry", "m2", "m4", "c31", "c32")


@contextmanager
def float_guard() -> Iterator[None]:
    """numpy's floating-point warnings off: overflow is checked on the results instead.

    Absurd magnitudes overflow on the way; :func:`check_finite` and
    :func:`check_bounds` report that once, located, instead of numpy printing
    a RuntimeWarning per operation.
    """
    with np.errstate(over="ignore", invalid="ignore", divide="ignore", under="ignore"):
        yield


def quiet_float(function: Callable[P, R]) -> Callable[P, R]:
    """Run ``function`` under :func:`float_guard`."""

    @functools.wraps(function)
    def wrapper(*args: P.args, **kwargs: P.kwargs) -> R:
        with float_guard():
            return function(*args, **kwargs)

    return wrapper


# ----------------------------------------------------------------- vibrations


def response_table(entry: SensorEntry) -> Table | None:
    """The sensor's own transmissibility ν_sensor(f), or None for ν ≡ 1."""
    return None if entry.sensor.response is None else as_table(entry.sensor.response)


def response_groups(entries: Sequence[SensorEntry]) -> list[tuple[Table | None, NDArray[np.intp]]]:
    """Sensors grouped by identical response tables: ``(table, indices)`` pairs.

    Profile statistics depend on the sensor only through ν_sensor(f), so they
    are computed once per group, not once per sensor.
    """
    groups: dict[tuple[tuple[float, float], ...] | None, list[int]] = {}
    for i, e in enumerate(entries):
        key = None if e.sensor.response is None else tuple(e.sensor.response)
        groups.setdefault(key, []).append(i)
    return [
        (None if key is None else as_table(key), np.array(idx, dtype=np.intp))
        for key, idx in groups.items()
    ]


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


def nan_multipliers(omega: FloatArray) -> Multipliers:
    """Multipliers of a profile a method refuses: NaN everywhere (sweep's empty cells)."""
    nan = np.full(omega.shape, np.nan)
    return Multipliers(asymmetry=nan, m2=nan, m4=nan, c31=nan, c32=nan, omega=omega.copy())


# ----------------------------------------------------------------- messages


_HINT = "the amplitudes, PSD levels, rms values, rates and coefficients"


def profile_problem(profile: ProfileEntry, message: str) -> Problem:
    """``message`` placed at the profile's ``id:`` in its file."""
    return profile.source.problem(message, ("profiles", profile.index, "id"))


def overflow_problem(profile: ProfileEntry, what: str, *, sensor: SensorEntry | None = None,
                     rate_given: bool = False, more: str = "") -> Problem:
    """The one wording of an overflow, at the profile's place in its file."""
    subject = (f"sensor {sensor.sensor.id!r} under profile {profile.profile.id!r}"
               if sensor is not None else f"profile {profile.profile.id!r}")
    note = " (with the rate given in place of the profile's)" if rate_given else ""
    return profile_problem(profile, f"{subject}: {what} overflows floating point{note}; "
                                    f"check {_HINT} for absurd magnitudes{more}")


def refusal_problem(profile: ProfileEntry, method: str, reason: str) -> Problem:
    """A method's refusal of a profile (:class:`ModelError`), worded for the user."""
    advice = ("; use --method exact, or choose other profiles with --profile"
              if method == "paper" else "")
    return profile_problem(profile, f"profile {profile.profile.id!r}: {reason}{advice}")


# ----------------------------------------------------------------- the pipeline


@dataclass(frozen=True)
class Group:
    """Sensors sharing one response ν_sensor(f), and every profile as they see it.

    ``multipliers[method]`` is stacked over the profiles (shape profiles, or
    profiles × rates); ``refused[method]`` maps a profile index to the reason
    the method gave (only when refusals are tolerated, as by ``sweep``).
    """

    response: Table | None
    index: NDArray[np.intp]
    vibrations: tuple[Vibration, ...]
    multipliers: dict[str, Multipliers] = field(default_factory=dict)
    refused: dict[str, dict[int, str]] = field(default_factory=dict)


@dataclass(frozen=True)
class Prepared:
    """What every command needs, in deg/s: chosen entries, coefficients, rates, groups.

    ``coefficients`` (sensors, 11) in deg/s powers; ``rates`` Ω_K per
    profile, shape (profiles, 3); ``rate_given``: a rate override replaced
    the profiles' own.
    """

    sensors: tuple[SensorEntry, ...]
    profiles: tuple[ProfileEntry, ...]
    coefficients: FloatArray
    rates: FloatArray
    groups: tuple[Group, ...]
    rate_given: bool


def prepare(
    catalog: Catalog,
    *,
    sensors: Sequence[str] = (),
    profiles: Sequence[str] = (),
    need: Sequence[str] = ("sensors", "profiles"),
    rate: Sequence[float] | None = None,
    omega: FloatArray | None = None,
    methods: Sequence[str] = ("exact",),
    by_response: bool = True,
    tolerate_refusals: bool | Sequence[str] = False,
) -> Prepared:
    """Run the pipeline; call it under :func:`float_guard`.

    ``omega`` replaces Ω_K3 by an array of rates (a sweep); otherwise each
    profile's Ω_K3 (or ``rate``'s) is used. ``methods`` are the closed forms
    whose multipliers are needed (none for brute force). ``by_response``
    False: one group, the profiles alone (ν_sensor ≡ 1). Every profile that
    overflows or that a method refuses is reported, one problem each.
    ``tolerate_refusals``: the methods (True: every method) whose refusal of a
    profile is kept in :attr:`Group.refused` with NaN multipliers instead.
    """
    s_entries, p_entries = select_entries(catalog, sensors, profiles, need=need)
    tolerated = (set(methods if tolerate_refusals else ()) if isinstance(tolerate_refusals, bool)
                 else set(tolerate_refusals))
    problems: dict[int, Problem] = {}
    refusal: tuple[int, str] | None = None  # the first refused profile, and why
    coefficients = coefficient_matrix(s_entries)
    _check_sensors(coefficients, s_entries)
    rates = np.array([resolve_rate(p, rate) for p in p_entries], dtype=float).reshape(-1, 3)
    for j in np.nonzero(~np.all(np.isfinite(rates), axis=1))[0].tolist():
        problems[j] = overflow_problem(p_entries[j], "the carrier rate in deg/s",
                                            rate_given=rate is not None)
    if by_response:
        layout = response_groups(s_entries) if s_entries and p_entries else []
    else:
        layout = [(None, np.arange(len(s_entries), dtype=np.intp))] if p_entries else []
    groups: list[Group] = []
    for response, index in layout:
        vibrations: list[Vibration | None] = []
        for j, p in enumerate(p_entries):
            try:
                vibrations.append(profile_vibration(p, response))
            except FLOAT_FAILURES:
                problems.setdefault(j, overflow_problem(p, "the vibration"))
                vibrations.append(None)
        group = Group(response, index, tuple(v for v in vibrations if v is not None))
        for method in methods:
            items: list[Multipliers] = []
            for j, (p, v) in enumerate(zip(p_entries, vibrations, strict=True)):
                w = rates[j, 2] if omega is None else omega
                if v is None:  # reported above
                    items.append(nan_multipliers(np.asarray(w, dtype=float)))
                    continue
                try:
                    m = profile_multipliers(v, w, method)
                except ModelError as exc:
                    if method not in tolerated:
                        refusal = refusal or (j, exc.reason)
                        problems.setdefault(j, refusal_problem(p, method, exc.reason))
                    group.refused.setdefault(method, {})[j] = exc.reason
                    m = nan_multipliers(np.asarray(w, dtype=float))
                except FLOAT_FAILURES:
                    problems.setdefault(j, overflow_problem(
                        p, f"a statistic of the vibration ({method} method)"))
                    m = nan_multipliers(np.asarray(w, dtype=float))
                else:
                    if not all(np.all(np.isfinite(getattr(m, f))) for f in _MULTIPLIER_FIELDS):
                        problems.setdefault(j, overflow_problem(
                            p, "a statistic of the vibration (<x3²>, <x3⁴>, <x3·xi>)"))
                items.append(m)
            group.multipliers[method] = stack_multipliers(items)
        groups.append(group)
    if problems:
        ordered = [problems[j] for j in sorted(problems)]
        if refusal is not None:
            raise ModelError(ordered, reason=refusal[1], profile=refusal[0])
        raise RangeError(ordered)
    return Prepared(s_entries, p_entries, coefficients, rates, tuple(groups),
                    rate_given=rate is not None)


def _check_sensors(coefficients: FloatArray, entries: Sequence[SensorEntry]) -> None:
    bad = np.nonzero(~np.all(np.isfinite(coefficients), axis=1))[0]
    if bad.size:
        raise RangeError([
            entries[i].source.problem(
                f"sensor {entries[i].sensor.id!r}: its coefficients overflow floating point "
                "in deg/s; check them for absurd magnitudes", ("sensors", entries[i].index, "id"))
            for i in bad.tolist()
        ])


# ----------------------------------------------------------------- checks


def check_finite(arrays: Sequence[FloatArray], prepared: Prepared,
                 exclude: Sequence[int] = (), what: str = "the vibration error") -> None:
    """Refuse results that overflowed (absurd amplitudes, rates or coefficients).

    Each array is indexed (sensor, profile, ...); the first sensor × profile
    with a non-finite value is named, at the profile's place in its file.
    Profiles in ``exclude`` (NaN by design: a method's refusal) are skipped.
    """
    s_entries, p_entries = prepared.sensors, prepared.profiles
    bad = np.zeros((len(s_entries), len(p_entries)), dtype=bool)
    if bad.size == 0:
        return
    for array in arrays:
        finite = np.isfinite(array).reshape((*bad.shape, -1))
        bad |= ~np.all(finite, axis=-1)
    if exclude:
        bad[:, list(exclude)] = False
    if not bad.any():
        return
    i, j = (int(k) for k in np.argwhere(bad)[0])
    count = int(bad.sum())
    more = f" ({count - 1} more sensor/profile pairs too)" if count > 1 else ""
    raise RangeError(overflow_problem(p_entries[j], what, sensor=s_entries[i],
                                      rate_given=prepared.rate_given, more=more))


def check_bounds(stacked: FloatArray, prepared: Prepared) -> None:
    """Refuse bounds that left floating-point range.

    ``stacked`` is indexed (..., profile, coefficient of :data:`BOUNDED`). A
    bound is +inf (unconstrained) or a positive normal number: 0, a subnormal
    or NaN can only come from a multiplier that overflowed (or a share that
    underflowed), and would read as "no coefficient allowed".
    """
    ok = np.isposinf(stacked) | (np.isfinite(stacked) & (stacked >= TINY))
    bad: NDArray[np.bool_] = ~np.all(ok.reshape(-1, *stacked.shape[-2:]), axis=0)  # (P, 7)
    if not bad.any():
        return
    problems = []
    for j in np.nonzero(bad.any(axis=1))[0].tolist():
        names = [BOUNDED[b] for b in np.nonzero(bad[j])[0].tolist()]
        problems.append(overflow_problem(prepared.profiles[j],
                                         f"the coefficient bound ({', '.join(names)})",
                                         rate_given=prepared.rate_given))
    raise RangeError(problems)
