"""The terminal tables of an analysis result: one table per profile (``--detail``)
or the compact matrix, a row per profile and a column per sensor."""

from __future__ import annotations

from typing import Any

import numpy as np

from gyrovib.api import AnalysisResult
from gyrovib.api.datasheet.specs import UNKNOWN_TERM_NOTES
from gyrovib.coefficients import POLYNOMIAL
from gyrovib.render.analysis_cells import (
    _SPECS_NOTE,
    _UNCERTAINTY_NOTE,
    G2_INDEX,
    JSON_TERMS,
    SATURATED_MARK,
    _all_terms,
    _labels,
    _lot_name,
    _numeric_note,
    _saturated,
    _saturation_note,
    _shown,
    _u_text,
    cells_text,
    grouped_warnings,
    row_cells,
    unknown_term,
)
from gyrovib.render.common import fmt, rich_text
from gyrovib.units import coefficient_unit

#: Short names of the terms of eq. (13) for the "dominant term" of the matrix: the
#: additive terms (JSON order), then Δ(1)·Ω, Δ(2)·Ω², Δ(3)·Ω³.
_DOMINANT = {"A1": "A1", "k2": "k2", "k4": "k4", "m31": "m31", "m32": "m32", "g2": "g²",
             "k3": "k3·M3", "k5": "k5·M5"}
_MULTIPLICATIVE = ("Δ(1)·Ω", "Δ(2)·Ω²", "Δ(3)·Ω³")


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
    magnitudes = [abs(v) if v == v else -1.0 for v in values]  # NaN, unknown: not a candidate
    k = int(np.argmax(magnitudes))
    return names[k] if magnitudes[k] > 0 else ""


#: Which worst-polynomial coefficients make each dominant term.
_MADE_OF = {"A1": ("A1",), "k2": ("k2",), "k4": ("k4",), "k3·M3": ("k3",), "k5·M5": ("k5",),
            "Δ(1)·Ω": ("k3", "k5"), "Δ(2)·Ω²": ("k4",), "Δ(3)·Ω³": ("k5",)}
_WORST = POLYNOMIAL


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


def next_step(result: AnalysisResult) -> str:
    """The one line that says what to run next after the matrix."""
    return ("Next: `gyrovib select --budget B` (e.g. 10deg/h) checks every sensor against "
            "your budget; `--detail`, or one or two `--profile ID`, shows each term.")


def _phase_notes(result: AnalysisResult) -> dict[tuple[int, int], str]:
    """The searched worst phases of each cell that has them, in the tables' order
    (profile by profile, sensor by sensor)."""
    notes: dict[tuple[int, int], str] = {}
    for j, profile in enumerate(result.profiles):
        for i, sensor in enumerate(result.sensors):
            if (i, j) in result.worst_phases:
                phases = "; ".join(", ".join(f"order {n} at {v:.4g}°" for n, v in g.items())
                                   for g in result.worst_phases[(i, j)] if g)
                notes[(i, j)] = f"{sensor} / {profile}: worst phases {phases}"
    return notes


class _Detail:
    """What the per-profile tables read of a result: its numbers as nested lists of
    Python floats (indexing them per row is ~10x cheaper than numpy's), the warnings'
    numbers and the notes on the worst phases, numbered after the warnings."""

    def __init__(self, result: AnalysisResult) -> None:
        e = result.error
        extra = getattr(result, "stderr", None)
        self.result = result
        self.additive_terms, self.extra_terms = e.additive_terms.tolist(), e.extra_terms.tolist()
        self.additive, self.multiplicative = e.additive.tolist(), e.multiplicative.tolist()
        self.total, self.rms = e.total.tolist(), e.rms.tolist()
        self.stderr = None if extra is None else extra.tolist()
        self.saturated = None if result.saturated is None else result.saturated.tolist()
        self.groups = grouped_warnings(result)
        self.number_of = {message: k for k, (message, _) in enumerate(self.groups, 1)}
        self.notes = _phase_notes(result)
        self.note_number = {cell: k for k, cell in enumerate(self.notes, len(self.groups) + 1)}

    def name(self, i: int, j: int) -> Any:
        """The sensor's cell: its name, the warnings' marks, SAT, the worst phases' note."""
        # lazy: rich only draws tables; csv and json output never load it
        from rich.text import Text

        result = self.result
        name = Text(_lot_name(result, i))
        if (i, j) in result.warnings:
            marks = ",".join(str(self.number_of[w]) for w in result.warnings[(i, j)])
            name.append(f" ⚠{marks}", style="yellow")
        if self.saturated is not None and self.saturated[i][j]:
            name.append(f" {SATURATED_MARK}", style="bold red")
        if (i, j) in self.note_number:
            name.append(f" ⚠{self.note_number[(i, j)]}", style="yellow")
        return name

    def row(self, i: int, j: int, shown: tuple[int, ...]) -> list[Any]:
        """The cells of sensor ``i`` under profile ``j``."""
        values = [*self.additive_terms[i][j], *self.extra_terms[i][j]]
        numbers = row_cells([*(values[k] for k in shown), self.additive[i][j],
                             self.multiplicative[i][j], self.total[i][j], self.rms[i][j]])
        if G2_INDEX in shown and unknown_term(self.result, i, j):
            numbers[shown.index(G2_INDEX)] = "?"  # not given or not published: unknown
        return [self.name(i, j), *numbers[:-1],
                *([fmt(self.stderr[i][j], 2)] if self.stderr is not None else []),
                *([_u_text(self.result, i, j)] if self.result.uncertainty is not None else []),
                numbers[-1]]

    def table(self, j: int) -> Any:
        """The table of profile ``j``: a row per sensor, a column per term."""
        # lazy: rich only draws tables; csv and json output never load it
        from rich.table import Table

        result = self.result
        omega, rate_unit = float(result.table_rates[j, 2]), result.table_rate_unit
        table = Table(
            title=f"{result.profiles[j]}  (Ω_K3 = {fmt(omega)} {rate_unit}, "
                  f"method {result.method})",
            title_justify="left", header_style="bold",
        )
        table.add_column("sensor", no_wrap=True)
        odd = bool(result.locked[j]) if result.locked else False
        for label in _labels(result, odd):
            table.add_column(label, justify="right", no_wrap=True)
        for label in ("Δ_VA", "Δ_VM", "Δ_V"):
            table.add_column(label, justify="right", no_wrap=True, style="bold")
        if self.stderr is not None:
            table.add_column("± stderr", justify="right", no_wrap=True)
        if result.uncertainty is not None:
            table.add_column("u(Δ_V)", justify="right", no_wrap=True)
        table.add_column("Δ_V(RMS)", justify="right", no_wrap=True, style="bold")
        shown = _shown(result.has_linear, odd)
        for i in range(len(result.sensors)):
            table.add_row(*self.row(i, j, shown))
        return table


def _detail_legend(result: AnalysisResult) -> str:
    legend = (f"Errors in {result.unit}. Δ0 = additive terms of eq. (14)/(15); Δ_VA their "
              "sum; Δ_VM = Δ(1)·Ω + Δ(2)·Ω² + Δ(3)·Ω³; Δ_V = Δ_VA + Δ_VM (eq. 13); "
              "Δ_V(RMS) of eq. (16); below 1e-12 of its row's largest a value is shown as 0.")
    if result.has_linear:
        legend += (" Δ0 g² = Δ0(6) = Σ G_jk·⟨a_j·a_k⟩, the rectification of the linear "
                   "vibration by the g²-sensitivity (VRE), docs/model.md section 8.")
    return legend


def _detail_notes(detail: _Detail) -> list[Any]:
    """The lines under the per-profile tables: the legend, the notes, the warnings."""
    # lazy: rich only draws tables; csv and json output never load it
    from rich.text import Text

    result = detail.result
    out: list[Any] = [Text(_detail_legend(result), style="dim")]
    if "specs" in result.sources:
        out.append(Text(_SPECS_NOTE, style="dim"))
    if result.uncertainty is not None:
        out.append(Text(_UNCERTAINTY_NOTE, style="dim"))
    if detail.saturated is not None and any(any(row) for row in detail.saturated):
        out.append(Text(_saturation_note(result), style="red"))
    if detail.stderr is not None:
        out.append(Text(_numeric_note(result), style="dim"))
    for k, (message, cells) in enumerate(detail.groups, 1):
        out.append(Text(f"⚠{k} {message} ({cells_text(result, cells)})", style="yellow"))
    for k, note in enumerate(detail.notes.values(), len(detail.groups) + 1):
        out.append(Text(f"⚠{k} {note}", style="yellow"))
    return out


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
    # lazy: rich only draws tables; csv and json output never load it
    from rich.text import Text

    tables = _Detail(result)
    out: list[Any] = []
    for j in range(len(result.profiles)):
        out.append(tables.table(j))
        for i in range(len(result.sensors)):
            why = worst_case_text(result, i, j)
            if why is not None:
                out.append(Text(why, style="dim"))
    out.extend(_detail_notes(tables))
    return rich_text(out, width=width, color=color, ascii=ascii)


def _matrix_cell(result: AnalysisResult, i: int, j: int, number_of: dict[str, int]) -> Any:
    """Sensor ``i`` under profile ``j`` in the matrix: the error, its dominant term,
    the warnings' marks and SAT."""
    # lazy: rich only draws tables; csv and json output never load it
    from rich.text import Text

    value = float(result.error.total[i, j] if result.source(i) == "specs"
                  else result.error.rms[i, j])
    # unknown (a g² figure not given or not published, an axis not recorded): '?' alone,
    # no dominant term among the terms that are known
    text = Text("?" if value != value else f"{fmt(abs(value), 3)} "
                f"{dominant_term(result, i, j)}".rstrip())
    if (i, j) in result.warnings:
        marks = ",".join(str(number_of[w]) for w in result.warnings[(i, j)])
        text.append(f" ⚠{marks}", style="yellow")
    if _saturated(result, i, j):
        text.append(f" {SATURATED_MARK}", style="bold red")
    return text


def _matrix_legend(result: AnalysisResult, spec: bool) -> str:
    legend = (f"Each row: a profile with its Ω_K3 in {result.table_rate_unit}. Dominant term: "
              "the term of eq. (13) of largest magnitude (A1, k2, k4, m31, m32, g² = the linear "
              "vibration's VRE term, k3·M3, k5·M5, or Δ(q)·Ω^q).")
    if spec:
        legend += " " + _SPECS_NOTE
    if any(w in UNKNOWN_TERM_NOTES for ws in result.warnings.values() for w in ws):
        legend += (" ?: unknown, the sensor's g² figure being unknown (not published, or "
                   "not given) under a linear vibration.")
    return legend


def _matrix(result: AnalysisResult, width: int | None = None, color: bool = False,
            ascii: bool = False) -> str:
    """The compact form: a row per profile, a column per sensor, each cell the error
    (Δ_V(RMS); a datasheet part's worst |Δ_V|) and its dominant term."""
    # lazy: rich only draws tables; csv and json output never load it
    from rich.table import Table
    from rich.text import Text

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
        cells = [_matrix_cell(result, i, j, number_of) for i in range(len(result.sensors))]
        cells_profile = Text(profile)
        cells_profile.append(f" ({fmt(float(result.table_rates[j, 2]), 3)})",
                             style="dim")
        table.add_row(cells_profile, *cells)
    out: list[Any] = [table, Text(_matrix_legend(result, spec), style="dim")]
    if result.saturated is not None and result.saturated.any():
        out.append(Text(_saturation_note(result), style="red"))
    for k, (message, cells_of) in enumerate(groups, 1):
        out.append(Text(f"⚠{k} {message} ({cells_text(result, cells_of)})", style="yellow"))
    out.append(Text(next_step(result), style="bold"))
    return rich_text(out, width=width, color=color, ascii=ascii)
