"""The pieces of the one preparation every command runs (:mod:`gyrovib.api.study.study`).

A profile's vibration at a sensor's nonlinear element, its phase-locked
groups and saturation swing, one profile's multipliers, the sensors grouped
by response, and the located wording of what overflowed or was refused; the
:class:`Prepared` a :class:`~gyrovib.api.study.study.Study` hands to its views. All
under :func:`float_guard`. A value that leaves floating-point range (an amplitude of
1e200, a rate of 1e308) or a profile a method cannot handle is reported here,
once, at the profile's place in its file (:class:`~gyrovib.errors.RangeError`,
:class:`~gyrovib.errors.ModelError`, exit status 2), never as NaN or null in
the output nor as an OverflowError.

The commands then evaluate the model (eq. 13-16, 23, 25) on a
:class:`Prepared` and check what they computed with :func:`check_finite` /
:func:`check_bounds`, which word their refusals the same way.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from gyrovib import units
from gyrovib.api.study.linear import profile_linear
from gyrovib.catalog.loader import ProfileEntry, SensorEntry
from gyrovib.core._types import FloatArray, Table
from gyrovib.core.analysis import BOUNDED, Multipliers, profile_multipliers
from gyrovib.core.harmonics import MAX_GROUPS, LockedGroup, locked_group
from gyrovib.core.linear import LinearVibration
from gyrovib.core.phases import MAX_SEARCH_COST, search_cost, worst_phase_multipliers
from gyrovib.core.saturation import DEFAULT_PEAK_FACTOR, group_peak, saturation_reach
from gyrovib.core.statistics import Vibration, vibration_at_sensor
from gyrovib.core.transmissibility import as_table, loglog_interp
from gyrovib.errors import Problem, RangeError, literal
from gyrovib.frozen import Frozen

#: Python's and numpy's ways of saying a number left floating-point range.
FLOAT_FAILURES = (OverflowError, FloatingPointError, ZeroDivisionError)
#: The smallest positive normal float: below it a share or a bound has lost its digits.
TINY = float(np.finfo(float).tiny)


@contextmanager
def float_guard() -> Iterator[None]:
    """numpy's floating-point warnings off: overflow is checked on the results instead.

    Absurd magnitudes overflow on the way; :func:`check_finite` and
    :func:`check_bounds` report that once, located, instead of numpy printing
    a RuntimeWarning per operation.
    """
    with np.errstate(over="ignore", invalid="ignore", divide="ignore", under="ignore"):
        yield


# ----------------------------------------------------------------- vibrations


def input_response(entry: SensorEntry) -> tuple[tuple[float, float], ...] | None:
    """The sensor's response where it acts before the nonlinearity, or None.

    Only ``response: {at: input, ...}`` shapes the vibration the nonlinear
    element sees (docs/model.md section 9); a bare table or ``at: output`` is an
    output filter, applied after the error is rectified: it earns no credit.
    """
    s = entry.sensor
    if s.response_table is None or s.response_at != "input":
        return None
    return tuple((float(f), float(g)) for f, g in s.response_table)


def response_table(entry: SensorEntry) -> Table | None:
    """The sensor's transmissibility ν_sensor(f) before its nonlinearity, or None for ν ≡ 1.

    An output-side response (the default) gives None: it does not reduce the error.
    """
    table = input_response(entry)
    return None if table is None else as_table(table)


def response_layout(entries: Sequence[SensorEntry],
                    ) -> list[tuple[Table | None, tuple[tuple[float, float], ...] | None,
                                    NDArray[np.intp]]]:
    """Sensors grouped by identical input-side responses: ``(table, key, indices)``, the
    key being the response as written. Profile statistics depend on the sensor only
    through the ν_sensor(f) that acts before its nonlinearity (:func:`input_response`),
    so they are computed once per group, not once per sensor."""
    groups: dict[tuple[tuple[float, float], ...] | None, list[int]] = {}
    for i, e in enumerate(entries):
        key = input_response(e)
        groups.setdefault(key, []).append(i)
    return [
        (None if key is None else as_table(key), key, np.array(idx, dtype=np.intp))
        for key, idx in groups.items()
    ]


def _gain_tables(entry: ProfileEntry, response: Table | None) -> list[Table]:
    """The ν(f) tables between the vibration and the nonlinear element: the profile's
    mount, then the sensor's response where it acts at the input (docs/model.md section 9)."""
    tables = [] if entry.profile.mount is None else [as_table(entry.profile.mount)]
    return tables if response is None else [*tables, response]


def profile_vibration(entry: ProfileEntry, response: Table | None = None) -> Vibration:
    """The vibration of a profile reaching a sensor of the given response, in deg/s."""
    p = entry.profile
    s = units.scale(entry.unit)
    gains = _gain_tables(entry, response)
    tones = [(t.frequency, np.asarray(t.amplitude) * s, t.phase) for t in p.harmonic]
    psd: list[Table | None] | None = None
    rms = None
    coherence: tuple[float, float] = (1.0, 1.0)
    if p.random is not None:
        coherence = (p.random.coherence[0], p.random.coherence[1])  # ρ12 acts on no x3 term
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


def profile_locked(entry: ProfileEntry, response: Table | None = None) -> tuple[LockedGroup, ...]:
    """The profile's phase-locked harmonic groups at the sensor, in deg/s (docs/model.md
    section 10).

    Each order n of a group is scaled by the mount's and the (input-side)
    response's ν(n·f0), as an independent tone at that frequency would be;
    an order with ``phase: worst`` gets phase 0 and is marked for the search.
    """
    p = entry.profile
    s = units.scale(entry.unit)
    tables = _gain_tables(entry, response)
    out = []
    for h in p.harmonic_groups:
        orders = [o.order for o in h.orders]
        freqs = np.asarray(orders, dtype=float) * float(h.fundamental)
        gains = np.ones(len(orders))
        for table in tables:
            gains = gains * np.asarray(loglog_interp(table, freqs), dtype=float)
        out.append(locked_group(
            orders, np.array([o.amplitude for o in h.orders], dtype=float) * s,
            np.array([(0.0, 0.0, 0.0) if o.worst_phase else o.phase for o in h.orders],
                     dtype=float),
            worst=[o.worst_phase for o in h.orders], fundamental=float(h.fundamental),
            gains=gains))
    return tuple(out)


def vibration_swing(vibration: Vibration, locked: Sequence[LockedGroup] = (),
                    peak_factor: float = DEFAULT_PEAK_FACTOR) -> float:
    """How far the vibration drives x3 from Ω_K3 (docs/model.md section 9), in its rate unit.

    Σ tone amplitudes + Σ true peaks of the locked groups + κ·σ3; the
    saturation reach is |Ω_K3| plus this.
    """
    peaks = [group_peak(g) for g in locked]
    return float(saturation_reach(0.0, vibration.tone_amplitudes, vibration.sigma[2],
                                  locked_peaks=np.asarray(peaks, dtype=float),
                                  kappa=peak_factor))


def nan_multipliers(omega: FloatArray) -> Multipliers:
    """Multipliers of a profile a method refuses: NaN everywhere (sweep's empty cells)."""
    nan = np.full(omega.shape, np.nan)
    return Multipliers(asymmetry=nan, m2=nan, m4=nan, c31=nan, c32=nan, omega=omega.copy())


# ----------------------------------------------------------------- messages


_HINT = "the amplitudes, PSD levels, rms values, rates and coefficients"


def profile_problem(profile: ProfileEntry, message: str,
                    arguments: tuple[str, ...] = ()) -> Problem:
    """``message`` placed at the profile's ``id:`` in its file; a message that names
    library ``arguments`` writes each ``{name}`` (:meth:`Problem.naming`)."""
    placed = profile.source.problem(message, ("profiles", profile.index, "id"))
    if not arguments:
        return placed
    return Problem.naming(message, arguments, placed.file, placed.line, placed.column)


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
    advice = ("; use {method} exact, or choose other profiles with {profiles}"
              if method == "paper" else "")
    said = f"profile {profile.profile.id!r}: {reason}"
    return profile_problem(profile, (literal(said) if advice else said) + advice,
                           ("method", "profiles") if advice else ())


def _harmonics_path(profile: ProfileEntry, group: int, *tail: Any) -> tuple[Any, ...]:
    """The path of ``tail`` inside locked group ``group`` of a profile: ``harmonics``
    is one mapping or a list of them in the file."""
    base: tuple[Any, ...] = ("profiles", profile.index, "harmonics")
    # (a path that leaves the document stops at the deepest node reached: a list's
    # first item is placed apart from the list itself, a mapping's "0" is not found)
    if profile.source.locate((*base, group)) != profile.source.locate(base):
        return (*base, group, *tail)
    return base + tuple(tail)


def cost_problems(entries: Sequence[ProfileEntry], rates: int, sensors: int,
                  phase_search: bool) -> dict[int, Problem]:
    """Profiles whose locked harmonics would cost more than the input's size warrants.

    Refused before any computation, each at the offending key: more than
    :data:`~gyrovib.core.harmonics.MAX_GROUPS` groups with no random part, and a
    ``phase: worst`` search (with ``phase_search``, over ``rates`` rates) estimated
    above :data:`~gyrovib.core.phases.MAX_SEARCH_COST` for one sensor — four
    objectives per rate for synthesis (with ``phase_search``) and one for the
    sensor's own search of ``analyze`` and ``select``. ``sensors`` does not enter:
    each sensor's search is the same size, run one after another with progress.
    """
    problems: dict[int, Problem] = {}
    for j, p in enumerate(entries):
        if not p.profile.harmonic_groups:
            continue
        problem = (_too_many_groups(p)
                   or _search_too_costly(p, rates, sensors, phase_search))
        if problem is not None:
            problems[j] = problem
    return problems


def _too_many_groups(p: ProfileEntry) -> Problem | None:
    """More phase-locked groups than :data:`~gyrovib.core.harmonics.MAX_GROUPS` and no
    random part (with one, the further groups are folded into its table)."""
    groups = p.profile.harmonic_groups
    if len(groups) <= MAX_GROUPS or p.profile.random is not None:
        return None
    return p.source.problem(
        f"profile {p.profile.id!r}: {len(groups)} phase-locked groups and no random part; "
        f"without one gyrovib averages E(Ω) over at most {MAX_GROUPS} groups (the joint "
        f"phases of the groups beyond the first take 256^(groups − 1) nodes per rate: "
        f"256^{len(groups) - 1} here); give the smaller groups' orders as independent "
        "tones under 'harmonic', or the profile's random part",
        _harmonics_path(p, MAX_GROUPS, "fundamental"))


def _search_size(groups: Sequence[Any]) -> tuple[int, int]:
    """The unknown relative phases of ``phase: worst`` orders (a group whose every order
    is ``worst`` has one fewer: its common phase is free), and the highest order."""
    dims = sum(sum(bool(o.worst_phase) for o in h.orders)
               - (1 if all(o.worst_phase for o in h.orders) else 0) for h in groups)
    return dims, max(o.order for h in groups for o in h.orders)


def _search_too_costly(p: ProfileEntry, rates: int, sensors: int,
                       phase_search: bool) -> Problem | None:
    """A ``phase: worst`` search estimated above :data:`~gyrovib.core.phases.MAX_SEARCH_COST`."""
    groups = p.profile.harmonic_groups
    worst = [(gi, oi) for gi, h in enumerate(groups) for oi, o in enumerate(h.orders)
             if o.worst_phase]
    if not worst:
        return None
    dims, n_max = _search_size(groups)
    # the synthesis searches four objectives per rate (a sweep's rates are the user's
    # to choose); the analysis one per sensor, one sensor after another with progress:
    # the number of sensors compared multiplies the time, it never refuses the input
    cost = search_cost(dims, (4 * rates if phase_search else 0) + 1, n_max)
    if cost <= MAX_SEARCH_COST:
        return None
    gi, oi = worst[0]
    return p.source.problem(
        f"profile {p.profile.id!r}: the search over {dims} unknown relative phase"
        f"{'s' if dims != 1 else ''} (phase: worst, orders up to {n_max}) at {rates} "
        f"rate{'s' if rates != 1 else ''} would take about {cost:,.0f} evaluations of "
        f"the profile per sensor, more than the {MAX_SEARCH_COST:,.0f} (a few seconds) "
        "gyrovib allows; give fewer orders phase: worst (their phases, if known), or "
        "fewer rates",
        _harmonics_path(p, gi, "orders", oi, "phase"))


# ----------------------------------------------------------------- the pipeline


@dataclass(frozen=True, eq=False, repr=False)
class Group(Frozen):
    """Sensors sharing one input-side response ν_sensor(f), and every profile as they see it.

    ``multipliers[method]`` is stacked over the profiles (shape profiles, or
    profiles × rates); ``refused[method]`` maps a profile index to the reason
    the method gave (only when refusals are tolerated, as by ``sweep``).
    ``locked[j]``: profile j's phase-locked groups as these sensors see them;
    ``swing[j]``: how far profile j drives x3 from Ω_K3 (:func:`vibration_swing`,
    deg/s, with the pipeline's peak factor κ).
    """

    response: Table | None
    index: NDArray[np.intp]
    vibrations: tuple[Vibration, ...]
    multipliers: dict[str, Multipliers] = field(default_factory=dict)
    refused: dict[str, dict[int, str]] = field(default_factory=dict)
    locked: tuple[tuple[LockedGroup, ...], ...] = ()
    swing: FloatArray = field(default_factory=lambda: np.zeros(0))

    def reach(self, rates: FloatArray) -> FloatArray:
        """|Ω_K3| + swing per profile (deg/s), for Ω_K3 ``rates`` (profiles,)."""
        out: FloatArray = np.abs(np.asarray(rates, dtype=float)) + self.swing
        return out


@dataclass(frozen=True, eq=False, repr=False)
class Prepared(Frozen):
    """What every command needs, in deg/s: chosen entries, coefficients, rates, groups.

    ``coefficients`` (sensors, 11) in deg/s powers; ``rates`` Ω_K per
    profile, shape (profiles, 3); ``rate_given``: a rate override replaced
    the profiles' own. ``linear``: each profile's linear vibration in g (None
    where it has none; docs/model.md section 8); ``g2``: the sensors' G_jk in deg/s
    per g², shape (sensors, 6).
    """

    sensors: tuple[SensorEntry, ...]
    profiles: tuple[ProfileEntry, ...]
    coefficients: FloatArray
    rates: FloatArray
    groups: tuple[Group, ...]
    rate_given: bool
    linear: tuple[LinearVibration | None, ...] = ()
    g2: FloatArray = field(default_factory=lambda: np.zeros((0, 6)))

    @property
    def has_linear(self) -> bool:
        """Whether any chosen profile has a linear vibration."""
        return any(v is not None for v in self.linear)


def linear_vibrations(entries: Sequence[ProfileEntry], problems: dict[int, Problem],
            ) -> tuple[tuple[LinearVibration | None, ...], list[FloatArray | None]]:
    """Each profile's linear vibration in g and its six moments ⟨a_j·a_k⟩ (g²), or None."""
    linear: list[LinearVibration | None] = []
    moments: list[FloatArray | None] = []
    for j, p in enumerate(entries):
        try:
            v = profile_linear(p)
            m = None if v is None else v.moments()
        except (*FLOAT_FAILURES, ValueError):
            v = m = None
        if p.profile.acceleration is not None and (m is None or not np.all(np.isfinite(m))):
            problems.setdefault(j, overflow_problem(p, "the linear vibration (⟨a_j·a_k⟩ in g²)"))
            v = m = None
        elif v is not None and not _valid_coherence(v):
            problems.setdefault(j, p.source.problem(
                f"profile {p.profile.id!r}: the acceleration coherences ρ12, ρ13, ρ23 = "
                   f"{', '.join(f'{c:g}' for c in v.coherence)} do not form a correlation "
                   "matrix (it must be positive semi-definite: no three axes can be that "
                   "correlated at once)",
                ("profiles", p.index, "acceleration", "random", "coherence")))
            v = m = None
        linear.append(v)
        moments.append(m)
    return tuple(linear), moments


def _valid_coherence(linear: LinearVibration) -> bool:
    """Whether ρ12, ρ13, ρ23 form a positive semi-definite correlation matrix."""
    r12, r13, r23 = (float(c) for c in linear.coherence)
    rho = np.array([[1.0, r12, r13], [r12, 1.0, r23], [r13, r23, 1.0]])
    return bool(np.linalg.eigvalsh(rho).min() >= -1e-12)


def multipliers_of_profile(vibration: Vibration, omega: FloatArray | float, method: str,
                 locked: Sequence[LockedGroup], phase_search: bool,
                 acceleration: FloatArray | None = None) -> Multipliers:
    """One profile's multipliers: with locked groups (section 10), and the worst phases."""
    if locked and method == "exact" and phase_search and any(g.worst.any() for g in locked):
        return worst_phase_multipliers(vibration, locked, omega, acceleration=acceleration)
    return profile_multipliers(vibration, omega, method, locked=locked,
                               acceleration=acceleration)


def check_sensors(values: FloatArray, entries: Sequence[SensorEntry],
                   what: str = "coefficients") -> None:
    bad = np.nonzero(~np.all(np.isfinite(values), axis=1))[0]
    if bad.size:
        raise RangeError([
            entries[i].source.problem(
                f"sensor {entries[i].sensor.id!r}: its {what} overflow floating point"
                f"{' in deg/s' if what == 'coefficients' else ''}; check them for absurd "
                "magnitudes", ("sensors", entries[i].index, "id"))
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

