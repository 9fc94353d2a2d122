"""Unit handling: catalogue values to deg/s on the way in, results to the output unit out.

A rate unit ``U`` equals ``s`` deg/s; a quantity carrying ``rate**p``
converts as ``q[U] = q[deg/s]·s**(-p)`` (docs/model.md, units).
"""

from __future__ import annotations

import operator
from collections.abc import Sequence

import numpy as np

from gyrovib import units
from gyrovib.catalog.loader import ProfileEntry, SensorEntry
from gyrovib.core._types import FloatArray
from gyrovib.core.analysis import BOUNDED, COEFFICIENTS, VibrationError
from gyrovib.errors import OptionError
from gyrovib.models.sensor import G2Quantity

_RATE_POWERS = np.array([units.COEFFICIENT_RATE_POWER[c] for c in COEFFICIENTS], dtype=float)
_GET_COEFFICIENTS = operator.attrgetter(*COEFFICIENTS)
_SPEC_ROW = tuple(1.0 if c == "k1" else 0.0 for c in COEFFICIENTS)


def unit_scales(entries: Sequence[SensorEntry] | Sequence[ProfileEntry]) -> FloatArray:
    """deg/s per rate unit of each entry's file."""
    known: dict[str, float] = {}
    out = []
    for e in entries:
        unit = e.unit
        s = known.get(unit)
        if s is None:
            s = known[unit] = units.scale(unit)
        out.append(s)
    return np.array(out, dtype=float)


def g2_value(value: float | str | G2Quantity, rate_unit: str) -> float:
    """A g² sensitivity as the catalogue holds it, in deg/s per g².

    A bare number is in the file's ``rate_unit`` per g² (as datasheets quote a
    VRE, whatever the file's acceleration unit: a bare number where that is not g
    is refused by the models); a :class:`~gyrovib.models.sensor.G2Quantity` carries
    its unit, a rate unit per g² or per (m/s²)²: G[deg/s/g²] = v·s_rate / a², a in
    g per acceleration unit (9.80665⁻¹ for m/s²), so per (m/s²)² is 96.17× per g².
    """
    if isinstance(value, (int, float)):
        return float(value) * units.scale(rate_unit)
    assert isinstance(value, G2Quantity), "a text form is a G2Quantity once validated"
    a = units.acceleration(value.acceleration_unit)
    return value.value * units.scale(value.rate_unit) / (a * a)


def coefficient_matrix(entries: Sequence[SensorEntry]) -> FloatArray:
    """Eq. (2) coefficients of every sensor in deg/s powers, shape (sensors, 11).

    A spec-form sensor (``specs:``) has no single conversion function: its row
    is k1 = 1 and zeros, a placeholder the commands replace by the worst case
    over its envelope (:mod:`gyrovib.api.datasheet.specs`).
    """
    raw = np.array(
        [_SPEC_ROW if e.sensor.specs is not None else _GET_COEFFICIENTS(e.sensor.rate_coefficients)
         for e in entries], dtype=float
    ).reshape(len(entries), len(COEFFICIENTS))
    scales = unit_scales(entries)
    if np.all(scales == 1.0):
        return raw
    out: FloatArray = raw * scales[:, None] ** _RATE_POWERS[None, :]
    return out


def sensor_ranges(entries: Sequence[SensorEntry]) -> FloatArray:
    """Full-scale range of each sensor in deg/s (inf where not given; a spec's own range)."""
    ranges = np.array(
        [e.sensor.range if e.sensor.range is not None
         else e.sensor.specs.range if e.sensor.specs is not None else np.inf
         for e in entries], dtype=float
    )
    out: FloatArray = ranges * unit_scales(entries)
    return out


def profile_rate(entry: ProfileEntry) -> FloatArray:
    """The profile's carrier rate Ω_K about x1, x2, x3 in deg/s."""
    return np.asarray(entry.profile.rate, dtype=float) * units.scale(entry.unit)


def resolve_rate(entry: ProfileEntry, override: Sequence[float] | None) -> FloatArray:
    """Ω_K in deg/s: the profile's, or an override (one number: Ω_K3 only; three: all)."""
    rate = profile_rate(entry)
    if override is None:
        return rate
    values = np.asarray(override, dtype=float)
    if values.size == 1:
        rate = rate.copy()
        rate[2] = float(values[0])
        return rate
    if values.size == 3:
        out: FloatArray = values.astype(float)
        return out
    raise OptionError("a rate is one number (Ω_K3) or three (Ω_K1, Ω_K2, Ω_K3)")


def to_unit(error: VibrationError, unit: str, *, in_place: bool = False) -> VibrationError:
    """Convert an error computed in deg/s to ``unit`` (Δ(q) carries rate^(1−q)).

    The additive terms of ``extra_terms`` (Δ0(6), k3·M3, k5·M5) are rates, like Δ0.
    ``in_place``: divide ``error``'s own arrays (the same values, without a second
    copy of a large result) and return it; a scale of 1 (deg/s) then costs nothing.
    """
    s = units.scale(unit)
    q_factor = np.array([1.0, s, s * s])
    if in_place:
        if s != 1.0:
            for array in (error.additive_terms, error.additive, error.multiplicative,
                          error.total, error.rms, error.extra_terms):
                np.divide(array, s, out=array)
            np.multiply(error.multiplicative_coefficients, q_factor,
                        out=error.multiplicative_coefficients)
        return error
    return VibrationError(
        additive_terms=error.additive_terms / s,
        multiplicative_coefficients=error.multiplicative_coefficients * q_factor,
        additive=error.additive / s,
        multiplicative=error.multiplicative / s,
        total=error.total / s,
        rms=error.rms / s,
        extra_terms=error.extra_terms / s,
    )


def error_arrays(error: VibrationError) -> list[FloatArray]:
    """The arrays of an error that must be finite (the sums follow from them)."""
    return [error.additive_terms, error.multiplicative_coefficients, error.total, error.rms,
            error.extra_terms]


def bound_factors(unit: str) -> dict[str, float]:
    """deg/s → ``unit`` factors of each bounded coefficient: ``s**(-p)`` for rate power p."""
    s = units.scale(unit)
    return {name: s ** (-units.COEFFICIENT_RATE_POWER[name]) for name in BOUNDED}


def catalog_unit(file_units: Sequence[str]) -> str | None:
    """The rate unit the entries' files share (canonical), or None when they differ."""
    found = {units.canonical_unit(u) for u in file_units}
    return found.pop() if len(found) == 1 else None
