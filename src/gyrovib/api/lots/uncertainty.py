"""The distribution of a sensor's coefficients, and the uncertainty of its vibration error.

docs/model.md section 14. A sensor with ``uncertainty`` (beside ``coefficients``)
or a ``lot`` has coefficients c ~ (μ, Σ): μ its coefficients (a lot: their
mean), Σ = diag(σ)·R·diag(σ) from its sigma and correlation pairs, in deg/s
powers (each σ converts as its coefficient). A lot of n units with n ≤ p (p
coefficients with a sigma) uses the diagonal only, with a warning
(:func:`gyrovib.core.lot.lot_covariance`).

Δ_V is linear in every coefficient but k1 (eq. 13–15): Δ_V = gᵀc with
g_i = Δ_V(e_i) (:func:`gyrovib.core.lot.sensitivity`, the engine itself on
the unit vectors, at k1 = 1; the asymmetry term is k1·A1·g_A, so the A1
entry is scaled by the sensor's own k1). Hence u(Δ_V) = √(gᵀΣg) (k = 1),
exactly (:func:`gyrovib.core.lot.dispersion`).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from gyrovib import units
from gyrovib.api.study.convert import unit_scales
from gyrovib.api.study.prepare import Group, Prepared
from gyrovib.catalog.loader import SensorEntry
from gyrovib.core._types import FloatArray
from gyrovib.core.analysis import COEFFICIENTS, Multipliers
from gyrovib.core.lot import (
    correlation_from_pairs,
    covariance_from,
    dispersion,
    lot_covariance,
    sensitivity,
    spread_problem,
    unmeasured_warning,
)
from gyrovib.frozen import Frozen


@dataclass(frozen=True, eq=False, repr=False)
class Distribution(Frozen):
    """A sensor's coefficients as a distribution, in deg/s powers.

    ``names``: the coefficients with a sigma (docs/model.md section 14 order);
    ``mean``: μ at those names; ``covariance``: Σ (p, p), the diagonal only for
    a lot with ``units`` ≤ p (then ``warning`` says so); ``units``: the lot's
    n, None for one unit's ``uncertainty``; ``k1``: the sensor's scale factor
    (1 in eq. 2); ``unmeasured``: why a yield from this lot is not a measurement
    (:func:`gyrovib.core.lot.spread_problem`: n ≤ p, a σ of 0, a singular
    correlation matrix; ``warning`` then says so too), None when it is one.
    """

    names: tuple[str, ...]
    mean: FloatArray
    covariance: FloatArray
    units: int | None
    warning: str | None
    k1: float
    unmeasured: str | None = None

    @property
    def is_lot(self) -> bool:
        """Whether this is a production lot (a part drawn from it), not one unit."""
        return self.units is not None


def distribution(entry: SensorEntry, row: FloatArray) -> Distribution | None:
    """The distribution of ``entry``'s coefficients, or None without uncertainty or lot.

    ``row``: the sensor's coefficients in deg/s powers (order of
    :data:`~gyrovib.core.analysis.COEFFICIENTS`; a lot's mean).
    """
    sensor = entry.sensor
    spread = sensor.lot if sensor.lot is not None else sensor.uncertainty
    if spread is None:
        return None
    sigma = spread.sigma.named()
    names = tuple(sigma)
    scale = float(unit_scales([entry])[0])
    factors = np.array([scale ** units.COEFFICIENT_RATE_POWER[n] for n in names])
    s = np.array([sigma[n] for n in names], dtype=float) * factors
    r = correlation_from_pairs(names, dict(spread.correlation))
    mean = np.array([row[COEFFICIENTS.index(n)] for n in names], dtype=float)
    k1 = float(row[COEFFICIENTS.index("k1")])
    if sensor.lot is not None:
        units_ = sensor.lot.units
        cov, warning = lot_covariance(s, r, units_)
        unmeasured = spread_problem(mean, s, r, units_, names, p=len(names))
        if unmeasured is not None:
            warning = unmeasured_warning(sensor.id, unmeasured)
        elif warning is not None:
            warning = f"lot {sensor.id!r}: {warning}"
        return Distribution(names, mean, cov, units_, warning, k1, unmeasured)
    return Distribution(names, mean, covariance_from(s, r), None, None, k1)


def distributions(prepared: Prepared) -> tuple[Distribution | None, ...]:
    """:func:`distribution` of every prepared sensor."""
    return tuple(distribution(e, prepared.coefficients[i])
                 for i, e in enumerate(prepared.sensors))


def lot_warnings(found: Sequence[Distribution | None]) -> tuple[str, ...]:
    """The warnings of lots too small for their correlations, once each."""
    return tuple(d.warning for d in found if d is not None and d.warning is not None)


def group_multipliers(prepared: Prepared, group: Group, method: str) -> Multipliers:
    """The group's multipliers under ``method``, or the exact ones where ``method`` has
    none (the numeric method: its g is the closed form's; its view hands in a
    preparation with the exact multipliers)."""
    if method in group.multipliers:
        return group.multipliers[method]
    return group.multipliers["exact"]


def sensor_sensitivity(multipliers: Multipliers, dist: Distribution) -> FloatArray:
    """g with Δ_V = gᵀc over ``dist.names`` (docs/model.md section 14), deg/s per coefficient
    unit, shape ``multipliers.omega.shape + (p,)``; the A1 entry at the sensor's k1."""
    return at_k1(sensitivity(multipliers, dist.names), dist)


def at_k1(g: FloatArray, dist: Distribution) -> FloatArray:
    """``g`` (..., p) over ``dist.names`` with its A1 entry times the sensor's k1."""
    if "A1" not in dist.names:
        return g
    g = g.copy()
    g[..., dist.names.index("A1")] *= dist.k1
    return g


def has_worst_phases(group: Group, j: int) -> bool:
    """Whether profile ``j`` has orders written ``phase: worst`` (docs/model.md section 10)."""
    return any(g.worst.any() for g in group.locked[j])


def uncertainty(prepared: Prepared, method: str,
                found: Sequence[Distribution | None] | None = None) -> FloatArray | None:
    """u(Δ_V) = √(gᵀΣg) (k = 1) of every sensor × profile in deg/s; NaN for a sensor
    without uncertainty or lot, and where a profile's phases are searched (``phase:
    worst``: Δ_V there is a maximum over phases, not one linear form). None when no
    chosen sensor has a distribution."""
    found = distributions(prepared) if found is None else found
    if all(d is None for d in found):
        return None
    out = np.full((len(prepared.sensors), len(prepared.profiles)), np.nan)
    for group in prepared.groups:
        members = [int(i) for i in group.index if found[int(i)] is not None]
        if not members:
            continue
        multipliers = group_multipliers(prepared, group, method)
        searched = [has_worst_phases(group, j) for j in range(len(prepared.profiles))]
        for i in members:
            dist = found[i]
            assert dist is not None
            u = dispersion(sensor_sensitivity(multipliers, dist), dist.covariance)
            out[i] = np.where(searched, np.nan, u)
    return out


def with_uncertainty(prepared: Prepared, method: str, unit: str) -> dict[str, Any]:
    """The fields of :class:`~gyrovib.api.evaluation.results.AnalysisResult` about distributions:
    ``uncertainty`` in ``unit`` (:func:`uncertainty`), ``lots``, ``notes`` (the warnings
    of lots too small for their correlations)."""
    found = distributions(prepared)
    if all(d is None for d in found):
        return {}
    u = uncertainty(prepared, method, found)
    assert u is not None
    return {"uncertainty": u / units.scale(unit),
            "lots": tuple(d is not None and d.is_lot for d in found),
            "notes": lot_warnings(found)}
