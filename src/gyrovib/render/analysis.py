"""Renderers of :class:`gyrovib.api.AnalysisResult`."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

import numpy as np

from gyrovib.api import AnalysisResult
from gyrovib.api.datasheet.specs import UNKNOWN_TERM_NOTES
from gyrovib.api.evaluation.results import JSON_TERMS as _JSON_TERMS
from gyrovib.core.analysis import ADDITIVE_TERMS, MULTIPLICATIVE_TERMS
from gyrovib.render.common import csv_text, dumps, fmt, header, markdown_table, number, rich_text

_ADDITIVE_LABELS = ("Δ0 A1", "Δ0 k2", "Δ0 k4", "Δ0 m31", "Δ0 m32")
#: The JSON keys of ``additive_terms`` (Δ0(1..5), g2 = Δ0(6), k3, k5): one order for
#: JSON, CSV, tables and frames.
JSON_TERMS = _JSON_TERMS
#: The odd-moment terms of locked harmonics (docs/model.md section 10), k3·M3 and k5·M5:
#: always in JSON (0 where x3 is symmetric), in tables only where a profile has them.
ODD_TERMS: tuple[str, ...] = ("k3", "k5")
_LABELS = dict(zip(JSON_TERMS, (*_ADDITIVE_LABELS, "Δ0 g²", "Δ0 k3", "Δ0 k5"), strict=True))
#: Where Δ0(6), the g² term, stands among :data:`JSON_TERMS`.
G2_INDEX = JSON_TERMS.index("g2")
#: The mark of a saturating sensor in tables (docs/model.md section 9).
SATURATED_MARK = "SAT"


def unknown_term(result: AnalysisResult, i: int, j: int) -> bool:
    """Whether a term of sensor ``i`` under profile ``j`` is left out because its figure
    is unknown (a VRE not published, a g² sensitivity not given): the value shown is
    then a lower bound, and the term itself reads "?", never 0."""
    return any(w in UNKNOWN_TERM_NOTES for w in result.warnings.get((i, j), ()))


def _shown(linear: bool, odd: bool) -> tuple[int, ...]:
    """Indices into :data:`JSON_TERMS` of the terms shown: Δ0(6) with a linear
    vibration, k3/k5 with locked harmonics."""
    return tuple(k for k, t in enumerate(JSON_TERMS)
                 if t in ADDITIVE_TERMS or (t == "g2" and linear) or (t in ODD_TERMS and odd))


def _all_terms(result: AnalysisResult, i: int, j: int) -> list[float]:
    e = result.error
    return [*map(float, e.additive_terms[i, j]), *map(float, e.extra_terms[i, j])]


def _terms(result: AnalysisResult, i: int, j: int, odd: bool) -> list[float]:
    """The additive terms of a row as tables and CSV show them."""
    values = _all_terms(result, i, j)
    return [values[k] for k in _shown(result.has_linear, odd)]


def _labels(result: AnalysisResult, odd: bool) -> tuple[str, ...]:
    return tuple(_LABELS[JSON_TERMS[k]] for k in _shown(result.has_linear, odd))


def _saturated(result: AnalysisResult, i: int, j: int) -> bool:
    sat = result.saturated
    return bool(sat is not None and sat[i, j])


def _saturation_note(result: AnalysisResult) -> str:
    return (f"{SATURATED_MARK}: saturated, |Ω_K3| + Σ tone amplitudes + locked peaks + "
            f"{result.peak_factor:g}σ at the nonlinear element exceeds the sensor's range "
            "(docs/model.md section 9): the error shown does not hold.")


def _u(result: AnalysisResult, i: int, j: int) -> float | None:
    """u(Δ_V) of a cell (docs/model.md section 14), None where the sensor has none."""
    u = result.uncertainty
    return None if u is None else number(u[i, j])


def _u_text(result: AnalysisResult, i: int, j: int) -> str:
    """u(Δ_V) for a table: '-' where not known (no uncertainty, or searched phases)."""
    u = _u(result, i, j)
    return "-" if u is None else fmt(u, 2)


def _lot_name(result: AnalysisResult, i: int) -> str:
    return result.sensors[i] + (f" {LOT_MARK}" if result.is_lot(i) else "")


#: The mark of a lot sensor, analysed at its mean, in tables.
LOT_MARK = "(lot)"
_UNCERTAINTY_NOTE = ("u(Δ_V): standard uncertainty (k = 1) of Δ_V from the coefficients' "
                     "uncertainty, √(gᵀΣg) with Δ_V = gᵀc (docs/model.md section 14); '-' where "
                     "not known. A sensor marked (lot) is a production lot, analysed at "
                     "its mean coefficients; its u is the spread of Δ_V over the lot.")


def _rows(result: AnalysisResult) -> Iterator[tuple[int, int]]:
    for j in range(len(result.profiles)):
        for i in range(len(result.sensors)):
            yield i, j


def _to_json_rows(result: AnalysisResult) -> str:
    """``analyze --format json`` (docs/output.md), one dict per row (the reference form)."""
    e = result.error
    extra = getattr(result, "stderr", None)
    results: list[dict[str, Any]] = []
    rates = result.rates.tolist()
    terms = [[[*t, *g] for t, g in zip(ts, gs, strict=True)]
             for ts, gs in zip(e.additive_terms.tolist(), e.extra_terms.tolist(), strict=True)]
    qs = e.multiplicative_coefficients.tolist()
    additive, mult, total, rms = (e.additive.tolist(), e.multiplicative.tolist(),
                                  e.total.tolist(), e.rms.tolist())
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


_COEFFICIENT_SOURCE = '"coefficients"'  # json.dumps("coefficients")


def _source_fields(result: AnalysisResult, i: int, j: int) -> dict[str, Any]:
    """``source``, and for a spec-form sensor its ``envelope`` (docs/model.md section 11)."""
    source = result.source(i)
    out: dict[str, Any] = {"source": source}
    if source == "specs" and result.worst_coefficients is not None:
        from gyrovib.api.datasheet.specs import WORST_COEFFICIENTS

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
    import json

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


def to_json(result: AnalysisResult) -> str:
    """``analyze --format json`` (docs/output.md).

    The same text as ``json.dumps`` of the document, written without a dict per
    row: each numeric column is encoded once (``float.__repr__`` is what the
    json encoder writes) and the rows are filled into a template, a block of
    sensors at a time.
    """
    e = result.error
    extra = getattr(result, "stderr", None)
    columns = [e.additive_terms[..., t] for t in range(len(ADDITIVE_TERMS))]
    columns += [e.extra_terms[..., k] for k in range(len(JSON_TERMS) - len(ADDITIVE_TERMS))]
    columns += [e.multiplicative_coefficients[..., q] for q in range(len(MULTIPLICATIVE_TERMS))]
    columns += [e.additive, e.multiplicative, e.total, e.rms]
    if not all(np.isfinite(c).all() for c in columns) or not np.isfinite(result.rates).all():
        return _to_json_rows(result)  # json refuses NaN/infinity; let it say so
    if "specs" in result.sources:
        return _to_json_rows(result)  # spec rows carry their envelope: one dict per row
    if result.worst_phases or result.uncertainty is not None:
        return _to_json_rows(result)  # a key of some rows only: the reference form
    import json  # not at import time: the tables do without it

    template = _row_template(extra is not None)
    n_s = len(result.sensors)
    sensors = [json.dumps(s) for s in result.sensors]
    by_profile: dict[int, list[tuple[int, tuple[str, ...]]]] = {}
    for (i, j), messages in result.warnings.items():
        by_profile.setdefault(j, []).append((i, messages))
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
            encoded = [list(map(float.__repr__, c[start:stop, j].tolist())) for c in columns]
            if extra is not None:
                encoded.append(["null" if v is None else float.__repr__(v)
                                for v in map(number, extra[start:stop, j].tolist())])
            sat = result.saturated
            encoded.append([_COEFFICIENT_SOURCE] * count)
            encoded.append(["false"] * count if sat is None else
                           ["true" if v else "false" for v in sat[start:stop, j].tolist()])
            rows = zip(sensors[start:stop], [profile_text] * count, [rate_text] * count,
                       *encoded, warnings[start:stop],
                       strict=True)
            blocks.append(", ".join([template % row for row in rows]))
    head = json.dumps(_head(result))[:-1]
    return f"{head}, \"results\": [{', '.join(blocks)}]}}\n"


def _csv_header(with_stderr: bool = False, linear: bool = False,
                uncertainty: bool = False) -> list[str]:
    return (["sensor", "profile", "rate_x1", "rate_x2", "rate_x3"]
            + [f"additive_{JSON_TERMS[k]}" for k in _shown(linear, True)]
            + [f"multiplicative_{q}" for q in MULTIPLICATIVE_TERMS]
            + ["additive", "multiplicative", "total", "rms"]
            + (["stderr"] if with_stderr else [])
            + (["uncertainty_total", "lot_mean"] if uncertainty else [])
            + ["saturated", "warnings"])


def to_csv(result: AnalysisResult) -> str:
    """One row per sensor × profile, every number at full precision.

    With the numeric method a ``stderr`` column (of ``total``) precedes ``warnings``;
    when some profile has a linear vibration, ``additive_g2`` (Δ0(6)) follows
    ``additive_m32``.
    """
    e = result.error
    extra = getattr(result, "stderr", None)

    def rows() -> Iterator[list[Any]]:
        for i, j in _rows(result):
            yield [
                result.sensors[i], result.profiles[j], *map(float, result.rates[j]),
                *_terms(result, i, j, True),
                *map(float, e.multiplicative_coefficients[i, j]),
                float(e.additive[i, j]), float(e.multiplicative[i, j]), float(e.total[i, j]),
                float(e.rms[i, j]), *([float(extra[i, j])] if extra is not None else []),
                *([_csv_u(result, i, j), "true" if result.is_lot(i) else "false"]
                  if result.uncertainty is not None else []),
                "true" if _saturated(result, i, j) else "false",
                "; ".join(result.warnings.get((i, j), ())),
            ]

    return csv_text(_csv_header(extra is not None, result.has_linear,
                                result.uncertainty is not None), rows())


def _csv_u(result: AnalysisResult, i: int, j: int) -> float | str:
    u = _u(result, i, j)
    return "" if u is None else u


def to_markdown(result: AnalysisResult) -> str:
    """A Markdown table (4 significant figures) with warnings as footnotes."""
    e = result.error
    extra = getattr(result, "stderr", None)
    odd = any(result.locked)
    head = ["sensor", "profile", f"Ω_K3 ({result.unit})", *_labels(result, odd),
            "Δ_VA", "Δ_VM", "Δ_V", *(["± stderr"] if extra is not None else []),
            *(["u(Δ_V)"] if result.uncertainty is not None else []), "Δ_V(RMS)",
            "saturated"]
    rows: list[list[str]] = []
    groups = grouped_warnings(result)
    number_of = {message: k for k, (message, _) in enumerate(groups, 1)}
    notes = [f"{message} ({cells_text(result, cells)})" for message, cells in groups]
    for i, j in _rows(result):
        mark = ""
        if (i, j) in result.warnings:
            mark = " ⚠" + ",".join(str(number_of[w]) for w in result.warnings[(i, j)])
        numbers = row_cells([*_terms(result, i, j, odd), float(e.additive[i, j]),
                             float(e.multiplicative[i, j]), float(e.total[i, j]),
                             float(e.rms[i, j])])
        shown = _shown(result.has_linear, odd)
        if G2_INDEX in shown and unknown_term(result, i, j):
            numbers[shown.index(G2_INDEX)] = "?"  # not given or not published: unknown
        rows.append([_lot_name(result, i) + mark, result.profiles[j], fmt(result.rates[j, 2]),
                     *numbers[:-1],
                     *([fmt(extra[i, j], 2)] if extra is not None else []),
                     *([_u_text(result, i, j)] if result.uncertainty is not None else []),
                     numbers[-1],
                     "yes" if _saturated(result, i, j) else "no"])
    text = (f"Vibration error, method `{result.method}`, rates in {result.unit}\n\n"
            + markdown_table(head, rows))
    if "specs" in result.sources:
        text += "\n" + _SPECS_NOTE + "\n"
    if result.uncertainty is not None:
        text += "\n" + _UNCERTAINTY_NOTE + "\n"
    if extra is not None:
        text += "\n" + _numeric_note(result) + "\n"
    if notes:
        text += "\n" + "\n".join(f"⚠{k}. {n}" for k, n in enumerate(notes, 1)) + "\n"
    return text


#: Below this fraction of a row's largest value, a number is rounding noise: shown as 0.
NEGLIGIBLE_IN_ROW = 1e-12
#: Short names of the terms of eq. (13) for the "dominant term" of the matrix: the
#: additive terms (JSON order), then Δ(1)·Ω, Δ(2)·Ω², Δ(3)·Ω³.
_DOMINANT = {"A1": "A1", "k2": "k2", "k4": "k4", "m31": "m31", "m32": "m32", "g2": "g²",
             "k3": "k3·M3", "k5": "k5·M5"}
_MULTIPLICATIVE = ("Δ(1)·Ω", "Δ(2)·Ω²", "Δ(3)·Ω³")


def row_cells(values: list[float], digits: int = 4) -> list[str]:
    """A table row's numbers, those below :data:`NEGLIGIBLE_IN_ROW` of its largest as 0."""
    finite = [abs(v) for v in values if v == v and abs(v) != float("inf")]
    scale = max(finite, default=0.0)
    return ["0" if v == v and scale > 0 and abs(v) < NEGLIGIBLE_IN_ROW * scale
            else fmt(v, digits) for v in values]


def dominant_term(result: AnalysisResult, i: int, j: int) -> str:
    """The term of eq. (13) with the largest magnitude for sensor ``i`` under profile ``j``
    ("" when there is no error)."""
    e = result.error
    values = _all_terms(result, i, j)
    names = [_DOMINANT[t] for t in JSON_TERMS]
    omega = float(result.rates[j, 2])
    qs = [float(q) for q in e.multiplicative_coefficients[i, j]]
    values += [q * omega ** (k + 1) for k, q in enumerate(qs)]
    names += list(_MULTIPLICATIVE)
    magnitudes = [abs(v) for v in values]
    k = int(np.argmax(magnitudes))
    return names[k] if magnitudes[k] > 0 else ""


#: Which worst-polynomial coefficients make each dominant term.
_MADE_OF = {"A1": ("A1",), "k2": ("k2",), "k4": ("k4",), "k3·M3": ("k3",), "k5·M5": ("k5",),
            "Δ(1)·Ω": ("k3", "k5"), "Δ(2)·Ω²": ("k4",), "Δ(3)·Ω³": ("k5",)}
_WORST = ("A1", "k2", "k3", "k4", "k5")


def worst_case_text(result: AnalysisResult, i: int, j: int) -> str | None:
    """Why a datasheet part's worst case is what it is, in one line (None for other rows).

    The coefficients of the worst polynomial behind its dominant term (e.g.
    ``A1 = -0.14``), and the datasheet figure that would shrink the error most:
    a smaller VRE where the g² term dominates, an asymmetry figure where the
    asymmetry dominates and none is published, otherwise a smaller
    nonlinearity (the envelope's worst case is proportional to it).
    """
    if result.source(i) != "specs" or result.worst_coefficients is None:
        return None
    term = dominant_term(result, i, j)
    if not term:
        return None
    from gyrovib.presentation.reasons import coefficient_unit

    x = dict(zip(_WORST, (float(v) for v in result.worst_coefficients[i, j]), strict=True))
    shown = [f"{name} = {fmt(x[name], 2)}"
             + (f" (a {fmt(abs(x[name]) * 100, 2)} % scale-factor asymmetry)" if name == "A1"
                else f" {coefficient_unit(name, result.unit)}")
             for name in _MADE_OF.get(term, ())]
    published = result.published[i] if result.published else ()
    if term == "g²":
        ask = "a smaller VRE"
    elif term == "A1" and "asymmetry" not in published:
        ask = "an asymmetry figure (a published bound on |A1| cuts the worst case)"
    else:
        ask = "a smaller nonlinearity (the worst case is proportional to it)"
    what = f"worst case {', '.join(shown)}, its {term} term dominating" if shown else (
        f"worst case dominated by its {term} term")
    return f"{result.sensors[i]}: {what}; the datasheet figure that would shrink it most: {ask}"


def grouped_warnings(result: AnalysisResult) -> list[tuple[str, list[tuple[int, int]]]]:
    """Each distinct warning once, with the (sensor, profile) cells it applies to, in the
    order they first appear (profile by profile, sensor by sensor)."""
    found: dict[str, list[tuple[int, int]]] = {}
    for j in range(len(result.profiles)):
        for i in range(len(result.sensors)):
            for message in result.warnings.get((i, j), ()):
                found.setdefault(message, []).append((i, j))
    return list(found.items())


def cells_text(result: AnalysisResult, cells: list[tuple[int, int]]) -> str:
    """Where a warning applies, compactly: sensors sharing their profiles named together."""
    by_sensor: dict[int, list[int]] = {}
    for i, j in cells:
        by_sensor.setdefault(i, []).append(j)
    groups: dict[tuple[int, ...], list[int]] = {}
    for i, found in by_sensor.items():
        groups.setdefault(tuple(found), []).append(i)
    every = tuple(range(len(result.profiles)))
    parts = []
    for profiles, sensors in groups.items():
        where = ("every profile" if profiles == every and len(every) > 1
                 else ", ".join(result.profiles[j] for j in profiles))
        parts.append(f"{', '.join(result.sensors[i] for i in sensors)} under {where}")
    return "; ".join(parts)


def next_step(result: AnalysisResult) -> str:
    """The one line that says what to run next after the matrix."""
    return ("Next: `gyrovib select --budget B` (e.g. 10deg/h) checks every sensor against "
            "your budget; `--detail`, or one or two `--profile ID`, shows each term.")


def to_table(result: AnalysisResult, width: int | None = None, color: bool = False,
             ascii: bool = False, detail: bool | None = None) -> str:
    """The error of every sensor under every profile, in words fit for a terminal.

    ``detail`` (default: with one or two profiles) gives one table per profile,
    sensors as rows and every term of eq. (13) as a column; otherwise one
    compact matrix, a row per profile and a column per sensor, each cell the
    error and its dominant term, then one line on what to run next. Warnings
    are printed once each, with the cells they apply to.
    """
    if detail is None:
        detail = len(result.profiles) <= 2
    if not detail:
        return _matrix(result, width=width, color=color, ascii=ascii)
    from rich.table import Table
    from rich.text import Text

    e = result.error
    extra = getattr(result, "stderr", None)
    out: list[Any] = []
    notes: list[str] = []
    groups = grouped_warnings(result)
    number_of = {message: k for k, (message, _) in enumerate(groups, 1)}
    any_saturated = False
    # nested lists of Python floats: indexing them per row is ~10x cheaper than numpy's
    additive_terms, extra_terms = e.additive_terms.tolist(), e.extra_terms.tolist()
    additive, multiplicative = e.additive.tolist(), e.multiplicative.tolist()
    total, rms = e.total.tolist(), e.rms.tolist()
    stderr = None if extra is None else extra.tolist()
    saturated = None if result.saturated is None else result.saturated.tolist()
    for j, profile in enumerate(result.profiles):
        omega, rate_unit = float(result.table_rates[j, 2]), result.table_rate_unit
        table = Table(
            title=f"{profile}  (Ω_K3 = {fmt(omega)} {rate_unit}, method {result.method})",
            title_justify="left", header_style="bold",
        )
        table.add_column("sensor", no_wrap=True)
        odd = bool(result.locked[j]) if result.locked else False
        for label in _labels(result, odd):
            table.add_column(label, justify="right", no_wrap=True)
        for label in ("Δ_VA", "Δ_VM", "Δ_V"):
            table.add_column(label, justify="right", no_wrap=True, style="bold")
        if extra is not None:
            table.add_column("± stderr", justify="right", no_wrap=True)
        if result.uncertainty is not None:
            table.add_column("u(Δ_V)", justify="right", no_wrap=True)
        table.add_column("Δ_V(RMS)", justify="right", no_wrap=True, style="bold")
        shown = _shown(result.has_linear, odd)
        for i, sensor in enumerate(result.sensors):
            name = Text(_lot_name(result, i))
            if (i, j) in result.warnings:
                marks = ",".join(str(number_of[w]) for w in result.warnings[(i, j)])
                name.append(f" ⚠{marks}", style="yellow")
            if saturated is not None and saturated[i][j]:
                name.append(f" {SATURATED_MARK}", style="bold red")
                any_saturated = True
            if (i, j) in result.worst_phases:
                phases = "; ".join(", ".join(f"order {n} at {v:.4g}°" for n, v in g.items())
                                   for g in result.worst_phases[(i, j)] if g)
                notes.append(f"{sensor} / {profile}: worst phases {phases}")
                name.append(f" ⚠{len(groups) + len(notes)}", style="yellow")
            values = [*additive_terms[i][j], *extra_terms[i][j]]
            numbers = row_cells([*(values[k] for k in shown), additive[i][j],
                                 multiplicative[i][j], total[i][j], rms[i][j]])
            if G2_INDEX in shown and unknown_term(result, i, j):
                numbers[shown.index(G2_INDEX)] = "?"  # not given or not published: unknown
            table.add_row(name, *numbers[:-1],
                          *([fmt(stderr[i][j], 2)] if stderr is not None else []),
                          *([_u_text(result, i, j)] if result.uncertainty is not None else []),
                          numbers[-1])
        out.append(table)
        for i in range(len(result.sensors)):
            why = worst_case_text(result, i, j)
            if why is not None:
                out.append(Text(why, style="dim"))
    legend = (f"Errors in {result.unit}. Δ0 = additive terms of eq. (14)/(15); Δ_VA their "
              "sum; Δ_VM = Δ(1)·Ω + Δ(2)·Ω² + Δ(3)·Ω³; Δ_V = Δ_VA + Δ_VM (eq. 13); "
              "Δ_V(RMS) of eq. (16); below 1e-12 of its row's largest a value is shown as 0.")
    if result.has_linear:
        legend += (" Δ0 g² = Δ0(6) = Σ G_jk·⟨a_j·a_k⟩, the rectification of the linear "
                   "vibration by the g²-sensitivity (VRE), docs/model.md section 8.")
    out.append(Text(legend, style="dim"))
    if "specs" in result.sources:
        out.append(Text(_SPECS_NOTE, style="dim"))
    if result.uncertainty is not None:
        out.append(Text(_UNCERTAINTY_NOTE, style="dim"))
    if any_saturated:
        out.append(Text(_saturation_note(result), style="red"))
    if extra is not None:
        out.append(Text(_numeric_note(result), style="dim"))
    for k, (message, cells) in enumerate(groups, 1):
        out.append(Text(f"⚠{k} {message} ({cells_text(result, cells)})", style="yellow"))
    for k, note in enumerate(notes, len(groups) + 1):
        out.append(Text(f"⚠{k} {note}", style="yellow"))
    return rich_text(out, width=width, color=color, ascii=ascii)


def _matrix(result: AnalysisResult, width: int | None = None, color: bool = False,
            ascii: bool = False) -> str:
    """The compact form: a row per profile, a column per sensor, each cell the error
    (Δ_V(RMS); a datasheet part's worst |Δ_V|) and its dominant term."""
    from rich.table import Table
    from rich.text import Text

    e = result.error
    groups = grouped_warnings(result)
    number_of = {message: k for k, (message, _) in enumerate(groups, 1)}
    spec = "specs" in result.sources
    table = Table(title=f"Vibration error in {result.unit}, method {result.method}: "
                        "Δ_V(RMS)" + (" (a datasheet part: its worst |Δ_V|)" if spec else "")
                        + " and the term that dominates it",
                  title_justify="left", header_style="bold")
    table.add_column("profile", no_wrap=True)
    for sensor in result.sensors:
        table.add_column(sensor, justify="right", overflow="fold")
    for j, profile in enumerate(result.profiles):
        cells: list[Any] = []
        for i in range(len(result.sensors)):
            value = e.total[i, j] if result.source(i) == "specs" else e.rms[i, j]
            # a term left out because its figure is unknown: the value is a lower bound
            at_least = "≥" if unknown_term(result, i, j) else ""
            text = Text(f"{at_least}{fmt(abs(float(value)), 3)} "
                        f"{dominant_term(result, i, j)}".rstrip())
            if (i, j) in result.warnings:
                marks = ",".join(str(number_of[w]) for w in result.warnings[(i, j)])
                text.append(f" ⚠{marks}", style="yellow")
            if _saturated(result, i, j):
                text.append(f" {SATURATED_MARK}", style="bold red")
            cells.append(text)
        cells_profile = Text(profile)
        cells_profile.append(f" ({fmt(float(result.table_rates[j, 2]), 3)})",
                             style="dim")
        table.add_row(cells_profile, *cells)
    rate_unit = result.table_rate_unit
    out: list[Any] = [table]
    legend = (f"Each row: a profile with its Ω_K3 in {rate_unit}. Dominant term: the term of "
              "eq. (13) of largest magnitude (A1, k2, k4, m31, m32, g² = the linear "
              "vibration's VRE term, k3·M3, k5·M5, or Δ(q)·Ω^q).")
    if spec:
        legend += " " + _SPECS_NOTE
    if any(w in UNKNOWN_TERM_NOTES for ws in result.warnings.values() for w in ws):
        legend += (" ≥: at least this much; a term whose figure is unknown (not published, "
                   "or not given) is left out.")
    out.append(Text(legend, style="dim"))
    if result.saturated is not None and result.saturated.any():
        out.append(Text(_saturation_note(result), style="red"))
    for k, (message, cells_of) in enumerate(groups, 1):
        out.append(Text(f"⚠{k} {message} ({cells_text(result, cells_of)})", style="yellow"))
    out.append(Text(next_step(result), style="bold"))
    return rich_text(out, width=width, color=color, ascii=ascii)


_SPECS_NOTE = ("Datasheet (spec-form) sensors: Δ_V is the worst |Δ_V| over every conversion "
               "function their datasheet permits, the terms those of the polynomial attaining "
               "it (m31 = m32 = 0), Δ_V(RMS) the RMS of the per-term maxima "
               "(docs/datasheets.md).")


def _numeric_note(result: AnalysisResult) -> str:
    return (f"Numeric: Δ_V is the average of eq. (2) over up to {result.samples} points per "
            f"sensor × profile (seed {result.seed}) minus eq. (2) at rest, ± its standard "
            "error (0 where the phase grid is exact); the other columns apply the term "
            "formulas to the sample moments of the same points.")
