"""Why a sensor fails a selection, in words (``select``'s ``reason``, the tables, JUnit).

Kept in the library, not the renderers, so that the JSON's ``reason`` and the
DataFrame's ``reason`` column are the same text. Numbers are written with 4
significant figures, as in the tables.
"""

from __future__ import annotations

import math

from gyrovib import units
from gyrovib.api.results import SelectionResult
from gyrovib.core.synthesis import BOUNDED


def fmt(value: float | None, digits: int = 4) -> str:
    """A number for a sentence: ``digits`` significant figures, '∞' for unbounded."""
    if value is None:
        return "∞"
    v = float(value)
    if math.isinf(v):
        return "∞" if v > 0 else "-∞"
    if math.isnan(v):
        return "nan"
    if v == 0:
        return "0"
    return f"{v:.{digits}g}"


def coefficient_unit(name: str, unit: str) -> str:
    """The unit of a coefficient's bound: ``1`` for A1, ``(deg/s)^-2`` for k3, …"""
    power = units.COEFFICIENT_RATE_POWER[name.split("_")[0]]
    if power == 0:
        return "1"
    return f"({unit})^{power}"


def failures(result: SelectionResult, i: int, j: int) -> list[str]:
    """Why sensor ``i`` fails under profile ``j`` (empty when it passes there).

    Only the criteria that count (``--criterion``) are listed.
    """
    reasons: list[str] = []
    spec = result.source(i) == "specs"
    if result.criterion in ("bounds", "both") and spec:
        reasons.extend(_spec_failures(result, i, j))
    elif result.criterion in ("bounds", "both"):
        for b, name in enumerate(BOUNDED):
            if not result.check_pass[i, j, b]:
                unit = coefficient_unit(name, result.unit)
                tail = "" if unit == "1" else f" {unit}"
                reasons.append(
                    f"|{name}| = {fmt(result.values[i, j, b])} exceeds its bound "
                    f"{fmt(result.bounds[i, j, b])}{tail}"
                )
        if result.vre_pass is not None and not result.vre_pass[i, j]:
            reasons.append(_vre_failure(result, i, j))
    if result.criterion in ("rms", "both") and not result.rms_pass[i, j]:
        reasons.append(f"Δ_V(RMS) = {fmt(result.rms[i, j])} {result.unit} exceeds the budget "
                       f"{fmt(result.budget)} {result.unit}")
    if result.criterion == "worst" and not result.passed[i, j] and result.total is not None:
        what = "worst |Δ_V| over the datasheet envelope" if spec else "|Δ_V|"
        reasons.append(f"{what} = {fmt(result.total[i, j])} {result.unit} exceeds the budget "
                       f"{fmt(result.budget)} {result.unit}")
    return reasons


def _vre_failure(result: SelectionResult, i: int, j: int) -> str:
    """A coefficient sensor's effective VRE above its bound (MODEL.md section 8)."""
    assert result.vre_value is not None and result.vre_bound is not None
    unit = f"{result.unit}/g^2"
    return (f"effective VRE |Δ0(6)|/Σ⟨a_j²⟩ = {fmt(result.vre_value[i, j])} {unit} exceeds "
            f"its bound {fmt(result.vre_bound[i, j])} {unit}")


def _spec_failures(result: SelectionResult, i: int, j: int) -> list[str]:
    """A datasheet sensor's figures above their spec bounds (MODEL.md section 11)."""
    out: list[str] = []
    assert result.nl_pass is not None and result.nl_value is not None
    assert result.nl_bound is not None and result.vre_pass is not None
    assert result.vre_value is not None and result.vre_bound is not None
    if not result.nl_pass[i, j]:
        out.append(f"datasheet nonlinearity {fmt(result.nl_value[i, j])} %FS exceeds the "
                   f"allowable {fmt(result.nl_bound[i, j])} %FS")
    if not result.vre_pass[i, j]:
        out.append(f"datasheet VRE {fmt(result.vre_value[i, j])} {result.unit}/g² exceeds the "
                   f"allowable {fmt(result.vre_bound[i, j])} {result.unit}/g²")
    return out


def reason(result: SelectionResult, i: int, j: int) -> str | None:
    """Why sensor ``i`` fails under profile ``j``, one line; None where it passes."""
    if result.passed[i, j]:
        return None
    return "; ".join(failures(result, i, j)) or None
