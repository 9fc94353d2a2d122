"""A whole catalogue file: the format version, the units, the sensors, the
profiles and the allocation of a budget."""

from typing import Annotated, Any, Literal

from pydantic import BeforeValidator, Field
from pydantic_core import PydanticCustomError

from gyrovib.models._types import Model, Named, Number, rule_error
from gyrovib.models.mission import Mission
from gyrovib.models.profile import Profile
from gyrovib.models.sensor import RateUnit, Sensor

#: The format version this gyrovib reads.
VERSION = 1


def _version(value: Any) -> Any:
    if type(value) is not int:
        raise PydanticCustomError("version", "the format version must be the number {expected}",
                                  {"expected": VERSION})
    if value != VERSION:
        raise rule_error(f"unsupported format version {value}; "
                         f"this gyrovib reads version {VERSION}")
    return value


class Units(Model):
    """'units:' — the units of every rate, PSD, coefficient and acceleration in the file."""

    rate: Annotated[RateUnit, Named("rate unit")] = Field(
        "deg/s", description="Unit of every rate, PSD and coefficient in this file: "
        "deg/s (default), deg/h, rad/s or rpm.")
    acceleration: Annotated[Literal["g", "m/s^2", "m/s2"], Named("acceleration unit")] = Field(
        "g", description="Unit of every linear acceleration in this file: g (default, "
        "9.80665 m/s^2) or m/s^2 (also written m/s2).")


Weight = Annotated[Number, Field(gt=0)]


class Allocation(Model):
    """How the budget is split (eq. 18, 21, 24): ratio r and share weights w, v."""

    r: Weight = Field(1.5, description="Ratio r of eq. (18); > 0.")
    #: w1..w5, or w1..w6 with w6 the weight of the g² term (MODEL.md section 8).
    w: Annotated[tuple[Weight, ...], Field(min_length=5, max_length=6)] = Field(
        (1.0, 1.0, 1.0, 0.5, 0.5),
        description="Share weights w of the five additive terms (A1, k2, k4, "
        "m31, m32), and optionally a sixth, w6, of the g² term of a profile with "
        "linear vibration (MODEL.md section 8; default 1); each > 0.")
    v: tuple[Weight, Weight, Weight] = Field(
        (1.0, 0.5, 0.5), description="Share weights v of the three multiplicative terms; "
        "each > 0.")


class Catalogue(Model):
    """A whole catalogue file. 'gyrovib: 1' is required."""

    gyrovib: Annotated[Literal[1], BeforeValidator(_version)] = Field(
        description="Format version; must be 1.")
    units: Units = Field(Units.model_construct(),
                         description="Units of the values in this file.")
    sensors: list[Sensor] = Field(
        [], description="Angular-rate sensors; ids unique across all files given.")
    profiles: list[Profile] = Field(
        [], description="Vibration environments; ids unique across all files given.")
    missions: list[Mission] = Field(
        [], description="Missions: ordered segments of profiles (docs/model.md section 12); "
        "ids unique across all files given.")
    allocation: Allocation | None = Field(
        None, description="How a budget is split among the terms (eq. 18, 21, 24).")

    @property
    def rate_unit(self) -> str:
        """The unit of every rate in the file (``units.rate``)."""
        return self.units.rate

    @property
    def acceleration_unit(self) -> str:
        """The unit of every acceleration in the file: ``"g"`` or ``"m/s^2"``
        (``m/s2`` as written is the same unit). Values are not converted here."""
        return "m/s^2" if self.units.acceleration == "m/s2" else self.units.acceleration

