"""Renderers of :class:`gyrovib.api.AnalysisResult`: JSON, CSV and Markdown here,
the terminal tables in :mod:`gyrovib.render.analysis_table`, the cells they share in
:mod:`gyrovib.render.analysis_cells`; this module is the face of all three."""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import Any

import numpy as np

from gyrovib.api import AnalysisResult
from gyrovib.api.datasheet.specs import WORST_COEFFICIENTS
from gyrovib.core.analysis import ADDITIVE_TERMS, MULTIPLICATIVE_TERMS
from gyrovib.presentation.frames import analysis_cells, analysis_columns
from gyrovib.render.analysis_cells import (  # noqa: F401  (the face of the renderers)
    _SPECS_NOTE,
    _UNCERTAINTY_NOTE,
    G2_INDEX,
    JSON_TERMS,
    LOT_MARK,
    NEGLIGIBLE_IN_ROW,
    ODD_TERMS,
    SATURATED_MARK,
    _labels,
    _lot_name,
    _numeric_note,
    _rows,
    _saturated,
    _shown,
    _terms,
    _u,
    _u_text,
    cells_text,
    grouped_warnings,
    row_cells,
    unknown_term,
)
from gyrovib.render.analysis_table import (  # noqa: F401  (the face of the renderers)
    dominant_term,
    next_step,
    to_table,
    worst_case_text,
)
from gyrovib.render.common import dumps, fmt, header, number
from gyrovib.render.formats import Cell, csv_of, markdown_of


def _to_json_rows(result: AnalysisResult) -> str:
    """``analyze --format json`` (docs/output.md), one dict per row (the reference form)."""
    e = result.error
    extra = getattr(result, "stderr", None)
    results: list[dict[str, Any]] = []
    rates = result.rates.tolist()
    terms = [[[*t, *g] for t, g in zip(ts, gs, strict=True)]
             for ts, gs in zip(_nulls(e.additive_terms), _nulls(e.extra_terms), strict=True)]
    qs = _nulls(e.multiplicative_coefficients)
    additive, mult, total, rms = (_nulls(e.additive), _nulls(e.multiplicative),
                                  _nulls(e.total), _nulls(e.rms))
    for i, j in _rows(result):
        row: dict[str, Any] = {
            "sensor": result.sensors[i],
            "profile": result.profiles[j],
            "rate": rates[j],
            "additive_terms": dict(zip(JSON_TERMS, terms[i][j], strict=True)),
            "multiplicative_coefficients": dict(zip(MULTIPLICATIVE_TERMS, qs[i][j], strict=True)),
            "additive": additive[i][j],
            "multiplicative": mult[i][j],
            "total": total[i][j],
            "rms": rms[i][j],
        }
        if extra is not None:
            row["stderr"] = number(extra[i, j])
        row.update(_source_fields(result, i, j))
        if result.uncertainty is not None and _u(result, i, j) is not None:
            row["uncertainty"] = {"total": _u(result, i, j)}
        if result.is_lot(i):
            row["lot_mean"] = True
        row["saturated"] = _saturated(result, i, j)
        if (i, j) in result.worst_phases:
            row["worst_phases"] = [dict(g) for g in result.worst_phases[(i, j)]]
        row["warnings"] = list(result.warnings.get((i, j), ()))
        results.append(row)
    document = _head(result)
    document["results"] = results
    return dumps(document)


def _nulls(array: np.ndarray) -> Any:
    """``array.tolist()`` with None (null) for NaN: an error that is unknown (an axis its
    profile's recording did not record). An infinity stays, for json to refuse."""
    cells: Any = array.astype(object)
    cells[np.isnan(array)] = None
    return cells.tolist()


_COEFFICIENT_SOURCE = '"coefficients"'  # json.dumps("coefficients")


def _source_fields(result: AnalysisResult, i: int, j: int) -> dict[str, Any]:
    """``source``, and for a spec-form sensor its ``envelope`` (docs/model.md section 11)."""
    source = result.source(i)
    out: dict[str, Any] = {"source": source}
    if source == "specs" and result.worst_coefficients is not None:
        assert result.rms_bound is not None
        x = result.worst_coefficients[i, j].tolist()
        out["envelope"] = {"worst_coefficients": dict(zip(WORST_COEFFICIENTS, x, strict=True)),
                           "rms_bound": float(result.rms_bound[i, j])}
    return out


def _head(result: AnalysisResult) -> dict[str, Any]:
    """The document's opening fields; the numeric method adds its samples and seed."""
    document = header(result.method, result.unit)
    if getattr(result, "samples", None) is not None:
        document["samples"] = result.samples
        document["seed"] = result.seed
    return document


#: Rows encoded per block: bounds the memory of the encoded columns.
_BLOCK = 4096


def _row_template(with_stderr: bool) -> str:
    """The text of one result row with ``%s`` for every value, keys as json writes them."""
    import json  # not at import time: the tables do without it

    def obj(pairs: list[tuple[str, str]]) -> str:
        return "{" + ", ".join(f"{json.dumps(k)}: {v}" for k, v in pairs) + "}"

    fields = [("sensor", "%s"), ("profile", "%s"), ("rate", "%s"),
              ("additive_terms", obj([(t, "%s") for t in JSON_TERMS])),
              ("multiplicative_coefficients", obj([(q, "%s") for q in MULTIPLICATIVE_TERMS])),
              ("additive", "%s"), ("multiplicative", "%s"), ("total", "%s"), ("rms", "%s")]
    if with_stderr:
        fields.append(("stderr", "%s"))
    fields.append(("source", "%s"))
    fields.append(("saturated", "%s"))
    fields.append(("warnings", "%s"))
    return obj(fields).replace("%s", "\0").replace("%", "%%").replace("\0", "%s")


def _reference_only(result: AnalysisResult, columns: list[np.ndarray]) -> bool:
    """Whether the rows must be written one dict at a time (:func:`_to_json_rows`)."""
    if not all(np.isfinite(c).all() for c in columns) or not np.isfinite(result.rates).all():
        return True  # json refuses NaN/infinity; let it say so
    if "specs" in result.sources:
        return True  # spec rows carry their envelope: one dict per row
    return bool(result.worst_phases) or result.uncertainty is not None  # a key of some
    # rows only: the reference form


def _encoded_block(result: AnalysisResult, columns: list[np.ndarray], j: int, start: int,
                   stop: int) -> list[list[str]]:
    """The values of rows ``start:stop`` of profile ``j``, column by column, as the
    json encoder writes them (``source`` and ``saturated`` included)."""
    extra = getattr(result, "stderr", None)
    count = stop - start
    encoded = [list(map(float.__repr__, c[start:stop, j].tolist())) for c in columns]
    if extra is not None:
        encoded.append(["null" if v is None else float.__repr__(v)
                        for v in map(number, extra[start:stop, j].tolist())])
    sat = result.saturated
    encoded.append([_COEFFICIENT_SOURCE] * count)
    encoded.append(["false"] * count if sat is None else
                   ["true" if v else "false" for v in sat[start:stop, j].tolist()])
    return encoded


def _warnings_by_profile(result: AnalysisResult) -> dict[int, list[tuple[int, tuple[str, ...]]]]:
    by_profile: dict[int, list[tuple[int, tuple[str, ...]]]] = {}
    for (i, j), messages in result.warnings.items():
        by_profile.setdefault(j, []).append((i, messages))
    return by_profile


def to_json(result: AnalysisResult) -> str:
    """``analyze --format json`` (docs/output.md).

    The same text as ``json.dumps`` of the document, written without a dict per
    row: each numeric column is encoded once (``float.__repr__`` is what the
    json encoder writes) and the rows are filled into a template, a block of
    sensors at a time.
    """
    e = result.error
    columns = [e.additive_terms[..., t] for t in range(len(ADDITIVE_TERMS))]
    columns += [e.extra_terms[..., k] for k in range(len(JSON_TERMS) - len(ADDITIVE_TERMS))]
    columns += [e.multiplicative_coefficients[..., q] for q in range(len(MULTIPLICATIVE_TERMS))]
    columns += [e.additive, e.multiplicative, e.total, e.rms]
    if _reference_only(result, columns):
        return _to_json_rows(result)
    import json  # not at import time: the tables do without it

    template = _row_template(getattr(result, "stderr", None) is not None)
    n_s = len(result.sensors)
    sensors = [json.dumps(s) for s in result.sensors]
    by_profile = _warnings_by_profile(result)
    blocks: list[str] = []
    for j, profile in enumerate(result.profiles):
        profile_text = json.dumps(profile)
        rate_text = json.dumps(result.rates[j].tolist())
        warnings = ["[]"] * n_s
        for i, messages in by_profile.get(j, ()):
            warnings[i] = json.dumps(list(messages))
        for start in range(0, n_s, _BLOCK):
            stop = min(start + _BLOCK, n_s)
            count = stop - start
            rows = zip(sensors[start:stop], [profile_text] * count, [rate_text] * count,
                       *_encoded_block(result, columns, j, start, stop), warnings[start:stop],
                       strict=True)
            blocks.append(", ".join([template % row for row in rows]))
    head = json.dumps(_head(result))[:-1]
    return f"{head}, \"results\": [{', '.join(blocks)}]}}\n"


def to_csv(result: AnalysisResult) -> str:
    """One row per sensor × profile, every number at full precision: ``analyze``'s
    records (:func:`gyrovib.presentation.frames.analysis_columns`, which the DataFrame
    shares).

    With the numeric method a ``stderr`` column (of ``total``) follows ``rms``;
    when some profile has a linear vibration, ``additive_g2`` (Δ0(6)) follows
    ``additive_m32``.
    """
    return csv_of(analysis_columns(result, csv=True), analysis_cells(result))


def markdown_cells(result: AnalysisResult) -> tuple[Cell[tuple[int, int]], ...]:
    """The Markdown table's columns, one row per sensor × profile, each naming the record
    it shows (:func:`~gyrovib.presentation.frames.analysis_columns`), each with its own
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
