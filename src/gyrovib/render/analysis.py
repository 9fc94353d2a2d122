"""Renderers of :class:`gyrovib.api.AnalysisResult`."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

from gyrovib.api import AnalysisResult
from gyrovib.core.analysis import ADDITIVE_TERMS, MULTIPLICATIVE_TERMS
from gyrovib.render.common import csv_text, dumps, fmt, header, markdown_table, number, rich_text

_ADDITIVE_LABELS = ("Δ0 A1", "Δ0 k2", "Δ0 k4", "Δ0 m31", "Δ0 m32")


def _rows(result: AnalysisResult) -> Iterator[tuple[int, int]]:
    for j in range(len(result.profiles)):
        for i in range(len(result.sensors)):
            yield i, j


def to_json(result: AnalysisResult) -> str:
    """INTERFACE.md ``analyze --format json``."""
    e = result.error
    extra = getattr(result, "stderr", None)
    results: list[dict[str, Any]] = []
    rates = result.rates.tolist()
    terms = e.additive_terms.tolist()
    qs = e.multiplicative_coefficients.tolist()
    additive, mult, total, rms = (e.additive.tolist(), e.multiplicative.tolist(),
                                  e.total.tolist(), e.rms.tolist())
    for i, j in _rows(result):
        row: dict[str, Any] = {
            "sensor": result.sensors[i],
            "profile": result.profiles[j],
            "rate": rates[j],
            "additive_terms": dict(zip(ADDITIVE_TERMS, terms[i][j], strict=True)),
            "multiplicative_coefficients": dict(zip(MULTIPLICATIVE_TERMS, qs[i][j], strict=True)),
            "additive": additive[i][j],
            "multiplicative": mult[i][j],
            "total": total[i][j],
            "rms": rms[i][j],
        }
        if extra is not None:
            row["stderr"] = number(extra[i, j])
        row["warnings"] = list(result.warnings.get((i, j), ()))
        results.append(row)
    document = header(result.method, result.unit)
    if getattr(result, "samples", None) is not None:
        document["samples"] = result.samples
        document["seed"] = result.seed
    document["results"] = results
    return dumps(document)


def _csv_header(with_stderr: bool = False) -> list[str]:
    return (["sensor", "profile", "rate_x1", "rate_x2", "rate_x3"]
            + [f"additive_{t}" for t in ADDITIVE_TERMS]
            + [f"multiplicative_{q}" for q in MULTIPLICATIVE_TERMS]
            + ["additive", "multiplicative", "total", "rms"]
            + (["stderr"] if with_stderr else []) + ["warnings"])


def to_csv(result: AnalysisResult) -> str:
    """One row per sensor × profile, every number at full precision.

    With the numeric method a ``stderr`` column (of ``total``) precedes ``warnings``.
    """
    e = result.error
    extra = getattr(result, "stderr", None)

    def rows() -> Iterator[list[Any]]:
        for i, j in _rows(result):
            yield [
                result.sensors[i], result.profiles[j], *map(float, result.rates[j]),
                *map(float, e.additive_terms[i, j]),
                *map(float, e.multiplicative_coefficients[i, j]),
                float(e.additive[i, j]), float(e.multiplicative[i, j]), float(e.total[i, j]),
                float(e.rms[i, j]), *([float(extra[i, j])] if extra is not None else []),
                "; ".join(result.warnings.get((i, j), ())),
            ]

    return csv_text(_csv_header(extra is not None), rows())


def to_markdown(result: AnalysisResult) -> str:
    """A Markdown table (4 significant figures) with warnings as footnotes."""
    e = result.error
    extra = getattr(result, "stderr", None)
    head = ["sensor", "profile", f"Ω_K3 ({result.unit})", *_ADDITIVE_LABELS,
            "Δ_VA", "Δ_VM", "Δ_V", *(["± stderr"] if extra is not None else []), "Δ_V(RMS)"]
    rows: list[list[str]] = []
    notes: list[str] = []
    for i, j in _rows(result):
        mark = ""
        if (i, j) in result.warnings:
            notes.extend(f"{result.sensors[i]} / {result.profiles[j]}: {w}"
                         for w in result.warnings[(i, j)])
            mark = f" ⚠{len(notes)}"
        rows.append([result.sensors[i] + mark, result.profiles[j], fmt(result.rates[j, 2]),
                     *(fmt(x) for x in e.additive_terms[i, j]), fmt(e.additive[i, j]),
                     fmt(e.multiplicative[i, j]), fmt(e.total[i, j]),
                     *([fmt(extra[i, j], 2)] if extra is not None else []), fmt(e.rms[i, j])])
    text = (f"Vibration error, method `{result.method}`, rates in {result.unit}\n\n"
            + markdown_table(head, rows))
    if extra is not None:
        text += "\n" + _numeric_note(result) + "\n"
    if notes:
        text += "\n" + "\n".join(f"⚠{k}. {n}" for k, n in enumerate(notes, 1)) + "\n"
    return text


def to_table(result: AnalysisResult, width: int | None = None, color: bool = False) -> str:
    """One rich table per profile, sensors as rows, warnings below."""
    from rich.table import Table
    from rich.text import Text

    e = result.error
    extra = getattr(result, "stderr", None)
    out: list[Any] = []
    notes: list[str] = []
    for j, profile in enumerate(result.profiles):
        omega = result.rates[j, 2]
        table = Table(
            title=f"{profile}  (Ω_K3 = {fmt(omega)} {result.unit}, method {result.method})",
            title_justify="left", header_style="bold",
        )
        table.add_column("sensor", no_wrap=True)
        for label in _ADDITIVE_LABELS:
            table.add_column(label, justify="right", no_wrap=True)
        for label in ("Δ_VA", "Δ_VM", "Δ_V"):
            table.add_column(label, justify="right", no_wrap=True, style="bold")
        if extra is not None:
            table.add_column("± stderr", justify="right", no_wrap=True)
        table.add_column("Δ_V(RMS)", justify="right", no_wrap=True, style="bold")
        for i, sensor in enumerate(result.sensors):
            name = Text(sensor)
            if (i, j) in result.warnings:
                notes.extend(f"{sensor} / {profile}: {w}" for w in result.warnings[(i, j)])
                name.append(f" ⚠{len(notes)}", style="yellow")
            table.add_row(name, *(fmt(x) for x in e.additive_terms[i, j]),
                          fmt(e.additive[i, j]), fmt(e.multiplicative[i, j]),
                          fmt(e.total[i, j]),
                          *([fmt(extra[i, j], 2)] if extra is not None else []),
                          fmt(e.rms[i, j]))
        out.append(table)
    legend = (f"All values in {result.unit}. Δ0 = additive terms of eq. (14)/(15); Δ_VA their "
              "sum; Δ_VM = Δ(1)·Ω + Δ(2)·Ω² + Δ(3)·Ω³; Δ_V = Δ_VA + Δ_VM (eq. 13); "
              "Δ_V(RMS) of eq. (16).")
    out.append(Text(legend, style="dim"))
    if extra is not None:
        out.append(Text(_numeric_note(result), style="dim"))
    for k, note in enumerate(notes, 1):
        out.append(Text(f"⚠{k} {note}", style="yellow"))
    return rich_text(out, width=width, color=color)


def _numeric_note(result: AnalysisResult) -> str:
    return (f"Numeric: Δ_V is the average of eq. (2) over up to {result.samples} points per "
            f"sensor × profile (seed {result.seed}) minus eq. (2) at rest, ± its standard "
            "error (0 where the phase grid is exact); the other columns apply the term "
            "formulas to the sample moments of the same points.")
