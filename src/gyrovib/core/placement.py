"""How a sensor sits in the vehicle: signed permutations of the axes (docs/model.md section 12).

Profiles, missions and recordings are written in vehicle axes X, Y, Z (a
profile's axes 1, 2, 3 are X, Y, Z). A :class:`Placement` says, for each sensor
axis x1, x2, x3, which vehicle axis it lies on and with which sign:
``x_i = s_i · V[π(i)]``. It is a signed permutation with determinant +1 (a
proper rotation: a mirror image of a gyro does not exist).

Mapping a profile into sensor axes, for per-axis data ``v`` (index = axis):

* signed quantities (carrier rates Ω_K, tone phasors): ``v'_i = s_i · v[π(i)]``;
* magnitudes (amplitudes, RMS, PSD levels): ``v'_i = v[π(i)]``;
* phases in degrees: ``φ'_i = φ[π(i)] + 180°`` where ``s_i = −1``
  (a flipped axis negates its signal, so its odd moments change sign);
* coherences, as a correlation matrix: ``R'_ij = s_i·s_j·R[π(i), π(j)]``
  (a coherence that involves exactly one flipped axis changes sign).

The default placement x1 = +X, x2 = +Y, x3 = +Z maps everything to itself.
A triad is the three placements that put x3 on +X, +Y and +Z with
(x1, x2) = (+Y, +Z), (+Z, +X), (+X, +Y): the cyclic rotations.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from gyrovib.core._types import FloatArray

#: Vehicle axis names, in index order.
AXES = ("X", "Y", "Z")
_TERM = re.compile(r"^\s*x([123])\s*=\s*([+-]?)\s*([XYZxyz])\s*$")


@dataclass(frozen=True, slots=True)
class Placement:
    """A signed permutation of the axes with determinant +1.

    ``source[i]``: the vehicle axis (0 = X, 1 = Y, 2 = Z) that sensor axis
    x(i+1) lies on; ``sign[i]``: +1 or −1.
    """

    source: tuple[int, int, int] = (0, 1, 2)
    sign: tuple[int, int, int] = (1, 1, 1)

    def __post_init__(self) -> None:
        if sorted(self.source) != [0, 1, 2]:
            raise ValueError("a placement must put the three sensor axes on three different "
                             "vehicle axes")
        if any(s not in (1, -1) for s in self.sign):
            raise ValueError("each axis sign must be +1 or -1")
        if round(self.determinant) != 1:
            raise ValueError(f"placement {self} has determinant -1: it is a mirror image, "
                             "not a rotation (flip one more axis, or swap two)")

    # ----------------------------------------------------------- properties

    @property
    def matrix(self) -> FloatArray:
        """The (3, 3) matrix P with ``x_sensor = P · V_vehicle``."""
        m = np.zeros((3, 3))
        m[np.arange(3), list(self.source)] = self.sign
        return m

    @property
    def determinant(self) -> float:
        return float(np.linalg.det(self.matrix))

    @property
    def is_default(self) -> bool:
        return self.source == (0, 1, 2) and self.sign == (1, 1, 1)

    @property
    def axis(self) -> str:
        """The vehicle axis the sensitive axis x3 lies on, e.g. ``"X"``."""
        return AXES[self.source[2]]

    def __str__(self) -> str:
        return ",".join(f"x{i + 1}={'+' if s > 0 else '-'}{AXES[a]}"
                        for i, (a, s) in enumerate(zip(self.source, self.sign, strict=True)))

    # --------------------------------------------------------------- mapping

    def signed(self, values: ArrayLike) -> FloatArray | NDArray[np.complex128]:
        """Signed per-axis data (last axis of length 3): ``v'_i = s_i·v[π(i)]``."""
        v = np.asarray(values)
        if not np.iscomplexobj(v):
            v = v.astype(float)
        out: FloatArray | NDArray[np.complex128] = (
            v[..., list(self.source)] * np.asarray(self.sign, dtype=float))
        return out

    def magnitudes(self, values: ArrayLike) -> FloatArray:
        """Unsigned per-axis data (amplitudes, RMS, PSD levels): ``v'_i = v[π(i)]``."""
        out: FloatArray = np.asarray(values, dtype=float)[..., list(self.source)]
        return out

    def phases(self, degrees: ArrayLike) -> FloatArray:
        """Per-axis phases in degrees: ``φ'_i = φ[π(i)] + 180°`` on a flipped axis."""
        ph = np.asarray(degrees, dtype=float)[..., list(self.source)]
        out: FloatArray = ph + np.where(np.asarray(self.sign) < 0, 180.0, 0.0)
        return out

    def correlation(self, matrix: ArrayLike) -> FloatArray:
        """A (3, 3) correlation matrix: ``R'_ij = s_i·s_j·R[π(i), π(j)]``."""
        p = self.matrix
        out: FloatArray = p @ np.asarray(matrix, dtype=float) @ p.T
        return out

    def rate_coherence(self, rho31: float, rho32: float, rho12: float | None = None
                       ) -> tuple[float, float, float]:
        """A rate profile's coherences (ρ31, ρ32, ρ12) in sensor axes.

        ``ρ12`` omitted is ``ρ31·ρ32`` (one common source), docs/model.md section 12.
        """
        r12 = rho31 * rho32 if rho12 is None else rho12
        r = self.correlation(rate_correlation(rho31, rho32, r12))
        return float(r[2, 0]), float(r[2, 1]), float(r[0, 1])

    def pair_coherence(self, rho12: float, rho13: float, rho23: float
                       ) -> tuple[float, float, float]:
        """An acceleration block's coherences (ρ12, ρ13, ρ23) in sensor axes."""
        m = np.eye(3)
        m[0, 1] = m[1, 0] = rho12
        m[0, 2] = m[2, 0] = rho13
        m[1, 2] = m[2, 1] = rho23
        r = self.correlation(m)
        return float(r[0, 1]), float(r[0, 2]), float(r[1, 2])


def rate_correlation(rho31: float, rho32: float, rho12: float) -> FloatArray:
    """The (3, 3) correlation matrix of a rate profile's random part."""
    m = np.eye(3)
    m[2, 0] = m[0, 2] = rho31
    m[2, 1] = m[1, 2] = rho32
    m[0, 1] = m[1, 0] = rho12
    return m


#: x1 = +X, x2 = +Y, x3 = +Z: today's reading; maps everything to itself.
DEFAULT = Placement()
#: The three placements of an IMU triad, sensitive axis on +X, +Y, +Z.
TRIAD = (
    Placement((1, 2, 0), (1, 1, 1)),
    Placement((2, 0, 1), (1, 1, 1)),
    Placement((0, 1, 2), (1, 1, 1)),
)


def parse(text: str) -> Placement | tuple[Placement, ...]:
    """``"triad"``, ``"default"`` or ``"x1=+Y,x2=+Z,x3=+X"`` → placement(s).

    Raises :class:`ValueError` with a message for the user.
    """
    words = text.strip()
    if words.lower() == "triad":
        return TRIAD
    if words.lower() == "default":
        return DEFAULT
    source: dict[int, int] = {}
    sign: dict[int, int] = {}
    for term in words.split(","):
        m = _TERM.match(term)
        if m is None:
            raise ValueError(f"cannot read {term.strip()!r} as a placement term: write "
                             "x1=+Y,x2=+Z,x3=+X (each sensor axis on a signed vehicle axis), "
                             "or 'triad'")
        i = int(m.group(1)) - 1
        if i in source:
            raise ValueError(f"x{i + 1} is placed twice")
        source[i] = AXES.index(m.group(3).upper())
        sign[i] = -1 if m.group(2) == "-" else 1
    if len(source) != 3:
        missing = ", ".join(f"x{i + 1}" for i in range(3) if i not in source)
        raise ValueError(f"a placement names all three sensor axes; missing {missing}")
    return Placement((source[0], source[1], source[2]), (sign[0], sign[1], sign[2]))
