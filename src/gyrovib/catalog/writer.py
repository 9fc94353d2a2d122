"""Catalogue YAML as gyrovib writes it: the one formatter of numbers, flow lists, tables,
mappings and quoted text for every catalogue file gyrovib emits (a recording's fitted
profile and mission, an envelope of recordings, an Allan ``noise:`` block, the sensors and
lot of ``gyrovib fit``).

The documents themselves are built beside the results they write (``api/recordings``,
``api/fleet``, ``api/noise``, ``api/ratetable``); what every one of them writes the same
way is here, so that a number cannot be spelled two ways in two files.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping

from gyrovib.errors import GyrovibError

#: Significant digits of a standard uncertainty in the catalogue ``fit -o`` writes; a value
#: is written to the same decimal place as its uncertainty (GUM 7.2.6 keeps two; one more
#: digit guards the rounding). Beyond them the digits are the machine's rounding, not the
#: data's.
SIGMA_DIGITS = 3
#: Decimal places of a written correlation: rounding each of the at most 45 pairs by
#: 5e-10 moves the matrix's eigenvalues by less than gyrovib.models' PSD_TOLERANCE (1e-8),
#: so a valid correlation matrix stays valid once written.
CORRELATION_PLACES = 9
#: Significant digits of a measured figure (a fitted spectrum, a rate, a duration).
MEASURED_DIGITS = 6


def number(value: float, significant: int = 12, quantum: float | None = None, *,
           typed: bool = True) -> str:
    """A float as a catalogue writes it.

    ``typed``: as YAML 1.2 and 1.1 both read a float (``1.5e-06`` with a dot in the
    mantissa, ``2.0`` not ``2``: ``1e-06`` would be a string to YAML 1.1), to
    ``significant`` digits or rounded to a multiple of ``quantum`` (a power of ten) when
    one is given; a value that is not finite is refused. Otherwise the shortest text of
    ``significant`` digits (``250``, ``1e-06``), and ``0`` for either zero.
    """
    v = float(value)
    if not typed:
        return "0" if v == 0 else format(v, f".{significant}g")
    if not math.isfinite(v):
        raise GyrovibError(f"cannot write the non-finite value {v!r} into a catalogue")
    text = format(v, f".{significant}g")
    if quantum is not None and v != 0:
        digits = max(1, min(12, math.floor(math.log10(abs(v))) - round(math.log10(quantum)) + 1))
        text = format(v, f".{digits}g") if abs(v) >= quantum / 2 else "0"
    if "e" in text:
        mantissa, exponent = text.split("e")
        if "." not in mantissa:
            mantissa += ".0"
        return f"{mantissa}e{exponent}"
    return text if "." in text else text + ".0"


def measured(value: float) -> str:
    """A measured figure: :data:`MEASURED_DIGITS` significant digits, shortest text."""
    return number(value, MEASURED_DIGITS, typed=False)


def quantum_of(sigma: float) -> float | None:
    """The decimal place a value with standard uncertainty ``sigma`` is written to: that of
    the uncertainty's :data:`SIGMA_DIGITS`-th significant digit (``None``, twelve significant
    digits, where the uncertainty is zero or not finite)."""
    s = float(sigma)
    if not math.isfinite(s) or s <= 0:
        return None
    return 10.0 ** (math.floor(math.log10(s)) - SIGMA_DIGITS + 1)


def flow_list(items: Iterable[str]) -> str:
    """``[a, b, c]`` of items already written."""
    return "[" + ", ".join(items) + "]"


def measured_list(values: Iterable[float]) -> str:
    """``[a, b, c]`` of measured figures (:func:`measured`)."""
    return flow_list(measured(float(v)) for v in values)


def measured_table(f: Iterable[float], g: Iterable[float]) -> str:
    """A breakpoint table ``[[f, g], ...]`` of measured figures."""
    return flow_list(f"[{measured(a)}, {measured(b)}]" for a, b in zip(f, g, strict=True))


def flow_mapping(items: Mapping[str, str]) -> str:
    """``{key: value, ...}`` of values already written."""
    return "{" + ", ".join(f"{k}: {v}" for k, v in items.items()) + "}"


def quoted(text: str) -> str:
    """A double-quoted YAML string (backslashes and quotes escaped)."""
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'
