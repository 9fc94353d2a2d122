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
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from gyrovib.core.statistics import (
    PAPER_RANDOM_ASYMMETRY,
    PAPER_TONE_ASYMMETRY,
    Vibration,
    rectified_excess,
)
from gyrovib.core.transmissibility import FloatArray
from gyrovib.errors import ModelError

#: Column order of a coefficient matrix (eq. 2).
COEFFICIENTS: tuple[str, ...] = ("k0", "k1", "A1", "k2", "k3", "k4", "k5", "m1", "m2", "m31", "m32")
COLUMN: dict[str, int] = {name: i for i, name in enumerate(COEFFICIENTS)}
#: Names of the additive terms Δ0(1..5): the coefficient each is proportional to.
ADDITIVE_TERMS: tuple[str, ...] = ("A1", "k2", "k4", "m31", "m32")
#: Names of the multiplicative coefficients Δ(1..3).
MULTIPLICATIVE_TERMS: tuple[str, ...] = ("q1", "q2", "q3")

METHODS = ("exact", "paper")


@dataclass(frozen=True)
class Multipliers:
    """What the error needs from a vibration, at each rate Ω_K3.

    All arrays share one shape (profiles, or profiles × rates).
    """

    asymmetry: FloatArray
    m2: FloatArray
    m4: FloatArray
    c31: FloatArray
    c32: FloatArray
    omega: FloatArray


def paper_kind(vibration: Vibration) -> str:
    """``"none"``, ``"tone"`` or ``"random"``: the cases the paper's formulas cover.

    Raises :class:`ModelError` for any other profile.
    """
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
    vibration: Vibration, omega: ArrayLike, method: str = "exact"
) -> Multipliers:
    """Multipliers of one vibration at the rates ``omega`` (any shape)."""
    w = np.asarray(omega, dtype=float)
    ones = np.ones_like(w)
    m2, m4 = vibration.m2, vibration.m4
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
    )


def stack_multipliers(items: Sequence[Multipliers]) -> Multipliers:
    """Stack per-profile multipliers along a new leading (profile) axis."""
    return Multipliers(
        *(np.stack([getattr(m, f) for m in items]) for f in Multipliers.__dataclass_fields__)
    )


@dataclass(frozen=True)
class VibrationError:
    """Eq. (13)-(16) for every sensor × profile (× rate): arrays in rate units.

    ``additive_terms[..., p]`` is Δ0(p+1); ``multiplicative_coefficients[..., q]``
    is Δ(q+1) (unit rate^-q); ``additive`` Δ_VA; ``multiplicative`` Δ_VM(Ω);
    ``total`` Δ_V; ``rms`` Δ_V(RMS).
    """

    additive_terms: FloatArray
    multiplicative_coefficients: FloatArray
    additive: FloatArray
    multiplicative: FloatArray
    total: FloatArray
    rms: FloatArray


def vibration_error(coefficients: ArrayLike, multipliers: Multipliers) -> VibrationError:
    """Evaluate eq. (14)-(16) for a coefficient matrix (sensors × 11, see COEFFICIENTS).

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
    q = np.stack(
        [
            3.0 * col("k3") * mu.m2 + 5.0 * col("k5") * mu.m4,
            6.0 * col("k4") * mu.m2,
            10.0 * col("k5") * mu.m2,
        ],
        axis=-1,
    )
    powers = np.stack([mu.omega, mu.omega**2, mu.omega**3], axis=-1)
    multiplicative_terms = q * powers
    additive = additive_terms.sum(axis=-1)
    multiplicative = multiplicative_terms.sum(axis=-1)
    rms = np.sqrt(np.sum(additive_terms**2, axis=-1) + np.sum(multiplicative_terms**2, axis=-1))
    return VibrationError(
        additive_terms=additive_terms,
        multiplicative_coefficients=q,
        additive=additive,
        multiplicative=multiplicative,
        total=additive + multiplicative,
        rms=rms,
    )
