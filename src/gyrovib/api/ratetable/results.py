"""The immutable result of ``gyrovib fit`` (docs/model.md section 14).

In a module of its own so that no other command defines its classes.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from gyrovib import units as rate_units
from gyrovib.api.evaluation.results import Result, freeze
from gyrovib.core.fit import SIGNIFICANT_T, RateFit
from gyrovib.core.lot import LotStatistics
from gyrovib.records import Column, frame_of


def output_unit(result: FitResult) -> str:
    """The unit of the output the fit read (``output units`` when the table did not say)."""
    return result.output_unit or "output units"


def coefficient_unit(name: str, rate_unit: str) -> str:
    """The unit of an eq. (2) coefficient built on ``rate_unit``: k0 in it, kn in
    rate^(1−n), m3i in 1/rate, A1 and mi dimensionless ("1")."""
    power = rate_units.COEFFICIENT_RATE_POWER[name]
    if power == 0:
        return "1"
    if power == 1:
        return rate_unit
    return f"({rate_unit})^{power}"


def lot_name(file: str) -> str:
    """The id of the lot entry ``fit -o`` writes for the table ``file``: ``lot-`` and the
    file's stem as an id (``lot-rate-table-gx100``)."""
    stem = re.sub(r"[^A-Za-z0-9._-]+", "-", Path(file).stem).strip("-.") or "table"
    return f"lot-{stem}"[:200]


def pair_key(a: str, b: str) -> str:
    """The key of a correlation pair, as the catalogue and the JSON write it: ``"A1 k2"``."""
    return f"{a} {b}"


@dataclass(frozen=True, eq=False, repr=False)
class FitResult(Result):
    """One least-squares fit per unit of a rate table, and the lot of them.

    ``fits[i]`` (:class:`gyrovib.core.fit.RateFit`) is unit ``units[i]``'s fit:
    eq. (2) coefficients ``names`` in :attr:`unit` powers (k1 = 1 exactly) with
    their covariance, the eq. (1) parameters in :attr:`output_unit`, residuals,
    nonlinearity. ``lot``: μ and Σ over the units (two or more), else None.
    ``lines[i]``: the file line of unit i's first point. ``warnings``: e.g. a lot
    too small for its correlations.
    """

    file: str
    unit: str
    output_unit: str | None
    order: int
    units: tuple[str, ...]
    names: tuple[str, ...]
    fits: tuple[RateFit, ...]
    lot: LotStatistics | None
    lines: tuple[int, ...]
    warnings: tuple[str, ...] = ()
    method: str = "least-squares"

    def __post_init__(self) -> None:
        super().__post_init__()
        for item in (*self.fits, self.lot):
            if item is not None:
                freeze(item)

    def _shape(self) -> tuple[int, ...]:
        return (len(self.units), len(self.names))

    def coefficient_units(self) -> tuple[str, ...]:
        """The unit of each of :attr:`names`."""
        return tuple(coefficient_unit(n, self.unit) for n in self.names)

    def coefficients(self) -> Any:
        """(units, coefficients): every unit's eq. (2) coefficients."""
        return np.array([f.values for f in self.fits])

    def rows(self) -> list[tuple[int, int]]:
        """The rows of :meth:`records`: (unit, coefficient) index pairs, units outermost."""
        return [(i, k) for i in range(len(self.units)) for k in range(len(self.names))]

    def records(self) -> tuple[Column[tuple[int, int]], ...]:
        """The columns of the CSV and the DataFrame, in order, with their units: one row
        per unit × coefficient (:meth:`rows`)."""
        fits, names, units = self.fits, self.names, self.coefficient_units()
        out = self.output_unit or None

        def nl(name: str) -> Callable[[tuple[int, int]], float]:
            return lambda r: float(getattr(fits[r[0]].nonlinearity, name))

        return (
            Column("unit", None, lambda r: self.units[r[0]]),
            Column("coefficient", None, lambda r: names[r[1]]),
            Column("value", None, lambda r: float(fits[r[0]].values[r[1]])),
            Column("sigma", None, lambda r: float(fits[r[0]].sigma[r[1]])),
            Column("t", None, lambda r: float(fits[r[0]].t[r[1]])),
            Column("significant", None,
                   lambda r: bool(abs(float(fits[r[0]].t[r[1]])) >= SIGNIFICANT_T)),
            Column("coefficient_unit", None, lambda r: units[r[1]]),
            Column("residual_rms", out, lambda r: float(fits[r[0]].residual_rms)),
            Column("nonlinearity.least_squares_max", "%FS", nl("least_squares_max")),
            Column("nonlinearity.endpoint_max", "%FS", nl("endpoint_max")),
            Column("nonlinearity.range", self.unit, nl("range")),
            Column("points", None, lambda r: fits[r[0]].points),
        )

    def to_frame(self) -> Any:
        """Tidy pandas DataFrame: one row per unit × coefficient, the columns of
        :meth:`records` (those of ``--format csv``); the lot in ``frame.attrs["lot"]``
        (the JSON's mapping) when there is one."""
        attrs: dict[str, Any] = {"method": self.method, "unit": self.unit,
                                 "output_unit": self.output_unit, "order": self.order,
                                 "file": self.file}
        if self.lot is not None:
            attrs["lot"] = lot_mapping(self)
        return frame_of(self.records(), self.rows(), attrs)


def pairs(names: tuple[str, ...], correlation: Any) -> dict[str, float]:
    """The correlation matrix as the pairs mapping ``{"A1 k2": ρ}`` (i < j, every pair;
    NaN pairs, of a zero σ, left out)."""
    out: dict[str, float] = {}
    for i in range(len(names)):
        for j in range(i + 1, len(names)):
            value = float(correlation[i, j])
            if np.isfinite(value):
                out[pair_key(names[i], names[j])] = value
    return out


def lot_mapping(result: FitResult) -> dict[str, Any]:
    """The lot as the catalogue's ``lot`` entry and the JSON's ``"lot"`` write it:
    units, mean, sigma, correlation pairs (none when only the diagonal is used)."""
    lot = result.lot
    if lot is None:
        return {}
    names = result.names
    return {
        "units": lot.units,
        "mean": dict(zip(names, map(float, lot.mean), strict=True)),
        "sigma": dict(zip(names, map(float, lot.sigma), strict=True)),
        "correlation": {} if lot.diagonal else pairs(names, lot.correlation),
    }

