"""``select``: which sensors meet a budget, by the bound checks and eq. (17)."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from gyrovib import units
from gyrovib.api.commands.bounds import (
    bounds,
    catalog_unit,
    check_method_budget,
    resolve_allocation,
)
from gyrovib.api.convert import bound_factors, sensor_ranges
from gyrovib.api.prepare import Prepared, check_bounds, check_finite, float_guard, prepare
from gyrovib.api.results import Limit, SelectionResult
from gyrovib.catalog.loader import Catalog
from gyrovib.catalog.records import Allocation
from gyrovib.core.analysis import COEFFICIENTS, vibration_error
from gyrovib.core.saturation import DEFAULT_PEAK_FACTOR
from gyrovib.core.saturation import saturated as saturated_at
from gyrovib.core.synthesis import BOUNDED, coefficient_bounds
from gyrovib.core.transmissibility import FloatArray
from gyrovib.errors import OptionError

CRITERIA = ("bounds", "rms", "both")
REQUIREMENTS = ("any", "all")
#: Relative slack of every ≤ comparison: a value at its bound, up to rounding
#: (e.g. a bound printed in deg/h and read back), passes.
PASS_RTOL = 1e-9


def _at_most(value: FloatArray, bound: FloatArray | float) -> NDArray[np.bool_]:
    out: NDArray[np.bool_] = value <= np.asarray(bound) * (1.0 + PASS_RTOL)
    return out


def _ratio(value: FloatArray, bound: FloatArray) -> FloatArray:
    """value/bound: 0 for a zero value or an infinite bound, +inf for a zero bound."""
    out: FloatArray = np.zeros(np.broadcast_shapes(value.shape, bound.shape))
    v = np.broadcast_to(value, out.shape)
    b = np.broadcast_to(bound, out.shape)
    q = v / b
    return np.where(v == 0, 0.0, np.where(b == 0, np.inf, np.where(np.isinf(b), 0.0, q)))


def _limits(criterion: str, failing: NDArray[np.intp], ratios: FloatArray, rms: FloatArray,
            budget: float, saturated: NDArray[np.bool_] | None = None,
            over: FloatArray | None = None) -> dict[int, Limit]:
    """Per failing sensor, the largest value/bound ratio (or Δ_V(RMS)/Δ*) that counts.

    Saturation comes first: a sensor that saturates somewhere is limited by
    its range (``"saturated"``, ratio reach/range, the worst profile).
    """
    limits: dict[int, Limit] = {}
    for i in failing.tolist():
        if saturated is not None and over is not None and saturated[i].any():
            js = np.flatnonzero(saturated[i])
            j = int(js[np.argmax(over[i, js])])
            limits[int(i)] = Limit("saturated", j, float(over[i, j]))
            continue
        candidates: list[Limit] = []
        if criterion in ("bounds", "both"):
            jb = np.unravel_index(int(np.argmax(ratios[i])), ratios[i].shape)
            j, b = int(jb[0]), int(jb[1])
            candidates.append(Limit(BOUNDED[b], j, float(ratios[i, j, b])))
        if criterion in ("rms", "both"):
            jr = int(np.argmax(rms[i]))
            candidates.append(Limit("rms", jr, float(rms[i, jr] / budget)))
        limits[int(i)] = max(candidates, key=lambda c: c.ratio)
    return limits


def select(
    catalog: Catalog,
    *,
    sensors: Sequence[str] = (),
    profiles: Sequence[str] = (),
    method: str = "exact",
    rate: Sequence[float] | None = None,
    budget: float,
    unit: str = "deg/s",
    criterion: str = "bounds",
    require: str = "any",
    allocation: Allocation | Sequence[float] | None = None,
    peak_factor: float = DEFAULT_PEAK_FACTOR,
) -> SelectionResult:
    """Which sensors meet the budget: the bound checks and eq. (17), per profile.

    Each sensor's bounds include its input-side response ν_sensor(f), the one
    written ``at: input`` (an output filter earns no credit; computed once
    per distinct response). ``criterion``: ``bounds`` (every |coefficient| at
    most its bound), ``rms`` (Δ_V(RMS) ≤ Δ*, eq. 17) or ``both``. A sensor
    passes when it passes under every chosen profile; ``require`` ``any``
    (at least one sensor passes) or ``all`` decides :attr:`requirement_met`.
    ``budget`` and ``rate`` are in deg/s; ``unit`` is the output unit.

    A sensor that saturates under a profile (MODEL.md section 9: |Ω_K3| +
    Σ tone amplitudes + locked peaks + κσ3 at its nonlinear element above its
    range, κ = ``peak_factor``) fails there whatever the criterion: the
    static model behind both tests does not hold (:attr:`SelectionResult.reasons`).
    """
    check_method_budget(method, budget)
    if criterion not in CRITERIA:
        raise OptionError(f"unknown criterion {criterion!r}; use one of {', '.join(CRITERIA)}")
    if require not in REQUIREMENTS:
        raise OptionError(f"unknown requirement {require!r}; use one of {', '.join(REQUIREMENTS)}")
    unit = units.canonical_unit(unit)
    constants = resolve_allocation(catalog, method, allocation)
    alone = bounds(catalog, profiles=profiles, method=method, rate=rate, budget=budget,
                   unit=unit, allocation=allocation)
    with float_guard():
        prepared = prepare(catalog, sensors=sensors, profiles=profiles, rate=rate,
                           methods=(method,), peak_factor=peak_factor)
        coeffs = prepared.coefficients
        n_s, n_p, n_b = len(prepared.sensors), len(prepared.profiles), len(BOUNDED)
        limits_deg = np.full((n_s, n_p, n_b), np.inf)
        rms = np.zeros((n_s, n_p))
        reach = np.zeros((n_s, n_p))
        for group in prepared.groups:
            multipliers = group.multipliers[method]
            limits_deg[group.index] = coefficient_bounds(multipliers, budget,
                                                         constants).stacked()[None]
            rms[group.index] = vibration_error(coeffs[group.index], multipliers).rms
            reach[group.index] = group.reach(prepared.rates[:, 2])[None]
        ranges = sensor_ranges(prepared.sensors)
        saturated = saturated_at(reach, ranges)
        check_finite([rms], prepared)
        check_bounds(limits_deg, prepared)
        factors = np.array([bound_factors(unit)[c] for c in BOUNDED])
        values_deg = np.abs(coeffs[:, [COEFFICIENTS.index(c) for c in BOUNDED]])[:, None, :]
        values_deg = np.broadcast_to(values_deg, (n_s, n_p, n_b))
        values, limits_out = values_deg * factors, limits_deg * factors
        check_finite([values], prepared, what=f"a coefficient in {unit}")
        check_bounds(limits_out, prepared)
        check_pass = _at_most(values_deg, limits_deg)
        bounds_pass = np.all(check_pass, axis=-1)
        rms_pass = _at_most(rms, budget)
        passed = {"bounds": bounds_pass, "rms": rms_pass,
                  "both": bounds_pass & rms_pass}[criterion] & ~saturated
        sensor_pass = np.all(passed, axis=1)
        margin = np.where(rms > 0, budget / np.where(rms > 0, rms, 1.0), np.inf)
        worst = margin.min(axis=1) if n_p else np.full(n_s, np.inf)
        ranking = tuple(int(i) for i in sorted(range(n_s), key=lambda i: (-worst[i], i)))
        limits = _limits(criterion, np.nonzero(~sensor_pass)[0],
                         _ratio(values_deg, limits_deg), rms, budget, saturated,
                         reach / ranges[:, None])
        reasons = _reasons(prepared, saturated, reach, ranges, peak_factor, unit)
    met = bool(np.any(sensor_pass)) if require == "any" else bool(np.all(sensor_pass))
    s = units.scale(unit)
    return SelectionResult(
        method=method,
        unit=unit,
        budget=budget / s,
        criterion=criterion,
        require=require,
        sensors=tuple(e.sensor.id for e in prepared.sensors),
        profiles=tuple(p.profile.id for p in prepared.profiles),
        rates=prepared.rates / s,
        profile_bounds=alone.bounds,
        values=values,
        bounds=limits_out,
        check_pass=check_pass,
        rms=rms / s,
        margin=margin,
        bounds_pass=bounds_pass,
        rms_pass=rms_pass,
        passed=passed,
        sensor_pass=sensor_pass,
        worst_margin=worst,
        ranking=ranking,
        limits=limits,
        requirement_met=met,
        allocation=constants,
        saturated=saturated,
        reasons=reasons,
        peak_factor=peak_factor,
        coefficient_unit=catalog_unit([e.unit for e in prepared.sensors])
        or alone.coefficient_unit,
    )


def reason(result: SelectionResult, i: int, j: int) -> str | None:
    """Why sensor ``i`` fails under profile ``j``, one line in :attr:`~SelectionResult.unit`
    (the JSON's and the frame's ``reason``); None where it passes.

    Saturation first, then the criteria that count (``criterion``).
    """
    if result.passed[i, j]:
        return None
    why: list[str] = []
    if (i, j) in result.reasons:
        why.append(result.reasons[(i, j)])
    if result.criterion in ("bounds", "both"):
        why.extend(f"|{name}| = {result.values[i, j, b]:.6g} exceeds its bound "
                   f"{result.bounds[i, j, b]:.6g}"
                   for b, name in enumerate(BOUNDED) if not result.check_pass[i, j, b])
    if result.criterion in ("rms", "both") and not result.rms_pass[i, j]:
        why.append(f"Δ_V(RMS) = {result.rms[i, j]:.6g} {result.unit} exceeds the budget "
                   f"{result.budget:.6g} {result.unit}")
    return "; ".join(why) if why else "fails the criterion"


def _reasons(prepared: Prepared, saturated: NDArray[np.bool_], reach: FloatArray,
             ranges: FloatArray, peak_factor: float, unit: str) -> dict[tuple[int, int], str]:
    """Per saturating (sensor, profile): why it fails, one line in ``unit``."""
    s = units.scale(unit)
    return {
        (i, j): (f"saturated: |Ω_K3| + Σ tone amplitudes + locked peaks + {peak_factor:g}σ3 = "
                 f"{reach[i, j] / s:.6g} {unit} exceeds the range {ranges[i] / s:.6g} {unit}")
        for i, j in (tuple(int(v) for v in ij) for ij in np.argwhere(saturated))}
