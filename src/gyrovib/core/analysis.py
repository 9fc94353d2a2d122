"""The vibration error of eq. (13)-(16), vectorised over sensors × profiles × rates.

A sensor enters only through its eq. (2) coefficients; a profile only through
five numbers per rate, its *multipliers* (docs/model.md table):

=========  ===================================  ==========================
name       exact                                paper (tone a | random σ)
=========  ===================================  ==========================
g_A        ½·E(Ω)                               0.673·a | 0.5·σ
M2         <x3²>                                a²/2 | σ²
M4         <x3⁴>                                0.375·a⁴ | σ⁴
C31, C32   <x3·x1>, <x3·x2>                     same as exact
=========  ===================================  ==========================

so that (eq. 14, 15)

    Δ0 = (k1·A1·g_A, k2·M2, k4·M4, m31·C31, m32·C32)
    Δ(1) = 3·k3·M2 + 5·k5·M4,   Δ(2) = 6·k4·M2,   Δ(3) = 10·k5·M2

and (eq. 13, 16) Δ_V = ΣΔ0 + Σ Δ(q)·Ω^q, Δ_V(RMS) = √(ΣΔ0² + Σ(Δ(q)·Ω^q)²).

Two optional multipliers extend this (docs/model.md sections 8 and 10): the
second moments of a linear vibration ⟨a_j·a_k⟩ (g², order
:data:`~gyrovib.core.linear.G2_TERMS`), which with the sensors' G (rate/g²)
give Δ0(6) = ΣG_jk·⟨a_j·a_k⟩; and the odd moments M3 = <x3³>, M5 = <x3⁵> of
phase-locked harmonics, which give k3·M3, k5·M5 and

    Δ(1) = 3k3·M2 + 4k4·M3 + 5k5·M4,   Δ(2) = 6k4·M2 + 10k5·M3.

These terms (:data:`EXTRA_TERMS`: g2, k3, k5) are kept apart from the five of
:data:`ADDITIVE_TERMS` in ``VibrationError.extra_terms``; where a profile has
neither (the fields are None) every other result is that of the five terms alone,
bit for bit.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from gyrovib.coefficients import ADDITIVE_TERMS as ADDITIVE_TERMS
from gyrovib.coefficients import ALL_TERMS as ALL_TERMS
from gyrovib.coefficients import BOUNDED as BOUNDED
from gyrovib.coefficients import COEFFICIENTS as COEFFICIENTS
from gyrovib.coefficients import EXTRA_TERMS as EXTRA_TERMS
from gyrovib.core._types import FloatArray
from gyrovib.core.harmonic_mixtures import (
    MAX_MIXTURE_NODES,
    MAX_SHIFT_TABLE,
    locked_mixture_excess,
    table_size,
    two_groups_excess,
)
from gyrovib.core.harmonics import (
    MAX_GROUPS,
    LockedGroup,
    combine_moments,
    group_moments,
    group_signal,
    locked_rectified_excess,
)
from gyrovib.core.statistics import (
    PAPER_RANDOM_ASYMMETRY,
    PAPER_TONE_ASYMMETRY,
    Vibration,
    rectified_excess,
)
from gyrovib.errors import ModelError
from gyrovib.frozen import Frozen

COLUMN: dict[str, int] = {name: i for i, name in enumerate(COEFFICIENTS)}
#: Names of the multiplicative coefficients Δ(1..3).
MULTIPLICATIVE_TERMS: tuple[str, ...] = ("q1", "q2", "q3")

METHODS = ("exact", "paper")


@dataclass(frozen=True, eq=False, repr=False)
class Multipliers(Frozen):
    """What the error needs from a vibration, at each rate Ω_K3.

    All arrays share one shape (profiles, or profiles × rates), rate units:
    ``asymmetry`` g_A = ½E(Ω) (rate), ``m2``, ``m4`` (rate², rate⁴), ``c31``,
    ``c32`` (rate²), ``omega`` Ω_K3 (rate). Optional (None: absent):
    ``m3``, ``m5`` (rate³, rate⁵), the odd moments of locked harmonics
    (docs/model.md section 10); ``acceleration`` (shape + (6,), g²), the second
    moments ⟨a_j·a_k⟩ of a linear vibration (docs/model.md section 8), order
    :data:`gyrovib.core.linear.G2_TERMS`.
    """

    asymmetry: FloatArray
    m2: FloatArray
    m4: FloatArray
    c31: FloatArray
    c32: FloatArray
    omega: FloatArray
    m3: FloatArray | None = None
    m5: FloatArray | None = None
    acceleration: FloatArray | None = None

    @property
    def has_odd(self) -> bool:
        """Whether odd moments (locked harmonics) are present."""
        return self.m3 is not None or self.m5 is not None

    @property
    def has_linear(self) -> bool:
        """Whether a linear vibration is present."""
        return self.acceleration is not None


def paper_kind(vibration: Vibration, *, linear: bool = False, locked: bool = False) -> str:
    """``"none"``, ``"tone"`` or ``"random"``: the cases the paper's formulas cover.

    Raises :class:`ModelError` for any other profile, and for a profile with
    a linear vibration (``linear``) or phase-locked harmonics (``locked``),
    which the paper's model does not have (docs/model.md sections 8 and 10).
    """
    if linear or locked:
        what = " or ".join(w for w, on in (("linear vibration (docs/model.md section 8)", linear),
                                           ("phase-locked harmonics (docs/model.md section 10)",
                                            locked)) if on)
        raise ModelError(
            f"the paper's model covers angular vibration by one harmonic tone or a random "
            f"process, not {what}; the exact method covers it"
        )
    n_tones = vibration.phasors.shape[0]
    if n_tones == 0:
        return "random" if vibration.has_random else "none"
    if n_tones == 1 and not vibration.has_random:
        return "tone"
    what = f"{n_tones} tone{'s' if n_tones > 1 else ''}" + (
        " and a random part" if vibration.has_random else ""
    )
    raise ModelError(reason=(
        f"the paper's formulas cover one harmonic tone or purely random vibration, not {what}"
    ))


def profile_multipliers(
    vibration: Vibration,
    omega: ArrayLike,
    method: str = "exact",
    *,
    locked: Sequence[LockedGroup] = (),
    acceleration: ArrayLike | None = None,
) -> Multipliers:
    """Multipliers of one vibration at the rates ``omega`` (any shape).

    ``locked``: phase-locked harmonic groups (docs/model.md section 10), each
    independent of the tones, the Gaussian part and the other groups; their
    moments combine by cumulants and E(Ω) is averaged over their periods.
    ``acceleration``: the six second moments ⟨a_j·a_k⟩ (g²) of a linear
    vibration (:func:`gyrovib.core.linear.acceleration_moments`). Without
    either, the result is the one of section 4, bit for bit.
    """
    w = np.asarray(omega, dtype=float)
    ones = np.ones_like(w)
    m2, m4 = vibration.m2, vibration.m4
    if method == "paper":
        paper_kind(vibration, linear=acceleration is not None, locked=bool(locked))
    if method == "exact" and locked:
        return _locked_multipliers(vibration, w, locked, acceleration)
    if method == "exact":
        flat = rectified_excess(w.ravel(), vibration.tone_amplitudes, float(vibration.sigma[2]))
        asym = 0.5 * flat.reshape(w.shape)
    elif method == "paper":
        kind = paper_kind(vibration)
        if kind == "tone":
            asym = PAPER_TONE_ASYMMETRY * float(vibration.tone_amplitudes[0]) * ones
        elif kind == "random":
            sigma = float(vibration.sigma[2])
            asym = PAPER_RANDOM_ASYMMETRY * sigma * ones
            m4 = sigma**4
        else:
            asym = 0.0 * ones
    else:
        raise ModelError(reason=f"unknown method {method!r}; the methods are {', '.join(METHODS)}")
    return Multipliers(
        asymmetry=asym,
        m2=m2 * ones,
        m4=m4 * ones,
        c31=vibration.cross(1) * ones,
        c32=vibration.cross(2) * ones,
        omega=w.copy(),
        acceleration=_acceleration(acceleration, w.shape),
    )


def _acceleration(acceleration: ArrayLike | None, shape: tuple[int, ...]) -> FloatArray | None:
    if acceleration is None:
        return None
    a = np.asarray(acceleration, dtype=float)
    if a.shape != (6,):
        raise ValueError("acceleration moments must have shape (6,)")
    out: FloatArray = np.broadcast_to(a, (*shape, 6)).copy()
    return out


#: Nodes per period of each locked group beyond the first in E(Ω) (several groups).
_EXTRA_GROUP_NODES = 256


def _locked_multipliers(vibration: Vibration, w: FloatArray, locked: Sequence[LockedGroup],
                        acceleration: ArrayLike | None) -> Multipliers:
    """Section 10: tones, Gaussian part and locked groups as independent components."""
    ones = np.ones_like(w)
    a = vibration.tone_amplitudes
    s3 = float(vibration.sigma[2])
    moments = [group_moments(g.orders, g.phasors) for g in locked]
    p2 = [a**2 / 2.0, np.asarray(s3**2)] + [mo.m2 for mo in moments]
    p3 = [np.zeros(a.shape), np.zeros(())] + [mo.m3 for mo in moments]
    p4 = [3.0 * a**4 / 8.0, np.asarray(3.0 * s3**4)] + [mo.m4 for mo in moments]
    p5 = [np.zeros(a.shape), np.zeros(())] + [mo.m5 for mo in moments]
    m2, m3, m4, m5 = combine_moments(*(
        [np.sum(np.asarray(x)) for x in parts] for parts in (p2, p3, p4, p5)))
    c31 = vibration.cross(1) + sum(float(mo.c31) for mo in moments)
    c32 = vibration.cross(2) + sum(float(mo.c32) for mo in moments)
    asym = _locked_asymmetry(w, locked, a, s3)
    return Multipliers(
        asymmetry=asym, m2=m2 * ones, m4=m4 * ones, c31=c31 * ones, c32=c32 * ones,
        omega=w.copy(), m3=m3 * ones, m5=m5 * ones,
        acceleration=_acceleration(acceleration, w.shape),
    )


def _locked_asymmetry(w: FloatArray, locked: Sequence[LockedGroup], a: FloatArray,
                      s3: float) -> FloatArray:
    """Half the excess E(Ω) of locked groups with tones of amplitudes ``a`` and a
    Gaussian part of standard deviation ``s3``, by the quickest exact route."""
    if len(locked) == 2 and a.size == 0 and s3 <= 0:
        # two groups alone: the second's period split at the first's kinks (1e-6 asked)
        return 0.5 * two_groups_excess(w, locked[0], locked[1])
    if s3 > 0 and (len(locked) > 1 or (a.size and table_size(a, s3) <= MAX_SHIFT_TABLE)):
        # tones and the Gaussian part tabulated once, the groups' periods on a grid (one
        # group with tones on a random part too narrow for the table: the group's grid
        # of direct evaluations below)
        return 0.5 * locked_mixture_excess(w, locked, a, s3)
    return _grid_asymmetry(w, locked, a, s3)


def _grid_asymmetry(w: FloatArray, locked: Sequence[LockedGroup], a: FloatArray,
                    s3: float) -> FloatArray:
    """Half of E(Ω): the first group against the independent tones, or alone, averaged
    over the further groups' phases on a grid of :data:`_EXTRA_GROUP_NODES` each (at most
    two groups: with a random part, more are folded into its table instead)."""
    if len(locked) > MAX_GROUPS:
        raise ModelError(reason=(
            f"E(Ω) for {len(locked)} phase-locked groups with no random part on the sensitive "
            f"axis: their joint phases would take {_EXTRA_GROUP_NODES}^{len(locked) - 1} "
            "nodes per rate (with a random part, the groups beyond the second are folded "
            "into its table); give the smaller groups' orders as independent tones"))
    if len(locked) > 1 and w.size * _EXTRA_GROUP_NODES * (1 << 14) > MAX_MIXTURE_NODES:
        raise ModelError(reason=(
            "E(Ω) for two phase-locked groups with independent tones and no random part "
            f"at {w.size} rates would take {w.size * _EXTRA_GROUP_NODES * (1 << 14):,} grid "
            f"points (both groups' periods on {_EXTRA_GROUP_NODES} × 16,384 nodes per rate: "
            "the tones' excess has kinks), more than the "
            f"{MAX_MIXTURE_NODES:,} gyrovib allows; give at most "
            f"{MAX_MIXTURE_NODES // (_EXTRA_GROUP_NODES << 14)} rates, the smaller group's "
            "orders as independent tones, or the tones as orders of a group"))
    shift = np.zeros(1)
    for g in locked[1:]:
        theta = 2.0 * math.pi * (np.arange(_EXTRA_GROUP_NODES) + 0.5) / _EXTRA_GROUP_NODES
        x3 = group_signal(g.orders, g.phasors[:, 2:3], theta)[0]
        shift = (shift[:, None] + x3[None, :]).ravel()
    flat = w.ravel()
    shifted = flat[:, None] + shift[None, :]
    e = locked_rectified_excess(shifted, locked[0], a, s3)
    if shift.size > 1:
        # E(Ω) = <E_1(Ω + s)> + <|Ω + s|> − |Ω| over the further groups' phases s
        e = e + np.abs(shifted) - np.abs(flat)[:, None]
    result: FloatArray = 0.5 * e.mean(axis=1).reshape(w.shape)
    return result


_OPTIONAL = ("m3", "m5", "acceleration")


def stack_multipliers(items: Sequence[Multipliers]) -> Multipliers:
    """Stack per-profile multipliers along a new leading (profile) axis.

    An optional field absent from some items is taken as 0 there; absent from
    all, it stays None.
    """
    fields = {f: np.stack([getattr(m, f) for m in items])
              for f in Multipliers.__dataclass_fields__ if f not in _OPTIONAL}
    for f in _OPTIONAL:
        present = [getattr(m, f) for m in items]
        if all(v is None for v in present):
            continue
        tail = (6,) if f == "acceleration" else ()
        fields[f] = np.stack([np.zeros(m.omega.shape + tail) if v is None else v
                              for m, v in zip(items, present, strict=True)])
    return Multipliers(**fields)


@dataclass(frozen=True, eq=False, repr=False)
class VibrationError(Frozen):
    """Eq. (13)-(16) for every sensor × profile (× rate): arrays in rate units.

    ``additive_terms[..., p]`` is Δ0(p+1) for :data:`ADDITIVE_TERMS`;
    ``extra_terms[..., e]`` the terms of :data:`EXTRA_TERMS` (g2 = Δ0(6),
    k3·M3, k5·M5; zeros where the profile has none);
    ``multiplicative_coefficients[..., q]`` is Δ(q+1) (unit rate^-q);
    ``additive`` Δ_VA; ``multiplicative`` Δ_VM(Ω); ``total`` Δ_V; ``rms`` Δ_V(RMS).
    """

    additive_terms: FloatArray
    multiplicative_coefficients: FloatArray
    additive: FloatArray
    multiplicative: FloatArray
    total: FloatArray
    rms: FloatArray
    extra_terms: FloatArray = None  # type: ignore[assignment]  # filled in __post_init__

    def __post_init__(self) -> None:
        if self.extra_terms is None:  # built without the section 8/10 terms: zeros
            zeros = np.zeros((*np.shape(self.additive_terms)[:-1], len(EXTRA_TERMS)))
            object.__setattr__(self, "extra_terms", zeros)


def vibration_error(
    coefficients: ArrayLike,
    multipliers: Multipliers,
    g2_sensitivity: ArrayLike | None = None,
) -> VibrationError:
    """Evaluate eq. (14)-(16) for a coefficient matrix (sensors × 11, see COEFFICIENTS).

    ``g2_sensitivity``: (sensors, 6) G_jk in rate/g² (order
    :data:`gyrovib.core.linear.G2_TERMS`), used where the multipliers carry
    a linear vibration (None: G = 0). With odd moments (docs/model.md section 10)
    Δ0 gains k3·M3 and k5·M5, Δ(1) gains 4k4·M3 and Δ(2) 10k5·M3.
    The result has shape ``(sensors,) + multipliers.omega.shape``.
    """
    c = np.asarray(coefficients, dtype=float)
    if c.ndim != 2 or c.shape[1] != len(COEFFICIENTS):
        raise ValueError(f"coefficients must have shape (n, {len(COEFFICIENTS)})")
    expand = (slice(None),) + (None,) * multipliers.omega.ndim

    def col(name: str) -> FloatArray:
        out: FloatArray = c[:, COLUMN[name]][expand]
        return out

    mu = multipliers
    additive_terms = np.stack(
        [
            col("k1") * col("A1") * mu.asymmetry,
            col("k2") * mu.m2,
            col("k4") * mu.m4,
            col("m31") * mu.c31,
            col("m32") * mu.c32,
        ],
        axis=-1,
    )
    zero = np.zeros(additive_terms.shape[:-1])
    extra = [zero, zero, zero]
    if mu.acceleration is not None and g2_sensitivity is not None:
        g = np.asarray(g2_sensitivity, dtype=float)
        if g.shape != (c.shape[0], 6):
            raise ValueError("g2_sensitivity must have shape (sensors, 6)")
        extra[0] = np.sum(g[(*expand, slice(None))] * mu.acceleration[None], axis=-1)
    q1 = 3.0 * col("k3") * mu.m2 + 5.0 * col("k5") * mu.m4
    q2 = 6.0 * col("k4") * mu.m2
    if mu.m3 is not None:
        extra[1] = col("k3") * mu.m3
        q1 = q1 + 4.0 * col("k4") * mu.m3
        q2 = q2 + 10.0 * col("k5") * mu.m3
    if mu.m5 is not None:
        extra[2] = col("k5") * mu.m5
    q = np.stack([q1, q2, 10.0 * col("k5") * mu.m2], axis=-1)
    powers = np.stack([mu.omega, mu.omega**2, mu.omega**3], axis=-1)
    multiplicative_terms = q * powers
    additive = additive_terms.sum(axis=-1)
    multiplicative = multiplicative_terms.sum(axis=-1)
    squares = np.sum(additive_terms**2, axis=-1)
    extra_terms = np.stack(np.broadcast_arrays(*extra), axis=-1)
    if mu.has_linear or mu.has_odd:
        additive = additive + extra_terms.sum(axis=-1)
        squares = squares + np.sum(extra_terms**2, axis=-1)
    rms = np.sqrt(squares + np.sum(multiplicative_terms**2, axis=-1))
    return VibrationError(
        additive_terms=additive_terms,
        multiplicative_coefficients=q,
        additive=additive,
        multiplicative=multiplicative,
        total=additive + multiplicative,
        rms=rms,
        extra_terms=extra_terms,
    )
