"""What ``gyrovib allan`` and the mission budget give (docs/model.md section 15):
immutable results."""

from __future__ import annotations

from dataclasses import dataclass

from gyrovib.core.transmissibility import FloatArray
from gyrovib.frozen import Frozen

#: The reported unit of each noise figure (its default in the catalogue).
FIGURE_UNITS = {"arw": "deg/sqrt(h)", "bias_instability": "deg/h", "rrw": "deg/h/sqrt(h)",
                "bias_repeatability": "deg/h"}
#: The terms of a mission budget, in the order they are reported.
BUDGET_TERMS = ("vibration", "arw", "bias_instability", "rrw", "repeatability")


@dataclass(frozen=True, eq=False, repr=False)
class Figure(Frozen):
    """A noise figure read from an Allan deviation: value and standard uncertainty in
    ``unit``; ``tau`` (s) where it was read, ``share`` of the fitted model's σ² its own
    term has there."""

    value: float
    unit: str
    uncertainty: float
    tau: float
    share: float


@dataclass(frozen=True, eq=False, repr=False)
class AxisAllan(Frozen):
    """One axis: τ (s), the overlapping Allan deviation σ(τ) in ``unit``, the figures
    N, B, K and the fitted model's (N, B, K) in the figures' units (0: a term the fit
    does not need)."""

    axis: str
    tau: FloatArray
    adev: FloatArray
    unit: str
    arw: Figure
    bias_instability: Figure
    rrw: Figure
    fitted: tuple[float, float, float]


@dataclass(frozen=True, eq=False, repr=False)
class AllanResult(Frozen):
    """Every recorded axis of a static recording: ``samples`` used (the longest
    contiguous segment, ``segments`` found), ``fs`` Hz, provenance ``file``, ``sha256``,
    and for a log the ``topic`` and ``instance`` read; ``warnings``: the reader's (the
    damage of a log, what its library printed)."""

    file: str
    sha256: str
    fs: float
    samples: int
    segments: int
    axes: tuple[AxisAllan, ...]
    topic: str | None = None
    instance: int | None = None
    warnings: tuple[str, ...] = ()

    @property
    def source(self) -> str | None:
        """``sensor_gyro instance 1``: the topic and instance read, or None."""
        if self.topic is None:
            return None
        return self.topic if self.instance is None else f"{self.topic} instance {self.instance}"


@dataclass(frozen=True, eq=False, repr=False)
class Budget(Frozen):
    """A mission's angle budget in deg for one sensor and axis (docs/model.md section 15).

    ``vibration`` θ_V (signed); ``arw`` N√T, ``bias_instability`` B·T, ``rrw``
    K·T^{3/2}/√3, ``repeatability`` R·T, each None where the catalogue does not give the
    figure (unknown, never 0); ``total`` = |θ_V| + k·RSS of the known noise terms, a
    lower bound when one is unknown (``unknown`` names them); ``coverage`` k;
    ``allowed``: with an angle budget, the largest value of each figure that meets it
    (:class:`Allowance`).
    """

    vibration: float
    arw: float | None
    bias_instability: float | None
    rrw: float | None
    repeatability: float | None
    total: float
    coverage: float
    unknown: tuple[str, ...]
    unit: str = "deg"
    allowed: Allowance | None = None

    @property
    def lower_bound(self) -> bool:
        """Whether ``total`` is only a lower bound (a noise figure is unknown)."""
        return bool(self.unknown)


@dataclass(frozen=True, eq=False, repr=False)
class Allowance(Frozen):
    """The largest value of each budget figure that still meets an angle budget θ*, the
    others as given (docs/model.md section 15 solved for one figure at a time).

    From total = |θ_V| + k·√(θ_ARW² + θ_B² + θ_RRW² + θ_R²) ≤ θ*: ``vibration`` the
    largest |θ_V| (deg); ``arw`` N (deg/√h), ``bias_instability`` B (deg/h),
    ``rrw`` K (deg/h/√h), ``repeatability`` R (deg/h). None: no value passes, and
    ``limited_by`` names, per such figure, the term that alone uses the allowance.
    ``upper``: the figures whose value is only an upper limit, because another
    noise figure is unknown (it can only take more of the allowance).
    """

    vibration: float | None
    arw: float | None
    bias_instability: float | None
    rrw: float | None
    repeatability: float | None
    limited_by: tuple[tuple[str, str], ...] = ()
    upper: tuple[str, ...] = ()

    def limit(self, term: str) -> str | None:
        """The term that alone uses the allowance where ``term`` has no passing value."""
        return dict(self.limited_by).get(term)


#: Each budget term's figure unit in an :class:`Allowance` (vibration: the angle, deg).
ALLOWANCE_UNITS = {"vibration": "deg", "arw": "deg/sqrt(h)", "bias_instability": "deg/h",
                   "rrw": "deg/h/sqrt(h)", "repeatability": "deg/h"}
