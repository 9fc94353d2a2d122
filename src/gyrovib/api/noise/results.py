"""What ``gyrovib allan`` and the mission budget give (docs/model.md section 15):
immutable results."""

from __future__ import annotations

from dataclasses import dataclass

from gyrovib.api.missions.results import ALLOWANCE_UNITS as ALLOWANCE_UNITS
from gyrovib.api.missions.results import Allowance as Allowance
from gyrovib.api.missions.results import Budget as Budget
from gyrovib.api.recordings.results import source_words
from gyrovib.core._types import FloatArray
from gyrovib.frozen import Frozen

#: The reported unit of each noise figure (its default in the catalogue).
FIGURE_UNITS = {"arw": "deg/sqrt(h)", "bias_instability": "deg/h", "rrw": "deg/h/sqrt(h)",
                "bias_repeatability": "deg/h", "quantization": "deg", "rate_ramp": "deg/h^2"}
#: The five terms of IEEE Std 952's model, as ``gyrovib allan`` reports them.
NOISE_TERMS = ("quantization", "arw", "bias_instability", "rrw", "rate_ramp")


@dataclass(frozen=True, eq=False, repr=False)
class Figure(Frozen):
    """One term of the noise model in ``unit``: a ``value`` with its ``interval`` at
    ``confidence``, or — where the record does not resolve the term — only an upper
    ``bound`` at ``confidence`` (``value`` and ``interval`` None). ``interval95`` is the
    value's 95 % interval (None for a bound)."""

    unit: str
    confidence: float
    value: float | None = None
    interval: tuple[float, float] | None = None
    interval95: tuple[float, float] | None = None
    bound: float | None = None

    @property
    def is_bound(self) -> bool:
        """Whether the figure is only an upper bound."""
        return self.value is None

    @property
    def upper(self) -> float:
        """The figure's value, or its bound."""
        out = self.value if self.value is not None else self.bound
        assert out is not None
        return out


@dataclass(frozen=True, eq=False, repr=False)
class GaussMarkov(Frozen):
    """A first-order Gauss–Markov term: ``sigma`` (in ``unit``: deg/h, or m/s² for an
    accelerometer) and correlation time ``tau_c`` (s); ``interval``: σ's at the result's
    confidence (None: unresolved)."""

    sigma: float
    tau_c: float
    interval: tuple[float, float] | None
    unit: str = "deg/h"


@dataclass(frozen=True, eq=False, repr=False)
class AxisAllan(Frozen):
    """One axis: τ (s), the overlapping Allan deviation σ(τ) in ``unit`` and its
    confidence limits ``ci_lo``, ``ci_hi`` (at the result's confidence, from each
    point's EDF ``edf``), the five terms of :data:`NOISE_TERMS` (each a :class:`Figure`),
    the Gauss–Markov term (None when the curve shows none), the fitted model's σ(τ) in
    ``unit``, the τ where the curve leaves the model's 99 % band (``misfit``), and the
    least τ fitted (``fitted_from``: above τ0 when a filter's roll-off is left out)."""

    axis: str
    tau: FloatArray
    adev: FloatArray
    unit: str
    ci_lo: FloatArray
    ci_hi: FloatArray
    edf: FloatArray
    figures: dict[str, Figure]
    gauss_markov: GaussMarkov | None
    model: FloatArray
    misfit: tuple[float, ...]
    fitted_from: float = 0.0

    @property
    def arw(self) -> Figure:
        """N (deg/√h)."""
        return self.figures["arw"]

    @property
    def bias_instability(self) -> Figure:
        """B (deg/h)."""
        return self.figures["bias_instability"]

    @property
    def rrw(self) -> Figure:
        """K (deg/h/√h)."""
        return self.figures["rrw"]


@dataclass(frozen=True, eq=False, repr=False)
class AllanResult(Frozen):
    """Every recorded axis of a static recording: ``samples`` used (the longest
    contiguous segment, ``segments`` found), ``fs`` Hz, provenance ``file``, ``sha256``,
    the ``confidence`` of the intervals, for a log the ``topic`` and ``instance`` read;
    ``warnings``: the reader's (the damage of a log, what its library printed), then the
    fit's (a model that does not fit, a filter's roll-off); and ``accel``: the
    accelerometer's axes where the record has specific force (in m/s²; ``arw`` is then
    its velocity random walk, ``rrw`` the random walk of its bias)."""

    file: str
    sha256: str
    fs: float
    samples: int
    segments: int
    axes: tuple[AxisAllan, ...]
    topic: str | None = None
    instance: int | None = None
    warnings: tuple[str, ...] = ()
    confidence: float = 0.68
    accel: tuple[AxisAllan, ...] = ()

    @property
    def source(self) -> str | None:
        """``sensor_gyro instance 1``: the topic and instance read, or None."""
        return source_words(self.topic, self.instance)
