"""The Study: the chosen sensors × profiles of a catalogue, prepared once.

Every command is a view of one :class:`Study`. It holds what does not depend
on the question asked — the chosen entries, the coefficients and rates in
deg/s, the sensors' g² sensitivities, each profile's linear vibration — and
computes on first demand, then keeps, what does:

* the vibration of each profile at the nonlinear element of each distinct
  input-side response ν_sensor(f) (:func:`~gyrovib.api.study.prepare.profile_vibration`,
  its phase-locked groups and its saturation swing), once per response;
* the multipliers of a method at the profiles' own rates or over a rate array
  (a sweep), once per response, method and rates.

:meth:`Study.prepare` assembles a :class:`~gyrovib.api.study.prepare.Prepared` from
these, and reports every profile that overflowed or that a method refused
(one problem each, at the profile's place in its file) exactly as a single
pass would. Call it under :func:`~gyrovib.api.study.prepare.float_guard`.

>>> from gyrovib import api
>>> study = Study.of(api.load())                      # doctest: +SKIP
>>> with float_guard():                               # doctest: +SKIP
...     exact = study.prepare(methods=("exact",))     # vibrations computed here
...     paper = study.prepare(methods=("paper",))     # and reused here
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any, TypeVar, cast

import numpy as np

from gyrovib.api.study.convert import coefficient_matrix, resolve_rate
from gyrovib.api.study.entries import select_entries
from gyrovib.api.study.linear import g2_matrix
from gyrovib.api.study.prepare import (
    FLOAT_FAILURES,
    Group,
    Prepared,
    check_sensors,
    cost_problems,
    float_guard,
    linear_vibrations,
    multipliers_of_profile,
    nan_multipliers,
    overflow_problem,
    profile_locked,
    profile_vibration,
    refusal_problem,
    response_layout,
    vibration_swing,
)
from gyrovib.catalog.loader import Catalog, ProfileEntry, SensorEntry
from gyrovib.core._types import FloatArray, Table
from gyrovib.core.analysis import Multipliers, stack_multipliers
from gyrovib.core.harmonics import LockedGroup
from gyrovib.core.linear import LinearVibration
from gyrovib.core.saturation import DEFAULT_PEAK_FACTOR
from gyrovib.core.statistics import Vibration
from gyrovib.errors import ModelError, OptionError, Problem, RangeError
from gyrovib.frozen import Frozen

__all__ = ["Study", "prepare"]

T = TypeVar("T")
_MULTIPLIER_FIELDS = ("asymmetry", "m2", "m4", "c31", "c32")


@dataclass(frozen=True, eq=False, repr=False)
class Seen(Frozen):
    """Every profile as the sensors of one input-side response see it (deg/s).

    ``vibrations[j]`` None where profile j overflowed (``problems[j]`` says so);
    ``locked[j]`` its phase-locked groups; ``swing[j]`` its saturation swing at
    the default κ (:func:`~gyrovib.api.study.prepare.vibration_swing`).
    """

    response: Table | None
    vibrations: tuple[Vibration | None, ...]
    locked: tuple[tuple[LockedGroup, ...], ...]
    swing: FloatArray
    problems: dict[int, Problem]


#: One profile's multipliers, or why there are none: ("refused", reason) or
#: ("overflow", what overflowed).
Outcome = Multipliers | tuple[str, str]


@dataclass(frozen=True, eq=False, repr=False)
class Study(Frozen):
    """The chosen sensors × profiles in deg/s, and a memory of what was computed on them.

    ``coefficients`` (sensors, 11), ``rates`` Ω_K (profiles, 3), ``g2``
    (sensors, 6) deg/s per g², ``linear`` each profile's linear vibration in g
    (None without), ``accelerations`` its six moments ⟨a_j·a_k⟩ (g²).
    ``catalog``: where they come from (its ``allocation:``, its files).
    ``problems``: what the profiles' rates or linear vibrations could not give
    (reported by :meth:`prepare` with the rest). Build with :meth:`of`.
    """

    catalog: Catalog
    sensors: tuple[SensorEntry, ...]
    profiles: tuple[ProfileEntry, ...]
    coefficients: FloatArray
    rates: FloatArray
    rate_given: bool
    g2: FloatArray
    linear: tuple[LinearVibration | None, ...]
    accelerations: tuple[FloatArray | None, ...]
    problems: dict[int, Problem]
    _memory: dict[Any, Any] = field(default_factory=dict, compare=False)

    @classmethod
    def of(cls, catalog: Catalog, *, sensors: Sequence[str] = (),
           profiles: Sequence[str] = (), need: Sequence[str] = ("sensors", "profiles"),
           rate: Sequence[float] | None = None) -> Study:
        """Choose the entries and convert them to deg/s (``rate`` overrides every Ω_K).

        A sensor whose coefficients or g² sensitivities overflow is refused here;
        a profile's overflowing rate or invalid linear vibration is kept in
        :attr:`problems` and reported by :meth:`prepare`.
        """
        s_entries, p_entries = select_entries(catalog, sensors, profiles, need=need)
        coefficients = coefficient_matrix(s_entries)
        check_sensors(coefficients, s_entries)
        problems: dict[int, Problem] = {}
        rates = np.array([resolve_rate(p, rate) for p in p_entries], dtype=float).reshape(-1, 3)
        for j in np.nonzero(~np.all(np.isfinite(rates), axis=1))[0].tolist():
            problems[j] = overflow_problem(p_entries[j], "the carrier rate in deg/s",
                                           rate_given=rate is not None)
        g2 = g2_matrix(s_entries)
        check_sensors(g2, s_entries, "g²-sensitivities (g2_sensitivity or vre) in deg/s per g²")
        with float_guard():
            linear, accelerations = linear_vibrations(p_entries, problems)
        return cls(catalog, s_entries, p_entries, coefficients, rates, rate is not None, g2, linear,
                   tuple(accelerations), problems)

    def narrowed(self, rows: Sequence[int]) -> Study:
        """The sensors at ``rows`` (in that order) over the same profiles, sharing
        this study's memory (what it keeps depends on the profiles and the
        responses, not on which sensors ask)."""
        index = np.asarray(rows, dtype=np.intp)
        return Study(self.catalog, tuple(self.sensors[i] for i in index.tolist()),
                     self.profiles, self.coefficients[index], self.rates, self.rate_given,
                     self.g2[index], self.linear, self.accelerations, self.problems,
                     self._memory)

    # ------------------------------------------------------------- memory

    def remember(self, key: Any, compute: Callable[[], T]) -> T:
        """``compute()`` the first time ``key`` is asked for, the kept value after."""
        if key not in self._memory:
            self._memory[key] = compute()
        return cast(T, self._memory[key])

    def seen(self, response: Table | None, key: Any) -> Seen:
        """The profiles at the nonlinear element behind ``response`` (computed once per key)."""
        found = self._memory.get(("seen", key))
        if found is None:
            found = self._memory[("seen", key)] = _see(self.profiles, response)
        assert isinstance(found, Seen)
        return found

    def swing(self, seen: Seen, key: Any, peak_factor: float,
              problems: dict[int, Problem]) -> FloatArray:
        """The saturation swing of every profile for κ = ``peak_factor`` (deg/s)."""
        if peak_factor == DEFAULT_PEAK_FACTOR:
            return seen.swing
        found = self._memory.get(("swing", key, peak_factor))
        if found is None:
            found = np.full(len(self.profiles), np.nan)
            for j, (v, locked) in enumerate(zip(seen.vibrations, seen.locked, strict=True)):
                if v is None:
                    continue
                try:
                    found[j] = vibration_swing(v, locked, peak_factor)
                except FLOAT_FAILURES:
                    problems.setdefault(j, overflow_problem(self.profiles[j], "the vibration"))
            self._memory[("swing", key, peak_factor)] = found
        assert isinstance(found, np.ndarray)
        return found

    def outcomes(self, seen: Seen, key: Any, method: str, omega: FloatArray | None,
                 phase_search: bool) -> tuple[Outcome, ...]:
        """Each profile's multipliers under ``method`` (computed once per key, method, rates)."""
        memo = ("multipliers", key, method, omega_key(omega), phase_search)
        found = self._memory.get(memo)
        if found is None:
            found = self._memory[memo] = tuple(
                _outcome(v, self.rates[j, 2] if omega is None else omega, method,
                         seen.locked[j], phase_search, self.accelerations[j])
                if v is not None else ("none", "")
                for j, v in enumerate(seen.vibrations))
        assert isinstance(found, tuple)
        return found

    # ------------------------------------------------------------- the pipeline

    def prepare(self, *, methods: Sequence[str] = ("exact",), omega: FloatArray | None = None,
                by_response: bool = True, tolerate_refusals: bool | Sequence[str] = False,
                peak_factor: float = DEFAULT_PEAK_FACTOR,
                phase_search: bool = True) -> Prepared:
        """The groups of sensors with the multipliers of ``methods``; see :func:`prepare`."""
        check_peak_factor(peak_factor)
        # refused before any computation: locked harmonics costing more than the
        # input's size warrants (too many groups, too wide a phase search)
        n_rates = 1 if omega is None else int(np.size(omega))
        costly = cost_problems(self.profiles, n_rates, len(self.sensors), phase_search)
        if costly:
            raise ModelError([costly[j] for j in sorted(costly)],
                             reason=next(iter(costly.values())).message)
        tolerated = (set(methods if tolerate_refusals else ())
                     if isinstance(tolerate_refusals, bool) else set(tolerate_refusals))
        problems = dict(self.problems)
        refusals: list[tuple[int, str]] = []  # the refused profiles, and why, in order
        groups: list[Group] = []
        for response, key, index in self.layout(by_response):
            seen = self.seen(response, key)
            for j, problem in seen.problems.items():
                problems.setdefault(j, problem)
            group = Group(response, index, tuple(v for v in seen.vibrations if v is not None),
                          locked=seen.locked,
                          swing=self.swing(seen, key, peak_factor, problems))
            for method in methods:
                group.multipliers[method] = self._stacked(
                    seen, key, method, omega, phase_search, method in tolerated,
                    group.refused, problems, refusals)
            groups.append(group)
        if problems:
            ordered = [problems[j] for j in sorted(problems)]
            if refusals:
                raise ModelError(ordered, reason=refusals[0][1], profile=refusals[0][0])
            raise RangeError(ordered)
        return Prepared(self.sensors, self.profiles, self.coefficients, self.rates,
                        tuple(groups), rate_given=self.rate_given, linear=self.linear,
                        g2=self.g2)

    def _stacked(self, seen: Seen, key: Any, method: str, omega: FloatArray | None,
                 phase_search: bool, tolerated: bool, refused: dict[str, dict[int, str]],
                 problems: dict[int, Problem], refusals: list[tuple[int, str]]) -> Multipliers:
        """One group's multipliers of ``method`` stacked over the profiles (kept by the study).

        A profile without multipliers gets NaN ones and a problem (an overflow,
        or a refusal unless ``tolerated``: then it is noted in ``refused``).
        """
        items: list[Multipliers] = []
        for j, got in enumerate(self.outcomes(seen, key, method, omega, phase_search)):
            if isinstance(got, Multipliers):
                if not all(np.all(np.isfinite(getattr(got, f))) for f in _MULTIPLIER_FIELDS):
                    problems.setdefault(j, overflow_problem(
                        self.profiles[j], "a statistic of the vibration (<x3²>, <x3⁴>, <x3·xi>)"))
                items.append(got)
                continue
            kind, why = got
            if kind == "refused":
                refused.setdefault(method, {})[j] = why
                if not tolerated:
                    refusals.append((j, why))
                    problems.setdefault(j, refusal_problem(self.profiles[j], method, why))
            elif kind == "overflow":
                problems.setdefault(j, overflow_problem(self.profiles[j], why))
            items.append(nan_multipliers(np.asarray(
                self.rates[j, 2] if omega is None else omega, dtype=float)))
        return self.remember(("stacked", key, method, omega_key(omega), phase_search),
                             lambda: stack_multipliers(items))

    def layout(self, by_response: bool) -> list[tuple[Table | None, Any, Any]]:
        """(response, memory key, sensor indices) per group; one group of all when not
        ``by_response`` (the profiles alone, ν_sensor ≡ 1)."""
        if not self.profiles:
            return []
        if not by_response:
            return [(None, None, np.arange(len(self.sensors), dtype=np.intp))]
        if not self.sensors:
            return []
        return [(table, key, index) for table, key, index in response_layout(self.sensors)]


def omega_key(omega: FloatArray | None) -> Any:
    """A rate array as a key of the study's memory (None: the profiles' own rates)."""
    return None if omega is None else (omega.shape, omega.tobytes())


def check_peak_factor(peak_factor: float) -> None:
    """κ must be a finite number ≥ 0."""
    if not (np.isfinite(peak_factor) and peak_factor >= 0):
        raise OptionError(argument="peak_factor", value=f"{peak_factor:g}",
                          reason="give a finite number ≥ 0")


def _see(profiles: Sequence[ProfileEntry], response: Table | None) -> Seen:
    vibrations: list[Vibration | None] = []
    locked: list[tuple[LockedGroup, ...]] = []
    swing = np.zeros(len(profiles))
    problems: dict[int, Problem] = {}
    with float_guard():
        for j, p in enumerate(profiles):
            try:
                vibration = profile_vibration(p, response)
                groups_j = profile_locked(p, response)
                swing[j] = vibration_swing(vibration, groups_j)
            except FLOAT_FAILURES:
                problems[j] = overflow_problem(p, "the vibration")
                vibrations.append(None)
                locked.append(())
                swing[j] = np.nan
            else:
                vibrations.append(vibration)
                locked.append(groups_j)
    return Seen(response, tuple(vibrations), tuple(locked), swing, problems)


def _outcome(vibration: Vibration, omega: FloatArray | float, method: str,
             locked: tuple[LockedGroup, ...], phase_search: bool,
             acceleration: FloatArray | None) -> Outcome:
    try:
        with float_guard():
            return multipliers_of_profile(vibration, omega, method, locked, phase_search,
                                          acceleration)
    except ModelError as exc:
        return ("refused", exc.reason)
    except FLOAT_FAILURES:
        return ("overflow", f"a statistic of the vibration ({method} method)")


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
    peak_factor: float = DEFAULT_PEAK_FACTOR,
    phase_search: bool = True,
) -> Prepared:
    """A :class:`Study` of ``catalog`` prepared once for one question; under :func:`float_guard`.

    ``omega`` replaces Ω_K3 by an array of rates (a sweep); otherwise each
    profile's Ω_K3 (or ``rate``'s) is used. ``methods`` are the closed forms
    whose multipliers are needed (none for brute force). ``by_response``
    False: one group, the profiles alone (ν_sensor ≡ 1). Every profile that
    overflows or that a method refuses is reported, one problem each.
    ``peak_factor``: κ of the saturation reach (:attr:`Group.swing`).
    Profiles with ``phase: worst`` orders get, with ``phase_search``, the
    largest multiplier of each term over the unknown phases (a bound for
    synthesis, :func:`~gyrovib.core.phases.worst_phase_multipliers`); without,
    those orders' nominal phase 0 (the caller searches itself).
    ``tolerate_refusals``: the methods (True: every method) whose refusal of a
    profile is kept in :attr:`Group.refused` with NaN multipliers instead.
    """
    check_peak_factor(peak_factor)
    study = Study.of(catalog, sensors=sensors, profiles=profiles, need=need, rate=rate)
    return study.prepare(methods=methods, omega=omega, by_response=by_response,
                         tolerate_refusals=tolerate_refusals, peak_factor=peak_factor,
                         phase_search=phase_search)
