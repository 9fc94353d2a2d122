"""Pydantic models of a catalogue file (README.md, "Catalogue files").

The models describe one file exactly as written, in the file's own rate unit.
Conversion to deg/s and the merging of several files happen in
:mod:`gyrovib.catalog.loader`.

These models are the authority on the format (the JSON Schema, and the
messages for a file that is not valid); a valid file is built as the plain
records of :mod:`gyrovib.catalog.records`, which mirror them without pydantic.
"""

from __future__ import annotations

import math
from typing import Annotated, Literal

from pydantic import (
    BaseModel,
    ConfigDict,
    Field,
    StringConstraints,
    field_validator,
    model_validator,
)
from pydantic_core import PydanticCustomError

from gyrovib.catalog.records import breakpoint_problem, psd_has_band

Number = Annotated[float, Field(strict=True, allow_inf_nan=False)]
NonNegative = Annotated[float, Field(strict=True, allow_inf_nan=False, ge=0)]
Positive = Annotated[float, Field(strict=True, allow_inf_nan=False, gt=0)]
Coherence = Annotated[float, Field(strict=True, allow_inf_nan=False, ge=-1, le=1)]
Identifier = Annotated[
    str,
    StringConstraints(pattern=r"^[A-Za-z0-9._-]+$", min_length=1, max_length=200),
    Field(strict=True),
]
Text = Annotated[str, Field(strict=True, max_length=10_000)]
Triple = tuple[Number, Number, Number]
NonNegativeTriple = tuple[NonNegative, NonNegative, NonNegative]
Breakpoint = tuple[Positive, NonNegative]

RateUnit = Literal["deg/s", "deg/h", "rad/s", "rpm"]


def _check_breakpoints(table: list[tuple[float, float]]) -> list[tuple[float, float]]:
    """Pydantic form of :func:`breakpoint_problem`: the error's context carries
    ``index``, the offending row, so the loader can point at it."""
    problem = breakpoint_problem(table)
    if problem is not None:
        raise PydanticCustomError("breakpoint_order", problem[1], {"index": problem[0]})
    return table


def _check_band(table: list[tuple[float, float]]) -> list[tuple[float, float]]:
    """A PSD is integrated between its breakpoints: it needs two distinct frequencies."""
    if not psd_has_band(table):
        raise ValueError(
            "a PSD needs breakpoints at two different frequencies at least: "
            "it is integrated over the band between them"
        )
    return table


Table = Annotated[list[Breakpoint], Field(min_length=1, max_length=100_000)]


class _Model(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)


class Units(_Model):
    """``units:`` — the rate unit of every rate, PSD and coefficient in the file."""

    rate: RateUnit = "deg/s"


class Coefficients(_Model):
    """Eq. (2), in rate units: an omitted coefficient is 0, except ``k1 = 1``."""

    k0: Number = 0.0
    k1: Number = 1.0
    A1: Number = 0.0
    k2: Number = 0.0
    k3: Number = 0.0
    k4: Number = 0.0
    k5: Number = 0.0
    m1: Number = 0.0
    m2: Number = 0.0
    m31: Number = 0.0
    m32: Number = 0.0


class OutputCoefficients(_Model):
    """Eq. (1), in output units per rate unit; divided by ``K1`` to give eq. (2)."""

    unit: Text | None = None
    K1: Number
    K0: Number = 0.0
    A1: Number = 0.0
    K2: Number = 0.0
    K3: Number = 0.0
    K4: Number = 0.0
    K5: Number = 0.0
    M1: Number = 0.0
    M2: Number = 0.0
    M31: Number = 0.0
    M32: Number = 0.0

    @field_validator("K1")
    @classmethod
    def _k1_nonzero(cls, value: float) -> float:
        if value == 0:
            raise ValueError(
                "K1 (output per rate unit) must not be zero: it divides every other coefficient"
            )
        return value

    @model_validator(mode="after")
    def _divisible(self) -> OutputCoefficients:
        for name in ("K0", "K2", "K3", "K4", "K5", "M1", "M2", "M31", "M32"):
            if not math.isfinite(getattr(self, name) / self.K1):
                raise ValueError(
                    f"K1 = {self.K1:g} is so small that {name} / K1 overflows; "
                    "check the units of K1"
                )
        return self

    def to_coefficients(self) -> Coefficients:
        """``k0 = K0/K1``, ``kn = Kn/K1``, ``mi = Mi/K1``, ``m3i = M3i/K1``; k1 = 1."""
        k = self.K1
        return Coefficients(
            k0=self.K0 / k,
            k1=1.0,
            A1=self.A1,
            k2=self.K2 / k,
            k3=self.K3 / k,
            k4=self.K4 / k,
            k5=self.K5 / k,
            m1=self.M1 / k,
            m2=self.M2 / k,
            m31=self.M31 / k,
            m32=self.M32 / k,
        )


class Sensor(_Model):
    """One angular-rate sensor: its conversion function and, optionally, ν_sensor(f)."""

    id: Identifier
    name: Text | None = None
    vendor: Text | None = None
    part: Text | None = None
    notes: Text | None = None
    range: Positive | None = None
    coefficients: Coefficients | None = None
    output_coefficients: OutputCoefficients | None = None
    response: Table | None = None

    _check_response = field_validator("response")(
        classmethod(lambda cls, v: None if v is None else _check_breakpoints(v))
    )

    @model_validator(mode="after")
    def _one_form(self) -> Sensor:
        if (self.coefficients is None) == (self.output_coefficients is None):
            raise ValueError(
                "give the conversion function once: either 'coefficients' (eq. 2) "
                "or 'output_coefficients' (eq. 1)"
            )
        return self

    @property
    def rate_coefficients(self) -> Coefficients:
        """The eq. (2) coefficients, whichever form the file used."""
        if self.coefficients is not None:
            return self.coefficients
        assert self.output_coefficients is not None
        return self.output_coefficients.to_coefficients()


class Tone(_Model):
    """One harmonic tone of eq. (3): per-axis amplitude (rate) and phase (degrees)."""

    frequency: Positive
    amplitude: NonNegativeTriple
    phase: Triple = (0.0, 0.0, 0.0)


class PSD(_Model):
    """Per-axis PSD breakpoints, rate²/Hz; an axis left out has none."""

    x1: Table | None = None
    x2: Table | None = None
    x3: Table | None = None

    _check = field_validator("x1", "x2", "x3")(
        classmethod(lambda cls, v: None if v is None else _check_band(_check_breakpoints(v)))
    )

    @model_validator(mode="after")
    def _some_axis(self) -> PSD:
        if self.x1 is None and self.x2 is None and self.x3 is None:
            raise ValueError("give the PSD of at least one axis (x1, x2 or x3)")
        return self


class Random(_Model):
    """The Gaussian broadband part: a PSD or the RMS per axis at the sensor."""

    psd: PSD | None = None
    rms: NonNegativeTriple | None = None
    coherence: tuple[Coherence, Coherence] = (1.0, 1.0)

    @model_validator(mode="after")
    def _one_form(self) -> Random:
        if (self.psd is None) == (self.rms is None):
            raise ValueError("give the random part as 'psd' or as 'rms', exactly one of them")
        return self


class Profile(_Model):
    """One vibration environment with the carrier's own rate Ω_K."""

    id: Identifier
    name: Text | None = None
    notes: Text | None = None
    rate: Triple = (0.0, 0.0, 0.0)
    harmonic: Annotated[list[Tone], Field(max_length=64)] = []
    random: Random | None = None
    mount: Table | None = None

    _check_mount = field_validator("mount")(
        classmethod(lambda cls, v: None if v is None else _check_breakpoints(v))
    )


Weight = Annotated[float, Field(strict=True, allow_inf_nan=False, gt=0)]


class Allocation(_Model):
    """How the budget is split (eq. 18, 21, 24): ratio r and share weights w, v."""

    r: Weight = 1.5
    w: tuple[Weight, Weight, Weight, Weight, Weight] = (1.0, 1.0, 1.0, 0.5, 0.5)
    v: tuple[Weight, Weight, Weight] = (1.0, 0.5, 0.5)


class CatalogFile(_Model):
    """A whole catalogue file. ``gyrovib: 1`` is required."""

    gyrovib: Annotated[int, Field(strict=True)]
    units: Units = Units()
    sensors: list[Sensor] = []
    profiles: list[Profile] = []
    allocation: Allocation | None = None

    @field_validator("gyrovib")
    @classmethod
    def _version(cls, value: int) -> int:
        if value != 1:
            raise ValueError(f"unsupported format version {value}; this gyrovib reads version 1")
        return value
