"""A run-up result as a catalogue sensor entry (``gyrovib: 1``) with the in-situ figures and
their standard uncertainties, which ``analyze``, ``select`` and ``mission`` read like any
other sensor.

The eq. (2) terms go in ``coefficients`` with the ``uncertainty`` block of docs/model.md
section 14 (σ and the correlation pairs); ``vre`` and the G_jk go in ``vre`` or
``g2_sensitivity``, whose format holds no uncertainty: theirs is written as a comment.
A term this test could not identify is not written (a comment says so). Terms not
estimated are taken from the catalogue sensor where it gives coefficients; otherwise
they are the format's default, 0, which the header says.
"""

from __future__ import annotations

import math
import os
import re
from typing import Any

import numpy as np

from gyrovib._version import __version__
from gyrovib.api.runup.results import Estimate, RunupResult
from gyrovib.api.study.convert import coefficient_matrix
from gyrovib.api.study.entries import select_entries
from gyrovib.api.study.linear import g2_matrix
from gyrovib.catalog.loader import parse_catalog
from gyrovib.catalog.writer import SIGMA_DIGITS
from gyrovib.core.analysis import COEFFICIENTS
from gyrovib.core.linear import G2_TERMS
from gyrovib.errors import GyrovibError

#: The eq. (2) terms that the ``coefficients`` block holds (and ``uncertainty``).
_RATE_TERMS = ("A1", "k2", "k4", "m31", "m32")


def _num(value: float, sigma: float | None = None) -> str:
    """A float as YAML 1.1 and 1.2 both read it (a dot in the mantissa), to the decimal
    place of ``sigma``'s :data:`SIGMA_DIGITS`-th digit when given, else 6 digits."""
    v = float(value)
    digits = 6
    if sigma is not None and math.isfinite(sigma) and sigma > 0 and v != 0:
        quantum = math.floor(math.log10(sigma)) - SIGMA_DIGITS + 1
        digits = max(1, min(12, math.floor(math.log10(abs(v))) - quantum + 1))
    text = format(v, f".{digits}g")
    if "e" in text:
        mantissa, exponent = text.split("e")
        return (mantissa if "." in mantissa else mantissa + ".0") + "e" + exponent
    return text if "." in text else text + ".0"


def _id(result: RunupResult) -> str:
    stem = result.sensor or os.path.basename(result.file).split(".")[0] or "sensor"
    clean = re.sub(r"[^A-Za-z0-9._-]+", "-", stem).strip("-.") or "sensor"
    return f"{clean}-insitu"[:200]


def _carried(result: RunupResult, catalog: Any) -> tuple[dict[str, float], dict[str, float]]:
    """The catalogue sensor's non-zero eq. (2) coefficients (deg/s powers) and g² terms
    (deg/s/g²), when it gives coefficients (not a datasheet); the g² terms only when
    the test estimated none."""
    if result.sensor is None or catalog is None:
        return {}, {}
    entry = select_entries(catalog, (result.sensor,), (), need=("sensors",))[0][0]
    if entry.sensor.specs is not None:
        return {}, {}
    row = coefficient_matrix([entry])[0]
    rate = {n: float(v) for n, v in zip(COEFFICIENTS, row, strict=True)
            if v != 0 and n not in ("k1",)}
    if any(e.name not in _RATE_TERMS for e in result.estimates):
        return rate, {}
    g2 = {n: float(v) for n, v in zip(G2_TERMS, g2_matrix([entry])[0], strict=True) if v != 0}
    return rate, g2


def _header(result: RunupResult, written: list[Estimate], left: list[Estimate],
            carried: bool) -> list[str]:
    lines = [
        f"# Written by gyrovib {__version__} runup from {os.path.basename(result.file)}"
        + ("" if result.source is None else f" ({result.source})")
        + f" (sha256 {result.sha256[:16]}…, {len(result.steps)} steps, fs {result.fs:.6g} Hz):",
        "# the installed sensor's in-situ figures (docs/model.md section 16), each with its "
        "standard",
        f"# uncertainty (k = 1; reduced χ² {result.reduced_chi2:.3g}, inflation "
        f"{result.inflation:.3g}).",
    ]
    lines += [f"# not written, not identifiable from this test: {e.name} ({e.separate})"
              for e in left]
    lines += [f"# {e.name} is not significant (|value| < 2u): written with its uncertainty; "
              "remove it to take it as 0" for e in written if e.status == "not significant"]
    if carried:
        lines.append(f"# the terms not estimated (or not identified) as catalogue sensor "
                     f"{result.sensor} gives them")
    else:
        lines.append("# terms not estimated here are the format's default, 0: add the "
                     "datasheet's or the rate table's")
    if not written:
        lines.append("# no term was identifiable: the entry holds no in-situ figure")
    return lines


def runup_yaml(result: RunupResult, catalog: Any = None) -> str:
    """The sensor entry (see the module docstring), validated by the catalogue loader."""
    written = [e for e in result.estimates if e.identifiable or e.status == "not significant"]
    left = [e for e in result.estimates if e not in written]
    carried, carried_g2 = _carried(result, catalog)
    rate = {e.name: e for e in written if e.name in _RATE_TERMS}
    values = {n: v for n, v in carried.items() if n not in rate}
    lines = [*_header(result, written, left, bool(carried or carried_g2)), "gyrovib: 1",
             "units:", "  rate: deg/s", "sensors:", f"  - id: {_id(result)}"]
    lines += _rate_lines(values, rate)
    if rate:
        lines += _correlation(result, list(rate))
    lines += _g2_lines([e for e in written if e.name not in _RATE_TERMS], carried_g2)
    text = "\n".join(lines) + "\n"
    try:  # what is written must load
        parse_catalog(text, "<runup sensor>")
    except GyrovibError as exc:  # a bug, not the user's: say it plainly
        raise GyrovibError(f"the in-situ sensor entry does not validate: "
                           f"{exc.problems[0].message}") from None
    return text


def _rate_lines(values: dict[str, float], rate: dict[str, Estimate]) -> list[str]:
    """``coefficients`` (carried and in-situ) and the in-situ terms' ``uncertainty``."""
    coeffs = [f"{n}: {_num(v)}" for n, v in values.items()]
    coeffs += [f"{n}: {_num(e.value, e.uncertainty)}" for n, e in rate.items()]
    lines = ["    coefficients: {" + ", ".join(coeffs) + "}"]
    if rate:
        lines += ["    uncertainty:",
                  "      sigma: {" + ", ".join(f"{n}: {_num(e.uncertainty, e.uncertainty)}"
                                               for n, e in rate.items()) + "}"]
    return lines


def _correlation(result: RunupResult, names: list[str]) -> list[str]:
    index = {e.name: k for k, e in enumerate(result.estimates)}
    pairs = []
    for i, a in enumerate(names):
        for b in names[i + 1:]:
            rho = result.correlation[index[a]][index[b]]
            if math.isfinite(rho):
                pairs.append(f"        {a} {b}: {float(np.clip(rho, -1.0, 1.0)):.9f}")
    return ["      correlation:" + (" {}" if not pairs else ""), *pairs]


def _g2_lines(estimates: list[Estimate], carried: dict[str, float]) -> list[str]:
    """``vre`` or ``g2_sensitivity`` in-situ (uncertainty as a comment), or the catalogue
    sensor's ``g2_sensitivity`` carried when the test estimated no g² term."""
    lines = []
    if carried:
        lines.append("    g2_sensitivity: {" + ", ".join(f"{n}: {_num(v)}"
                                                       for n, v in carried.items()) + "}")
    for e in estimates:
        if e.name == "vre":
            lines.append(f"    vre: {_num(e.value, e.uncertainty)}    # ± "
                         f"{_num(e.uncertainty, e.uncertainty)} {e.unit} (standard "
                         "uncertainty; the format holds none for vre)")
    g = [e for e in estimates if e.name.startswith("G")]
    if g:
        lines.append("    g2_sensitivity:")
        lines += [f"      {e.name}: {_num(e.value, e.uncertainty)}    # ± "
                  f"{_num(e.uncertainty, e.uncertainty)} {e.unit}" for e in g]
    return lines


__all__ = ["runup_yaml"]
