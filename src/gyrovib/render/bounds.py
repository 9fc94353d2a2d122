"""Renderers of :class:`gyrovib.api.BoundsResult` (eq. 23, 25)."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
from rich.text import Text

from gyrovib.api import BoundsResult
from gyrovib.api.evaluation.records import bounds_columns
from gyrovib.core.synthesis import (
    BOUNDED,
    AllocationConstants,
    CoefficientBounds,
)
from gyrovib.render.common import dumps, fmt, header, rich_text
from gyrovib.render.formats import Cell, csv_of, json_of, markdown_of, table_of
from gyrovib.units import coefficient_unit


#: Unit of the VRE bound in an output rate unit (rate per g², docs/model.md section 8).
def vre_unit(unit: str) -> str:
    """``deg/s/g^2`` for ``deg/s``: the unit of a VRE (rate per g²)."""
    return f"{unit}/g^2"


def to_json(result: BoundsResult) -> str:
    """``bounds --format json`` (docs/output.md): its ``profiles`` are the result's records
    (:func:`gyrovib.api.evaluation.records.bounds_columns`, as the CSV and the frame)."""
    document = header(result.method, result.unit)
    document["budget"] = result.budget
    document["profiles"] = json_of(bounds_columns(result), range(len(result.profiles)))
    return dumps(document)


def to_csv(result: BoundsResult) -> str:
    """One row per profile: the result's records
    (:func:`gyrovib.api.evaluation.records.bounds_columns`, which the DataFrame shares); an
    unconstrained bound is written ``inf``."""
    return csv_of(bounds_columns(result), range(len(result.profiles)))


def _spec_cells(result: BoundsResult, j: int) -> tuple[Cell[str], ...]:
    """The datasheet figures' table under profile ``j``: one row per figure
    (:data:`_SPEC_ROWS`), its allowable value, unit, share of Δ* and how it is read."""
    sb = result.spec_bounds
    assert sb is not None
    total = sb.weights[0] * (sb.share_nl[j] > 0) + sb.weights[1] * (sb.share_vre[j] > 0)
    figures = {"nonlinearity": (bound_text("nonlinearity", sb.nonlinearity[j]),
                                f"%FS of {'2R' if sb.of == 'span' else 'R'}",
                                f"{fmt(sb.share_nl[j], 3)}" if total else "0",
                                f"{sb.fit}, {sb.measure}; R = {fmt(sb.range)} {result.unit}"),
               "VRE": (bound_text("VRE", sb.vre[j]), f"{result.unit}/g²",
                       fmt(sb.share_vre[j], 3), "|G_jj| of the datasheet: the VRE to ask for")}

    def part(k: int) -> Callable[[str], str]:
        return lambda figure: figures[figure][k]

    return (Cell("datasheet figure", str), Cell("allowable", part(0), "right", style="bold"),
            Cell("unit", part(1)), Cell("share of Δ*", part(2)), Cell("read as", part(3)))


#: The rows of the datasheet figures' table.
_SPEC_ROWS = ("nonlinearity", "VRE")

_SPEC_LEGEND = ("Datasheet bounds (docs/model.md section 11): a part of range R whose nonlinearity "
                "(so read) and VRE are within these meets the budget whatever its polynomial "
                "(NL_max·W(1) + VRE_max·Σ⟨a²⟩ = Δ*). unbounded = the profile does not excite it. "
                "For a purchase spec, ask for these two figures. The coefficient allocation "
                "above has its own VRE bound (share α6 of the additive terms, for a "
                "coefficient-form sensor's effective VRE |Δ0(6)|/Σ⟨a_j²⟩ beside its other "
                "coefficients; `bounds.vre` in --format json, or this command without "
                "--range); it is not the datasheet figure, and is not repeated here.")


def shares(constants: AllocationConstants, linear: bool = False, m3: bool = False,
           m5: bool = False) -> dict[str, str]:
    """The share of Δ* behind each bound, as printed in the tables.

    ``linear``: for a profile with linear vibration, whose additive shares
    include α6 for the g² term (docs/model.md section 8), so that α1..α5 shrink.
    ``m3`` / ``m5``: a profile whose phase-locked harmonics give M3 ≠ 0 /
    M5 ≠ 0 (docs/model.md section 10): k3 / k5 gain additive shares, and with M3 ≠ 0
    Δ(1) is split between k3, k4, k5 (β1/3 each) and Δ(2) between k4, k5 (β2/2).
    """
    a, b = constants.alpha, constants.beta
    extra: dict[str, str] = {}
    w, we = constants.weights, constants.extra_weights
    present = [linear, m3, m5]
    norm = math.sqrt(float(np.sum(w**2)) + sum(float(e) ** 2 for on, e in
                                                zip(present, we, strict=True) if on))
    scale = constants.c_additive / norm
    if any(present):
        a = w * scale
    if linear:
        extra["vre"] = f"α6 = {float(we[0]) * scale:.4g}"
    if m3:
        third, half2 = float(b[0]) / 3.0, float(b[1]) / 2.0
        k3_add = f"α = {float(we[1]) * scale:.4g} | "
        k5_add = f"α = {float(we[2]) * scale:.4g} | " if m5 else ""
        return {
            "A1": f"α1 = {a[0]:.4g}",
            "k2": f"α2 = {a[1]:.4g}",
            "k3": f"{k3_add}β1/3 = {third:.4g}",
            "k4": f"α3 = {a[2]:.4g} | β1/3 = {third:.4g} | β2/2 = {half2:.4g}",
            "k5": f"{k5_add}β1/3 = {third:.4g} | β2/2 = {half2:.4g} | β3 = {b[2]:.4g}",
            "m31": f"α4 = {a[3]:.4g}",
            "m32": f"α5 = {a[4]:.4g}",
            **extra,
        }
    # the exact method splits β1 equally between k3 and the linear k5 (they add
    # linearly in Δ(1), docs/model.md section 6); the paper prints its own 0.35
    half = abs(constants.k3 - float(b[0]) / 2.0) <= 1e-12 * float(b[0])
    k3 = f"β1/2 = {constants.k3:.4g}" if half else f"{constants.k3:.4g} (paper)"
    k5 = (f"β1/2 = {constants.k5_linear:.4g}" if half
          else f"{constants.k5_linear:.4g} (paper)")
    return {
        "A1": f"α1 = {a[0]:.4g}",
        "k2": f"α2 = {a[1]:.4g}",
        "k3": k3,
        "k4": f"α3 = {a[2]:.4g} | β2 = {b[1]:.4g}",
        "k5": (f"α = {float(we[2]) * scale:.4g} | " if m5 else "") + f"{k5} | β3 = {b[2]:.4g}",
        "m31": f"α4 = {a[3]:.4g}",
        "m32": f"α5 = {a[4]:.4g}",
        **extra,
    }


def shares_text(constants: AllocationConstants, linear: bool = False) -> str:
    """The shares of Δ*, each printed once: ``A1 α1 = 0.4447, …``.

    ``linear``: some profile has a linear vibration, whose g² term takes the
    share α6 so that α1…α5 shrink (docs/model.md section 8); a share that
    differs there is followed by its value under such a profile in brackets
    (``α1 = 0.4447 [0.3922]``), and ``vre α6 = [0.3922]`` exists only there.
    """
    plain = shares(constants)
    if not linear:
        return ", ".join(f"{k} {v}" for k, v in plain.items())
    moved = shares(constants, linear=True)
    out = []
    for name, text in moved.items():
        if name not in plain:  # the g² term's own share: only under linear vibration
            label, _, value = text.partition(" = ")
            out.append(f"{name} {label} = [{value}]")
            continue
        parts = []
        for before, after in zip(plain[name].split(" | "), text.split(" | "), strict=True):
            value = after.partition(" = ")[2]
            parts.append(before if before == after else f"{before} [{value}]")
        out.append(f"{name} " + " | ".join(parts))
    return ", ".join(out)

#: The parts whose least is each coefficient's bound (docs/model.md sections 6 and 10):
#: label and attribute of :class:`~gyrovib.core.synthesis.CoefficientBounds`. The
#: section-10 parts exist only with odd moments (None, or not finite, otherwise).
_CANDIDATES = {
    "k3": (("additive", "k3_additive"), ("linear", "k3_linear")),
    "k4": (("additive", "k4_additive"), ("multiplicative", "k4_multiplicative"),
           ("linear", "k4_linear")),
    "k5": (("additive", "k5_additive"), ("linear", "k5_linear"),
           ("quadratic", "k5_quadratic"), ("cubic", "k5_cubic")),
}
_ALWAYS = {"k4_additive", "k4_multiplicative", "k5_linear", "k5_cubic"}


def _which(bounds: Any, j: int, name: str) -> str:
    """For k3/k4/k5: the parts the bound is the least of, the smallest (binding) named."""
    parts = []
    for label, attr in _CANDIDATES.get(name, ()):
        values = getattr(bounds, attr, None)
        if values is None:
            continue
        value = float(values[j])
        if attr in _ALWAYS or np.isfinite(value):
            parts.append((label, value))
    if len(parts) < 2 or any(value != value for _, value in parts):  # NaN: unknown
        return ""
    if all(value == float("inf") for _, value in parts):
        return ", ".join(f"{label} ∞" for label, _ in parts) + ": unconstrained"
    binding = min(parts, key=lambda part: part[1])[0]
    return (", ".join(f"{label} {fmt(value)}" for label, value in parts)
            + f": {binding} binds")


#: |A1| < 2 for any rate sensor: its scale factors k1(1 ± A1/2) keep their sign.
A1_LIMIT = 2.0
UNBOUNDED = "unbounded"


def bound_text(name: str, value: float) -> str:
    """A coefficient's bound as a table writes it: ``unbounded`` where it constrains
    nothing (+inf: the coefficient does not act; A1: no |A1| < 2 uses up its share)."""
    v = float(value)
    if v != v:  # unknown: a profile fitted from a recording without what it depends on
        return "?"
    if v == float("inf") or (name == "A1" and v >= A1_LIMIT):
        return UNBOUNDED
    return fmt(v)


def has_vre(bounds: CoefficientBounds, j: int) -> bool:
    """Whether profile ``j`` has a linear vibration to bound (a finite VRE bound)."""
    return bounds.vre is not None and bool(np.isfinite(bounds.vre[j]))


def _rows(result: BoundsResult, j: int) -> list[str]:
    """The coefficients bounded under profile ``j``: with a linear vibration and no
    ``--range``, the effective VRE too."""
    if has_vre(result.bounds, j) and result.spec_bounds is None:
        return [*BOUNDED, "vre"]
    return list(BOUNDED)


def _cells(result: BoundsResult, j: int) -> tuple[Cell[str], ...]:
    """The coefficients' table under profile ``j``: one row per coefficient (:func:`_rows`),
    its bound (bold), unit, share of Δ* and the candidates it is the least of."""
    odd = [getattr(result.bounds, name) for name in ("k3_additive", "k5_additive")]
    m3, m5 = (part is not None and bool(np.isfinite(part[j])) for part in odd)
    share = shares(result.allocation, linear=has_vre(result.bounds, j), m3=m3, m5=m5)
    unit, converted, vre = result.table_unit, result.table_bounds, result.bounds.vre

    def bound(name: str) -> str:
        values = vre if name == "vre" else getattr(converted, name)
        assert values is not None
        return bound_text(name, values[j])

    return (Cell("coefficient", str), Cell("|bound|", bound, "right", style="bold"),
            Cell("unit", lambda n: vre_unit(result.unit) if n == "vre"
                 else coefficient_unit(n, unit)),
            Cell("share of Δ*", share.__getitem__),
            Cell("candidates", lambda n: "|Δ0(6)|/Σ⟨a_j²⟩" if n == "vre"
                 else _which(converted, j, n)))


def _title(result: BoundsResult, j: int) -> str:
    """The profile, its Ω_K3 in the catalogue's rate unit and Δ* in the output unit."""
    rate_unit = result.table_unit
    omega = float(result.table_rates[j, 2])
    return (f"{result.profiles[j]}  (Ω_K3 = {fmt(omega)} {rate_unit}, "
            f"Δ* = {fmt(result.budget)} {result.unit}, method {result.method})")


def unit_note(result: Any) -> str:
    """Where tables write coefficients in another unit than the rates, say so."""
    unit = result.table_unit
    if unit == result.unit:
        return ""
    return (f" Coefficients and their bounds are written in the catalogue's rate unit, "
            f"{unit}, to stay readable; --format json gives them in {result.unit}.")


_LEGEND = ("A sensor whose every |coefficient| is at most its bound meets the budget "
           "(eq. 17) under this allocation: sufficient, not necessary. unbounded = "
           "unconstrained (the coefficient does not act under this profile; for A1, no "
           "|A1| < 2, the most a rate sensor can have, uses up its share). k1 = 1; the "
           "sensor's own "
           "response is taken as 1 (see `gyrovib select`).")
_VRE_LEGEND = (" vre bounds the effective vibration rectification |Δ0(6)|/Σ⟨a_j²⟩ of the "
               "linear vibration, per g² (docs/model.md section 8); for a datasheet VRE v "
               "(G11 = G22 = G33 = v) it is a bound on |v|.")


def _legend(result: BoundsResult) -> str:
    linear = any(has_vre(result.bounds, j) for j in range(len(result.profiles)))
    return _LEGEND + (_VRE_LEGEND if linear else "")


def to_markdown(result: BoundsResult) -> str:
    """One Markdown table per profile."""
    parts = [f"Allowable coefficients, eq. (23) and (25), method `{result.method}`, "
             f"budget Δ* = {fmt(result.budget)} {result.unit}\n"]
    for j in range(len(result.profiles)):
        parts.append(f"**{_title(result, j)}**\n\n" + markdown_of(_cells(result, j),
                                                                  _rows(result, j)))
        if result.spec_bounds is not None:
            parts.append(markdown_of(_spec_cells(result, j), _SPEC_ROWS))
    parts.append(_legend(result) + unit_note(result) + "\n")
    if result.spec_bounds is not None:
        parts.append(_SPEC_LEGEND + "\n")
    return "\n".join(parts)


def to_table(result: BoundsResult, width: int | None = None, color: bool = False,
             ascii: bool = False) -> str:
    """One table per profile, one row per bounded coefficient."""

    out: list[Any] = []
    for j in range(len(result.profiles)):
        out.append(table_of(_cells(result, j), _rows(result, j), title=_title(result, j),
                            title_justify="left"))
        if result.spec_bounds is not None:
            out.append(table_of(_spec_cells(result, j), _SPEC_ROWS))
    out.append(Text(_legend(result) + unit_note(result), style="dim"))
    if result.spec_bounds is not None:
        out.append(Text(_SPEC_LEGEND, style="dim"))
    return rich_text(out, width=width, color=color, ascii=ascii)
