"""The bound checks of ``select``, one verdict per sensor form.

A coefficient sensor passes the bounds when every |coefficient| is at most its
bound, eq. (23)/(25), and its effective VRE |Δ0(6)|/Σ⟨a_j²⟩ at most the ``vre``
bound (docs/model.md sections 7, 8); a datasheet sensor when its nonlinearity and
VRE are at most their spec bounds (section 11). Each form gives a verdict of the
same shape (:class:`BoundVerdict`): which of its rows pass, the largest
value/bound ratio of each cell, the margin its cells are judged by, and what
limits a failing row. The view (``selection_of``) joins the verdicts and never
asks which form a sensor has.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np
from numpy.typing import NDArray

from gyrovib.api.datasheet.spec_bounds import SpecChecks
from gyrovib.api.evaluation.results import Limit
from gyrovib.core._types import FloatArray
from gyrovib.core.synthesis import BOUNDED
from gyrovib.frozen import Frozen

#: Relative slack of every ≤ comparison: a value at its bound, up to rounding
#: (e.g. a bound printed in deg/h and read back), passes.
PASS_RTOL = 1e-9
#: Names of the coefficient checks: the coefficients of :data:`BOUNDED`, then the VRE.
CHECKS: tuple[str, ...] = (*BOUNDED, "vre")


def at_most(value: FloatArray, bound: FloatArray | float) -> NDArray[np.bool_]:
    """value ≤ bound, up to :data:`PASS_RTOL`."""
    out: NDArray[np.bool_] = value <= np.asarray(bound) * (1.0 + PASS_RTOL)
    return out


def ratio(value: FloatArray, bound: FloatArray) -> FloatArray:
    """value/bound: 0 for a zero value or an infinite bound, +inf for a zero bound."""
    out: FloatArray = np.zeros(np.broadcast_shapes(value.shape, bound.shape))
    v = np.broadcast_to(value, out.shape)
    b = np.broadcast_to(bound, out.shape)
    q = v / b
    return np.where(v == 0, 0.0, np.where(b == 0, np.inf, np.where(np.isinf(b), 0.0, q)))


@dataclass(frozen=True, eq=False, repr=False)
class CoefficientChecks(Frozen):
    """Every sensor's coefficients and effective VRE against their bounds, deg/s.

    ``values``, ``limits``: (sensors, profiles, :data:`BOUNDED`), |coefficient| and
    its bound; ``vre``, ``vre_bound``: (sensors, profiles), deg/s per g².
    """

    values: FloatArray
    limits: FloatArray
    vre: FloatArray
    vre_bound: FloatArray

    @property
    def check_pass(self) -> NDArray[np.bool_]:
        return at_most(self.values, self.limits)

    @property
    def vre_pass(self) -> NDArray[np.bool_]:
        return at_most(self.vre, self.vre_bound)

    @property
    def ratios(self) -> FloatArray:
        """(sensors, profiles, :data:`CHECKS`): each value over its bound."""
        return np.concatenate([ratio(self.values, self.limits),
                               ratio(self.vre, self.vre_bound)[..., None]], axis=-1)


class BoundVerdict(Protocol):
    """One form's bound checks on its ``rows`` (sensor indices), (rows, profiles)."""

    @property
    def rows(self) -> NDArray[np.intp]:
        """Its sensors."""
        ...

    @property
    def passed(self) -> NDArray[np.bool_]:
        """Whether each of its cells passes the bound checks."""
        ...

    @property
    def largest(self) -> FloatArray:
        """The largest value/bound ratio of each cell."""
        ...

    def judged(self, criterion: str, rms: FloatArray, total: FloatArray) -> FloatArray:
        """What the margin Δ*/x of its rows takes as x, deg/s (rows, profiles)."""
        ...

    def limits(self, row: int) -> list[Limit]:
        """The bound checks that limit its ``row``-th sensor (candidates, the worst per
        check or one over all checks)."""
        ...


@dataclass(frozen=True, eq=False, repr=False)
class CoefficientVerdict(Frozen):
    """The coefficient form's verdict: every coefficient and the VRE, eq. (23)/(25)."""

    rows: NDArray[np.intp]
    passed: NDArray[np.bool_]
    ratios: FloatArray

    @classmethod
    def of(cls, rows: NDArray[np.intp], checks: CoefficientChecks) -> CoefficientVerdict:
        passed = np.all(checks.check_pass[rows], axis=-1) & checks.vre_pass[rows]
        return cls(rows, passed, checks.ratios[rows])

    @property
    def largest(self) -> FloatArray:
        out: FloatArray = self.ratios.max(axis=-1)
        return out

    def judged(self, criterion: str, rms: FloatArray, total: FloatArray) -> FloatArray:
        """Δ_V(RMS), or |Δ_V| under the ``worst`` criterion."""
        out: FloatArray = (total if criterion == "worst" else rms)[self.rows]
        return out

    def limits(self, row: int) -> list[Limit]:
        """The largest ratio over every profile and check."""
        ratios = self.ratios[row]
        jb = np.unravel_index(int(np.argmax(ratios)), ratios.shape)
        j, b = int(jb[0]), int(jb[1])
        return [Limit(CHECKS[b], j, float(ratios[j, b]))]


@dataclass(frozen=True, eq=False, repr=False)
class DatasheetVerdict(Frozen):
    """The datasheet form's verdict: its nonlinearity and VRE against their spec bounds."""

    rows: NDArray[np.intp]
    passed: NDArray[np.bool_]
    nonlinearity: FloatArray
    vre: FloatArray

    @classmethod
    def of(cls, rows: NDArray[np.intp], own: SpecChecks) -> DatasheetVerdict:
        """``own``: the spec checks of these rows, in their order."""
        return cls(rows, own.nl_pass & own.vre_pass, ratio(own.nl_value, own.nl_bound),
                   ratio(np.nan_to_num(own.vre_value), own.vre_bound))

    @property
    def largest(self) -> FloatArray:
        out: FloatArray = np.maximum(self.nonlinearity, self.vre)
        return out

    def judged(self, criterion: str, rms: FloatArray, total: FloatArray) -> FloatArray:
        """Always the worst |Δ_V| over the envelope."""
        out: FloatArray = total[self.rows]
        return out

    def limits(self, row: int) -> list[Limit]:
        """The worst profile of each figure."""
        out = []
        for name, ratios in (("nonlinearity", self.nonlinearity[row]), ("vre", self.vre[row])):
            j = int(np.argmax(ratios))
            out.append(Limit(name, j, float(ratios[j])))
        return out
