"""A sensor: its conversion function (eq. 1, eq. 2 or a datasheet), its own
response and its g² sensitivity. Values are in the file's units."""

import math
import re
from typing import Annotated, Any, ClassVar, Literal, get_args

from pydantic import (
    AfterValidator,
    Discriminator,
    Field,
    Strict,
    Tag,
    WithJsonSchema,
    field_validator,
    model_validator,
)

from gyrovib.errors import CatalogError
from gyrovib.models._types import (
    FREE_TEXT,
    ID_TEXT,
    MAX_MAGNITUDE,
    NUMBER_TEXT,
    RATE,
    Group,
    Hint,
    Identifier,
    Model,
    Named,
    Number,
    Table,
    Text,
    by_kind,
    groups_schema,
    in_unit,
    one_of,
    raise_at,
    rule_error,
    value_kind,
)
from gyrovib.models.noise import Noise
from gyrovib.models.uncertainty import LotSpread, Uncertainty

#: Units a rate may be written in (``units.rate``).
RateUnit = Literal["deg/s", "deg/h", "rad/s", "rpm"]
#: Units of a datasheet nonlinearity: percent of full scale, or an absolute rate.
NonlinearityUnit = Literal["%FS", "deg/s", "deg/h", "rad/s", "rpm"]

# ---------------------------------------------------------------- eq. (2)


def _rate_coefficient(default: float, text: str) -> Any:
    return Field(default, description=text, json_schema_extra=in_unit("rate"))


class Coefficients(Model):
    """Eq. (2), in rate units: an omitted coefficient is 0, except 'k1 = 1'."""

    k0: Number = _rate_coefficient(0.0, f"Bias, {RATE}.")
    k1: Number = _rate_coefficient(1.0, "Scale factor (1 in eq. 2).")
    A1: Number = _rate_coefficient(0.0, "Scale-factor asymmetry (dimensionless).")
    k2: Number = _rate_coefficient(0.0, "Second-order nonlinearity, rate^-1.")
    k3: Number = _rate_coefficient(0.0, "Third-order nonlinearity, rate^-2.")
    k4: Number = _rate_coefficient(0.0, "Fourth-order nonlinearity, rate^-3.")
    k5: Number = _rate_coefficient(0.0, "Fifth-order nonlinearity, rate^-4.")
    m1: Number = _rate_coefficient(0.0, "Cross-axis sensitivity to x1 (dimensionless).")
    m2: Number = _rate_coefficient(0.0, "Cross-axis sensitivity to x2 (dimensionless).")
    m31: Number = _rate_coefficient(0.0, "Product cross-axis term x3·x1, rate^-1.")
    m32: Number = _rate_coefficient(0.0, "Product cross-axis term x3·x2, rate^-1.")


# ---------------------------------------------------------------- eq. (1)


def _output_coefficient(name: str) -> Any:
    return Field(0.0, description=f"As {name.lower()} of eq. (2), times K1 (output units).",
                 json_schema_extra=in_unit("output"))


class OutputCoefficients(Model):
    """Eq. (1), in output units per rate unit; divided by 'K1' to give eq. (2)."""

    unit: Text | None = Field(None, description="The output unit (free text, e.g. mV or LSB).")
    K1: Number = Field(description="Scale factor, output per rate unit; required and non-zero.",
                       json_schema_extra={**in_unit("output/rate"), "not": {"const": 0}})
    K0: Number = Field(0.0, description="Bias, output units.", json_schema_extra=in_unit("output"))
    A1: Number = Field(0.0, description="Scale-factor asymmetry (dimensionless).")
    K2: Number = _output_coefficient("K2")
    K3: Number = _output_coefficient("K3")
    K4: Number = _output_coefficient("K4")
    K5: Number = _output_coefficient("K5")
    M1: Number = _output_coefficient("M1")
    M2: Number = _output_coefficient("M2")
    M31: Number = _output_coefficient("M31")
    M32: Number = _output_coefficient("M32")

    @field_validator("K1")
    @classmethod
    def _k1_nonzero(cls, value: float) -> float:
        if value == 0:
            raise rule_error("K1 (output per rate unit) must not be zero: "
                             "it divides every other coefficient")
        return value

    @model_validator(mode="after")
    def _divisible(self) -> "OutputCoefficients":
        k1 = self.K1
        for name in ("K0", "K2", "K3", "K4", "K5", "M1", "M2", "M31", "M32"):
            if not math.isfinite(getattr(self, name) / k1):
                raise rule_error(f"K1 = {k1:g} is so small that {name} / K1 overflows; "
                                 "check the units of K1")
        return self

    def to_coefficients(self) -> Coefficients:
        """``k0 = K0/K1``, ``kn = Kn/K1``, ``mi = Mi/K1``, ``m3i = M3i/K1``; k1 = 1."""
        k = self.K1
        return Coefficients.model_construct(
            k0=self.K0 / k, k1=1.0, A1=self.A1, k2=self.K2 / k, k3=self.K3 / k,
            k4=self.K4 / k, k5=self.K5 / k, m1=self.M1 / k, m2=self.M2 / k,
            m31=self.M31 / k, m32=self.M32 / k)


# ---------------------------------------------------------------- g² sensitivity

G2_WHY = (" (in its unit: datasheets quote "
          "about 1e-3 deg/s/g², and the model squares it times the acceleration to the 4th "
          "power, which must stay a finite floating-point number)")
#: One g² sensitivity term, signed and bounded.
G2Term = Annotated[Number, Field(ge=-MAX_MAGNITUDE, le=MAX_MAGNITUDE), Hint(G2_WHY)]
#: A g² sensitivity bound (a datasheet VRE), >= 0.
G2Bound = Annotated[Number, Field(ge=0, le=MAX_MAGNITUDE), Hint(G2_WHY)]

#: How "per acceleration squared" may be written: per g², or per (m/s²)².
G2_PER = {"g^2": "g", "g²": "g", "(m/s^2)^2": "m/s^2", "(m/s²)²": "m/s^2"}
#: Every unit a g² sensitivity may be written in: a rate unit per acceleration².
G2Unit = Literal[
    "deg/s/g^2", "deg/s/g²", "deg/s/(m/s^2)^2", "deg/s/(m/s²)²", "deg/h/g^2", "deg/h/g²",
    "deg/h/(m/s^2)^2", "deg/h/(m/s²)²", "rad/s/g^2", "rad/s/g²", "rad/s/(m/s^2)^2",
    "rad/s/(m/s²)²", "rpm/g^2", "rpm/g²", "rpm/(m/s^2)^2", "rpm/(m/s²)²"]
#: A g² sensitivity written as text: a number, spaces, a unit ("0.0004 deg/s/g^2").
G2_TEXT = (rf"^ *({NUMBER_TEXT}) +((?:{'|'.join(re.escape(r) for r in get_args(RateUnit))})/"
           rf"(?:{'|'.join(re.escape(a) for a in G2_PER)})) *$")


class G2Quantity(Model):
    """A g² sensitivity with its unit: a rate unit per g² or per (m/s²)²."""

    value: G2Term = Field(description="The value, in unit; signed.")
    unit: Annotated[G2Unit, Named("g² sensitivity unit")] = Field(
        description="A rate unit per g² (deg/s/g^2, a datasheet VRE's) or per (m/s²)² "
        "(deg/s/(m/s^2)^2).")

    @property
    def rate_unit(self) -> str:
        """The rate unit of :attr:`unit` (``deg/s``, ...)."""
        return str(self.unit).split("/" + self.per, 1)[0]

    @property
    def per(self) -> str:
        """The acceleration² part of :attr:`unit` as written (``g^2``, ``(m/s^2)^2``, ...)."""
        return next(a for a in G2_PER if str(self.unit).endswith("/" + a))

    @property
    def acceleration_unit(self) -> str:
        """The acceleration unit squared in :attr:`unit`: ``g`` or ``m/s^2``."""
        return G2_PER[self.per]


class G2BoundQuantity(G2Quantity):
    """A g² sensitivity bound (a VRE) with its unit; >= 0."""

    value: G2Bound = Field(description="The value, in unit; >= 0.")


def _g2_text(value: str) -> G2Quantity:
    match = re.match(G2_TEXT, value)
    if match is None:
        raise rule_error(
            f"cannot read {value!r} as a g² sensitivity: write a number, a space and a unit, "
            "a rate unit per g² or per (m/s²)², e.g. '0.0004 deg/s/g^2' "
            "(rate units: " + ", ".join(get_args(RateUnit)) + "; per " + ", ".join(G2_PER)
            + ")")
    return G2Quantity(value=float(match.group(1)), unit=match.group(2))


def _in_band(q: G2Quantity, low: float) -> G2Quantity:
    if not low <= q.value <= MAX_MAGNITUDE:
        raise rule_error(f"{q.value!r} {q.unit} is outside [{low:g}, {MAX_MAGNITUDE:g}]{G2_WHY}")
    return q


def _signed(q: G2Quantity) -> G2Quantity:
    return _in_band(q, -MAX_MAGNITUDE)


def _non_negative(q: G2Quantity) -> G2Quantity:
    return _in_band(q, 0.0)


_G2_KIND = Discriminator(value_kind, custom_error_type="kind", custom_error_message=(
    "a number (rate per g²), a text such as '0.0004 deg/s/g^2' or a mapping {value, unit}"))
_G2_TEXT_SCHEMA = WithJsonSchema({"type": "string", "pattern": G2_TEXT})

#: A signed g² sensitivity term as written: a bare number (rate per g²), a text such as
#: '0.0004 deg/s/g^2' or a mapping {value, unit}.
G2Value = Annotated[
    Annotated[G2Term, Tag("<number>")]
    | Annotated[str, Strict(), AfterValidator(_g2_text), AfterValidator(_signed),
                _G2_TEXT_SCHEMA, Tag("<text>")]
    | Annotated[G2Quantity, Tag("<mapping>")], _G2_KIND]
#: A g² sensitivity bound (a VRE) as written, >= 0.
G2BoundValue = Annotated[
    Annotated[G2Bound, Tag("<number>")]
    | Annotated[str, Strict(), AfterValidator(_g2_text), AfterValidator(_non_negative),
                _G2_TEXT_SCHEMA, Tag("<text>")]
    | Annotated[G2BoundQuantity, Tag("<mapping>")], _G2_KIND]
#: What a g² sensitivity holds once validated: rate per g² (a bare number), or a value
#: with its unit; :mod:`gyrovib.api` converts it.
G2Written = float | G2Quantity


def _written(value: Any) -> G2Written:
    """A validated g² sensitivity (a text has become a :class:`G2Quantity`)."""
    assert isinstance(value, (float, G2Quantity))
    return value


def _g(text: str) -> Any:
    return Field(0.0, description=text, json_schema_extra=in_unit("rate/g^2"))


class G2Sensitivity(Model):
    """Acceleration-squared sensitivity (IEEE 528/1431), signed: each term rate per g²
    (a bare number), or written with its unit ('0.0004 deg/s/(m/s^2)^2', {value, unit})."""

    G11: G2Value = _g("G11: along x1 squared (a datasheet VRE), rate/g².")
    G22: G2Value = _g("G22: along x2 squared, rate/g².")
    G33: G2Value = _g("G33: along x3 squared, rate/g².")
    G12: G2Value = _g("G12: anisoelastic x1·x2, rate/g².")
    G13: G2Value = _g("G13: anisoelastic x1·x3, rate/g².")
    G23: G2Value = _g("G23: anisoelastic x2·x3, rate/g².")


# ---------------------------------------------------------------- datasheet

#: The band a full-scale range may lie in, deg/s (converted to the file's rate unit).
RANGE_BAND = (1e-3, 1e7)
RANGE_WHY = ("from a slow-rate gyro's milli-degree per second to ten million deg/s "
             "(28,000 revolutions per second), beyond any spinning body a gyro is put on")
#: The largest nonlinearity in %FS: a residual larger than the full scale is no gyro.
MAX_NONLINEARITY_PERCENT = 100.0
#: The largest scale-factor asymmetry, in %.
MAX_ASYMMETRY_PERCENT = 100.0


class Nonlinearity(Model):
    """A datasheet nonlinearity: the bound on the residual from a reference line."""

    value: Annotated[Number, Field(gt=0)] = Field(description="The bound; > 0.")
    unit: Annotated[NonlinearityUnit, Named("nonlinearity unit")] = Field(
        description="%FS, or a rate unit (deg/s, deg/h, rad/s, rpm; not "
        "necessarily the file's) for an absolute bound.")
    fit: Annotated[Literal["least-squares", "minimax", "endpoint"], Named("fit")] = Field(
        "least-squares",
        description="Reference line: least-squares (default), minimax or endpoint.")
    measure: Annotated[Literal["max", "rms"], Named("measure")] = Field(
        "max", description="max (default): every point within the bound; rms: the RMS "
        "residual (not with fit minimax).")
    of: Annotated[Literal["range", "span"], Named("base")] = Field(
        "range",
        description="%FS of the range R (default) or of the span 2R; only with %FS.")

    model_config = Model.model_config | {"json_schema_extra": {"allOf": [
        {"if": {"required": ["unit"], "properties": {"unit": {"enum": list(get_args(RateUnit))}}},
         "then": {"not": {"required": ["of"]}}},
        {"not": {"required": ["measure", "fit"], "properties": {
            "measure": {"const": "rms"}, "fit": {"const": "minimax"}}}},
        {"if": {"required": ["unit"], "properties": {"unit": {"const": "%FS"}}},
         "then": {"properties": {"value": {"maximum": MAX_NONLINEARITY_PERCENT}}}}]}}

    @model_validator(mode="after")
    def _rules(self) -> "Nonlinearity":
        if self.unit == "%FS" and self.value > MAX_NONLINEARITY_PERCENT:
            raise_at(("value",), rule_error(
                f"a nonlinearity of {self.value:g} %FS is more than "
                f"{MAX_NONLINEARITY_PERCENT:g} %FS: a residual larger than the full scale "
                "is not a gyro's nonlinearity (check the unit: ppm of FS is 1e-4 %FS)"),
                self.value, "Nonlinearity")
        if "of" in self.model_fields_set and self.unit != "%FS":
            raise_at(("of",), rule_error(
                f"'of' applies to a nonlinearity in %FS only; {self.value!r} "
                f"{self.unit} is already an absolute rate: remove 'of'"), self.of, "Nonlinearity")
        if self.measure == "rms" and self.fit == "minimax":
            raise_at(("measure",), rule_error(
                "an RMS nonlinearity needs a reference line fixed in advance: use fit "
                "least-squares or endpoint with measure rms (minimax goes with measure max)"),
                self.measure, "Nonlinearity")
        return self


class Asymmetry(Model):
    """A datasheet scale-factor asymmetry."""

    value: Annotated[Number, Field(ge=0)] = Field(description="The bound; >= 0.")
    unit: Annotated[Literal["ppm", "%"], Named("asymmetry unit")] = Field(
        description="ppm or %.")

    model_config = Model.model_config | {"json_schema_extra": {"allOf": [
        {"if": {"required": ["unit"], "properties": {"unit": {"const": unit}}},
         "then": {"properties": {"value": {"maximum": MAX_ASYMMETRY_PERCENT * per_percent}}}}
        for unit, per_percent in (("%", 1.0), ("ppm", 1e4))]}}

    @model_validator(mode="after")
    def _bounded(self) -> "Asymmetry":
        if self.value > MAX_ASYMMETRY_PERCENT * (1e4 if self.unit == "ppm" else 1.0):
            raise_at(("value",), rule_error(
                f"an asymmetry of {self.value:g} {self.unit} is more than "
                f"{MAX_ASYMMETRY_PERCENT:g} % ({MAX_ASYMMETRY_PERCENT * 1e4:g} ppm): the two "
                "scale factors would differ by more than their mean"), self.value, "Asymmetry")
        return self


class Specs(Model):
    """A sensor given by its datasheet (docs/model.md section 11).

    ``range``: R in the file's rate unit; ``nonlinearity``: its ``value`` in its own
    ``unit`` (``"%FS"`` of R or of the span 2R as ``of`` says, or an absolute rate in
    the rate unit named, not necessarily the file's); ``asymmetry``: ``value`` in
    ``"ppm"`` or ``"%"``, or None; ``vre``: the bound on |G_jj|, rate per
    acceleration unit², or None.
    """

    range: Annotated[Number, Field(gt=0)] = Field(
        description=f"Full-scale range R, {RATE}; > 0.", json_schema_extra=in_unit("rate"))
    nonlinearity: Nonlinearity = Field(
        description="The nonlinearity spec: value, unit, fit, measure, of.")
    asymmetry: Asymmetry | None = Field(
        None, description="Scale-factor asymmetry bound: |A1| <= value.")
    vre: G2BoundValue | None = Field(
        None, description="Vibration rectification bound |G_jj| <= vre: rate per g² (a bare "
        "number, as datasheets quote it), or with its unit ('0.0004 deg/s/g^2', "
        "{value, unit}).",
        json_schema_extra=in_unit("rate/g^2"))


# ---------------------------------------------------------------- the sensor


class Response(Model):
    """A sensor's own response with the place where it acts (docs/model.md section 9)."""

    at: Annotated[Literal["output", "input"], Named("response position")] = Field(
        "output", description="output (default): after the nonlinearity, no credit against "
        "the vibration error; input: it scales the vibration like a mount.")
    table: Table = Field(description="ν(f): [[f Hz, gain], ...], frequencies increasing.")


ResponseForm = Annotated[
    Annotated[Table, Tag("<list>")] | Annotated[Response, Tag("<mapping>")],
    by_kind("list or mapping")]


class Lot(LotSpread):
    """A part as drawn from production (docs/model.md section 14): c ~ N(mean, Σ)."""

    mean: Coefficients = Field(description="Mean of the units' eq. (2) coefficients, in rate "
                               "units (the lot is analysed at its mean).")


_SENSOR_GROUPS = (
    Group(("coefficients", "output_coefficients", "specs", "lot"),
          "give the conversion function once: either 'coefficients' (eq. 2), "
          "'output_coefficients' (eq. 1), 'specs' (the datasheet) or 'lot' (a production "
          "lot)"),
    Group(("g2_sensitivity", "vre"),
          "give the g² sensitivity once: 'g2_sensitivity' or its shorthand 'vre' "
          "(G11 = G22 = G33), not both", optional=True),
)


class Sensor(Model):
    """One angular-rate sensor: its conversion function and, optionally, ν_sensor(f).

    Values are in the file's own units (rates in ``units.rate``, accelerations in
    ``units.acceleration``). Exactly one of ``coefficients`` (eq. 2),
    ``output_coefficients`` (eq. 1), ``specs`` (the datasheet) and ``lot`` (a
    production lot, docs/model.md section 14) is given, and ``uncertainty`` only beside
    ``coefficients``; ``response`` is as written (a bare table acting at the output, or a
    :class:`Response`): read it through ``response_table`` and ``response_at``;
    ``g2`` is the g² sensitivity from either of its forms.
    """

    id: Identifier = Field(description=ID_TEXT)
    name: Text | None = Field(None, description=FREE_TEXT)
    vendor: Text | None = Field(None, description=FREE_TEXT)
    part: Text | None = Field(None, description="Free text (part number).")
    notes: Text | None = Field(None, description=FREE_TEXT)
    range: Annotated[Number, Field(gt=0)] | None = Field(
        None, description=f"Full-scale range, {RATE}; > 0.", json_schema_extra=in_unit("rate"))
    coefficients: Coefficients | None = Field(
        None, description="Conversion function of eq. (2), in rate units (k1 = 1). "
        "Give this or output_coefficients.")
    output_coefficients: OutputCoefficients | None = Field(
        None, description="Conversion function of eq. (1), in output units. "
        "Give this or coefficients.")
    specs: Specs | None = Field(
        None, description="Datasheet specifications instead of coefficients: the worst "
        "conversion function they allow is used (docs/model.md section 11).")
    response: ResponseForm | None = Field(
        None, description="The sensor's own transmissibility ν(f): a table "
        "[[f Hz, gain], ...] (acting at the output), or {at, table}.")
    g2_sensitivity: G2Sensitivity | None = Field(
        None, description="Acceleration-squared sensitivity G_jk, rate per g² "
        "(docs/model.md section 8); an omitted term is 0.", json_schema_extra=in_unit("rate/g^2"))
    vre: G2Value | None = Field(
        None, description="Shorthand for g2_sensitivity with G11 = G22 = G33 = vre "
        "(rate per g², signed; or with its unit, '0.0004 deg/s/g^2' or {value, unit}) "
        "and no cross terms.", json_schema_extra=in_unit("rate/g^2"))
    uncertainty: Uncertainty | None = Field(
        None, description="Standard uncertainties and correlations of the coefficients "
        "(docs/model.md section 14); only beside 'coefficients'.")
    lot: Lot | None = Field(
        None, description="A production lot instead of one unit: the mean, standard "
        "deviations and correlations of its units' coefficients (docs/model.md section 14).")
    noise: Noise | None = Field(
        None, description="Noise figures at rest (docs/model.md section 15): arw, "
        "bias_instability, rrw, bias_repeatability; an omitted one is unknown. Either form.")

    model_config = Model.model_config | {"json_schema_extra": {"allOf": [
        groups_schema(*_SENSOR_GROUPS), {"dependencies": {"uncertainty": ["coefficients"]}}]}}

    check_one_of: ClassVar[Any] = one_of(*_SENSOR_GROUPS)

    @model_validator(mode="after")
    def _uncertainty_beside_coefficients(self) -> "Sensor":
        if self.uncertainty is not None and self.coefficients is None:
            raise_at(("uncertainty",), rule_error(
                "'uncertainty' goes beside 'coefficients' (eq. 2) only; a lot gives its "
                "spread in 'lot' itself"), self.uncertainty, "Sensor")
        return self

    @property
    def response_table(self) -> list[tuple[float, float]] | None:
        """ν_sensor(f) as ``[(f Hz, gain), ...]``, whichever form was written, or None."""
        return self.response.table if isinstance(self.response, Response) else self.response

    @property
    def response_at(self) -> str:
        """Where the response acts: ``"output"`` (no credit) or ``"input"`` (docs/model.md 9)."""
        if isinstance(self.response, Response):
            return self.response.at
        return str(Response.model_fields["at"].default)

    @property
    def g2(self) -> tuple[G2Written, G2Written, G2Written, G2Written, G2Written, G2Written]:
        """(G11, G22, G33, G12, G13, G23) as written: a number is in the file's rate unit
        per g², a :class:`G2Quantity` carries its unit; 0 if not given.
        :mod:`gyrovib.api` converts them (``api.linear.g2_matrix``)."""
        if self.g2_sensitivity is not None:
            g = self.g2_sensitivity
            t = [_written(x) for x in (g.G11, g.G22, g.G33, g.G12, g.G13, g.G23)]
            return (t[0], t[1], t[2], t[3], t[4], t[5])
        v = 0.0 if self.vre is None else _written(self.vre)
        return (v, v, v, 0.0, 0.0, 0.0)

    def bare_g2(self) -> list[tuple[tuple[str, ...], float]]:
        """Where a g² sensitivity is a bare number (read per g²), with its value; zeros
        (the same in every unit) left out."""
        out: list[tuple[tuple[str, ...], float]] = []
        if self.g2_sensitivity is not None:
            out += [(("g2_sensitivity", k), v) for k, v in self.g2_sensitivity
                    if isinstance(v, float) and v != 0]
        if isinstance(self.vre, float) and self.vre != 0:
            out.append((("vre",), self.vre))
        if self.specs is not None and isinstance(self.specs.vre, float) and self.specs.vre != 0:
            out.append((("specs", "vre"), self.specs.vre))
        return out

    @property
    def rate_coefficients(self) -> Coefficients:
        """The eq. (2) coefficients, whichever form the file used."""
        if self.coefficients is not None:
            return self.coefficients
        if self.lot is not None:  # a lot is analysed at its mean
            return self.lot.mean
        if self.output_coefficients is None:  # the datasheet form: no single function
            raise CatalogError(f"sensor {self.id!r} is given by its datasheet ('specs:'), "
                               "not by coefficients; it has no conversion function to use here")
        return self.output_coefficients.to_coefficients()
