"""A whole catalogue file: the format version, the units, the sensors, the
profiles and the allocation of a budget."""

from typing import Annotated, Any, Literal, get_args

from pydantic import BeforeValidator, Field, ValidationError, model_validator
from pydantic_core import InitErrorDetails, PydanticCustomError

from gyrovib import units as rate_units
from gyrovib.models._types import Model, Named, Number, rule_error
from gyrovib.models.mission import Mission
from gyrovib.models.profile import Profile
from gyrovib.models.sensor import RANGE_BAND, RANGE_WHY, RateUnit, Sensor
from gyrovib.units import STANDARD_GRAVITY

#: The acceleration units in which a bare g² sensitivity would be ambiguous.
_NOT_G = ("m/s^2", "m/s2")

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
    #: w1..w5, or w1..w6 with w6 the weight of the g² term (docs/model.md section 8).
    w: Annotated[tuple[Weight, ...], Field(min_length=5, max_length=6)] = Field(
        (1.0, 1.0, 1.0, 0.5, 0.5),
        description="Share weights w of the five additive terms (A1, k2, k4, "
        "m31, m32), and optionally a sixth, w6, of the g² term of a profile with "
        "linear vibration (docs/model.md section 8; default 1); each > 0.")
    v: tuple[Weight, Weight, Weight] = Field(
        (1.0, 0.5, 0.5), description="Share weights v of the three multiplicative terms; "
        "each > 0.")


def range_band(unit: str) -> tuple[float, float]:
    """:data:`RANGE_BAND` (deg/s) in the rate ``unit``."""
    s = rate_units.scale(unit)
    return RANGE_BAND[0] / s, RANGE_BAND[1] / s


def _unit_rules_schema() -> dict[str, Any]:
    """What JSON Schema can say of :meth:`Catalogue._unit_rules`: each range within the
    band of the file's rate unit."""
    default = str(Units.model_fields["rate"].default)
    others = [u for u in get_args(RateUnit) if u != default]

    def when(unit: str) -> dict[str, Any]:
        return {"required": ["units"], "properties": {"units": {
            "required": ["rate"], "properties": {"rate": {"const": unit}}}}}

    def band(unit: str) -> dict[str, Any]:
        low, high = range_band(unit)
        bounded = {"minimum": low, "maximum": high}
        return {"properties": {"sensors": {"items": {"properties": {
            "range": bounded, "specs": {"properties": {"range": bounded}}}}}}}

    rules = [{"if": when(u), "then": band(u)} for u in others]
    rules.append({"if": {"not": {"anyOf": [when(u) for u in others]}}, "then": band(default)})
    # a g² sensitivity in a file whose acceleration unit is not g carries its unit
    written = {"not": {"type": "number", "not": {"const": 0}}}
    rules.append({
        "if": {"required": ["units"], "properties": {"units": {
            "required": ["acceleration"], "properties": {"acceleration": {"enum": list(_NOT_G)}}}}},
        "then": {"properties": {"sensors": {"items": {"properties": {
            "vre": written, "specs": {"properties": {"vre": written}},
            "g2_sensitivity": {"additionalProperties": written, "properties": {
                k: written for k in ("G11", "G22", "G33", "G12", "G13", "G23")}}}}}}}})
    return {"allOf": rules}


class Catalogue(Model):
    """A whole catalogue file. 'gyrovib: 1' is required."""

    model_config = Model.model_config | {"json_schema_extra": _unit_rules_schema()}

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

    @model_validator(mode="after")
    def _unit_rules(self) -> "Catalogue":
        """The rules that need the file's units: ranges in their band, an absolute
        nonlinearity within the range."""
        problems = [(i, p) for i, sensor in enumerate(self.sensors)
                    for p in _range_problems(sensor, self.units.rate)]
        if self.units.acceleration in _NOT_G:
            problems += [(i, (loc, value, _bare_g2(loc, value, self.units.rate,
                                                    self.acceleration_unit)))
                         for i, sensor in enumerate(self.sensors)
                         for loc, value in sensor.bare_g2()]
        problems.sort(key=lambda p: p[0])
        found = [InitErrorDetails(type=rule_error(message), loc=("sensors", i, *loc),
                                  input=value)
                 for i, (loc, value, message) in problems]
        if found:
            raise ValidationError.from_exception_data("Catalogue", found)
        return self

    @property
    def rate_unit(self) -> str:
        """The unit of every rate in the file (``units.rate``)."""
        return self.units.rate

    @property
    def acceleration_unit(self) -> str:
        """The unit of every acceleration in the file: ``"g"`` or ``"m/s^2"``
        (``m/s2`` as written is the same unit). Values are not converted here."""
        return "m/s^2" if self.units.acceleration == "m/s2" else self.units.acceleration


def _range_problems(sensor: Sensor, unit: str) -> list[tuple[tuple[str, ...], float, str]]:
    """(where, value, message) of every range outside :data:`RANGE_BAND` and every
    absolute nonlinearity larger than its range, ``unit`` the file's rate unit."""
    out: list[tuple[tuple[str, ...], float, str]] = []
    s = rate_units.scale(unit)
    low, high = range_band(unit)
    places: list[tuple[tuple[str, ...], float | None]] = [(("range",), sensor.range)]
    if sensor.specs is not None:
        places.append((("specs", "range"), sensor.specs.range))
    for loc, value in places:
        if value is not None and not low <= value <= high:
            band = f"{RANGE_BAND[0]:g} to {RANGE_BAND[1]:g} deg/s"
            if unit != "deg/s":
                band += f" ({low:.4g} to {high:.4g} {unit})"
            out.append((loc, value, f"a full-scale range of {value:g} {unit} is outside "
                        f"{band}, the band of any gyro's range: {RANGE_WHY}"))
    spec = sensor.specs
    if spec is not None and spec.nonlinearity.unit != "%FS" and not out:
        nl = spec.nonlinearity
        b = nl.value * rate_units.scale(nl.unit)
        if b > spec.range * s:
            out.append((("specs", "nonlinearity", "value"), nl.value,
                        f"a nonlinearity of {nl.value:g} {nl.unit} is more than the range "
                        f"({spec.range:g} {unit}): a residual larger than the full scale "
                        "is not a gyro's nonlinearity"))
    return out


def _bare_g2(loc: tuple[str, ...], value: float, rate: str, acceleration: str) -> str:
    """Why a bare g² sensitivity is refused in a file whose acceleration unit is not g:
    both readings, and how to write the one meant."""
    ratio = STANDARD_GRAVITY**2
    key = loc[-1]
    return (f"a bare g² sensitivity is read per g², but this file's accelerations are in "
            f"{acceleration}: {value:g} read per g² is {value:g} {rate}/g²; read per "
            f"({acceleration})² it would be {value * ratio:.4g} {rate}/g², {ratio:.3g}× "
            f"larger. Write the unit: '{key}: {value:g} {rate}/g^2' (a datasheet's VRE) or "
            f"'{key}: {{value: {value:g}, unit: {rate}/(m/s^2)^2}}'")
