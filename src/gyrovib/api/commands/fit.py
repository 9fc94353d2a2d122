"""``gyrovib fit``: rate-table points to eq. (2) coefficients, per unit and per lot.

docs/model.md section 14: one least-squares fit of eq. (1) per unit
(:func:`gyrovib.core.fit.fit_rate_table`), eq. (2) by division by K1 with the
delta-method covariance; with two or more units the lot's mean and sample
covariance (:func:`gyrovib.core.lot.lot_statistics`).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from gyrovib.api.ratetable.reading import MAX_PROBLEMS, RateTable, read_rate_table
from gyrovib.api.ratetable.results import FitResult, lot_name
from gyrovib.core.fit import DEFAULT_ORDER, MAX_ORDER, IdentificationError, RateFit, fit_rate_table
from gyrovib.core.lot import LotStatistics, lot_statistics, unmeasured_warning
from gyrovib.errors import OptionError, Problem


def fit(table: RateTable | str | Path, order: int = DEFAULT_ORDER, *, rate_unit: str = "deg/s",
        output_unit: str | None = None) -> FitResult:
    """Fit every unit of ``table`` (a :class:`~gyrovib.api.ratetable.RateTable`, or the
    path of a rate-table CSV read in ``rate_unit`` and ``output_unit``).

    Raises :class:`~gyrovib.core.fit.IdentificationError` naming each unit whose
    points cannot identify eq. (1) at ``order`` and what they lack, placed at the
    unit's first line; :class:`~gyrovib.api.ratetable.RateTableError` for a file
    that cannot be read. A lot whose yield would not be a measurement (too few
    units, no spread: :func:`gyrovib.core.lot.spread_problem`) is fitted with a
    warning that names it and says why.
    """
    if isinstance(order, bool) or not isinstance(order, int | np.integer) or not (
            1 <= order <= MAX_ORDER):
        raise OptionError(argument="order", value=repr(order),
                          reason=f"eq. (1) has orders 1 to {MAX_ORDER}")
    if not isinstance(table, RateTable):
        table = read_rate_table(table, rate_unit, output_unit)
    fits = _fit_units(table, int(order))
    names = fits[0].names
    lot = (lot_statistics(np.array([f.values for f in fits]), names) if len(fits) >= 2
           else None)
    return FitResult(
        file=table.file,
        unit=table.rate_unit,
        output_unit=table.output_unit,
        order=int(order),
        units=table.units,
        names=names,
        fits=tuple(fits),
        lot=lot,
        lines=tuple(int(n[0]) for n in table.lines),
        warnings=_lot_warnings(lot, lot_name(table.file)),
    )


def _fit_units(table: RateTable, order: int) -> list[RateFit]:
    """Every unit's fit; raises with every unit that cannot be fitted (the first
    :data:`MAX_PROBLEMS` listed at their first line, the rest counted)."""
    fits: list[RateFit] = []
    problems: list[Problem] = []
    more = 0  # units refused beyond the first MAX_PROBLEMS, counted, not listed
    for k, unit in enumerate(table.units):
        try:
            fits.append(fit_rate_table(table.rate[k], table.output[k], order,
                                       table.cross[k], table.cross_axes))
        except IdentificationError as exc:
            if len(problems) >= MAX_PROBLEMS:
                more += 1
                continue
            size = table.rate[k].size
            who = (f"unit {unit!r} ({size} point{'s' if size != 1 else ''}): "
                   if table.unit_column else "")
            problems.append(Problem(f"{who}{exc.reason}", table.file,
                                    int(table.lines[k][0]), None))
    if more:
        problems.append(Problem(f"... and {more} more unit{'s' if more != 1 else ''} that "
                                "cannot be fitted", table.file))
    if problems:
        raise IdentificationError(problems)
    return fits


def _lot_warnings(lot: LotStatistics | None, name: str) -> tuple[str, ...]:
    """The lot's warning, naming it: why a yield from it would not be a measurement (too
    few units for its correlations, n ≤ p, among them)."""
    if lot is None:
        return ()
    if lot.unmeasured is not None:
        return (unmeasured_warning(name, lot.unmeasured),)
    return () if lot.warning is None else (lot.warning,)
