"""The synthesis of eq. (18)-(25): allowable coefficients for a budget Δ*_V.

The budget is split by fixed ratios (docs/model.md):

* eq. (18)-(20): Δ_VA(RMS) = r·Δ_VM(RMS), so the additive part gets
  ``c_A = r/√(1+r²)`` of Δ* and the multiplicative part ``c_M = 1/√(1+r²)``;
* eq. (21): the additive terms Δ0(1..5) (A1, k2, k4, m31, m32) get shares in
  the ratio ``w``: ``α_p = w_p·c_A/‖w‖``;
* eq. (24): the multiplicative terms Δ(1)·Ω̄, Δ(2)·Ω̄², Δ(3)·Ω̄³ get shares in
  the ratio ``v``: ``β_q = v_q·c_M/‖v‖``; Δ(1) holds k3 and k5, each gets
  ``β_1/√2``.

so that ``Σ α_p² + Σ β_q² = c_A² + c_M² = 1``: when every term uses exactly
its share, Δ_V(RMS) = Δ* (eq. 16, 17).

Each share divided by the term's multiplier (:class:`~gyrovib.core.analysis.Multipliers`,
``k1 = 1``) is a bound, eq. (23) and (25)::

    |A1|   ≤ α_1·Δ*/g_A                  |k2| ≤ α_2·Δ*/M2
    |k4|_A ≤ α_3·Δ*/M4                   |m3i| ≤ α_{3+i}·Δ*/|C3i|
    |k3|   ≤ (β_1/√2)·Δ*/(|Ω̄|·3M2)       |k5|_M1 ≤ (β_1/√2)·Δ*/(|Ω̄|·5M4)
    |k4|_M ≤ β_2·Δ*/(Ω̄²·6M2)             |k5|_M2 ≤ β_3·Δ*/(|Ω̄|³·10M2)
    |k4| ≤ min(|k4|_A, |k4|_M)           |k5| ≤ min(|k5|_M1, |k5|_M2)

A zero multiplier leaves its coefficient unconstrained: the bound is +inf.
Bounds carry the unit of their coefficient (rate^(1−n) for kn, 1/rate for
m3i, 1 for A1) in whatever rate unit the multipliers and Δ* share.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from gyrovib.core.analysis import Multipliers
from gyrovib.core.transmissibility import FloatArray

#: The coefficients that receive a bound, in report order.
BOUNDED: tuple[str, ...] = ("A1", "k2", "k3", "k4", "k5", "m31", "m32")
#: The two candidates behind the k4 and k5 bounds.
PARTS: tuple[str, ...] = ("k4_additive", "k4_multiplicative", "k5_linear", "k5_cubic")

#: The paper's allocation: r of eq. (18), w of eq. (21), v of eq. (24).
DEFAULT_R = 1.5
DEFAULT_W: tuple[float, ...] = (1.0, 1.0, 1.0, 0.5, 0.5)
DEFAULT_V: tuple[float, ...] = (1.0, 0.5, 0.5)


@dataclass(frozen=True)
class AllocationConstants:
    """Shares of Δ* (dimensionless).

    ``alpha``: α_1..α_5 for A1, k2, k4 (additive), m31, m32 (eq. 21, 22);
    ``beta``: β_1..β_3 for Δ(1)·Ω̄, Δ(2)·Ω̄², Δ(3)·Ω̄³ (eq. 24);
    ``k3``, ``k5_linear``: the shares of β_1 given to k3 and to k5 in Δ(1);
    ``c_additive``, ``c_multiplicative``: c_A and c_M of eq. (20).
    """

    alpha: FloatArray
    beta: FloatArray
    k3: float
    k5_linear: float
    c_additive: float
    c_multiplicative: float


def _positive_finite(name: str, values: Sequence[float], size: int) -> FloatArray:
    arr = np.asarray(values, dtype=float).reshape(-1)
    if arr.size != size:
        raise ValueError(f"{name} must have {size} value(s), not {arr.size}")
    if not (np.all(np.isfinite(arr)) and np.all(arr > 0)):
        raise ValueError(f"{name} must be positive and finite")
    return arr


def allocation_constants(
    r: float = DEFAULT_R,
    w: Sequence[float] = DEFAULT_W,
    v: Sequence[float] = DEFAULT_V,
) -> AllocationConstants:
    """The shares derived from an allocation (eq. 20, 21, 24).

    ``c_A = r/√(1+r²)``, ``c_M = 1/√(1+r²)``, ``α_p = w_p·c_A/‖w‖``,
    ``β_q = v_q·c_M/‖v‖``; k3 and the linear k5 each get ``β_1/√2``.
    The defaults (r = 1.5, w = (1, 1, 1, ½, ½), v = (1, ½, ½)) give
    c_A = 0.8321, c_M = 0.5547, α = 0.4447 | 0.2224, β = 0.4529 | 0.2265 and
    0.3203 for k3 and k5.
    """
    rr = float(_positive_finite("r", [r], 1)[0])
    ww = _positive_finite("w", w, 5)
    vv = _positive_finite("v", v, 3)
    norm = math.hypot(1.0, rr)
    c_a, c_m = rr / norm, 1.0 / norm
    alpha = ww * c_a / float(np.linalg.norm(ww))
    beta = vv * c_m / float(np.linalg.norm(vv))
    share = float(beta[0]) / math.sqrt(2.0)
    return AllocationConstants(alpha=alpha, beta=beta, k3=share, k5_linear=share,
                               c_additive=c_a, c_multiplicative=c_m)


#: The constants printed in the paper, eq. (22) and (25): 0.44 (A1, k2, k4),
#: 0.22 (m31, m32), 0.49 and 0.24 (β), 0.35 (k3 and the linear k5).
#: 0.49 does not follow from the paper's own eq. (20) (docs/model.md).
PAPER_CONSTANTS = AllocationConstants(
    alpha=np.array([0.44, 0.44, 0.44, 0.22, 0.22]),
    beta=np.array([0.49, 0.24, 0.24]),
    k3=0.35,
    k5_linear=0.35,
    c_additive=0.832,
    c_multiplicative=0.555,
)


@dataclass(frozen=True)
class CoefficientBounds:
    """Allowable |coefficient| values, eq. (23) and (25); +inf where unconstrained.

    Every array has the shape of the multipliers (profiles, or groups ×
    profiles, or × rates). ``k4`` and ``k5`` are the minima of their parts.
    """

    A1: FloatArray
    k2: FloatArray
    k3: FloatArray
    k4: FloatArray
    k5: FloatArray
    m31: FloatArray
    m32: FloatArray
    k4_additive: FloatArray
    k4_multiplicative: FloatArray
    k5_linear: FloatArray
    k5_cubic: FloatArray

    def stacked(self) -> FloatArray:
        """The seven bounds of :data:`BOUNDED` along a new last axis."""
        return np.stack([getattr(self, name) for name in BOUNDED], axis=-1)

    def scaled(self, factors: dict[str, float]) -> CoefficientBounds:
        """Each bound multiplied by ``factors[coefficient]`` (a unit conversion).

        The parts take the factor of k4 and k5.
        """
        def f(name: str) -> float:
            return factors[name.split("_")[0]]

        return CoefficientBounds(**{name: getattr(self, name) * f(name)
                                    for name in self.__dataclass_fields__})


def _share(numerator: FloatArray, denominator: FloatArray) -> FloatArray:
    """``numerator/denominator``, +inf where the denominator is 0 (unconstrained)."""
    den = np.abs(np.asarray(denominator, dtype=float))
    num = np.broadcast_to(np.asarray(numerator, dtype=float), den.shape)
    out: FloatArray = np.full(den.shape, np.inf)
    with np.errstate(over="ignore"):
        np.divide(num, den, out=out, where=den > 0)
    return out


def coefficient_bounds(
    multipliers: Multipliers, budget: ArrayLike, constants: AllocationConstants
) -> CoefficientBounds:
    """Eq. (23) and (25): the bounds for a budget ``budget`` (Δ*, rate units).

    ``budget`` broadcasts against the multipliers' shape. The multipliers are
    those of the chosen method: for ``exact`` g_A = ½·E(Ω̄), M2, M4 exactly;
    for ``paper`` g_A = 0.673·a | 0.5·σ, M2 = 0.5a² | σ², M4 = 0.375a⁴ | σ⁴,
    so that 3M2, 5M4, 6M2, 10M2 are the paper's 1.5a² | 3σ², 1.875a⁴ | 5σ⁴,
    3a² | 6σ², 5a² | 10σ².
    """
    mu = multipliers
    d = np.asarray(budget, dtype=float)
    a, b = constants.alpha, constants.beta
    w = np.abs(np.asarray(mu.omega, dtype=float))
    m2 = np.asarray(mu.m2, dtype=float)
    m4 = np.asarray(mu.m4, dtype=float)
    k4_additive = _share(a[2] * d, m4)
    k4_multiplicative = _share(b[1] * d, w**2 * 6.0 * m2)
    k5_linear = _share(constants.k5_linear * d, w * 5.0 * m4)
    k5_cubic = _share(b[2] * d, w**3 * 10.0 * m2)
    return CoefficientBounds(
        A1=_share(a[0] * d, mu.asymmetry),
        k2=_share(a[1] * d, m2),
        k3=_share(constants.k3 * d, w * 3.0 * m2),
        k4=np.minimum(k4_additive, k4_multiplicative),
        k5=np.minimum(k5_linear, k5_cubic),
        m31=_share(a[3] * d, mu.c31),
        m32=_share(a[4] * d, mu.c32),
        k4_additive=k4_additive,
        k4_multiplicative=k4_multiplicative,
        k5_linear=k5_linear,
        k5_cubic=k5_cubic,
    )
