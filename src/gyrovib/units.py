"""Angular-rate units and the conversions of docs/model.md.

Pure Python, no numpy: used by the catalogue loader, the CLI option parsers
and the result converters alike.

Internally gyrovib computes in deg/s. A rate unit ``U`` equals ``s`` deg/s;
a quantity carrying ``rate**p`` converts as ``q[U] = q[deg/s] * s**(-p)``.
"""

from __future__ import annotations

import math
import re

from gyrovib.errors import OptionError

#: deg/s per unit.
RATE_UNITS: dict[str, float] = {
    "deg/s": 1.0,
    "deg/h": 1.0 / 3600.0,
    "rad/s": 180.0 / math.pi,
    "rpm": 6.0,
}

_ALIASES: dict[str, str] = {
    "°/s": "deg/s",
    "dps": "deg/s",
    "°/h": "deg/h",
    "deg/hr": "deg/h",
    "dph": "deg/h",
    "rad/sec": "rad/s",
}

#: The power of "rate" carried by each conversion-function coefficient (eq. 2).
COEFFICIENT_RATE_POWER: dict[str, int] = {
    "k0": 1,
    "k1": 0,
    "A1": 0,
    "k2": -1,
    "k3": -2,
    "k4": -3,
    "k5": -4,
    "m1": 0,
    "m2": 0,
    "m31": -1,
    "m32": -1,
}


def canonical_unit(name: str) -> str:
    """Return the canonical spelling of a rate unit, or raise :class:`OptionError`."""
    key = name.strip()
    key = _ALIASES.get(key, key)
    if key not in RATE_UNITS:
        known = ", ".join(RATE_UNITS)
        raise OptionError(f"unknown rate unit {name!r}; use one of {known}")
    return key


def scale(unit: str) -> float:
    """deg/s per ``unit``."""
    return RATE_UNITS[canonical_unit(unit)]


def factor(unit: str, power: int) -> float:
    """Multiplier taking a quantity of ``rate**power`` from ``unit`` to deg/s."""
    return scale(unit) ** power


_QUANTITY = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(\S.*?)?\s*$")


def coefficient_factor(name: str, source: str, target: str) -> float:
    """Factor taking coefficient ``name`` (or its bound) from rate unit ``source`` to ``target``.

    A coefficient of rate power p (:data:`COEFFICIENT_RATE_POWER`) in unit U is
    c[deg/s]·scale(U)^(−p), so c[target] = c[source]·(scale(target)/scale(source))^(−p).
    """
    power = COEFFICIENT_RATE_POWER[name.split("_")[0]]
    return float((scale(target) / scale(source)) ** (-power))


def coefficient_unit(name: str, unit: str) -> str:
    """The unit of coefficient ``name`` (or its bound) in rate unit ``unit``: ``1`` for A1,
    ``(deg/s)^-2`` for k3, …"""
    power = COEFFICIENT_RATE_POWER[name.split("_")[0]]
    return "1" if power == 0 else f"({unit})^{power}"


def quantity_unit(text: str) -> str | None:
    """The canonical unit a quantity such as ``"36deg/h"`` carries, or None for a bare number.

    Text that is not a quantity gives None (:func:`parse_rate` reports it).
    """
    match = _QUANTITY.match(text)
    if match is None or not match.group(2):
        return None
    try:
        return canonical_unit(match.group(2))
    except OptionError:
        return None


def parse_rate(text: str, default_unit: str) -> float:
    """Parse ``"0.01"``, ``"36deg/h"`` or ``"0.01 deg/s"`` into deg/s.

    A bare number is in ``default_unit``. Raises :class:`OptionError` for
    anything else, and for NaN or infinite values.
    """
    match = _QUANTITY.match(text)
    if match is None:
        raise OptionError(
            f"cannot read {text!r} as a rate: write a number, optionally with a unit, "
            "e.g. 0.01, 36deg/h or '0.01 deg/s'"
        )
    value = float(match.group(1))
    unit = canonical_unit(match.group(2)) if match.group(2) else canonical_unit(default_unit)
    result = value * RATE_UNITS[unit]
    if not math.isfinite(result):
        raise OptionError(f"{text!r} is not a finite rate")
    return result


class NotPositive(OptionError):
    """A quantity that had to be positive was not (its text or number in ``value``, as
    written by ``repr``)."""

    def __init__(self, value: object) -> None:
        super().__init__(f"{value!r} must be positive")
        self.value = repr(value)


def quantity(value: str | float, unit: str, *, positive: bool = False) -> float:
    """A rate in deg/s: a number in ``unit``, or a text with its own unit (``"36deg/h"``).

    The one reading of "a number with a unit", shared by the command line's
    options and the notebook's arguments (each words the refusal for its
    own face). Raises :class:`OptionError` for text that is not a finite rate
    or a number that overflows in deg/s, :class:`NotPositive` for a value
    ≤ 0 when ``positive``.
    """
    if isinstance(value, str):
        rate = parse_rate(value, unit)
    else:
        rate = float(value) * scale(unit)
        if not math.isfinite(rate):
            raise OptionError(f"{value!r} {canonical_unit(unit)} overflows")
    if positive and not rate > 0:
        raise NotPositive(value)
    return rate


#: Standard gravity, m/s² per g (ISO 80000-3).
#: The noise figures of a sensor (docs/model.md section 15): per figure, its default
#: unit first, and every unit it may be written in with its factor to the default.
#: 1 deg/s/√Hz = 1 deg/√s (a one-sided PSD's √ level) = 60 deg/√h; 1 deg/h/√Hz = 1/60
#: deg/√h; deg/s of a bias is 3600 deg/h; 1 deg/s/√s = 216 000 deg/h/√h.
NOISE_UNITS: dict[str, dict[str, float]] = {
    "arw": {"deg/sqrt(h)": 1.0, "deg/√h": 1.0, "°/sqrt(h)": 1.0, "°/√h": 1.0,
            "deg/s/sqrt(Hz)": 60.0, "deg/s/√Hz": 60.0, "°/s/sqrt(Hz)": 60.0, "°/s/√Hz": 60.0,
            "deg/h/sqrt(Hz)": 1.0 / 60.0, "deg/h/√Hz": 1.0 / 60.0, "°/h/sqrt(Hz)": 1.0 / 60.0,
            "°/h/√Hz": 1.0 / 60.0, "deg/sqrt(s)": 60.0, "deg/√s": 60.0},
    "bias_instability": {"deg/h": 1.0, "°/h": 1.0, "deg/s": 3600.0, "°/s": 3600.0},
    "rrw": {"deg/h/sqrt(h)": 1.0, "deg/h/√h": 1.0, "°/h/sqrt(h)": 1.0, "°/h/√h": 1.0,
            "deg/s/sqrt(s)": 216_000.0, "deg/s/√s": 216_000.0},
    "bias_repeatability": {"deg/h": 1.0, "°/h": 1.0, "deg/s": 3600.0, "°/s": 3600.0},
}


def noise_factor(figure: str, unit: str) -> float:
    """The factor from ``unit`` to the default unit of noise ``figure``."""
    return NOISE_UNITS[figure][unit]


STANDARD_GRAVITY = 9.80665
#: g per unit of each linear-acceleration unit a catalogue may use (``units.acceleration``).
ACCELERATION_UNITS: dict[str, float] = {
    "g": 1.0,
    "m/s^2": 1.0 / STANDARD_GRAVITY,
    "m/s2": 1.0 / STANDARD_GRAVITY,
}


def acceleration(unit: str) -> float:
    """g per ``unit`` of linear acceleration (``"g"``, ``"m/s^2"`` or ``"m/s2"``).

    An acceleration ``a`` in ``unit`` is ``a·acceleration(unit)`` g; a PSD in
    unit²/Hz takes the square, and a g²-sensitivity (rate per unit²) the
    inverse square (docs/model.md section 8).
    """
    try:
        return ACCELERATION_UNITS[unit.strip()]
    except KeyError:
        known = ", ".join(ACCELERATION_UNITS)
        raise OptionError(f"unknown acceleration unit {unit!r}; use one of {known}") from None
