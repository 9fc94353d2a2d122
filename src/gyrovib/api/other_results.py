"""The immutable results of ``sweep``, ``bounds`` and ``select``.

Apart from :mod:`gyrovib.api.results` (which still gives their names) so that
a first ``gyrovib analyze`` does not define their classes (~0.5 ms each).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from gyrovib.api.results import _Frozen, _SensorsByProfiles
from gyrovib.core.analysis import VibrationError
from gyrovib.core.transmissibility import FloatArray
from gyrovib.frozen import Frozen

if TYPE_CHECKING:
    from gyrovib.api.spec_bounds import DatasheetBounds
    from gyrovib.api.yields import LotYields
    from gyrovib.core.synthesis import AllocationConstants, CoefficientBounds


@dataclass(frozen=True, eq=False, repr=False)
class SweepResult(_SensorsByProfiles):
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
    peak_factor: float = 3.0

    def _shape(self) -> tuple[int, ...]:
        return (len(self.sensors), len(self.profiles), len(self.rates))


@dataclass(frozen=True, eq=False, repr=False)
class BoundsResult(_Frozen):
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
    #: (:class:`gyrovib.api.spec_bounds.DatasheetBounds`).
    spec_bounds: DatasheetBounds | None = None
    #: the rate unit tables write coefficient bounds in (the catalogue's own, so that
    #: k5 reads 6.7e-06 (deg/s)^-4 rather than 6e-23 (deg/h)^-4); None: :attr:`unit`.
    coefficient_unit: str | None = None

    def _shape(self) -> tuple[int, ...]:
        return (len(self.profiles),)


@dataclass(frozen=True, eq=False, repr=False)
class Limit(Frozen):
    """What stops a failing sensor: the worst coefficient (or ``"rms"``) and where."""

    name: str
    profile: int
    ratio: float


@dataclass(frozen=True, eq=False, repr=False)
class SelectionResult(_SensorsByProfiles):
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
    #: (sensor, profile) → why it fails there beyond the criterion (one line).
    reasons: Mapping[tuple[int, int], str] = field(default_factory=dict)
    #: κ of the saturation reach.
    peak_factor: float = 3.0
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

    def sensor_status(self, i: int) -> str:
        """Sensor ``i`` over every profile: ``fail`` if it fails one, else ``unverified``
        if one is unverified, else ``pass``."""
        found = {self.status(i, j) for j in range(len(self.profiles))}
        for status in ("fail", "unverified"):
            if status in found:
                return status
        return "pass"

    def sensor_unknown(self, i: int) -> tuple[str, ...]:
        """The unknown figures of sensor ``i`` that matter under some profile, in order."""
        found = {n for (k, _), names in self.unknown.items() if k == i for n in names}
        return tuple(n for n in ("vre", "m31", "m32") if n in found)
