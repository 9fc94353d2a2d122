"""The catalogue format, defined once, as plain data.

Every key a catalogue file may hold is listed here with its type, bounds,
default, unit and description, together with the rules that span several keys
(exactly one of a group, K1 ≠ 0, ...). Everything else reads this module:

* :mod:`gyrovib.catalog.validate` checks parsed YAML against it and builds the
  records of :mod:`gyrovib.catalog.records` (or collects located errors);
* :mod:`gyrovib.catalog.jsonschema` writes it as a draft-07 JSON Schema;
* :mod:`gyrovib.catalog.locate` and :mod:`gyrovib.catalog.messages` use it to
  suggest keys and phrase messages.

A new field is one :class:`~gyrovib.catalog.kinds.Field` line in
:data:`FORMAT` (and, if the code reads it, one attribute in ``records.py``);
the vocabulary (value types, fields, rules) is :mod:`gyrovib.catalog.kinds`.
See docs/architecture.md.
"""

from __future__ import annotations

import math
from typing import Any

from gyrovib.catalog.kinds import (
    EXPANDED,
    REQUIRED,
    Check,
    Choice,
    Either,
    Field,
    FieldCheck,
    Fixed,
    Group,
    Identifier,
    Integer,
    ListOf,
    Number,
    Object,
    Ref,
    Table,
    Text,
    Version,
)

#: Units a rate may be written in (``units.rate``).
RATE_UNITS = ("deg/s", "deg/h", "rad/s", "rpm")
#: Units a linear acceleration may be written in (``units.acceleration``);
#: ``m/s2`` is another spelling of ``m/s^2``.
ACCELERATION_UNITS = ("g", "m/s^2", "m/s2")
#: Units of a datasheet nonlinearity: percent of full scale, or an absolute rate.
NONLINEARITY_UNITS = ("%FS", *RATE_UNITS)
#: Units of a datasheet scale-factor asymmetry.
ASYMMETRY_UNITS = ("ppm", "%")
#: Reference lines of a datasheet nonlinearity (MODEL.md section 11).
NONLINEARITY_FITS = ("least-squares", "minimax", "endpoint")
#: How a nonlinearity's residual is measured.
NONLINEARITY_MEASURES = ("max", "rms")
#: What a %FS nonlinearity is a percentage of.
NONLINEARITY_OF = ("range", "span")
#: Where a sensor's own response acts (MODEL.md section 9).
RESPONSE_AT = ("output", "input")
#: Most harmonic tones (or harmonic orders) of one profile.
MAX_TONES = 64
#: Largest finite float; the JSON Schema bounds numbers by it so that .inf is refused.
FLOAT_MAX = 1.7976931348623157e308


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


def _of_with_rate_unit(given: dict[str, Any]) -> str | None:
    if "of" in given and given.get("unit") in RATE_UNITS:
        return (f"'of' applies to a nonlinearity in %FS only; {given['value']!r} "
                f"{given['unit']} is already an absolute rate: remove 'of'")
    return None


def _rms_minimax(values: dict[str, Any]) -> str | None:
    if values["measure"] == "rms" and values["fit"] == "minimax":
        return ("an RMS nonlinearity needs a reference line fixed in advance: use fit "
                "least-squares or endpoint with measure rms (minimax goes with measure max)")
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


def _per_axis_psd(summary: str, unit: str, shown: str) -> Object:
    """A PSD given per axis x1, x2, x3 in ``unit``²/Hz (angular rate or acceleration)."""
    return Object(
        summary,
        tuple(Field(axis, Table(band=True), None, nullable=True, unit=f"{unit}^2/Hz",
                    description=f"[[f Hz, S {shown}], ...] for axis {axis}; left out means none.")
              for axis in ("x1", "x2", "x3")),
        groups=(Group(("x1", "x2", "x3"), "give the PSD of at least one axis (x1, x2 or x3)",
                      at_least=True),),
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
        "'units:' — the units of every rate, PSD, coefficient and acceleration in the file.",
        (
            Field("rate", Choice(RATE_UNITS, "rate unit"), "deg/s",
                  description="Unit of every rate, PSD and coefficient in this file: "
                  "deg/s (default), deg/h, rad/s or rpm."),
            Field("acceleration", Choice(ACCELERATION_UNITS, "acceleration unit"), "g",
                  description="Unit of every linear acceleration in this file: g (default, "
                  "9.80665 m/s^2) or m/s^2 (also written m/s2)."),
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
            Field("specs", Ref("Specs"), None, nullable=True,
                  description="Datasheet specifications instead of coefficients: the worst "
                  "conversion function they allow is used (MODEL.md section 11)."),
            Field("response", Either((Table(), Ref("Response"))), None, nullable=True,
                  description="The sensor's own transmissibility ν(f): a table "
                  "[[f Hz, gain], ...] (acting at the output), or {at, table}."),
            Field("g2_sensitivity", Ref("G2Sensitivity"), None, nullable=True,
                  unit="rate/g^2",
                  description="Acceleration-squared sensitivity G_jk, rate per g² "
                  "(MODEL.md section 8); an omitted term is 0."),
            Field("vre", _ANY, None, nullable=True, unit="rate/g^2",
                  description="Shorthand for g2_sensitivity with G11 = G22 = G33 = vre "
                  "(rate per g², signed) and no cross terms."),
        ),
        groups=(
            Group(("coefficients", "output_coefficients", "specs"),
                  "give the conversion function once: either 'coefficients' (eq. 2), "
                  "'output_coefficients' (eq. 1) or 'specs' (the datasheet)"),
            Group(("g2_sensitivity", "vre"),
                  "give the g² sensitivity once: 'g2_sensitivity' or its shorthand 'vre' "
                  "(G11 = G22 = G33), not both", optional=True),
        ),
    ),
    "Response": Object(
        "A sensor's own response with the place where it acts (MODEL.md section 9).",
        (
            Field("at", Choice(RESPONSE_AT, "response position"), "output",
                  description="output (default): after the nonlinearity, no credit against "
                  "the vibration error; input: it scales the vibration like a mount."),
            Field("table", Table(), REQUIRED,
                  description="ν(f): [[f Hz, gain], ...], frequencies increasing."),
        ),
    ),
    "G2Sensitivity": Object(
        "Acceleration-squared sensitivity (IEEE 528/1431), rate per g², signed.",
        tuple(Field(name, _ANY, 0.0, unit="rate/g^2", description=text) for name, text in (
            ("G11", "G11: along x1 squared (a datasheet VRE), rate/g²."),
            ("G22", "G22: along x2 squared, rate/g²."),
            ("G33", "G33: along x3 squared, rate/g²."),
            ("G12", "G12: anisoelastic x1·x2, rate/g²."),
            ("G13", "G13: anisoelastic x1·x3, rate/g²."),
            ("G23", "G23: anisoelastic x2·x3, rate/g²."),
        )),
    ),
    "Specs": Object(
        "A sensor given by its datasheet (MODEL.md section 11).",
        (
            Field("range", _POSITIVE, REQUIRED, unit="rate",
                  description=f"Full-scale range R, {_RATE}; > 0."),
            Field("nonlinearity", Ref("Nonlinearity"), REQUIRED,
                  description="The nonlinearity spec: value, unit, fit, measure, of."),
            Field("asymmetry", Ref("Asymmetry"), None, nullable=True,
                  description="Scale-factor asymmetry bound: |A1| <= value."),
            Field("vre", _NON_NEGATIVE, None, nullable=True, unit="rate/g^2",
                  description="Vibration rectification bound |G_jj| <= vre, rate per g²."),
        ),
    ),
    "Nonlinearity": Object(
        "A datasheet nonlinearity: the bound on the residual from a reference line.",
        (
            Field("value", _POSITIVE, REQUIRED, description="The bound; > 0."),
            Field("unit", Choice(NONLINEARITY_UNITS, "nonlinearity unit"), REQUIRED,
                  description="%FS, or a rate unit (deg/s, deg/h, rad/s, rpm; not "
                  "necessarily the file's) for an absolute bound."),
            Field("fit", Choice(NONLINEARITY_FITS, "fit"), "least-squares",
                  description="Reference line: least-squares (default), minimax or endpoint."),
            Field("measure", Choice(NONLINEARITY_MEASURES, "measure"), "max",
                  description="max (default): every point within the bound; rms: the RMS "
                  "residual (not with fit minimax)."),
            Field("of", Choice(NONLINEARITY_OF, "base"), "range",
                  description="%FS of the range R (default) or of the span 2R; only with %FS."),
        ),
        checks=(
            Check(_of_with_rate_unit, at="of", raw=True, schema={
                "if": {"required": ["unit"], "properties": {"unit": {"enum": list(RATE_UNITS)}}},
                "then": {"not": {"required": ["of"]}}}),
            Check(_rms_minimax, at="measure", schema={
                "not": {"required": ["measure", "fit"], "properties": {
                    "measure": {"const": "rms"}, "fit": {"const": "minimax"}}}}),
        ),
    ),
    "Asymmetry": Object(
        "A datasheet scale-factor asymmetry.",
        (
            Field("value", _NON_NEGATIVE, REQUIRED, description="The bound; >= 0."),
            Field("unit", Choice(ASYMMETRY_UNITS, "asymmetry unit"), REQUIRED,
                  description="ppm or %."),
        ),
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
    "PSD": _per_axis_psd("Per-axis PSD breakpoints, rate²/Hz; an axis left out has none.",
                         "rate", "rate²/Hz"),
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
            Field("harmonics", Either((Ref("Harmonics"), ListOf(Ref("Harmonics")))), None,
                  nullable=True,
                  description="Phase-locked harmonics of one source (MODEL.md section 10): "
                  "one group, or a list of groups."),
            Field("acceleration", Ref("Acceleration"), None, nullable=True,
                  description="Linear vibration at the sensor's axes (MODEL.md section 8)."),
        ),
    ),
    "Harmonics": Object(
        "One group of phase-locked harmonics: orders of one fundamental.",
        (
            Field("fundamental", _POSITIVE, REQUIRED, unit="Hz",
                  description="Fundamental frequency f0 in Hz; > 0."),
            Field("orders", ListOf(Ref("Order"), MAX_TONES, unique="order", min_length=1),
                  REQUIRED, description="The harmonics n·f0, each order once."),
        ),
    ),
    "Order": Object(
        "One harmonic of a locked group.",
        (
            Field("order", Integer(minimum=1), REQUIRED,
                  description="The harmonic number n (frequency n·f0); a positive integer."),
            Field("amplitude", _NON_NEGATIVE_TRIPLE, REQUIRED, unit="rate",
                  description=f"Amplitude per axis x1, x2, x3, {_RATE}; >= 0."),
            Field("phase", Either((_TRIPLE, Choice(("worst",), "phase"))), (0.0, 0.0, 0.0),
                  unit="deg",
                  description="Phase per axis in degrees, or the word worst: the worst "
                  "case over the relative phases."),
        ),
    ),
    "Acceleration": Object(
        "Linear vibration at the sensor's axes, in the file's acceleration unit.",
        (
            Field("harmonic", ListOf(Ref("AccelerationTone"), MAX_TONES), [],
                  description="Harmonic tones of the acceleration, zero or more."),
            Field("random", Ref("AccelerationRandom"), None, nullable=True,
                  description="Gaussian broadband acceleration: a PSD or the RMS per axis."),
            Field("mount", Table(), None, nullable=True,
                  description="Mount transmissibility for the linear vibration "
                  "[[f Hz, gain], ...]; default: the profile's mount."),
        ),
    ),
    "AccelerationTone": Object(
        "One harmonic tone of the acceleration.",
        (
            Field("frequency", _POSITIVE, REQUIRED, unit="Hz",
                  description="Frequency in Hz; > 0."),
            Field("amplitude", _NON_NEGATIVE_TRIPLE, REQUIRED, unit="acceleration",
                  description="Amplitude per axis x1, x2, x3, in units.acceleration; >= 0."),
            Field("phase", _TRIPLE, (0.0, 0.0, 0.0), unit="deg",
                  description="Phase per axis, degrees."),
        ),
    ),
    "AccelerationRandom": Object(
        "The Gaussian broadband part of the acceleration.",
        (
            Field("psd", Ref("AccelerationPSD"), None, nullable=True,
                  description="PSD breakpoints per axis, acceleration²/Hz."),
            Field("rms", _NON_NEGATIVE_TRIPLE, None, nullable=True, unit="acceleration",
                  description="RMS per axis, in units.acceleration."),
            Field("coherence", Fixed(3, _COHERENCE), (0.0, 0.0, 0.0),
                  description="Coherences ρ12, ρ13, ρ23, each in [-1, 1]; default 0 "
                  "(independent axes)."),
        ),
        groups=(Group(("psd", "rms"),
                      "give the random acceleration as 'psd' or as 'rms', exactly one of them"),),
    ),
    "AccelerationPSD": _per_axis_psd(
        "Per-axis acceleration PSD breakpoints, (units.acceleration)²/Hz.",
        "acceleration", "g²/Hz"),
    "Allocation": Object(
        "How the budget is split (eq. 18, 21, 24): ratio r and share weights w, v.",
        (
            Field("r", _WEIGHT, 1.5, description="Ratio r of eq. (18); > 0."),
            Field("w", Fixed(5, _WEIGHT, most=6), (1.0, 1.0, 1.0, 0.5, 0.5),
                  description="Share weights w of the five additive terms (A1, k2, k4, "
                  "m31, m32), and optionally a sixth, w6, of the g² term of a profile with "
                  "linear vibration (MODEL.md section 8; default 1); each > 0."),
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
