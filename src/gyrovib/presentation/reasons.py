"""Why a sensor fails a selection, in words (``select``'s ``reason``, the tables, JUnit).

One wording for the renderers and the DataFrames alike, so that the JSON's
``reason`` and the DataFrame's ``reason`` column are the same text; the results carry
the numbers (a saturating sensor's reach and range, the unknown figures) and no words.
Numbers are written with 4 significant figures, as in the tables.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from gyrovib import units
from gyrovib.core.synthesis import BOUNDED
from gyrovib.formatting import NEGLIGIBLE as NEGLIGIBLE
from gyrovib.formatting import fmt as fmt

if TYPE_CHECKING:
    from gyrovib.api import LotYields, SelectionResult


def coefficient_unit(name: str, unit: str) -> str:
    """The unit of a coefficient's bound: ``1`` for A1, ``(deg/s)^-2`` for k3, …"""
    power = units.COEFFICIENT_RATE_POWER[name.split("_")[0]]
    if power == 0:
        return "1"
    return f"({unit})^{power}"


def saturation_reason(reach: float, range_: float, peak_factor: float, unit: str) -> str:
    """Why a saturating sensor fails (docs/model.md section 9); ``reach``, ``range_`` in
    ``unit``."""
    return (f"saturated: |Ω_K3| + Σ tone amplitudes + locked peaks + {peak_factor:g}σ3 = "
            f"{reach:.6g} {unit} exceeds the range {range_:.6g} {unit}")


def saturation_text(result: SelectionResult, i: int, j: int) -> str | None:
    """Why sensor ``i`` saturates under profile ``j`` (None where it does not)."""
    found = result.saturation.get((i, j))
    if found is None:
        return None
    return saturation_reason(found[0], found[1], result.peak_factor, result.unit)


def failures(result: SelectionResult, i: int, j: int, *, table: bool = False) -> list[str]:
    """Why sensor ``i`` fails under profile ``j`` (empty when it passes there).

    Saturation first (it fails a sensor whatever the criterion), then only the
    criteria that count (``--criterion``). ``table``: as the tables write it,
    coefficients in the catalogue's unit (:attr:`~SelectionResult.table_unit`) and a negligible
    Δ_V(RMS) as 0; otherwise in :attr:`~SelectionResult.unit` (JSON, frames).
    """
    reasons: list[str] = []
    if result.is_unverified(i, j):
        reasons.append(unverified_reason(result, i, j))
    saturated = saturation_text(result, i, j)
    if saturated is not None:
        reasons.append(saturated)
    if result.yields is not None and result.yields.is_lot(i):  # judged by its yield
        return reasons + yield_reason(result.yields, i, j)
    spec = result.source(i) == "specs"
    if result.criterion in ("bounds", "both"):
        reasons.extend(_spec_failures(result, i, j) if spec
                       else _coefficient_failures(result, i, j, table))
    if result.criterion in ("rms", "both") and not result.rms_pass[i, j]:
        value = float(result.rms[i, j])
        rms = "0" if table and abs(value) < NEGLIGIBLE * result.budget else fmt(value)
        reasons.append(f"Δ_V(RMS) = {rms} {result.unit} exceeds the budget "
                       f"{fmt(result.budget)} {result.unit}")
    if result.criterion == "worst" and not result.passed[i, j] and result.total is not None:
        what = "worst |Δ_V| over the datasheet envelope" if spec else "|Δ_V|"
        reasons.append(f"{what} = {fmt(result.total[i, j])} {result.unit} exceeds the budget "
                       f"{fmt(result.budget)} {result.unit}")
    return reasons


def _coefficient_failures(result: SelectionResult, i: int, j: int, table: bool) -> list[str]:
    """The coefficient checks a coefficient sensor fails under profile ``j``, and its VRE."""
    out = []
    rate_unit = result.table_unit if table else result.unit
    values = result.table_values if table else result.values
    bounds = result.table_bounds if table else result.bounds
    for b, name in enumerate(BOUNDED):
        if not result.check_pass[i, j, b]:
            unit = coefficient_unit(name, rate_unit)
            tail = "" if unit == "1" else f" {unit}"
            value, bound = float(values[i, j, b]), float(bounds[i, j, b])
            out.append(f"|{name}| = {fmt(value)} exceeds its bound {fmt(bound)}{tail}")
    if result.vre_pass is not None and not result.vre_pass[i, j]:
        out.append(_vre_failure(result, i, j))
    return out


def unverified_reason(result: SelectionResult, i: int, j: int) -> str:
    """Why sensor ``i`` is unverified under profile ``j``: the unpublished figures that can
    decide it (docs/model.md section 11), e.g. ``unverified: VRE not published (…)``; for
    a lot whose spread is not measured, why its yield is no measurement (section 14)."""
    names = result.unknown.get((i, j), ())
    figures = tuple(n for n in names if n != "spread")
    out = [unverified_text(figures, spec=result.source(i) == "specs")] if figures else []
    if "spread" in names and result.yields is not None:
        out.append(unmeasured_text(result.yields, i, j))
    return "; ".join(out)


def unmeasured_text(yields: LotYields, i: int, j: int) -> str:
    """The reason of a lot whose yield is not a measurement (docs/model.md section 14)."""
    return (f"unverified: the yield {yield_text(yields, i, j)} is not a measurement, the "
            f"lot's spread is not measured: {yields.unmeasured[i]} -- measure more units, "
            "or --assume-unknown zero to take the lot as given")


#: Why each unknown figure can matter, as a reason names it.
UNKNOWN_WORDS = {
    "vre": "VRE not published (the profile has linear vibration, so its g² term "
           "G_jj·⟨a_j²⟩ can rectify; docs/model.md section 8)",
    "m31": "m31 not published (the profile has cross-axis vibration x1 correlated with "
           "x3, so m31·C31 can rectify; docs/model.md section 11)",
    "m32": "m32 not published (the profile has cross-axis vibration x2 correlated with "
           "x3, so m32·C32 can rectify; docs/model.md section 11)",
    "spread": "the lot's spread is not measured (too few units, or units without spread: "
              "its yield is not a measurement; docs/model.md section 14)",
    # the noise figures of a mission's budget (docs/model.md section 15)
    "arw": "angle random walk not given (N·√T)",
    "bias_instability": "bias instability not given (B·T)",
    "rrw": "rate random walk not given (K·T^1.5/√3)",
    "bias_repeatability": "bias repeatability not given (R·T; 0 if the bias is calibrated "
                          "at each start)",
}


#: What a profile fitted from a recording may lack (docs/model.md section 13), as a reason
#: names it.
NOT_RECORDED_WORDS = {"x1": "axis x1", "x2": "axis x2", "x3": "axis x3 (the sensitive axis)",
                      "acceleration": "the accelerations"}


def unverified_text(names: Sequence[str], spec: bool = True) -> str:
    """The reason of an unverified verdict whose unpublished figures are ``names``
    (``select`` and ``mission`` alike); ``spec``: a datasheet part (else a coefficient
    sensor, whose missing g² figure is "not given" rather than "not published"). Names of
    :data:`NOT_RECORDED_WORDS` are parts a fitted profile's recording did not record."""
    parts = [n for n in names if n in NOT_RECORDED_WORDS]
    figures = [n for n in names if n not in NOT_RECORDED_WORDS]
    out = []
    if parts:
        out.append("unverified: the profile was fitted from a recording without "
                   + ", ".join(NOT_RECORDED_WORDS[n] for n in parts)
                   + ", and this sensor's error depends on it (unknown, not 0; docs/model.md "
                   "section 13) -- record every axis")
    if figures:
        out.append("unverified: passes on its published figures, but "
                   + "; ".join(UNKNOWN_WORDS[n] if spec or n != "vre" else G2_WORDS
                               for n in figures)
                   + " -- ask the vendor, or --assume-unknown zero to take it as 0")
    return "; ".join(out)


#: Why a coefficient-form sensor's missing g² figure can matter, as a reason names it.
G2_WORDS = ("g² sensitivity not given (no g2_sensitivity or vre in the catalogue; the profile "
            "has linear vibration, so its g² term G_jj·⟨a_j²⟩ can rectify; docs/model.md "
            "section 8)")


def unknown_label(result: SelectionResult, i: int, name: str) -> str:
    """An unknown figure of sensor ``i`` as tables name it: ``VRE`` (a datasheet part's),
    ``g²`` (a coefficient-form sensor's g² sensitivity), ``m31``, ``m32``."""
    if name != "vre":
        return name
    return "VRE" if result.source(i) == "specs" else "g²"


def _vre_failure(result: SelectionResult, i: int, j: int) -> str:
    """A coefficient sensor's effective VRE above its bound (docs/model.md section 8)."""
    assert result.vre_value is not None and result.vre_bound is not None
    unit = f"{result.unit}/g^2"
    return (f"effective VRE |Δ0(6)|/Σ⟨a_j²⟩ = {fmt(result.vre_value[i, j])} {unit} exceeds "
            f"its bound {fmt(result.vre_bound[i, j])} {unit}")


def _spec_failures(result: SelectionResult, i: int, j: int) -> list[str]:
    """A datasheet sensor's figures above their spec bounds (docs/model.md section 11)."""
    out: list[str] = []
    assert result.nl_pass is not None and result.nl_value is not None
    assert result.nl_bound is not None and result.vre_pass is not None
    assert result.vre_value is not None and result.vre_bound is not None
    if not result.nl_pass[i, j]:
        out.append(f"datasheet nonlinearity {fmt(result.nl_value[i, j])} %FS exceeds the "
                   f"allowable {fmt(result.nl_bound[i, j])} %FS")
    if not result.vre_pass[i, j] and not np.isnan(result.vre_value[i, j]):
        out.append(f"datasheet VRE {fmt(result.vre_value[i, j])} {result.unit}/g² exceeds the "
                   f"allowable {fmt(result.vre_bound[i, j])} {result.unit}/g²")
    return out


def reason(result: SelectionResult, i: int, j: int) -> str | None:
    """Why sensor ``i`` fails under profile ``j``, one line in :attr:`~SelectionResult.unit`
    (the JSON's and the frame's ``reason``); None where it passes."""
    if result.passed[i, j]:
        return None
    return "; ".join(failures(result, i, j)) or None


def yield_text(yields: LotYields, i: int, j: int) -> str:
    """A lot's yield in words: ``0.9912 (exact)`` or ``0.9911 [0.9905, 0.9917] (monte-carlo,
    100000 draws)``."""
    value = float(yields.value[i, j])
    if yields.method == "exact":
        return f"{fmt(value, 4)} (exact)"
    return (f"{fmt(value, 4)} [{fmt(float(yields.low[i, j]), 4)}, "
            f"{fmt(float(yields.high[i, j]), 4)}] (monte-carlo, {yields.draws} draws)")


def yield_reason(yields: LotYields, i: int, j: int) -> list[str]:
    """Why lot ``i`` fails under profile ``j`` by its yield (empty when the yield is
    enough: it fails there by saturation only)."""
    if float(yields.value[i, j]) >= yields.target:
        return []
    return [f"yield {yield_text(yields, i, j)} is below {yields.target:g}"]
