"""Renderers of :class:`gyrovib.api.FitResult` (``gyrovib fit``, docs/model.md section 14):
table, JSON, CSV, Markdown, the catalogue YAML of ``-o`` and the residual plot."""

from __future__ import annotations

from typing import Any

from rich.text import Text

from gyrovib.api.ratetable.results import (
    FitResult,
    lot_mapping,
    output_unit,
    pairs,
)
from gyrovib.core.fit import SIGNIFICANT_T
from gyrovib.render.common import dumps, fmt, header, number, png, rich_text
from gyrovib.render.formats import Cell, csv_of, markdown_of, table_of
from gyrovib.render.plot import _figure_class


def _numbers(names: tuple[str, ...], values: Any) -> dict[str, float | None]:
    return {n: number(v) for n, v in zip(names, values, strict=True)}


def unit_document(result: FitResult, i: int) -> dict[str, Any]:
    """One unit as the JSON writes it (docs/rate-table.md)."""
    f = result.fits[i]
    names = result.names
    return {
        "unit": result.units[i],
        "coefficients": _numbers(names, f.values),
        "uncertainty": {"sigma": _numbers(names, f.sigma),
                        "correlation": pairs(names, f.correlation)},
        "t": _numbers(names, f.t),
        "residual_rms": number(f.residual_rms),
        "nonlinearity": {"least_squares_max": number(f.nonlinearity.least_squares_max),
                         "endpoint_max": number(f.nonlinearity.endpoint_max),
                         "unit": "%FS", "range": number(f.nonlinearity.range)},
        "points": f.points,
    }


def to_json(result: FitResult) -> str:
    """The JSON document: header, file, order, output unit, ``units`` (one object per
    unit), ``lot`` when there are two or more units, ``warnings``."""
    document = header(result.method, result.unit)
    document.update({"output_unit": result.output_unit, "file": result.file,
                     "order": result.order,
                     "units": [unit_document(result, i) for i in range(len(result.units))]})
    if result.lot is not None:
        document["lot"] = lot_mapping(result)
    document["warnings"] = list(result.warnings)
    return dumps(document)


def to_csv(result: FitResult) -> str:
    """One row per unit × coefficient: the result's records (the DataFrame's columns)."""
    return csv_of(result.records(), result.rows())


def _title(result: FitResult, i: int) -> str:
    f = result.fits[i]
    out = output_unit(result)
    return (f"{result.units[i]}: {f.points} points, K1 = {fmt(f.scale_factor, 6)} ± "
            f"{fmt(f.scale_factor_sigma, 2)} {out} per {result.unit}, residual rms "
            f"{fmt(f.residual_rms, 3)} {out}")


def _nonlinearity(result: FitResult, i: int) -> str:
    nl = result.fits[i].nonlinearity
    return (f"nonlinearity over ±{fmt(nl.range)} {result.unit}: "
            f"{fmt(nl.least_squares_max, 3)} %FS (least-squares line), "
            f"{fmt(nl.endpoint_max, 3)} %FS (endpoint line)")


def _unit_cells(result: FitResult) -> tuple[Cell[tuple[int, int]], ...]:
    """A unit's table (terminal and Markdown): one row per coefficient, a row being the
    records' (unit, coefficient) (:meth:`FitResult.records`)."""
    fits, units = result.fits, result.coefficient_units()

    def note(r: tuple[int, int]) -> str:
        significant = abs(float(fits[r[0]].t[r[1]])) >= SIGNIFICANT_T
        return "" if significant else "not significant (|t| < 2)"

    return (Cell("coefficient", of="coefficient"),
            Cell("value", lambda r: fmt(fits[r[0]].values[r[1]]), "right", of="value"),
            Cell("σ", lambda r: fmt(fits[r[0]].sigma[r[1]], 2), "right", of="sigma"),
            Cell("t", lambda r: fmt(float(fits[r[0]].t[r[1]]), 3), "right", of="t"),
            Cell("unit", lambda r: units[r[1]], of="coefficient_unit"),
            Cell("note", note, no_wrap=False, of="significant"))


def _lot_cells(result: FitResult) -> tuple[Cell[int], ...]:
    """The lot's table: one row per coefficient (its index)."""
    lot = result.lot
    assert lot is not None
    units = result.coefficient_units()
    return (Cell("coefficient", result.names.__getitem__),
            Cell("mean", lambda k: fmt(lot.mean[k]), "right"),
            Cell("σ (unit to unit)", lambda k: fmt(lot.sigma[k], 3), "right"),
            Cell("unit", units.__getitem__))


def _unit_rows(result: FitResult, i: int) -> list[tuple[int, int]]:
    return [(i, k) for k in range(len(result.names))]


def _lot_title(result: FitResult) -> str:
    return f"The lot: {len(result.units)} units of {result.file}"


def _legend(result: FitResult) -> str:
    return (f"Eq. (2) coefficients (k1 = 1 by construction: eq. (1) divided by K1), in "
            f"{result.unit} powers, with standard uncertainties σ (delta method) and "
            "t = value/σ; a term with |t| < 2 is kept, flagged. Nonlinearity: the fitted "
            "curve's largest deviation from its least-squares line and from its endpoint "
            f"line, in % of the largest |rate| tested (docs/model.md section 14). Fit of order "
            f"{result.order}.")


def to_table(result: FitResult, width: int | None = None, color: bool = False,
             ascii: bool = False) -> str:
    """One table per unit (coefficients, σ, t), then the lot's mean and spread."""

    items: list[Any] = []
    for i in range(len(result.units)):
        items += [table_of(_unit_cells(result), _unit_rows(result, i), result.records(),
                           title=_title(result, i)),
                  Text(_nonlinearity(result, i))]
    if result.lot is not None:
        items.append(table_of(_lot_cells(result), range(len(result.names)),
                              title=_lot_title(result)))
    items.append(Text(_legend(result), style="dim"))
    items += [Text(f"warning: {w}", style="yellow") for w in result.warnings]
    return rich_text(items, width=width, color=color, ascii=ascii)


def to_markdown(result: FitResult) -> str:
    """One Markdown table per unit, then the lot's."""
    parts = [f"Rate-table fit of `{result.file}`, order {result.order}\n"]
    for i in range(len(result.units)):
        parts.append(f"**{_title(result, i)}**\n\n"
                     + markdown_of(_unit_cells(result), _unit_rows(result, i), result.records())
                     + f"\n{_nonlinearity(result, i)}\n")
    if result.lot is not None:
        parts.append(f"**{_lot_title(result)}**\n\n"
                     + markdown_of(_lot_cells(result), range(len(result.names))))
    parts.append(_legend(result) + "\n")
    parts += [f"Warning: {w}\n" for w in result.warnings]
    return "\n".join(parts)


# --------------------------------------------------------------------------- catalogue YAML


# --------------------------------------------------------------------------- plot


def residuals_png(result: FitResult, dpi: int = 100) -> bytes:
    """Residuals U − Û against the rate, one panel per unit (matplotlib, optional)."""

    figure_class = _figure_class()
    n = len(result.units)
    columns = min(n, 2)
    rows = (n + columns - 1) // columns
    fig = figure_class(figsize=(5.0 * columns, 1.0 + 2.4 * rows), dpi=dpi, layout="constrained")
    axes = fig.subplots(rows, columns, squeeze=False, sharex=True)
    out = output_unit(result)
    for k, (name, f) in enumerate(zip(result.units, result.fits, strict=True)):
        ax = axes[k // columns][k % columns]
        ax.axhline(0.0, color="0.6", lw=0.8)
        ax.plot(f.rates, f.residuals, "o", ms=3.5, color="C0")
        ax.set_title(f"{name}: residual rms {fmt(f.residual_rms, 3)} {out}", fontsize=9,
                     loc="left")
        ax.set_ylabel(f"residual ({out})")
        ax.set_xlabel(f"rate ({result.unit})")
    for k in range(n, rows * columns):
        axes[k // columns][k % columns].set_visible(False)
    return png(fig)
