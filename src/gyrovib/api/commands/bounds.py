"""``bounds``: the inverse problem, allowable coefficients per profile (eq. 18-25)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import cast

import numpy as np

from gyrovib import units
from gyrovib.api.datasheet.spec_bounds import datasheet_bounds
from gyrovib.api.evaluation.results import BoundsResult
from gyrovib.api.evaluation.unknown import unknown_bounds
from gyrovib.api.study.convert import bound_factors, catalog_unit
from gyrovib.api.study.prepare import (
    TINY,
    Prepared,
    check_bounds,
    float_guard,
    overflow_problem,
)
from gyrovib.api.study.study import Study
from gyrovib.catalog.loader import Catalog, CatalogSource
from gyrovib.core._types import FloatArray
from gyrovib.core.analysis import METHODS
from gyrovib.core.synthesis import (
    DEFAULT_R,
    DEFAULT_V,
    DEFAULT_W,
    PAPER_CONSTANTS,
    AllocationConstants,
    CoefficientBounds,
    allocation_constants,
    coefficient_bounds,
)
from gyrovib.errors import GyrovibError, OptionError, RangeError, literal
from gyrovib.models import Allocation


def _is_default(allocation: Allocation) -> bool:
    return (allocation.r == DEFAULT_R and tuple(allocation.w) == DEFAULT_W
            and tuple(allocation.v) == DEFAULT_V)


def resolve_allocation(
    catalog: Catalog, method: str, allocation: Allocation | Sequence[float] | None = None
) -> AllocationConstants:
    """The shares of the budget for ``method``.

    ``allocation`` (an :class:`Allocation`, or 1 number r, or 9 numbers
    r, w1..w5, v1..v3, or 10 numbers r, w1..w6, v1..v3 with w6 the weight of
    the g² term of profiles with linear vibration, docs/model.md section 8) wins
    over the catalogue's ``allocation:`` section; the
    paper's r = 1.5, w = (1, 1, 1, ½, ½), v = (1, ½, ½) is the default.
    ``exact`` derives the shares (eq. 20, 21, 24); ``paper`` uses the printed
    constants and therefore refuses any other allocation. Shares so unequal
    that one underflows floating point are refused.
    """
    chosen, where, source = _chosen(catalog, allocation)
    if method == "paper":
        if not _is_default(chosen):
            raise OptionError(reason=(
                "{method} paper uses the paper's printed shares (0.44, 0.22, 0.49, 0.24, "
                f"0.35) and cannot honour the custom allocation given by {literal(where)}; "
                "use {method} exact, or drop the allocation"), others=("method", "allocation"))
        return PAPER_CONSTANTS
    try:
        constants = allocation_constants(chosen.r, chosen.w, chosen.v)
    except ValueError as exc:
        raise OptionError(f"allocation: {exc}") from None
    _check_shares(constants, where, source)
    return constants


def _chosen(catalog: Catalog, allocation: Allocation | Sequence[float] | None,
            ) -> tuple[Allocation, str, CatalogSource | None]:
    """The allocation that applies, where it was given (for messages), and the
    catalogue file that gave it (None: the option, or the default)."""
    if allocation is None:
        if catalog.allocation is None:
            return Allocation(), "{allocation}", None
        source = next((s for s in catalog.sources if s.model.allocation is not None), None)
        where = f"the 'allocation:' section of {source.name}" if source else "the catalogue"
        return catalog.allocation, where, source
    if isinstance(allocation, Allocation) or hasattr(allocation, "r"):
        return cast(Allocation, allocation), "{allocation}", None
    return _from_numbers([float(x) for x in allocation]), "{allocation}", None


def _from_numbers(values: list[float]) -> Allocation:
    """r alone, or r, w1..w5[, w6], v1..v3."""
    if not all(math.isfinite(x) and x > 0 for x in values):
        raise OptionError("an allocation's r, w and v must be positive and finite")
    if len(values) == 1:
        return Allocation(r=values[0])
    if len(values) in (9, 10):
        n_w = len(values) - 4
        return Allocation(r=values[0], w=tuple(values[1:1 + n_w]), v=tuple(values[1 + n_w:]))
    raise OptionError(
        "an allocation is r alone, 9 numbers r,w1,...,w5,v1,v2,v3 or 10 numbers "
        f"r,w1,...,w6,v1,v2,v3 (w6: the g² term); got {len(values)}"
    )


def _check_shares(constants: AllocationConstants, where: str,
                  source: CatalogSource | None) -> None:
    """Refuse shares so unequal that one underflows floating point."""
    shares = np.concatenate([constants.alpha, constants.beta, [constants.k3],
                             constants.extra_weights[:1] * constants.c_additive
                             / math.hypot(float(np.linalg.norm(constants.weights)),
                                          float(constants.extra_weights[0]))])
    if not np.all(shares >= TINY):
        message = (f"the allocation given by {where} makes a share of the budget underflow "
                   f"floating point (smallest share {float(shares.min()):.3g}); keep r, w "
                   "and v within a few hundred orders of magnitude of each other")
        if source is not None:
            raise GyrovibError(source.problem(message, ("allocation",)))
        raise OptionError(reason=message, others=("allocation",))


def check_vre_bound(vre: FloatArray | None, prepared: Prepared) -> None:
    """Refuse a VRE bound (docs/model.md section 8) that left floating-point range.

    Like :func:`~gyrovib.api.study.prepare.check_bounds`: +inf (no linear
    vibration) or a positive normal number; anything else comes from an
    overflowed ⟨a_j²⟩ or an underflowed share.
    """
    if vre is None:
        return
    v = np.asarray(vre, dtype=float).reshape(-1, len(prepared.profiles))
    ok = np.isposinf(v) | (np.isfinite(v) & (v >= TINY))
    bad = np.nonzero(~np.all(ok, axis=0))[0].tolist()
    if bad:
        raise RangeError([overflow_problem(prepared.profiles[j], "the VRE bound",
                                           rate_given=prepared.rate_given) for j in bad])


def check_method_budget(method: str, budget: float) -> None:
    """Refuse an unknown closed-form method or a budget that is not positive and finite."""
    if method not in METHODS:
        raise OptionError(f"unknown method {method!r}; use one of {', '.join(METHODS)}")
    if not (math.isfinite(budget) and budget > 0):
        raise OptionError(f"the budget must be positive and finite, not {budget!r}")


def bounds(
    catalog: Catalog,
    *,
    profiles: Sequence[str] = (),
    method: str = "exact",
    rate: Sequence[float] | None = None,
    budget: float,
    unit: str = "deg/s",
    allocation: Allocation | Sequence[float] | None = None,
    range_: float | None = None,
    nl_fit: str = "least-squares",
    nl_measure: str = "max",
    nl_of: str = "range",
    spec_weights: tuple[float, float] = (1.0, 1.0),
) -> BoundsResult:
    """The inverse problem: allowable coefficients per profile, eq. (23), (25).

    ``budget`` is Δ*_V in deg/s; ``rate`` overrides Ω_K (deg/s) as in
    :func:`~gyrovib.api.analyze`; ``unit`` is the output unit. A bound that
    overflows (is 0 or subnormal where the profile constrains it) is refused.
    With linear vibration in some profile, ``bounds.vre`` bounds the effective
    VRE |Δ0(6)|/Σ⟨a_j²⟩ in ``unit`` per g² (+inf for the profiles without;
    None when no profile has any), docs/model.md section 8.

    ``range_`` R (deg/s) adds the datasheet bounds (docs/model.md section 11): the
    allowable nonlinearity in %FS of R (or of the span 2R, ``nl_of``) read as
    ``nl_fit``/``nl_measure``, and the allowable VRE, from the split
    ``spec_weights`` (NL:VRE) of Δ* (:attr:`BoundsResult.spec_bounds`).
    """
    check_method_budget(method, budget)
    resolve_allocation(catalog, method, allocation)  # its refusal before the entries'
    study = Study.of(catalog, profiles=profiles, need=("profiles",), rate=rate)
    return bounds_of(study, method=method, budget=budget, unit=unit, allocation=allocation,
                     range_=range_, nl_fit=nl_fit, nl_measure=nl_measure, nl_of=nl_of,
                     spec_weights=spec_weights)


def bounds_of(study: Study, *, method: str = "exact", budget: float, unit: str = "deg/s",
              allocation: Allocation | Sequence[float] | None = None,
              range_: float | None = None, nl_fit: str = "least-squares",
              nl_measure: str = "max", nl_of: str = "range",
              spec_weights: tuple[float, float] = (1.0, 1.0)) -> BoundsResult:
    """:func:`bounds` as a view of a :class:`~gyrovib.api.study.study.Study` (its profiles
    alone)."""
    check_method_budget(method, budget)
    unit = units.canonical_unit(unit)
    constants = resolve_allocation(study.catalog, method, allocation)
    with float_guard():
        prepared, _, scaled = profile_bounds(study, method, budget, constants, unit)
        datasheet = None
        if range_ is not None:
            multipliers = prepared.groups[0].multipliers[method] if prepared.groups else None
            datasheet = datasheet_bounds(multipliers, len(prepared.profiles), budget, range_,
                                         unit, nl_fit, nl_measure, nl_of, spec_weights)
    return BoundsResult(
        method=method,
        unit=unit,
        budget=budget / units.scale(unit),
        profiles=tuple(p.profile.id for p in prepared.profiles),
        rates=prepared.rates / units.scale(unit),
        bounds=unknown_bounds(prepared.profiles, scaled),
        allocation=constants,
        spec_bounds=datasheet,
        coefficient_unit=catalog_unit([p.unit for p in prepared.profiles]),
    )


def profile_bounds(study: Study, method: str, budget: float, constants: AllocationConstants,
                   unit: str) -> tuple[Prepared, CoefficientBounds, CoefficientBounds]:
    """Eq. (23), (25) for the profiles alone (ν_sensor ≡ 1): deg/s and ``unit``, checked."""
    prepared = study.prepare(methods=(method,), by_response=False)
    if prepared.groups:
        raw = coefficient_bounds(prepared.groups[0].multipliers[method], budget, constants)
    else:
        empty = np.zeros(0)
        raw = CoefficientBounds(**{n: empty for n in CoefficientBounds.__dataclass_fields__})
    scaled = raw.scaled(bound_factors(unit))
    check_bounds(raw.stacked(), prepared)
    check_bounds(scaled.stacked(), prepared)
    check_vre_bound(raw.vre, prepared)
    check_vre_bound(scaled.vre, prepared)
    return prepared, raw, scaled
