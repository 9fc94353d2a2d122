"""The value types the catalogue models are written in, and the rule helpers.

A number is strict: a float, or an integer (converted), never a boolean nor a
text such as ``"1e3"``; NaN, infinities and integers too large for a float are
refused. Free text and ids are strict text. Each bound is written once, on the
field that carries it (see the model modules); the types here carry none but
the ones every value of the type shares (a breakpoint's frequency is > 0).
"""

import itertools
import math
from collections.abc import Callable
from typing import Annotated, Any, NamedTuple

from pydantic import (
    AfterValidator,
    AllowInfNan,
    BaseModel,
    BeforeValidator,
    ConfigDict,
    Discriminator,
    Field,
    Strict,
    ValidationError,
    model_validator,
)
from pydantic_core import InitErrorDetails, PydanticCustomError

#: Most rows of a breakpoint table.
MAX_TABLE = 100_000
#: Longest free text.
MAX_TEXT = 10_000
#: Longest id.
MAX_ID = 200
#: What an id may hold.
ID_PATTERN = r"^[A-Za-z0-9._-]+$"

ID_TEXT = "Unique id: letters, digits, '.', '_' and '-'."
FREE_TEXT = "Free text."
RATE = "in the file's rate unit (units.rate)"

# ---------------------------------------------------------------- physical limits
#
# Every magnitude a catalogue gives is bounded so that what the model computes from
# it stays a finite float (max ~1.8e308). The largest rate at a sensor is a
# profile's magnitude × a mount's gain × an input-side response's gain × 57.3
# (rad/s to deg/s) × 4,161 terms (64 groups of 64 orders, 64 tones, the random
# part): 1e12 × 1e4 × 1e4 × 57.3 × 4161 ≈ 2.4e25 deg/s. The highest power of it
# the model computes is the 10th (the square, in the RMS, of a fifth-order term):
# ≈ 6e253, which leaves a factor 1e54 for the sensor's coefficients. An
# acceleration enters squared (G·a², squared again in the RMS: a⁴·G²).

#: The largest magnitude of a rate or acceleration a profile gives (a tone or
#: harmonic amplitude, an rms, the carrier rate, the σ a PSD integrates to), in the
#: file's unit, and of a g² sensitivity in its unit.
MAX_MAGNITUDE = 1e12
#: The largest gain of a transmissibility table (a mount, a sensor's response): 80 dB.
MAX_GAIN = 1e4
#: The largest level of a PSD breakpoint, unit²/Hz, and the largest variance ∫S df.
MAX_VARIANCE = 1e24
assert MAX_VARIANCE == MAX_MAGNITUDE**2 or math.isclose(MAX_VARIANCE, MAX_MAGNITUDE**2)
#: Why: appended to a magnitude's out-of-bounds message.
MAGNITUDE_WHY = (" (in the file's unit: beyond any physical vibration, and the model raises "
                 "the rate at the sensor to the 10th power, which must stay a finite "
                 "floating-point number)")
ACCELERATION_WHY = (" (in the file's unit: beyond any physical vibration, and the model "
                    "raises the acceleration to the 4th power, which must stay a finite "
                    "floating-point number)")
GAIN_WHY = (" (80 dB: beyond any mount or sensor resonance, and a gain multiplies every "
            "amplitude the model raises to the 10th power)")
PSD_WHY = (" (a PSD level in unit²/Hz: the square of the largest rate or acceleration a "
           "profile may give, 1e+12, which keeps the model's powers finite)")


class Model(BaseModel):
    """Every catalogue mapping: immutable, closed (an unknown key is an error),
    built on first use."""

    model_config = ConfigDict(frozen=True, extra="forbid", defer_build=True,
                              validate_default=False)


class Named(NamedTuple):
    """Metadata of a choice: what its values are called in messages ("rate unit")."""

    what: str


class Hint(NamedTuple):
    """Metadata of a bounded number: appended to an out-of-bounds message."""

    text: str


def in_unit(kind: str) -> dict[str, Any]:
    """``json_schema_extra`` naming the kind of unit a value is in."""
    return {"unit": kind}


# ---------------------------------------------------------------- errors


def rule_error(message: str) -> PydanticCustomError:
    """A broken rule; the message is the sentence the user reads."""
    return PydanticCustomError("rule", "{message}", {"message": message})


def raise_at(loc: tuple[Any, ...], error: PydanticCustomError, value: Any, title: str) -> None:
    """Raise ``error`` placed at ``loc`` below the value being validated."""
    raise ValidationError.from_exception_data(
        title, [InitErrorDetails(type=error, loc=loc, input=value)])


def details(exc: ValidationError) -> list[InitErrorDetails]:
    """The errors of ``exc``, ready to be raised again together with others."""
    out: list[InitErrorDetails] = []
    for e in exc.errors(include_url=False):
        ctx = e.get("ctx") or {}
        out.append(InitErrorDetails(type=PydanticCustomError(e["type"], e["msg"], ctx),
                                    loc=e["loc"], input=e["input"]))
    return out


class Group(NamedTuple):
    """Among ``fields``, exactly one (``at_least``: one or more) is given a non-null
    value; ``optional``: none at all is allowed too (then it is "at most one")."""

    fields: tuple[str, ...]
    message: str
    at_least: bool = False
    optional: bool = False

    def broken(self, data: dict[Any, Any]) -> bool:
        given = sum(1 for name in self.fields if data.get(name) is not None)
        if given == 0:
            return not self.optional
        return given > 1 and not self.at_least


def given(name: str) -> dict[str, Any]:
    """JSON Schema: ``name`` is given a non-null value."""
    return {"required": [name], "properties": {name: {"not": {"type": "null"}}}}


def groups_schema(*groups: Group) -> dict[str, Any]:
    """What JSON Schema can say of the groups (``json_schema_extra`` of the model)."""
    rules: list[dict[str, Any]] = []
    for group in groups:
        branches = [given(name) for name in group.fields]
        if group.at_least:
            rules.append({"anyOf": branches})
        elif group.optional:
            rules.append({"not": {"anyOf": [{"allOf": [a, b]} for i, a in enumerate(branches)
                                            for b in branches[i + 1:]]}})
        else:
            rules.append({"oneOf": branches})
    return rules[0] if len(rules) == 1 else {"allOf": rules}


def one_of(*groups: Group) -> Any:
    """A model validator for the one-of rules of a mapping: judged on the mapping as
    written, and reported together with its other problems (not only once they are
    mended)."""

    def check(cls: type[BaseModel], data: Any, handler: Callable[[Any], Any]) -> Any:
        if not isinstance(data, dict):
            return handler(data)
        broken = [g.message for g in groups if g.broken(data)]
        if not broken:
            return handler(data)
        found: list[InitErrorDetails] = []
        try:
            handler(data)
        except ValidationError as exc:
            found = details(exc)
        found += [InitErrorDetails(type=rule_error(m), loc=(), input=data) for m in broken]
        raise ValidationError.from_exception_data(cls.__name__, found)

    return model_validator(mode="wrap")(classmethod(check))  # type: ignore[arg-type]


# ---------------------------------------------------------------- numbers

#: A number written in a text ("0.0004 deg/s/g^2", "0.12 deg/sqrt(h)"): a regular expression.
NUMBER_TEXT = r"[-+]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][-+]?[0-9]+)?"
#: A finite float (an integer is converted); no boolean, no text.
Number = Annotated[float, Strict(), AllowInfNan(False)]
#: A rate or acceleration magnitude of a profile, >= 0 (see MAX_MAGNITUDE).
Magnitude = Annotated[Number, Field(ge=0, le=MAX_MAGNITUDE), Hint(MAGNITUDE_WHY)]
#: An acceleration magnitude of a profile, >= 0 (see MAX_MAGNITUDE).
AccelerationMagnitude = Annotated[Number, Field(ge=0, le=MAX_MAGNITUDE), Hint(ACCELERATION_WHY)]
#: A signed rate of a profile (see MAX_MAGNITUDE).
SignedMagnitude = Annotated[Number, Field(ge=-MAX_MAGNITUDE, le=MAX_MAGNITUDE),
                            Hint(MAGNITUDE_WHY)]


def _integral(value: Any) -> Any:
    """2.0 is the integer 2 (as in JSON Schema)."""
    if type(value) is float and value.is_integer():
        return int(value)
    return value


#: The validator that makes an integer of an integral float (2.0 is 2, as in JSON
#: Schema); an integer field is written ``Annotated[int, Strict(), <bounds>, AsInteger]``
AsInteger = BeforeValidator(_integral)
#: Free text.
Text = Annotated[str, Strict(), Field(max_length=MAX_TEXT)]
#: An id.
Identifier = Annotated[str, Strict(), Field(min_length=1, max_length=MAX_ID,
                                            pattern=ID_PATTERN)]
Triple = tuple[Number, Number, Number]


# ---------------------------------------------------------------- breakpoint tables


def breakpoint_problem(table: list[tuple[float, float]]) -> tuple[str, int] | None:
    """The first row that breaks the order of a breakpoint table, with a message.

    Frequencies must increase; one repeat (a step) is allowed, not three in a row.
    """
    for i in range(1, len(table)):
        f0, f1 = table[i - 1][0], table[i][0]
        if f1 < f0:
            return (f"breakpoint frequencies must increase: {f1:g} Hz follows {f0:g} Hz "
                    "(sort the rows by frequency)"), i
        if f1 == f0 and i >= 2 and table[i - 2][0] == f0:
            return f"frequency {f0:g} Hz appears more than twice (a step uses two rows)", i
    return None


def _ordered(table: list[tuple[float, float]]) -> list[tuple[float, float]]:
    problem = breakpoint_problem(table)
    if problem is not None:
        raise_at((problem[1],), rule_error(problem[0]), table[problem[1]], "Table")
    return table


def _band(table: list[tuple[float, float]]) -> list[tuple[float, float]]:
    """A PSD is integrated between its breakpoints: it needs two distinct frequencies."""
    if table[0][0] == table[-1][0]:
        raise rule_error("a PSD needs breakpoints at two different frequencies at least: "
                         "it is integrated over the band between them")
    return table


def psd_variance(table: list[tuple[float, float]]) -> float:
    """∫ S(f) df of a breakpoint table, log-log interpolated between its rows (eq. 6
    without a gain); inf when it overflows. A segment with a zero end is bounded by
    its larger level × its width.

    Between (fa, Sa) and (fb, Sb), S = Sa·(f/fa)^B with B = ln(Sb/Sa)/ln(fb/fa), so
    ∫ = Sa·fa·(e^x − 1)/(B + 1) with x = (B + 1)·ln(fb/fa) (Sa·fa·ln(fb/fa) when
    B = −1); computed through logarithms so that no step overflows first.
    """
    total = 0.0
    for (fa, sa), (fb, sb) in itertools.pairwise(table):
        if fb <= fa:
            continue
        if sa > 0 and sb > 0:
            span = math.log(fb) - math.log(fa)
            b1 = (math.log(sb) - math.log(sa)) / span + 1.0
            x = b1 * span
            log_scale = math.log(sa) + math.log(fa)
            if abs(x) < 1e-12:
                log_part = log_scale + math.log(span)
            elif x > 0:
                log_part = log_scale + x + math.log(-math.expm1(-x)) - math.log(b1)
            else:
                log_part = log_scale + math.log(-math.expm1(x)) - math.log(-b1)
            if log_part > 709.0:
                return math.inf
            total += math.exp(log_part)
        else:
            total += max(sa, sb) * (fb - fa)
    return total


def _finite_variance(table: list[tuple[float, float]]) -> list[tuple[float, float]]:
    variance = psd_variance(table)
    if not variance <= MAX_VARIANCE:
        raise rule_error(
            f"this PSD integrates to a variance ∫S df of {variance:.3g} unit², more than "
            f"{MAX_VARIANCE:g} (an rms of {MAX_MAGNITUDE:g} in its unit): beyond any physical "
            "vibration, and the model raises the vibration at the sensor to the 4th power "
            "and beyond, which must stay a finite floating-point number")
    return table


Row = tuple[Annotated[Number, Field(gt=0)],
            Annotated[Number, Field(ge=0, le=MAX_GAIN), Hint(GAIN_WHY)]]
PSDRow = tuple[Annotated[Number, Field(gt=0)],
               Annotated[Number, Field(ge=0, le=MAX_VARIANCE), Hint(PSD_WHY)]]
#: Transmissibility breakpoints ``[[f Hz > 0, gain in [0, MAX_GAIN]], ...]``,
#: frequencies increasing (a repeated frequency is a step).
Table = Annotated[list[Row], Field(min_length=1, max_length=MAX_TABLE),
                  AfterValidator(_ordered)]
#: A PSD's breakpoints, integrated over: two distinct frequencies at least, levels
#: and their integral bounded (see MAX_VARIANCE).
#: (One row is refused by the band rule, whose message says why; the schema says
#: two rows at least.)
BandTable = Annotated[list[PSDRow], Field(min_length=1, max_length=MAX_TABLE,
                                          json_schema_extra={"minItems": 2}),
                      AfterValidator(_ordered), AfterValidator(_band),
                      AfterValidator(_finite_variance)]


# ---------------------------------------------------------------- either


def yaml_kind(value: Any) -> str | None:
    """The YAML kind of a value: the tag of the union member written that way."""
    if isinstance(value, dict):
        return "<mapping>"
    if isinstance(value, (list, tuple)):
        return "<list>"
    if isinstance(value, str):
        return "<text>"
    if isinstance(value, BaseModel):
        return "<mapping>"
    return None


def value_kind(value: Any) -> str | None:
    """As :func:`yaml_kind`, and ``<number>`` for a number (not a boolean): the tag of a
    quantity written as a bare number, a text with its unit or a mapping."""
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return "<number>"
    return yaml_kind(value)


def by_kind(expected: str) -> Discriminator:
    """A union chosen by the kind of value written (mapping, list or text); when none
    fits, a ``kind`` error whose message is ``expected`` ("list or mapping")."""
    return Discriminator(yaml_kind, custom_error_type="kind", custom_error_message=expected)


#: Tags that name a union member in an error's location, not a key of the file.
TAGS = frozenset(("<mapping>", "<list>", "<text>", "<number>"))
