"""The synthesis of eq. (18)-(25): allowable coefficients for a budget Δ*_V.

The budget is split by fixed ratios (docs/model.md):

* eq. (18)-(20): Δ_VA(RMS) = r·Δ_VM(RMS), so the additive part gets
  ``c_A = r/√(1+r²)`` of Δ* and the multiplicative part ``c_M = 1/√(1+r²)``;
* eq. (21): the additive terms Δ0(1..5) (A1, k2, k4, m31, m32) get shares in
  the ratio ``w``: ``α_p = w_p·c_A/‖w‖``;
* eq. (24): the multiplicative terms Δ(1)·Ω̄, Δ(2)·Ω̄², Δ(3)·Ω̄³ get shares in
  the ratio ``v``: ``β_q = v_q·c_M/‖v‖``; Δ(1) holds k3 and k5, whose
  contributions add linearly, so each gets ``β_1/2`` (docs/model.md section 6; the
  paper prints 0.35 ≈ β_1/√2, which can overrun the share by √2).

so that ``Σ α_p² + Σ β_q² = c_A² + c_M² = 1``: when every term uses exactly
its share, Δ_V(RMS) = Δ* (eq. 16, 17).

Each share divided by the term's multiplier (:class:`~gyrovib.core.analysis.Multipliers`,
``k1 = 1``) is a bound, eq. (23) and (25)::

    |A1|   ≤ α_1·Δ*/g_A                  |k2| ≤ α_2·Δ*/M2
    |k4|_A ≤ α_3·Δ*/M4                   |m3i| ≤ α_{3+i}·Δ*/|C3i|
    |k3|   ≤ (β_1/2)·Δ*/(|Ω̄|·3M2)        |k5|_M1 ≤ (β_1/2)·Δ*/(|Ω̄|·5M4)
    |k4|_M ≤ β_2·Δ*/(Ω̄²·6M2)             |k5|_M2 ≤ β_3·Δ*/(|Ω̄|³·10M2)
    |k4| ≤ min(|k4|_A, |k4|_M)           |k5| ≤ min(|k5|_M1, |k5|_M2)

Linear vibration (docs/model.md section 8) appends an additive share w6 = 1 for
Δ0(6), bounding the effective VRE: ``vre = α_6·Δ*/Σ_j⟨a_j²⟩``. Odd moments
(section 10) append additive shares of weight 1 for k3·M3 and k5·M5 (where
M3 ≠ 0, resp. M5 ≠ 0), and split each multiplicative share equally among
its contributors: Δ(1) → k3, k4, k5 (β_1/3 each, where M3 ≠ 0), Δ(2) → k4,
k5 (β_2/2 each)::

    |k3|_A ≤ α_k3·Δ*/|M3|                |k3|_L ≤ (β_1/3)·Δ*/(|Ω̄|·3M2)
    |k4|_L ≤ (β_1/3)·Δ*/(|Ω̄|·4|M3|)      |k4|_M ≤ (β_2/2)·Δ*/(Ω̄²·6M2)
    |k5|_A ≤ α_k5·Δ*/|M5|                |k5|_M1 ≤ (β_1/3)·Δ*/(|Ω̄|·5M4)
    |k5|_Q ≤ (β_2/2)·Δ*/(Ω̄²·10|M3|)      |k5|_M2 ≤ β_3·Δ*/(|Ω̄|³·10M2)

each coefficient's bound being the least of its parts. The additive
normalisation ‖w‖ runs over the shares present in each profile, so the
shares still satisfy Σα² + Σβ² = 1 there.

A zero multiplier leaves its coefficient unconstrained: the bound is +inf.
Bounds carry the unit of their coefficient (rate^(1−n) for kn, 1/rate for
m3i, 1 for A1) in whatever rate unit the multipliers and Δ* share.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from gyrovib.core._types import FloatArray
from gyrovib.core.analysis import BOUNDED as BOUNDED  # defined there: analyze needs no synthesis
from gyrovib.core.analysis import Multipliers
from gyrovib.frozen import Frozen

#: The two candidates behind the k4 and k5 bounds.
PARTS: tuple[str, ...] = ("k4_additive", "k4_multiplicative", "k5_linear", "k5_cubic")
#: The parts that odd moments add (docs/model.md section 10; finite only where M3, M5 ≠ 0).
ODD_PARTS: tuple[str, ...] = ("k3_additive", "k3_linear", "k4_linear", "k5_additive",
                              "k5_quadratic")
#: Weights of the shares appended for Δ0(6) (g2), k3·M3 and k5·M5 (docs/model.md 8, 10).
DEFAULT_EXTRA_W: tuple[float, ...] = (1.0, 1.0, 1.0)

#: The paper's allocation: r of eq. (18), w of eq. (21), v of eq. (24).
DEFAULT_R = 1.5
DEFAULT_W: tuple[float, ...] = (1.0, 1.0, 1.0, 0.5, 0.5)
DEFAULT_V: tuple[float, ...] = (1.0, 0.5, 0.5)


@dataclass(frozen=True, eq=False, repr=False)
class AllocationConstants(Frozen):
    """Shares of Δ* (dimensionless).

    ``alpha``: α_1..α_5 for A1, k2, k4 (additive), m31, m32 (eq. 21, 22);
    ``beta``: β_1..β_3 for Δ(1)·Ω̄, Δ(2)·Ω̄², Δ(3)·Ω̄³ (eq. 24);
    ``k3``, ``k5_linear``: the shares of β_1 given to k3 and to k5 in Δ(1)
    where x3 is symmetric (β_1/2 exact, 0.35 paper);
    ``c_additive``, ``c_multiplicative``: c_A and c_M of eq. (20);
    ``weights``: w_1..w_5 behind α; ``extra_weights``: the weights of the
    shares appended for g2 (w6), k3·M3 and k5·M5 (docs/model.md sections 8, 10).
    """

    alpha: FloatArray
    beta: FloatArray
    k3: float
    k5_linear: float
    c_additive: float
    c_multiplicative: float
    weights: FloatArray = field(default_factory=lambda: np.asarray(DEFAULT_W))
    extra_weights: FloatArray = field(default_factory=lambda: np.asarray(DEFAULT_EXTRA_W))


def _positive_finite(name: str, values: ArrayLike, size: int) -> FloatArray:
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
    ``β_q = v_q·c_M/‖v‖``; k3 and the linear k5 each get ``β_1/2``
    (docs/model.md section 6). The defaults (r = 1.5, w = (1, 1, 1, ½, ½),
    v = (1, ½, ½)) give c_A = 0.8321, c_M = 0.5547, α = 0.4447 | 0.2224,
    β = 0.4529 | 0.2265 and 0.2265 for k3 and k5. ``w`` may carry a sixth
    weight, w6 for the g2 term (default 1), used only for profiles with
    linear vibration; α (5,) is for profiles without.
    """
    rr = float(_positive_finite("r", [r], 1)[0])
    w_all = np.asarray(w, dtype=float).reshape(-1)
    ww = _positive_finite("w", w_all[:5] if w_all.size == 6 else w_all, 5)
    extra = np.asarray(DEFAULT_EXTRA_W, dtype=float)
    if w_all.size == 6:
        extra = np.concatenate([_positive_finite("w6", w_all[5:], 1), extra[1:]])
    vv = _positive_finite("v", v, 3)
    norm = math.hypot(1.0, rr)
    c_a, c_m = rr / norm, 1.0 / norm
    alpha = ww * c_a / float(np.linalg.norm(ww))
    beta = vv * c_m / float(np.linalg.norm(vv))
    share = float(beta[0]) / 2.0
    return AllocationConstants(alpha=alpha, beta=beta, k3=share, k5_linear=share,
                               c_additive=c_a, c_multiplicative=c_m, weights=ww,
                               extra_weights=extra)


#: The constants printed in the paper, eq. (22) and (25): 0.44 (A1, k2, k4),
#: 0.22 (m31, m32), 0.49 and 0.24 (β), 0.35 (k3 and the linear k5).
#: 0.49 does not follow from the paper's own eq. (20) (docs/model.md).
PAPER_CONSTANTS = AllocationConstants(
    alpha=np.array([0.44, 0.44, 0.44, 0.22, 0.22]),
    # the paper has no linear vibration and no odd moments: its method refuses them
    beta=np.array([0.49, 0.24, 0.24]),
    k3=0.35,
    k5_linear=0.35,
    c_additive=0.832,
    c_multiplicative=0.555,
)


@dataclass(frozen=True, eq=False, repr=False)
class CoefficientBounds(Frozen):
    """Allowable |coefficient| values, eq. (23) and (25); +inf where unconstrained.

    Every array has the shape of the multipliers (profiles, or groups ×
    profiles, or × rates). ``k4`` and ``k5`` are the minima of their parts.
    ``vre`` (rate/g²; +inf without linear vibration) bounds the effective VRE
    |Δ0(6)|/Σ⟨a_j²⟩; it is None when the multipliers carry no linear
    vibration at all. The parts of :data:`ODD_PARTS` are None when they carry
    no odd moments; ``k3`` is then today's single bound (``k3_linear``).
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
    vre: FloatArray | None = None
    k3_additive: FloatArray | None = None
    k3_linear: FloatArray | None = None
    k4_linear: FloatArray | None = None
    k5_additive: FloatArray | None = None
    k5_quadratic: FloatArray | None = None

    def stacked(self) -> FloatArray:
        """The seven bounds of :data:`BOUNDED` along a new last axis."""
        return np.stack([getattr(self, name) for name in BOUNDED], axis=-1)

    def scaled(self, factors: dict[str, float]) -> CoefficientBounds:
        """Each bound multiplied by ``factors[coefficient]`` (a unit conversion).

        The parts take the factor of their coefficient. ``vre`` (rate/g², rate
        power 1) takes ``factors["vre"]``, or 1/``factors["k2"]`` (rate power −1)
        when that is not given.
        """
        def f(name: str) -> float:
            if name == "vre":
                return factors.get("vre", 1.0 / factors["k2"])
            return factors[name.split("_")[0]]

        scaled: dict[str, Any] = {
            name: None if getattr(self, name) is None else getattr(self, name) * f(name)
            for name in self.__dataclass_fields__}
        return CoefficientBounds(**scaled)


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
    3a² | 6σ², 5a² | 10σ². With linear vibration or odd moments in the
    multipliers, the shares of docs/model.md sections 8 and 10 (module docstring).
    """
    mu = multipliers
    d = np.asarray(budget, dtype=float)
    b = constants.beta
    w = np.abs(np.asarray(mu.omega, dtype=float))
    m2 = np.asarray(mu.m2, dtype=float)
    m4 = np.asarray(mu.m4, dtype=float)
    shape = w.shape
    if not (mu.has_linear or mu.has_odd):
        a = constants.alpha
        alpha = [a[p] for p in range(5)]
        k3_share: FloatArray | float = constants.k3
        k5_share: FloatArray | float = constants.k5_linear
        k4_mult_share: FloatArray | float = b[1]
    else:
        ms = (np.zeros(shape) if mu.acceleration is None
              else np.asarray(mu.acceleration, dtype=float)[..., :3].sum(axis=-1))
        m3 = np.zeros(shape) if mu.m3 is None else np.asarray(mu.m3, dtype=float)
        m5 = np.zeros(shape) if mu.m5 is None else np.asarray(mu.m5, dtype=float)
        ww, we = constants.weights, constants.extra_weights
        present = [ms > 0, m3 != 0, m5 != 0]
        norm = np.sqrt(float(np.sum(ww**2))
                       + sum(np.where(on, e * e, 0.0) for on, e in zip(present, we, strict=True)))
        scale = constants.c_additive / norm
        plain = ~(present[0] | present[1] | present[2])
        # a profile with none of the extra shares keeps the constants themselves, bit for bit
        alpha = [np.where(plain, constants.alpha[p], ww[p] * scale) for p in range(5)]
        odd = m3 != 0
        k3_share = np.where(odd, b[0] / 3.0, constants.k3)
        k5_share = np.where(odd, b[0] / 3.0, constants.k5_linear)
        k4_mult_share = np.where(odd, b[1] / 2.0, b[1])
    k4_additive = _share(alpha[2] * d, m4)
    k4_multiplicative = _share(k4_mult_share * d, w**2 * 6.0 * m2)
    k5_linear = _share(k5_share * d, w * 5.0 * m4)
    k5_cubic = _share(b[2] * d, w**3 * 10.0 * m2)
    k3_linear = _share(k3_share * d, w * 3.0 * m2)
    out = dict(
        A1=_share(alpha[0] * d, mu.asymmetry),
        k2=_share(alpha[1] * d, m2),
        k3=k3_linear,
        k4=np.minimum(k4_additive, k4_multiplicative),
        k5=np.minimum(k5_linear, k5_cubic),
        m31=_share(alpha[3] * d, mu.c31),
        m32=_share(alpha[4] * d, mu.c32),
        k4_additive=k4_additive,
        k4_multiplicative=k4_multiplicative,
        k5_linear=k5_linear,
        k5_cubic=k5_cubic,
    )
    if mu.has_linear:
        out["vre"] = _share(we[0] * scale * d, ms)
    if mu.has_odd:
        k3_additive = _share(we[1] * scale * d, m3)
        k4_linear = _share(b[0] / 3.0 * d, w * 4.0 * m3)
        k5_additive = _share(we[2] * scale * d, m5)
        k5_quadratic = _share(b[1] / 2.0 * d, w**2 * 10.0 * m3)
        out.update(
            k3=np.minimum(k3_additive, k3_linear),
            k4=np.minimum(np.minimum(k4_additive, k4_multiplicative), k4_linear),
            k5=np.minimum(np.minimum(k5_linear, k5_cubic), np.minimum(k5_additive, k5_quadratic)),
            k3_additive=k3_additive, k3_linear=k3_linear, k4_linear=k4_linear,
            k5_additive=k5_additive, k5_quadratic=k5_quadratic,
        )
    return CoefficientBounds(**out)
