"""The immutable results of the four commands.

Frozen dataclasses whose numpy arrays are read-only (``flags.writeable`` is
False, also inside the nested :class:`~gyrovib.core.analysis.VibrationError`,
:class:`~gyrovib.core.synthesis.CoefficientBounds` and
:class:`~gyrovib.core.synthesis.AllocationConstants`) and whose mappings are
read-only views. ``repr`` is one short line (kind, method, unit, shape), not
the arrays.

:class:`AnalysisResult` is defined here; the results of ``sweep``, ``bounds``
and ``select`` in :mod:`gyrovib.api.other_results`, imported from here on first
use of their names (a first ``analyze`` does not define their classes).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from gyrovib.core.analysis import ADDITIVE_TERMS, EXTRA_TERMS, VibrationError
from gyrovib.core.transmissibility import FloatArray
from gyrovib.frozen import Frozen

if TYPE_CHECKING:
    from gyrovib.api.other_results import BoundsResult as BoundsResult
    from gyrovib.api.other_results import Limit as Limit
    from gyrovib.api.other_results import SelectionResult as SelectionResult
    from gyrovib.api.other_results import SweepResult as SweepResult

#: The keys of ``additive_terms`` in JSON, CSV, tables and frames, in this order:
#: Δ0(1..5) (eq. 14/15), g2 = Δ0(6) (docs/model.md section 8), k3 and k5 (section 10).
JSON_TERMS: tuple[str, ...] = (*ADDITIVE_TERMS, *EXTRA_TERMS)


def _freeze(value: Any) -> Any:
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
            _freeze(getattr(value, f.name))
    return value


class _Frozen(Frozen):
    """Read-only arrays and mappings after construction; a one-line repr."""

    def __post_init__(self) -> None:
        for f in dataclasses.fields(self):  # type: ignore[arg-type]
            object.__setattr__(self, f.name, _freeze(getattr(self, f.name)))

    def _shape(self) -> tuple[int, ...]:
        raise NotImplementedError

    def __reduce__(self) -> tuple[Any, ...]:
        """Pickle as a fresh construction (read-only views do not pickle themselves)."""
        values = [getattr(self, f.name) for f in dataclasses.fields(self)]  # type: ignore[arg-type]
        return (type(self), tuple(dict(v) if isinstance(v, Mapping) else v for v in values))

    def to_frame(self) -> Any:
        """Tidy pandas DataFrame, columns named as the JSON keys (:mod:`gyrovib.api.frames`)."""
        from gyrovib.api.frames import to_frame

        return to_frame(self)

    def __repr__(self) -> str:
        method = getattr(self, "method", "exact+paper")
        unit = getattr(self, "unit", "")
        return (f"{type(self).__name__}(method={method!r}, unit={unit!r}, "
                f"shape={self._shape()!r})")


class _SensorsByProfiles(_Frozen):
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
class AnalysisResult(_SensorsByProfiles):
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
    peak_factor: float = 3.0
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


#: The results of sweep, bounds and select live in :mod:`gyrovib.api.other_results`
#: (so that ``analyze`` defines none of their classes); still reachable from here.
_ELSEWHERE = ("SweepResult", "BoundsResult", "Limit", "SelectionResult")


def __getattr__(name: str) -> Any:
    if name in _ELSEWHERE:
        from gyrovib.api import other_results

        return getattr(other_results, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
