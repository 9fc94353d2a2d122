"""``bounds``: the inverse problem, allowable coefficients per profile (eq. 18-25)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import cast

import numpy as np

from gyrovib import units
from gyrovib.api.convert import bound_factors
from gyrovib.api.prepare import TINY, check_bounds, float_guard, prepare
from gyrovib.api.results import BoundsResult
from gyrovib.catalog.loader import Catalog
from gyrovib.catalog.records import Allocation
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
from gyrovib.errors import GyrovibError, OptionError


def _is_default(allocation: Allocation) -> bool:
    return (allocation.r == DEFAULT_R and tuple(allocation.w) == DEFAULT_W
            and tuple(allocation.v) == DEFAULT_V)


def resolve_allocation(
    catalog: Catalog, method: str, allocation: Allocation | Sequence[float] | None = None
) -> AllocationConstants:
    """The shares of the budget for ``method``.

    ``allocation`` (an :class:`Allocation`, or 1 number r, or 9 numbers
    r, w1..w5, v1..v3) wins over the catalogue's ``allocation:`` section; the
    paper's r = 1.5, w = (1, 1, 1, ½, ½), v = (1, ½, ½) is the default.
    ``exact`` derives the shares (eq. 20, 21, 24); ``paper`` uses the printed
    constants and therefore refuses any other allocation. Shares so unequal
    that one underflows floating point are refused.
    """
    where = "--allocation"
    source = None
    if allocation is None:
        chosen = catalog.allocation
        if catalog.allocation is not None:
            source = next((s for s in catalog.sources if s.model.allocation is not None), None)
            where = f"the 'allocation:' section of {source.name}" if source else "the catalogue"
    elif isinstance(allocation, Allocation) or hasattr(allocation, "r"):
        chosen = cast(Allocation, allocation)
    else:
        values = [float(x) for x in allocation]
        if not all(math.isfinite(x) and x > 0 for x in values):
            raise OptionError("an allocation's r, w and v must be positive and finite")
        if len(values) == 1:
            chosen = Allocation(r=values[0])
        elif len(values) == 9:
            chosen = Allocation(r=values[0], w=tuple(values[1:6]), v=tuple(values[6:9]))
        else:
            raise OptionError(
                f"an allocation is r alone or 9 numbers r,w1,...,w5,v1,v2,v3; got {len(values)}"
            )
    if chosen is None:
        chosen = Allocation()
    if method == "paper":
        if not _is_default(chosen):
            raise OptionError(
                f"--method paper uses the paper's printed shares (0.44, 0.22, 0.49, 0.24, 0.35) "
                f"and cannot honour the custom allocation given by {where}; "
                "use --method exact, or drop the allocation"
            )
        return PAPER_CONSTANTS
    try:
        constants = allocation_constants(chosen.r, chosen.w, chosen.v)
    except ValueError as exc:
        raise OptionError(f"allocation: {exc}") from None
    shares = np.concatenate([constants.alpha, constants.beta, [constants.k3]])
    if not np.all(shares >= TINY):
        message = (f"the allocation given by {where} makes a share of the budget underflow "
                   f"floating point (smallest share {float(shares.min()):.3g}); keep r, w "
                   "and v within a few hundred orders of magnitude of each other")
        if source is not None:
            raise GyrovibError(source.problem(message, ("allocation",)))
        raise OptionError(message)
    return constants


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
) -> BoundsResult:
    """The inverse problem: allowable coefficients per profile, eq. (23), (25).

    ``budget`` is Δ*_V in deg/s; ``rate`` overrides Ω_K (deg/s) as in
    :func:`~gyrovib.api.analyze`; ``unit`` is the output unit. A bound that
    overflows (is 0 or subnormal where the profile constrains it) is refused.
    """
    check_method_budget(method, budget)
    unit = units.canonical_unit(unit)
    constants = resolve_allocation(catalog, method, allocation)
    with float_guard():
        prepared = prepare(catalog, profiles=profiles, need=("profiles",), rate=rate,
                           methods=(method,), by_response=False)
        if prepared.groups:
            raw = coefficient_bounds(prepared.groups[0].multipliers[method], budget, constants)
        else:
            empty = np.zeros(0)
            raw = CoefficientBounds(**{n: empty for n in CoefficientBounds.__dataclass_fields__})
        scaled = raw.scaled(bound_factors(unit))
        check_bounds(raw.stacked(), prepared)
        check_bounds(scaled.stacked(), prepared)
    return BoundsResult(
        method=method,
        unit=unit,
        budget=budget / units.scale(unit),
        profiles=tuple(p.profile.id for p in prepared.profiles),
        rates=prepared.rates / units.scale(unit),
        bounds=scaled,
        allocation=constants,
        coefficient_unit=catalog_unit([p.unit for p in prepared.profiles]),
    )


def catalog_unit(file_units: Sequence[str]) -> str | None:
    """The rate unit the entries' files share (canonical), or None when they differ."""
    found = {units.canonical_unit(u) for u in file_units}
    return found.pop() if len(found) == 1 else None
