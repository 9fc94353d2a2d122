"""Renderers of :class:`gyrovib.api.SweepResult`: Δ_V over a range of Ω_K3."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

import numpy as np
from rich.table import Table
from rich.text import Text

from gyrovib.api import SweepResult
from gyrovib.api.evaluation.records import sweep_columns
from gyrovib.records import names, written
from gyrovib.render.common import (
    csv_cell,
    csv_head,
    dumps,
    float_cells,
    fmt,
    fmt_budget,
    header,
    number,
    rich_text,
)

METHODS = ("exact", "paper")


def _saturated(result: SweepResult) -> Any:
    sat = result.saturated
    if sat is None:
        return np.zeros((len(result.sensors), len(result.profiles), len(result.rates)), bool)
    return sat


def _series(result: SweepResult) -> Iterator[tuple[int, int]]:
    for j in range(len(result.profiles)):
        for i in range(len(result.sensors)):
            yield i, j


def to_json(result: SweepResult, budget: float | None = None) -> str:
    """One series per sensor × profile; the paper's arrays are ``null`` where it refuses."""
    document = header("exact", result.unit)
    document["methods"] = list(METHODS)
    if budget is not None:
        document["budget"] = budget
    document["rates"] = result.rates.tolist()
    document["paper_refused"] = dict(result.paper_refused)
    series: list[dict[str, Any]] = []
    for i, j in _series(result):
        row: dict[str, Any] = {"sensor": result.sensors[i], "profile": result.profiles[j]}
        for method in METHODS:
            err = getattr(result, method)
            if method == "paper" and result.profiles[j] in result.paper_refused:
                row[method] = None
            else:
                row[method] = {"total": [number(x) for x in err.total[i, j]],
                               "rms": [number(x) for x in err.rms[i, j]]}
        row["saturated"] = [bool(v) for v in _saturated(result)[i, j]]
        series.append(row)
    document["series"] = series
    return dumps(document)


def to_csv(result: SweepResult, budget: float | None = None) -> str:
    """Long format: one row per sensor × profile × rate; empty paper cells where it refuses.

    The text of :func:`to_csv_chunks`, joined.
    """
    return "".join(to_csv_chunks(result, budget))


def to_csv_chunks(result: SweepResult, budget: float | None = None) -> Iterator[str]:
    """:func:`to_csv` in pieces: the header, then one piece per sensor × profile series.

    The records are those the DataFrame declares
    (:func:`gyrovib.api.evaluation.records.sweep_columns`; a test holds this writer to them),
    written column by column (each number ``repr`` of its float, as
    :func:`~gyrovib.render.common.csv_text` writes it): the rate column is
    written once for every series, a series' sensor and profile cells once as
    its rows' common prefix, and only one series' text is held at a time.
    """
    yield csv_head(names(written(sweep_columns(result), "csv")))
    rates = float_cells(result.rates)
    n = len(rates)
    if not n:
        return
    saturated = _saturated(result)
    e, p = result.exact, result.paper
    for i, j in _series(result):
        refused = result.profiles[j] in result.paper_refused
        prefix = f"{csv_cell(result.sensors[i])},{csv_cell(result.profiles[j])},"
        # where the paper refuses, its two empty cells ride on the saturated column
        flags = (",,False", ",,True") if refused else ("False", "True")
        sat = saturated[i, j]
        cells = ([flags[1]] * n if sat.all() else [flags[0]] * n if not sat.any()
                 else list(map(flags.__getitem__, sat.tolist())))
        columns = [rates, float_cells(e.total[i, j]), float_cells(e.rms[i, j])]
        if not refused:
            columns += [float_cells(p.total[i, j]), float_cells(p.rms[i, j])]
        columns.append(cells)
        yield prefix + ("\n" + prefix).join(map(",".join, zip(*columns, strict=True))) + "\n"


def to_table(result: SweepResult, budget: float | None = None, width: int | None = None,
             color: bool = False,
             ascii: bool = False) -> str:
    """One table per profile × sensor: the rates as rows, exact and paper side by side."""

    out: list[Any] = []
    any_saturated = False
    for i, j in _series(result):
        refused = result.profiles[j] in result.paper_refused
        table = Table(title=f"{result.sensors[i]} / {result.profiles[j]}", title_justify="left",
                      header_style="bold")
        table.add_column(f"Ω_K3 ({result.unit})", justify="right", no_wrap=True)
        for label in ("Δ_V exact", "Δ_V paper", "Δ_V(RMS) exact", "Δ_V(RMS) paper"):
            table.add_column(label, justify="right", no_wrap=True)
        for r, rate in enumerate(result.rates):
            e, p = result.exact, result.paper
            sat = " SAT" if _saturated(result)[i, j, r] else ""
            if sat:
                any_saturated = True
            table.add_row(fmt(rate) + sat, fmt_budget(e.total[i, j, r], budget),
                          "" if refused else fmt_budget(p.total[i, j, r], budget),
                          fmt_budget(e.rms[i, j, r], budget),
                          "" if refused else fmt_budget(p.rms[i, j, r], budget))
        out.append(table)
    legend = (f"All values in {result.unit}. Δ_V of eq. (13), Δ_V(RMS) of eq. (16), at each "
              "Ω_K3 with Ω_K1, Ω_K2 of the profile.")
    if budget is not None:
        legend += f" Budget Δ*_V = {fmt(budget)} {result.unit}."
    out.append(Text(legend, style="dim"))
    if any_saturated:
        out.append(Text(f"SAT: the sensor saturates at that rate (|Ω_K3| + Σ tone amplitudes + "
                        f"locked peaks + {result.peak_factor:g}σ3 exceeds its range, docs/model.md "
                        "section 9): the values there do not hold.", style="red"))
    for profile, why in result.paper_refused.items():
        out.append(Text(f"paper: no values for {profile}: {why}", style="dim"))
    return rich_text(out, width=width, color=color, ascii=ascii)
