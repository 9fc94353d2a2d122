"""What ``gyrovib runup`` gives (docs/model.md section 16): immutable results.

Rates are in deg/s, accelerations in g, times in s from the recording's first sample;
each estimate carries its own unit. An unknown figure is NaN here (null in JSON, empty
in CSV, '?' in tables), never 0.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from gyrovib.api.recordings.results import source_words
from gyrovib.frozen import Frozen
from gyrovib.records import Column, known

#: Statuses of a step against the catalogue sensor's prediction.
WITHIN, OUTSIDE, UNVERIFIED = "within", "outside", "unverified"


@dataclass(frozen=True, eq=False, repr=False)
class Step(Frozen):
    """One step of constant vibration.

    ``start``/``end`` (s), ``mean`` ȳ_s and ``variance`` of that mean ((deg/s)²);
    ``x3_rms`` (deg/s) and ``accel_rms`` (g, Σ over the axes; NaN when not recorded):
    the vibration level; ``regressors``: φ_s of the estimated terms; ``shift`` the mean
    less the baseline's (and less the drift when it is estimated) with its standard
    ``uncertainty``; ``fitted`` the fit's shift; ``residual`` ȳ_s − ŷ_s; ``predicted``
    the catalogue sensor's shift (NaN: no sensor, or unknown); ``bound``: the prediction
    is a datasheet's worst case (a magnitude); ``status`` against it (None: no sensor);
    ``outlier``: residual beyond 3σ; ``moved``: the carrier shows the vehicle moving.
    """

    index: int
    start: float
    end: float
    baseline: bool
    mean: float
    variance: float
    x3_rms: float
    accel_rms: float
    regressors: tuple[tuple[str, float], ...]
    shift: float
    uncertainty: float
    fitted: float
    residual: float
    predicted: float
    bound: bool
    status: str | None
    outlier: bool
    moved: bool

    @property
    def duration(self) -> float:
        """T_s, s."""
        return self.end - self.start

    @property
    def sigma(self) -> float:
        """The standard deviation of the step's mean (deg/s)."""
        return math.sqrt(self.variance)


@dataclass(frozen=True, eq=False, repr=False)
class Estimate(Frozen):
    """An in-situ coefficient: ``value`` ± ``uncertainty`` (standard, inflated by the
    reduced χ² when it exceeds 1) in ``unit``; ``identifiable`` from these steps;
    ``status`` ``found`` (|value| ≥ 2u), ``not significant`` or ``not identifiable``;
    ``separate``: what step would separate it (None when nothing is missing);
    ``catalogue``: the sensor's own figure in ``unit`` (NaN: none, or unknown), a bound
    on |value| where ``catalogue_bound``; ``vif``: its variance inflation factor."""

    name: str
    value: float
    uncertainty: float
    unit: str
    identifiable: bool
    status: str
    separate: str | None
    catalogue: float
    catalogue_bound: bool
    vif: float

    @property
    def ratio(self) -> float:
        """In-situ over catalogue (NaN where either is unknown or the catalogue's is 0)."""
        if not (math.isfinite(self.catalogue) and self.catalogue != 0
                and math.isfinite(self.value)):
            return math.nan
        return self.value / self.catalogue


@dataclass(frozen=True, eq=False, repr=False)
class RunupResult(Frozen):
    """A run-up test (docs/model.md section 16).

    ``drift`` d (deg/s per s) ± ``drift_uncertainty``, NaN when the steps' order does
    not separate it (``drift_vif`` says how far it is from being separable); ``chi2``
    and ``dof`` of the weighted fit, ``inflation`` the factor on the covariance;
    ``correlation`` of the estimates (row per estimate); ``constant`` c (deg/s);
    ``sensor``: the catalogue sensor compared (None); ``steps_given``: the steps came
    from the user, not from the recording; ``limits``: what the test cannot see
    (always said); ``notes``: what the reader should know of this result; ``warnings``:
    the reader's about the file (a log cut short, clipped samples); ``topic`` and
    ``instance``: the log's topic or message read, and which instance (None otherwise).
    """

    file: str
    sha256: str
    fs: float
    samples: int
    crossover: float
    steps: tuple[Step, ...]
    estimates: tuple[Estimate, ...]
    constant: float
    drift: float
    drift_uncertainty: float
    drift_vif: float
    chi2: float
    dof: int
    inflation: float
    correlation: tuple[tuple[float, ...], ...]
    sensor: str | None
    steps_given: bool
    limits: tuple[str, ...]
    notes: tuple[str, ...]
    warnings: tuple[str, ...] = ()
    topic: str | None = None
    instance: int | None = None

    @property
    def source(self) -> str | None:
        """The log's topic and instance read, in words (``sensor_combined``), or None."""
        return source_words(self.topic, self.instance)

    @property
    def requirement_met(self) -> bool:
        """No step's measured shift lies outside its prediction's interval."""
        return not any(s.status == OUTSIDE for s in self.steps)

    @property
    def reduced_chi2(self) -> float:
        """χ²/dof (NaN with no degree of freedom)."""
        return self.chi2 / self.dof if self.dof > 0 else math.nan


__all__ = ["OUTSIDE", "UNVERIFIED", "WITHIN", "Estimate", "RunupResult", "Step"]


def _number(name: str, unit: str | None) -> Column[Any]:
    """A figure of a row, NaN (unknown) written as an empty CSV cell."""
    return Column(name, unit, lambda row: getattr(row, name), cell=known)


#: What only the JSON's steps have.
_JSON_ONLY = ("csv", "frame")

#: The records of the steps, declared once: one row per step, the CSV's columns and the
#: JSON's ``steps`` (its keys in order; there the step is its ``index``, the shift's
#: mean and regressors, whether the prediction is a bound and the residual in σ).
STEP_RECORDS: tuple[Column[Step], ...] = (
    Column("kind", None, lambda s: "step", skip=("json",)),
    Column("step", None, lambda s: s.index, key="index"),
    Column("start", "s", lambda s: s.start),
    Column("end", "s", lambda s: s.end),
    Column("duration", "s", lambda s: s.duration),
    Column("baseline", None, lambda s: s.baseline),
    Column("mean", "deg/s", lambda s: s.mean, skip=_JSON_ONLY),
    _number("x3_rms", "deg/s"), _number("accel_rms", "g"), _number("shift", "deg/s"),
    _number("uncertainty", "deg/s"),
    Column("regressors", None, lambda s: {k: known(v) for k, v in s.regressors},
           skip=_JSON_ONLY),
    _number("fitted", "deg/s"), _number("predicted", "deg/s"),
    Column("predicted_bound", None, lambda s: s.bound, skip=_JSON_ONLY),
    _number("residual", "deg/s"),
    Column("residual_sigma", None, lambda s: s.residual / s.sigma if s.sigma > 0 else None,
           skip=_JSON_ONLY),
    Column("status", None, lambda s: s.status),
    Column("outlier", None, lambda s: s.outlier),
    Column("moved", None, lambda s: s.moved),
)

#: The CSV's records of the estimates, declared once: one row per estimate (each in the
#: unit of its ``unit`` column).
ESTIMATE_RECORDS: tuple[Column[Estimate], ...] = (
    Column("kind", None, lambda e: "estimate"),
    Column("name", None, lambda e: e.name),
    _number("value", None), _number("uncertainty", None),
    Column("unit", None, lambda e: e.unit),
    Column("identifiable", None, lambda e: e.identifiable),
    Column("status", None, lambda e: e.status),
    _number("catalogue", None),
    Column("catalogue_bound", None, lambda e: e.catalogue_bound),
    _number("ratio", None),
    Column("separate", None, lambda e: e.separate),
)
