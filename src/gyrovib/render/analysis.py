"""Renderers of :class:`gyrovib.api.AnalysisResult`: JSON, CSV and Markdown here,
the terminal tables in :mod:`gyrovib.render.analysis_table`, the cells they share in
:mod:`gyrovib.render.analysis_cells`; this module is the face of all three."""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import Any

from gyrovib.api import AnalysisResult
from gyrovib.api.evaluation.records import analysis_cells, analysis_columns
from gyrovib.render.analysis_cells import (  # noqa: F401  (the face of the renderers)
    _SPECS_NOTE,
    _UNCERTAINTY_NOTE,
    G2_INDEX,
    JSON_TERMS,
    SATURATED_MARK,
    _labels,
    _lot_name,
    _numeric_note,
    _saturated,
    _shown,
    _terms,
    _u_text,
    cells_text,
    grouped_warnings,
    row_cells,
    unknown_term,
)
from gyrovib.render.analysis_table import (  # noqa: F401  (the face of the renderers)
    dominant_term,
    to_table,
    worst_case_text,
)
from gyrovib.render.common import dumps, fmt, header
from gyrovib.render.formats import Cell, csv_of, json_text, markdown_of


def _head(result: AnalysisResult) -> dict[str, Any]:
    """The document's opening fields; the numeric method adds its samples and seed."""
    document = header(result.method, result.unit)
    if getattr(result, "samples", None) is not None:
        document["samples"] = result.samples
        document["seed"] = result.seed
    return document


def to_json(result: AnalysisResult) -> str:
    """``analyze --format json`` (docs/output.md): the document's head, then its
    ``results``, one entry per row of ``analyze``'s records
    (:func:`gyrovib.api.evaluation.records.analysis_columns`, which the CSV and the
    DataFrame share), written by the fast JSON writer (:func:`json_text`: the text
    ``json.dumps`` gives)."""
    head = dumps(_head(result))[:-2]
    rows = json_text(analysis_columns(result), analysis_cells(result))
    return f"{head}, \"results\": {rows}}}\n"


def to_csv(result: AnalysisResult) -> str:
    """One row per sensor × profile, every number at full precision: ``analyze``'s
    records (:func:`gyrovib.api.evaluation.records.analysis_columns`, which the DataFrame
    shares).

    With the numeric method a ``stderr`` column (of ``total``) follows ``rms``;
    when some profile has a linear vibration, ``additive_g2`` (Δ0(6)) follows
    ``additive_m32``.
    """
    return csv_of(analysis_columns(result), analysis_cells(result))


def markdown_cells(result: AnalysisResult) -> tuple[Cell[tuple[int, int]], ...]:
    """The Markdown table's columns, one row per sensor × profile, each naming the record
    it shows (:func:`~gyrovib.api.evaluation.records.analysis_columns`), each with its own
    text (the records are not built for the Markdown): a row's numbers
    at 4 significant figures, those negligible beside its largest as 0 (:func:`row_cells`),
    an unknown term '?'."""
    e, odd = result.error, any(result.locked)
    shown = _shown(result.has_linear, odd)
    number_of = {message: k for k, (message, _) in enumerate(grouped_warnings(result), 1)}

    @functools.lru_cache(maxsize=1)  # the cells of a row are written one after the other
    def numbers(c: tuple[int, int]) -> list[str]:
        i, j = c
        out = row_cells([*_terms(result, i, j, odd), float(e.additive[i, j]),
                         float(e.multiplicative[i, j]), float(e.total[i, j]),
                         float(e.rms[i, j])])
        if G2_INDEX in shown and unknown_term(result, i, j):
            out[shown.index(G2_INDEX)] = "?"  # not given or not published: unknown
        return out

    def number(k: int) -> Callable[[tuple[int, int]], str]:
        return lambda c: numbers(c)[k]

    def name(c: tuple[int, int]) -> str:
        marks = ",".join(str(number_of[w]) for w in result.warnings.get(c, ()))
        return _lot_name(result, c[0]) + (f" ⚠{marks}" if marks else "")

    n, extra = len(shown), result.stderr
    return (Cell("sensor", name, of="sensor"),
            Cell("profile", lambda c: result.profiles[c[1]], of="profile"),
            Cell(f"Ω_K3 ({result.unit})", lambda c: fmt(result.rates[c[1], 2]), of="rate_x3"),
            *(Cell(label, number(k), of=f"additive_{JSON_TERMS[t]}")
              for k, (label, t) in enumerate(zip(_labels(result, odd), shown, strict=True))),
            *(Cell(label, number(n + k), of=part) for k, (label, part) in enumerate(
                (("Δ_VA", "additive"), ("Δ_VM", "multiplicative"), ("Δ_V", "total")))),
            *([Cell("± stderr", lambda c: fmt(float(extra[c]), 2), of="stderr")]
              if extra is not None else []),
            *([Cell("u(Δ_V)", lambda c: _u_text(result, *c), of="uncertainty_total")]
              if result.uncertainty is not None else []),
            Cell("Δ_V(RMS)", number(n + 3), of="rms"),
            Cell("saturated", lambda c: "yes" if _saturated(result, *c) else "no",
                 of="saturated"))


def _markdown_notes(result: AnalysisResult, notes: list[str]) -> str:
    """The paragraphs under the Markdown table: the notes, then the warnings."""
    text = ""
    if "specs" in result.sources:
        text += "\n" + _SPECS_NOTE + "\n"
    if result.uncertainty is not None:
        text += "\n" + _UNCERTAINTY_NOTE + "\n"
    if getattr(result, "stderr", None) is not None:
        text += "\n" + _numeric_note(result) + "\n"
    if notes:
        text += "\n" + "\n".join(f"⚠{k}. {n}" for k, n in enumerate(notes, 1)) + "\n"
    return text


def to_markdown(result: AnalysisResult) -> str:
    """A Markdown table (4 significant figures) with warnings as footnotes."""
    notes = [f"{message} ({cells_text(result, cells)})"
             for message, cells in grouped_warnings(result)]
    table = markdown_of(markdown_cells(result), analysis_cells(result))
    return (f"Vibration error, method `{result.method}`, rates in {result.unit}\n\n"
            + table + _markdown_notes(result, notes))
