"""The immutable results of the four commands: analyze, sweep, bounds, select.

Frozen dataclasses whose numpy arrays are read-only (``flags.writeable`` is
False, also inside the nested :class:`~gyrovib.core.analysis.VibrationError`,
:class:`~gyrovib.core.synthesis.CoefficientBounds` and
:class:`~gyrovib.core.synthesis.AllocationConstants`) and whose mappings are
read-only views. ``repr`` is one short line (kind, method, unit, shape), not
the arrays.

Every result subclasses :class:`Result` (a :class:`~gyrovib.frozen.Frozen`
dataclass, the one immutability mechanism of the library), declared
``@dataclass(frozen=True, eq=False, repr=False)``.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from gyrovib import units
from gyrovib.api.missions.results import worst_status
from gyrovib.core._types import FloatArray
from gyrovib.core.analysis import ALL_TERMS, VibrationError
from gyrovib.core.synthesis import BOUNDED
from gyrovib.formatting import NEGLIGIBLE
from gyrovib.frozen import Frozen
from gyrovib.limits import DEFAULT_PEAK_FACTOR
from gyrovib.reasons import ASSUME_ZERO, Failure
from gyrovib.records import frame_of

if TYPE_CHECKING:
    from gyrovib.api import LotYields
    from gyrovib.api.datasheet.spec_bounds import DatasheetBounds
    from gyrovib.core.synthesis import AllocationConstants, CoefficientBounds

#: The keys of ``additive_terms`` in JSON, CSV, tables and frames, in this order:
#: Δ0(1..5) (eq. 14/15), g2 = Δ0(6) (docs/model.md section 8), k3 and k5 (section 10).
JSON_TERMS: tuple[str, ...] = ALL_TERMS


def freeze(value: Any) -> Any:
    """Make the arrays in ``value`` (and in nested dataclasses) read-only; return it.

    Mappings come back as read-only views of a copy.
    """
    if isinstance(value, np.ndarray):
        value.flags.writeable = False
        return value
    if isinstance(value, Mapping):
        return MappingProxyType(dict(value))
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        for f in dataclasses.fields(value):
            freeze(getattr(value, f.name))
    return value


class Result(Frozen):
    """Read-only arrays and mappings after construction; a one-line repr."""

    def __post_init__(self) -> None:
        for f in dataclasses.fields(self):  # type: ignore[arg-type]
            object.__setattr__(self, f.name, freeze(getattr(self, f.name)))

    def _shape(self) -> tuple[int, ...]:
        raise NotImplementedError

    def __reduce__(self) -> tuple[Any, ...]:
        """Pickle as a fresh construction (read-only views do not pickle themselves)."""
        values = [getattr(self, f.name) for f in dataclasses.fields(self)]  # type: ignore[arg-type]
        return (type(self), tuple(dict(v) if isinstance(v, Mapping) else v for v in values))

    def to_frame(self) -> Any:
        """Tidy pandas DataFrame of the result's records, declared once
        (:mod:`gyrovib.api.evaluation.records`): one row per record, the CSV's columns and
        what only the JSON has; the document-level fields in ``frame.attrs``."""
        # lazy: the start-up budget; the records (datasheet envelope names) for a frame only
        from gyrovib.api.evaluation.records import declared

        return frame_of(*declared(self))

    def __repr__(self) -> str:
        method = getattr(self, "method", "exact+paper")
        unit = getattr(self, "unit", "")
        return (f"{type(self).__name__}(method={method!r}, unit={unit!r}, "
                f"shape={self._shape()!r})")


class SensorsByProfiles(Result):
    """A result per sensor × profile (× rate): how each sensor is given, where it saturates.

    Its dataclasses declare the fields; ``saturated`` left ``None`` is all False.
    """

    sensors: tuple[str, ...]
    profiles: tuple[str, ...]
    sources: tuple[str, ...]
    saturated: NDArray[np.bool_] | None

    def source(self, i: int) -> str:
        """``"specs"`` or ``"coefficients"``: how sensor ``i`` is given."""
        return self.sources[i] if self.sources else "coefficients"

    def __post_init__(self) -> None:
        if self.saturated is None:
            object.__setattr__(self, "saturated", np.zeros(self._shape(), dtype=bool))
        super().__post_init__()

    def _shape(self) -> tuple[int, ...]:
        return (len(self.sensors), len(self.profiles))


@dataclass(frozen=True, eq=False, repr=False)
class AnalysisResult(SensorsByProfiles):
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
    warnings: Mapping[tuple[int, int], tuple[str, ...]] = field(default_factory=dict)
    #: ``numeric`` only: standard error of ``error.total`` (0 where exact), else None.
    stderr: FloatArray | None = None
    #: ``numeric`` only: evaluations of eq. (2) per sensor × profile, and the seed.
    samples: int | None = None
    seed: int | None = None
    #: Per profile: whether it has a linear vibration (Δ0(6), ``error.extra_terms[..., 0]``).
    linear: tuple[bool, ...] = ()
    #: Per sensor ``"coefficients"`` or ``"specs"`` (empty: every sensor has coefficients).
    sources: tuple[str, ...] = ()
    #: Spec-form sensors (docs/model.md section 11): the worst polynomial (A1, k2…k5) in
    #: :attr:`unit` powers, (sensors, profiles, 5), and the per-term RMS bound
    #: (sensors, profiles); NaN on coefficient-form rows; None without spec sensors.
    worst_coefficients: FloatArray | None = None
    rms_bound: FloatArray | None = None
    #: Per sensor, the datasheet figures a spec-form sensor publishes ("nonlinearity",
    #: "asymmetry", "vre"); () for a coefficient-form sensor (or no spec sensors).
    published: tuple[tuple[str, ...], ...] = ()
    #: (sensors, profiles): the saturation reach exceeds the sensor's range (docs/model.md 9).
    saturated: NDArray[np.bool_] | None = None
    #: κ of the saturation reach.
    peak_factor: float = DEFAULT_PEAK_FACTOR
    #: per profile: whether it has phase-locked harmonic groups (docs/model.md 10).
    locked: tuple[bool, ...] = ()
    #: (sensor, profile) → per locked group, {order: phase found (deg)} of the
    #: orders written ``phase: worst``; only for such profiles.
    worst_phases: Mapping[tuple[int, int], tuple[dict[str, float], ...]] = field(
        default_factory=dict)
    #: The rate unit of the profiles' files (None: they differ): tables write the
    #: vehicle's rates in it, the errors in :attr:`unit` (JSON: all in :attr:`unit`).
    rate_unit: str | None = None
    #: (sensors, profiles): u(Δ_V) = √(gᵀΣg) (k = 1) in :attr:`unit` of sensors with
    #: ``uncertainty`` or ``lot`` (docs/model.md section 14), NaN for the others (and where
    #: phases are searched); None when no sensor has one.
    uncertainty: FloatArray | None = None
    #: Per sensor: a production lot, analysed at its mean (empty: none is).
    lots: tuple[bool, ...] = ()
    #: Warnings about the run, not one cell (a lot too small for its correlations).
    notes: tuple[str, ...] = ()

    @property
    def has_linear(self) -> bool:
        """Whether any profile has a linear vibration (the g² term, docs/model.md section 8)."""
        return any(self.linear)

    def is_lot(self, i: int) -> bool:
        """Whether sensor ``i`` is a production lot (its row is the lot's mean)."""
        return bool(self.lots) and self.lots[i]

    @property
    def table_rate_unit(self) -> str:
        """The rate unit tables write the vehicle's rates in: :attr:`rate_unit`, the
        profiles' files' own, else :attr:`unit`."""
        return self.rate_unit or self.unit

    @property
    def table_rates(self) -> FloatArray:
        """:attr:`rates` in :attr:`table_rate_unit`, as tables show them."""
        return _rates_in(self.rates, self.unit, self.table_rate_unit)


def _rates_in(rates: FloatArray, unit: str, target: str) -> FloatArray:
    """Rates in ``unit`` converted to ``target``."""
    if target == unit:
        return rates
    out: FloatArray = rates * units.scale(unit) / units.scale(target)
    return out


@dataclass(frozen=True, eq=False, repr=False)
class SweepResult(SensorsByProfiles):
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
    paper_refused: Mapping[str, str] = field(default_factory=dict)
    #: (sensor, profile) pairs whose g² figure is not given under the profile's linear
    #: vibration: their Δ_V and Δ_V(RMS) are NaN at every rate (unknown, as in analyze).
    g2_unknown: tuple[tuple[str, str], ...] = ()
    #: Per sensor ``"coefficients"`` or ``"specs"`` (empty: every sensor has coefficients).
    sources: tuple[str, ...] = ()
    #: Spec-form sensors: the exact method's worst polynomial (A1, k2…k5) at each
    #: rate, (sensors, profiles, rates, 5) in :attr:`unit` powers (NaN on
    #: coefficient rows), with the datasheet envelope per sensor (``nl_limit``,
    #: the residual limit b in :attr:`unit`, NaN on coefficient rows; ``nl_fit``;
    #: ``nl_range`` R in :attr:`unit`); None without spec sensors.
    worst_coefficients: FloatArray | None = None
    nl_limit: FloatArray | None = None
    nl_range: FloatArray | None = None
    nl_fit: tuple[str, ...] = ()
    #: (sensors, profiles, rates): the sensor saturates at that Ω_K3 (docs/model.md section 9).
    saturated: NDArray[np.bool_] | None = None
    #: κ of the saturation reach.
    peak_factor: float = DEFAULT_PEAK_FACTOR

    def _shape(self) -> tuple[int, ...]:
        return (len(self.sensors), len(self.profiles), len(self.rates))


@dataclass(frozen=True, eq=False, repr=False)
class BoundsResult(Result):
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
    #: ``--range``: the allowable datasheet figures
    #: (:class:`gyrovib.api.datasheet.spec_bounds.DatasheetBounds`).
    spec_bounds: DatasheetBounds | None = None
    #: the rate unit tables write coefficient bounds in (the catalogue's own, so that
    #: k5 reads 6.7e-06 (deg/s)^-4 rather than 6e-23 (deg/h)^-4); None: :attr:`unit`.
    coefficient_unit: str | None = None

    def _shape(self) -> tuple[int, ...]:
        return (len(self.profiles),)

    @property
    def table_unit(self) -> str:
        """The rate unit tables write coefficient bounds in (:attr:`coefficient_unit`)."""
        return self.coefficient_unit or self.unit

    @property
    def table_bounds(self) -> CoefficientBounds:
        """:attr:`bounds` in :attr:`table_unit` powers, as tables show them (the VRE
        bound stays in :attr:`unit` per g²)."""
        return _in_table_unit(self.bounds, self.unit, self.table_unit)

    @property
    def table_rates(self) -> FloatArray:
        """:attr:`rates` (Ω_K per profile) in :attr:`table_unit`, as tables show them."""
        return _rates_in(self.rates, self.unit, self.table_unit)


def _coefficient_factors(unit: str, table_unit: str) -> dict[str, float]:
    """Each bounded coefficient's factor from ``unit`` powers to ``table_unit`` powers."""
    return {name: units.coefficient_factor(name, unit, table_unit) for name in BOUNDED}


def _in_table_unit(bounds: CoefficientBounds, unit: str, table_unit: str) -> CoefficientBounds:
    if table_unit == unit:
        return bounds
    return bounds.scaled({**_coefficient_factors(unit, table_unit), "vre": 1.0})


@dataclass(frozen=True, eq=False, repr=False)
class Limit(Frozen):
    """What stops a failing sensor: the worst coefficient (or ``"rms"``) and where."""

    name: str
    profile: int
    ratio: float


@dataclass(frozen=True, eq=False, repr=False)
class SelectionResult(SensorsByProfiles):
    """Every chosen sensor checked against the budget under every chosen profile.

    Arrays are indexed (sensor, profile[, coefficient of :data:`BOUNDED`]) and
    are in :attr:`unit`. ``values`` are the sensors' |coefficients| (k1 taken
    as 1); ``bounds`` each sensor's own bounds (its response ν_sensor included);
    ``profile_bounds`` those of the profiles alone; the ``vre`` check is
    kept apart (``vre_value``, ``vre_bound``, ``vre_pass``). ``margin`` is Δ*/Δ_V(RMS)
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
    limits: Mapping[int, Limit]
    requirement_met: bool
    allocation: AllocationConstants
    #: The ``vre`` check, (sensor, profile), in :attr:`unit` per g². A coefficient
    #: sensor (docs/model.md section 8): its effective VRE |Δ0(6)|/Σ⟨a_j²⟩ (0 where the
    #: profile has no linear vibration), its bound (+inf there) and whether it is
    #: within it (part of ``bounds_pass``). A spec-form sensor (section 11): its
    #: datasheet VRE (NaN: no VRE spec, taken as 0) against the allowable VRE.
    vre_value: FloatArray | None = None
    vre_bound: FloatArray | None = None
    vre_pass: NDArray[np.bool_] | None = None
    #: |Δ_V| per sensor × profile (for a spec-form sensor the worst case), in :attr:`unit`.
    total: FloatArray | None = None
    #: Per sensor ``"coefficients"`` or ``"specs"`` (empty: every sensor has coefficients).
    sources: tuple[str, ...] = ()
    #: Spec-form sensors against their spec bounds (docs/model.md section 11), (sensors,
    #: profiles), NaN (pass True) on coefficient rows: the nonlinearity and its
    #: allowable value in %FS (the sensor's own range or span).
    nl_value: FloatArray | None = None
    nl_bound: FloatArray | None = None
    nl_pass: NDArray[np.bool_] | None = None
    #: (sensors, profiles): saturates there (docs/model.md section 9), which fails it.
    saturated: NDArray[np.bool_] | None = None
    #: (sensor, profile) → (saturation reach, range) in :attr:`unit` where the sensor
    #: saturates (docs/model.md section 9): the reach |Ω_K3| + Σ tone amplitudes + locked
    #: peaks + κσ3 (κ: :attr:`peak_factor`) exceeds the range.
    saturation: Mapping[tuple[int, int], tuple[float, float]] = field(default_factory=dict)
    #: κ of the saturation reach.
    peak_factor: float = DEFAULT_PEAK_FACTOR
    #: as :attr:`BoundsResult.coefficient_unit`, for coefficient values and bounds in tables.
    coefficient_unit: str | None = None
    #: (sensors, profiles): the sensor would pass there on its published figures, but
    #: an unpublished one (``unknown``) can change the verdict: neither passed
    #: (``passed`` is False there) nor ranked on it. None: nowhere.
    unverified: NDArray[np.bool_] | None = None
    #: (sensors, profiles): the margin of the test that decides the cell under
    #: :attr:`criterion` (``bounds``: the least bound/value ratio of the checks,
    #: a datasheet part's NL and VRE against their allowable figures; ``rms``:
    #: Δ*/Δ_V(RMS); ``worst``: Δ*/|Δ_V|; ``both``: the smaller of bounds and rms),
    #: above 1 where that test passes; +inf: nothing to bound. ``margin`` keeps
    #: Δ*/Δ_V(RMS) (a datasheet part: Δ*/worst |Δ_V|) whatever the criterion.
    criterion_margin: FloatArray | None = None
    #: (sensor, profile) → the tests among ``bounds``, ``rms``, ``worst`` not deciding
    #: the cell whose verdict differs from the cell's (on the published figures).
    disagrees: Mapping[tuple[int, int], tuple[str, ...]] = field(default_factory=dict)
    #: (sensor, profile) → the unpublished figures that can matter there
    #: (``"vre"``, ``"m31"``, ``"m32"``; docs/model.md section 11), also under
    #: ``assume_unknown="zero"``, where they are taken as 0.
    unknown: Mapping[tuple[int, int], tuple[str, ...]] = field(default_factory=dict)
    #: Per sensor with unknown figures: the questions for the vendor (the
    #: figures that would decide it, with the value that would pass).
    questions: Mapping[int, tuple[str, ...]] = field(default_factory=dict)
    #: ``"none"`` (an unknown figure leaves the verdict open) or ``"zero"``
    #: (``--assume-unknown zero``: taken as 0, as stated in the output).
    assume_unknown: str = "none"
    #: ``--yield``: the lots' yields (docs/model.md section 14), by which lots are judged;
    #: None without --yield or without lots.
    yields: LotYields | None = None
    #: Warnings about the run, not one cell (a lot too small for its correlations).
    notes: tuple[str, ...] = ()
    #: How a reason names taking an unpublished figure as 0 (a note naming the argument).
    assume_zero: str = ASSUME_ZERO

    @property
    def has_linear(self) -> bool:
        """Whether some profile has a linear vibration (so the ``vre`` check can bind)."""
        return self.profile_bounds.vre is not None

    def is_unverified(self, i: int, j: int) -> bool:
        """Whether sensor ``i``'s verdict under profile ``j`` hangs on an unknown figure."""
        return bool(self.unverified is not None and self.unverified[i, j])

    def status(self, i: int, j: int) -> str:
        """``"pass"``, ``"fail"`` or ``"unverified"`` of sensor ``i`` under profile ``j``."""
        if self.passed[i, j]:
            return "pass"
        return "unverified" if self.is_unverified(i, j) else "fail"

    def check(self, i: int, j: int, b: int) -> bool | None:
        """Whether coefficient ``b`` (of :data:`BOUNDED`) of sensor ``i`` is within its bound
        under profile ``j``; None where the bound is unknown (the profile was fitted from a
        recording without an axis it depends on) and the coefficient is not 0."""
        if np.isnan(self.bounds[i, j, b]) and self.values[i, j, b] != 0:
            return None
        return bool(self.check_pass[i, j, b])

    def vre_check(self, i: int, j: int) -> bool | None:
        """The VRE check of cell ``(i, j)`` as :meth:`check` (None: no VRE check, its
        bound unknown for a VRE that is not 0, or the VRE itself unknown, an unpublished
        or ungiven figure, where a bound applies, unless :attr:`assume_unknown` takes it
        as 0)."""
        if self.vre_pass is None:
            return None
        if self.vre_bound is not None and np.isnan(self.vre_bound[i, j]) and (
                self.vre_value is None or self.vre_value[i, j] != 0):
            return None
        if (self.vre_value is not None and self.vre_bound is not None
                and np.isnan(self.vre_value[i, j]) and np.isfinite(self.vre_bound[i, j])
                and self.assume_unknown != "zero"):
            return None  # an unknown figure against a bound: neither passed nor failed
        return bool(self.vre_pass[i, j])

    def nl_check(self, i: int, j: int) -> bool | None:
        """A datasheet part's nonlinearity check of cell ``(i, j)`` as :meth:`check` (None:
        no such check, or its allowable NL unknown, x3 not recorded)."""
        if self.nl_pass is None or self.nl_bound is None or np.isnan(self.nl_bound[i, j]):
            return None
        return bool(self.nl_pass[i, j])

    def sensor_status(self, i: int) -> str:
        """Sensor ``i`` over every profile: ``fail`` if it fails one, else ``unverified``
        if one is unverified, else ``pass``."""
        return worst_status(self.status(i, j) for j in range(len(self.profiles)))

    def sensor_unknown(self, i: int) -> tuple[str, ...]:
        """The unknown figures of sensor ``i`` that matter under some profile, in order."""
        found = {n for (k, _), names in self.unknown.items() if k == i for n in names}
        return tuple(n for n in ("vre", "m31", "m32", "spread", "x1", "x2", "x3",
                                 "acceleration") if n in found)

    def failures(self, i: int, j: int, *, table: bool = False) -> tuple[Failure, ...]:
        """Why sensor ``i`` fails under profile ``j`` (empty where it passes), as codes and
        numbers (:mod:`gyrovib.reasons` words them): an unknown figure first, saturation
        (it fails a sensor whatever the criterion), a lot's yield, then only the criteria
        that count. ``table``: as the tables show it, coefficients in :attr:`table_unit`
        and a negligible Δ_V(RMS) as 0."""
        out = [*self._unverified(i, j)]
        if (i, j) in self.saturation:
            out.append(Failure("saturated", (*self.saturation[i, j], self.peak_factor),
                               unit=self.unit))
        if self.yields is not None and self.yields.is_lot(i):  # judged by its yield
            found = self.yields.at(i, j)
            return (*out, *([Failure("yield", (self.yields.target,), lot=found)]
                            if not found.value >= self.yields.target else []))
        if self.criterion in ("bounds", "both"):
            out += (self._datasheet_failures(i, j) if self.source(i) == "specs"
                    else self._coefficient_failures(i, j, table))
        if self.criterion in ("rms", "both") and not self.rms_pass[i, j]:
            rms = float(self.rms[i, j])
            negligible = table and abs(rms) < NEGLIGIBLE * self.budget
            out.append(Failure("rms", (0.0 if negligible else rms, self.budget), unit=self.unit))
        if self.criterion == "worst" and not self.passed[i, j] and self.total is not None:
            out.append(Failure("worst", (float(self.total[i, j]), self.budget), unit=self.unit,
                               spec=self.source(i) == "specs"))
        return tuple(out)

    def _unverified(self, i: int, j: int) -> list[Failure]:
        """The unknown figures that leave cell ``(i, j)`` open, with (a lot whose spread is
        not measured) its yield, which is no measurement (docs/model.md sections 11, 14)."""
        if not self.is_unverified(i, j):
            return []
        names = self.unknown.get((i, j), ())
        y = self.yields if "spread" in names else None
        return [Failure("unverified", names=tuple(n for n in names if n != "spread"),
                        spec=self.source(i) == "specs", lot=None if y is None else y.at(i, j),
                        note="" if y is None else f"{y.unmeasured[i]}",
                        advice=self.assume_zero)]

    def _coefficient_failures(self, i: int, j: int, table: bool) -> list[Failure]:
        """The coefficient checks a coefficient sensor fails, then its effective VRE above
        its bound (docs/model.md section 8); a VRE not given is no such failure (its
        unknown figure is reported as such, never as 'nan exceeds its bound')."""
        values = self.table_values if table else self.values
        bounds = self.table_bounds if table else self.bounds
        out = [Failure("coefficient", (float(values[i, j, b]), float(bounds[i, j, b])),
                       (name,), self.table_unit if table else self.unit)
               for b, name in enumerate(BOUNDED) if not self.check_pass[i, j, b]]
        if self.vre_pass is not None and not self.vre_pass[i, j]:
            assert self.vre_value is not None and self.vre_bound is not None
            if np.isnan(self.vre_value[i, j]):
                return out
            out.append(Failure("vre", (float(self.vre_value[i, j]),
                                       float(self.vre_bound[i, j])), unit=self.unit))
        return out

    def _datasheet_failures(self, i: int, j: int) -> list[Failure]:
        """A datasheet part's figures above their allowable values (docs/model.md
        section 11)."""
        assert self.nl_pass is not None and self.nl_value is not None
        assert self.nl_bound is not None and self.vre_pass is not None
        assert self.vre_value is not None and self.vre_bound is not None
        out = []
        if not self.nl_pass[i, j]:
            out.append(Failure("nonlinearity", (float(self.nl_value[i, j]),
                                                float(self.nl_bound[i, j]))))
        if not self.vre_pass[i, j] and not np.isnan(self.vre_value[i, j]):
            out.append(Failure("datasheet_vre", (float(self.vre_value[i, j]),
                                                 float(self.vre_bound[i, j])), unit=self.unit))
        return out

    @property
    def table_unit(self) -> str:
        """The rate unit tables write coefficients in (:attr:`coefficient_unit`)."""
        return self.coefficient_unit or self.unit

    @property
    def table_values(self) -> FloatArray:
        """:attr:`values` in :attr:`table_unit` powers, as tables show them."""
        return self._in_table_unit(self.values)

    @property
    def table_bounds(self) -> FloatArray:
        """:attr:`bounds` in :attr:`table_unit` powers, as tables show them."""
        return self._in_table_unit(self.bounds)

    def _in_table_unit(self, array: FloatArray) -> FloatArray:
        if self.table_unit == self.unit:
            return array
        factors = _coefficient_factors(self.unit, self.table_unit)
        out: FloatArray = array * np.array([factors[name] for name in BOUNDED])
        return out
