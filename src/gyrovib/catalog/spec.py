"""The catalogue format, defined once, as plain data.

Every key a catalogue file may hold is listed here with its type, bounds,
default, unit and description, together with the rules that span several keys
(exactly one of a group, K1 ≠ 0, ...). Everything else reads this module:

* :mod:`gyrovib.catalog.validate` checks parsed YAML against it and builds the
  records of :mod:`gyrovib.catalog.records` (or collects located errors);
* :mod:`gyrovib.catalog.jsonschema` writes it as a draft-07 JSON Schema;
* :mod:`gyrovib.catalog.locate` and :mod:`gyrovib.catalog.messages` use it to
  suggest keys and phrase messages.

A new field is one :class:`Field` line in :data:`FORMAT` (and, if the code
reads it, one attribute in ``records.py``). See docs/architecture.md.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

#: Units a rate may be written in (``units.rate``).
RATE_UNITS = ("deg/s", "deg/h", "rad/s", "rpm")
#: Units a linear acceleration may be written in (``units.acceleration``).
ACCELERATION_UNITS = ("g", "m/s^2", "m/s2")
#: Most rows of a breakpoint table.
MAX_TABLE = 100_000
#: Most harmonic tones (or harmonic orders) of one profile.
MAX_TONES = 64
#: Longest free text.
MAX_TEXT = 10_000
#: Longest id.
MAX_ID = 200
#: What an id may hold.
ID_PATTERN = r"^[A-Za-z0-9._-]+$"
#: Largest finite float; the JSON Schema bounds numbers by it so that .inf is refused.
FLOAT_MAX = 1.7976931348623157e308


class _Required:
    def __repr__(self) -> str:
        return "REQUIRED"


#: Default of a field that must be given.
REQUIRED: Any = _Required()


class _Expanded:
    def __repr__(self) -> str:
        return "EXPANDED"


#: Default of an object field: the object with all of its own defaults.
EXPANDED: Any = _Expanded()


# ------------------------------------------------------------------ value types


@dataclass(frozen=True)
class Number:
    """A finite float (an integer is accepted and converted); optional bounds."""

    minimum: float | None = None
    exclusive_minimum: bool = False
    maximum: float | None = None
    #: Appended to an out-of-bounds message.
    hint: str = ""


@dataclass(frozen=True)
class Integer:
    """An integer (not a float, not a boolean), optionally ``>= minimum``."""

    minimum: int | None = None


@dataclass(frozen=True)
class Version:
    """The format version: the integer ``value``."""

    value: int


@dataclass(frozen=True)
class Text:
    """Free text, at most ``max_length`` characters."""

    max_length: int = MAX_TEXT


@dataclass(frozen=True)
class Identifier:
    """An id: :data:`ID_PATTERN`, 1 to :data:`MAX_ID` characters."""

    pattern: str = ID_PATTERN
    max_length: int = MAX_ID


@dataclass(frozen=True)
class Choice:
    """One word of ``values``; ``what`` names it in messages ("rate unit")."""

    values: tuple[str, ...]
    what: str = ""


@dataclass(frozen=True)
class Fixed:
    """A list of exactly ``n`` values of one type (a triple, a pair...)."""

    n: int
    item: Any


@dataclass(frozen=True)
class Table:
    """Breakpoints ``[[f Hz > 0, value >= 0], ...]``, frequencies increasing
    (a repeated frequency is a step); ``band``: at least two distinct frequencies."""

    band: bool = False
    max_rows: int = MAX_TABLE


@dataclass(frozen=True)
class Ref:
    """A mapping described by ``FORMAT[name]``."""

    name: str


@dataclass(frozen=True)
class ListOf:
    """A list of ``item``, at most ``max_length`` long; ``unique``: a key of the
    items whose values must differ."""

    item: Any
    max_length: int | None = None
    unique: str | None = None


@dataclass(frozen=True)
class Either:
    """One of several types, chosen by the kind of value written: the first
    option whose YAML kind (mapping, list, text, number) matches is used."""

    options: tuple[Any, ...]


@dataclass(frozen=True)
class Field:
    name: str
    type: Any
    default: Any = None
    #: ``null`` is accepted and means "not given" (for optional fields).
    nullable: bool = False
    description: str = ""
    #: The kind of unit the value is in: "rate", "acceleration", "Hz", "deg", ...
    unit: str = ""


@dataclass(frozen=True)
class Group:
    """Among ``fields``, exactly one (or, ``at_least``, one or more) non-null."""

    fields: tuple[str, ...]
    message: str
    at_least: bool = False
    #: Whether none at all is allowed (then it is "at most one").
    optional: bool = False


@dataclass(frozen=True)
class FieldCheck:
    """A rule on one valid field: ``test(value)`` gives a message (or
    ``(message, row)`` pointing at a row) when broken, else None; ``schema``:
    what JSON Schema can say of it."""

    field: str
    test: Callable[[Any], Any]
    schema: dict[str, Any] | None = None


@dataclass(frozen=True)
class Check:
    """A rule on a whole valid mapping: ``test(values)`` gives a message or None.
    ``at``: the field the message is placed at (default: the mapping)."""

    test: Callable[[dict[str, Any]], str | None]
    at: str | None = None


@dataclass(frozen=True)
class Object:
    description: str
    fields: tuple[Field, ...]
    groups: tuple[Group, ...] = ()
    field_checks: tuple[FieldCheck, ...] = ()
    checks: tuple[Check, ...] = ()

    def field(self, name: str) -> Field | None:
        for f in self.fields:
            if f.name == name:
                return f
        return None


# ------------------------------------------------------------------ rules


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


def band_problem(table: list[tuple[float, float]]) -> str | None:
    """A PSD is integrated between its breakpoints: it needs two distinct frequencies."""
    if table[0][0] != table[-1][0]:
        return None
    return ("a PSD needs breakpoints at two different frequencies at least: "
            "it is integrated over the band between them")


def _k1_nonzero(value: float) -> str | None:
    if value == 0:
        return "K1 (output per rate unit) must not be zero: it divides every other coefficient"
    return None


_DIVIDED = ("K0", "K2", "K3", "K4", "K5", "M1", "M2", "M31", "M32")


def _divisible(values: dict[str, Any]) -> str | None:
    k1 = values["K1"]
    for name in _DIVIDED:
        if not math.isfinite(values[name] / k1):
            return f"K1 = {k1:g} is so small that {name} / K1 overflows; check the units of K1"
    return None


def _version(value: int) -> str | None:
    if value != 1:
        return f"unsupported format version {value}; this gyrovib reads version 1"
    return None


# ------------------------------------------------------------------ the format

_RATE = "in the file's rate unit (units.rate)"
_ANY = Number()
_POSITIVE = Number(minimum=0, exclusive_minimum=True)
_NON_NEGATIVE = Number(minimum=0)
_WEIGHT = _POSITIVE
_TRIPLE = Fixed(3, _ANY)
_NON_NEGATIVE_TRIPLE = Fixed(3, _NON_NEGATIVE)
_COHERENCE = Number(minimum=-1, maximum=1, hint=" (a coherence lies in [-1, 1])")
_TEXT = "Free text."
_ID = "Unique id: letters, digits, '.', '_' and '-'."

_RATE_FORM = (
    ("k0", 0.0, f"Bias, {_RATE}."),
    ("k1", 1.0, "Scale factor (1 in eq. 2)."),
    ("A1", 0.0, "Scale-factor asymmetry (dimensionless)."),
    ("k2", 0.0, "Second-order nonlinearity, rate^-1."),
    ("k3", 0.0, "Third-order nonlinearity, rate^-2."),
    ("k4", 0.0, "Fourth-order nonlinearity, rate^-3."),
    ("k5", 0.0, "Fifth-order nonlinearity, rate^-4."),
    ("m1", 0.0, "Cross-axis sensitivity to x1 (dimensionless)."),
    ("m2", 0.0, "Cross-axis sensitivity to x2 (dimensionless)."),
    ("m31", 0.0, "Product cross-axis term x3·x1, rate^-1."),
    ("m32", 0.0, "Product cross-axis term x3·x2, rate^-1."),
)

FORMAT: dict[str, Object] = {
    "CatalogFile": Object(
        "A whole catalogue file. 'gyrovib: 1' is required.",
        (
            Field("gyrovib", Version(1), REQUIRED, description="Format version; must be 1."),
            Field("units", Ref("Units"), EXPANDED,
                  description="Units of the values in this file."),
            Field("sensors", ListOf(Ref("Sensor")), [],
                  description="Angular-rate sensors; ids unique across all files given."),
            Field("profiles", ListOf(Ref("Profile")), [],
                  description="Vibration environments; ids unique across all files given."),
            Field("allocation", Ref("Allocation"), None, nullable=True,
                  description="How a budget is split among the terms (eq. 18, 21, 24)."),
        ),
        field_checks=(FieldCheck("gyrovib", _version),),
    ),
    "Units": Object(
        "'units:' — the rate unit of every rate, PSD and coefficient in the file.",
        (
            Field("rate", Choice(RATE_UNITS, "rate unit"), "deg/s",
                  description="Unit of every rate, PSD and coefficient in this file: "
                  "deg/s (default), deg/h, rad/s or rpm."),
        ),
    ),
    "Coefficients": Object(
        "Eq. (2), in rate units: an omitted coefficient is 0, except 'k1 = 1'.",
        tuple(Field(n, _ANY, d, description=t, unit="rate") for n, d, t in _RATE_FORM),
    ),
    "OutputCoefficients": Object(
        "Eq. (1), in output units per rate unit; divided by 'K1' to give eq. (2).",
        (
            Field("unit", Text(), None, nullable=True,
                  description="The output unit (free text, e.g. mV or LSB)."),
            Field("K1", _ANY, REQUIRED, unit="output/rate",
                  description="Scale factor, output per rate unit; required and non-zero."),
            Field("K0", _ANY, 0.0, description="Bias, output units.", unit="output"),
            Field("A1", _ANY, 0.0, description="Scale-factor asymmetry (dimensionless)."),
            *(Field(upper, _ANY, 0.0, unit="output",
                    description=f"As {upper.lower()} of eq. (2), times K1 (output units).")
              for upper in ("K2", "K3", "K4", "K5", "M1", "M2", "M31", "M32")),
        ),
        field_checks=(FieldCheck("K1", _k1_nonzero, {"not": {"const": 0}}),),
        checks=(Check(_divisible),),
    ),
    "Sensor": Object(
        "One angular-rate sensor: its conversion function and, optionally, ν_sensor(f).",
        (
            Field("id", Identifier(), REQUIRED, description=_ID),
            Field("name", Text(), None, nullable=True, description=_TEXT),
            Field("vendor", Text(), None, nullable=True, description=_TEXT),
            Field("part", Text(), None, nullable=True, description="Free text (part number)."),
            Field("notes", Text(), None, nullable=True, description=_TEXT),
            Field("range", _POSITIVE, None, nullable=True, unit="rate",
                  description=f"Full-scale range, {_RATE}; > 0."),
            Field("coefficients", Ref("Coefficients"), None, nullable=True,
                  description="Conversion function of eq. (2), in rate units (k1 = 1). "
                  "Give this or output_coefficients."),
            Field("output_coefficients", Ref("OutputCoefficients"), None, nullable=True,
                  description="Conversion function of eq. (1), in output units. "
                  "Give this or coefficients."),
            Field("response", Table(), None, nullable=True,
                  description="The sensor's own transmissibility ν(f): [[f Hz, gain], ...], "
                  "frequencies increasing (a repeated frequency is a step)."),
        ),
        groups=(Group(("coefficients", "output_coefficients"),
                      "give the conversion function once: either 'coefficients' (eq. 2) "
                      "or 'output_coefficients' (eq. 1)"),),
    ),
    "Tone": Object(
        "One harmonic tone of eq. (3): per-axis amplitude (rate) and phase (degrees).",
        (
            Field("frequency", _POSITIVE, REQUIRED, unit="Hz",
                  description="Frequency in Hz; > 0."),
            Field("amplitude", _NON_NEGATIVE_TRIPLE, REQUIRED, unit="rate",
                  description=f"Amplitude per axis x1, x2, x3, {_RATE}; >= 0."),
            Field("phase", _TRIPLE, (0.0, 0.0, 0.0), unit="deg",
                  description="Phase per axis, degrees."),
        ),
    ),
    "PSD": Object(
        "Per-axis PSD breakpoints, rate²/Hz; an axis left out has none.",
        tuple(Field(axis, Table(band=True), None, nullable=True, unit="rate^2/Hz",
                    description=f"[[f Hz, S rate²/Hz], ...] for axis {axis}; left out means none.")
              for axis in ("x1", "x2", "x3")),
        groups=(Group(("x1", "x2", "x3"), "give the PSD of at least one axis (x1, x2 or x3)",
                      at_least=True),),
    ),
    "Random": Object(
        "The Gaussian broadband part: a PSD or the RMS per axis at the sensor.",
        (
            Field("psd", Ref("PSD"), None, nullable=True,
                  description="PSD breakpoints per axis, rate²/Hz, log-log interpolated."),
            Field("rms", _NON_NEGATIVE_TRIPLE, None, nullable=True, unit="rate",
                  description=f"RMS per axis at the sensor, {_RATE}; no spectrum, "
                  "so ν(f) does not apply."),
            Field("coherence", Fixed(2, _COHERENCE), (1.0, 1.0),
                  description="Coherences ρ31, ρ32, each in [-1, 1]; default 1."),
        ),
        groups=(Group(("psd", "rms"),
                      "give the random part as 'psd' or as 'rms', exactly one of them"),),
    ),
    "Profile": Object(
        "One vibration environment with the carrier's own rate Ω_K.",
        (
            Field("id", Identifier(), REQUIRED, description=_ID),
            Field("name", Text(), None, nullable=True, description=_TEXT),
            Field("notes", Text(), None, nullable=True, description=_TEXT),
            Field("rate", _TRIPLE, (0.0, 0.0, 0.0), unit="rate",
                  description=f"Carrier rate Ω_K about x1, x2, x3, {_RATE}."),
            Field("harmonic", ListOf(Ref("Tone"), MAX_TONES), [],
                  description="Harmonic tones of eq. (3), zero or more."),
            Field("random", Ref("Random"), None, nullable=True,
                  description="Gaussian broadband vibration: a PSD or the RMS per axis."),
            Field("mount", Table(), None, nullable=True,
                  description="Isolation-mount transmissibility ν(f): [[f Hz, gain], ...]."),
        ),
    ),
    "Allocation": Object(
        "How the budget is split (eq. 18, 21, 24): ratio r and share weights w, v.",
        (
            Field("r", _WEIGHT, 1.5, description="Ratio r of eq. (18); > 0."),
            Field("w", Fixed(5, _WEIGHT), (1.0, 1.0, 1.0, 0.5, 0.5),
                  description="Share weights w of the five additive terms; each > 0."),
            Field("v", Fixed(3, _WEIGHT), (1.0, 0.5, 0.5),
                  description="Share weights v of the three multiplicative terms; each > 0."),
        ),
    ),
}

#: The object a whole file is.
ROOT = "CatalogFile"
#: The top-level key holding the format version.
VERSION_KEY = "gyrovib"
#: Top-level lists of items with an id unique across files, with the item's name.
SECTIONS = (("sensors", "sensor"), ("profiles", "profile"))
#: The key of an item's id.
ID_KEY = "id"
#: The top-level key every merged file must agree on.
SHARED_KEY = "allocation"


def defaults(name: str, fmt: dict[str, Object] | None = None) -> dict[str, Any]:
    """Field name → default of ``FORMAT[name]`` (None for required fields;
    an object field's own defaults expanded)."""
    fmt = FORMAT if fmt is None else fmt
    out: dict[str, Any] = {}
    for f in fmt[name].fields:
        if f.default is REQUIRED:
            out[f.name] = None
        elif f.default is EXPANDED:
            out[f.name] = defaults(f.type.name, fmt)
        else:
            out[f.name] = f.default
    return out
