"""Renderers of :class:`gyrovib.api.SelectionResult`."""

from __future__ import annotations

import gc
import json
import math
from collections.abc import Iterator
from typing import Any

from rich.table import Table
from rich.text import Text

from gyrovib.api import SelectionResult
from gyrovib.api.evaluation.records import profile_columns, selection_cells, selection_columns
from gyrovib.core.synthesis import BOUNDED
from gyrovib.reasons import reason as reason_text
from gyrovib.reasons import saturation_reason, worded, yield_text
from gyrovib.render.analysis_cells import SATURATED_MARK
from gyrovib.render.bounds import (
    shares_text,
    unit_note,
    vre_unit,
)
from gyrovib.render.common import (
    dumps,
    fmt,
    fmt_budget,
    header,
    number,
    rich_text,
)
from gyrovib.render.formats import Cell, csv_of, json_of, markdown_of, table_of
from gyrovib.units import coefficient_unit

_CRITERION = {
    "bounds": "every |coefficient| within its bound (eq. 23, 25; sufficient, not necessary)",
    "rms": "Δ_V(RMS) ≤ Δ* (eq. 17)",
    "worst": "|Δ_V| ≤ Δ* (a datasheet sensor: its worst case over the envelope)",
    "both": "every |coefficient| within its bound and Δ_V(RMS) ≤ Δ*",
}


# ------------------------------------------------------------------ reasons


def failures(result: SelectionResult, i: int, j: int) -> list[str]:
    """Why sensor ``i`` fails under profile ``j``, as the tables write it (coefficients in
    the catalogue's unit: :meth:`~gyrovib.api.SelectionResult.failures`)."""
    return worded(result.failures(i, j, table=True))


def reason(result: SelectionResult, i: int, j: int) -> str | None:
    """Why sensor ``i`` fails under profile ``j``, one line in :attr:`~SelectionResult.unit`
    (the JSON's ``reason``, as the frame's); None where it passes."""
    return None if result.passed[i, j] else reason_text(result.failures(i, j))


def unknown_label(result: SelectionResult, i: int, name: str) -> str:
    """An unknown figure of sensor ``i`` as tables name it: ``VRE`` (a datasheet part's),
    ``g²`` (a coefficient-form sensor's g² sensitivity), ``m31``, ``m32``."""
    if name != "vre":
        return name
    return "VRE" if result.source(i) == "specs" else "g²"

__all__ = ["failures", "limit_text", "reason", "to_csv", "to_json", "to_markdown", "to_table"]


def _vre(result: SelectionResult, i: int, j: int) -> tuple[float, float]:
    assert result.vre_value is not None and result.vre_bound is not None
    return float(result.vre_value[i, j]), float(result.vre_bound[i, j])


def _vre_text(result: SelectionResult, i: int, j: int, relation: str) -> str:
    """The VRE check of sensor ``i`` under profile ``j`` in words (docs/model.md section 8)."""
    value, bound = _vre(result, i, j)
    unit = vre_unit(result.unit)
    return (f"effective VRE |Δ0(6)|/Σ⟨a_j²⟩ = {fmt(value)} {unit} {relation} "
            f"{fmt(bound)} {unit}")


def limit_text(result: SelectionResult, i: int) -> str:
    """One line on what limits failing sensor ``i``."""
    limit = result.limits[i]
    j = limit.profile
    profile = result.profiles[j]
    ratio = fmt(limit.ratio, 3)
    if limit.name == "saturated":
        reach, range_ = result.saturation[i, j]
        return (f"its range under {profile}: "
                f"{saturation_reason(reach, range_, result.peak_factor, result.unit)}")
    if limit.name == "yield" and result.yields is not None:
        return (f"yield {yield_text(result.yields.at(i, j))} under {profile}, below "
                f"{result.yields.target:g}")
    if limit.name == "rms":
        return (f"Δ_V(RMS) = {fmt_budget(result.rms[i, j], result.budget)} {result.unit} is "
                f"{ratio}× the budget under {profile}")
    if limit.name == "vre" and result.source(i) != "specs":
        return f"vre: {_vre_text(result, i, j, f'is {ratio}× its bound')} under {profile}"
    if limit.name in ("nonlinearity", "vre", "worst"):
        return _spec_limit_text(result, i, limit.name, j, ratio)
    b = BOUNDED.index(limit.name)
    name = limit.name
    unit = coefficient_unit(name, result.table_unit)
    tail = "" if unit == "1" else f" {unit}"
    return (f"{name}: |{name}| = {fmt(float(result.table_values[i, j, b]))} "
            f"is {ratio}× its bound {fmt(float(result.table_bounds[i, j, b]))}"
            f"{tail} under {profile}")


def _spec_limit_text(result: SelectionResult, i: int, name: str, j: int, ratio: str) -> str:
    """The limiting datasheet figure (or worst case) of failing sensor ``i``."""
    profile = result.profiles[j]
    if name == "nonlinearity":
        assert result.nl_value is not None and result.nl_bound is not None
        return (f"nonlinearity: the datasheet's {fmt(result.nl_value[i, j])} %FS is {ratio}× "
                f"the allowable {fmt(result.nl_bound[i, j])} %FS under {profile}"
                + _worst_note(result, i))
    if name == "vre":
        assert result.vre_value is not None and result.vre_bound is not None
        return (f"VRE: the datasheet's {fmt(result.vre_value[i, j])} {result.unit}/g² is "
                f"{ratio}× the allowable {fmt(result.vre_bound[i, j])} {result.unit}/g² "
                f"under {profile}" + _worst_note(result, i))
    assert result.total is not None
    what = ("worst |Δ_V| over the datasheet envelope" if result.source(i) == "specs"
            else "|Δ_V|")
    return (f"{what} = {fmt(result.total[i, j])} {result.unit} is {ratio}× the budget "
            f"under {profile}")


def _worst_note(result: SelectionResult, i: int) -> str:
    """``; worst |Δ_V| … (margin …)``: the datasheet's worst case, by which it is ranked."""
    if result.total is None or not len(result.profiles):
        return ""
    j = int(result.margin[i].argmin())
    return (f"; worst |Δ_V| over the envelope {fmt(result.total[i, j])} {result.unit} under "
            f"{result.profiles[j]} (margin {_margin(result.worst_margin[i])})")


def _margin(value: float) -> str:
    return fmt(value, 3)


def _summary(result: SelectionResult) -> str:
    n_pass = int(result.sensor_pass.sum())
    verdict = "met" if result.requirement_met else "NOT met"
    need = "at least one sensor" if result.require == "any" else "every sensor"
    n_open = sum(1 for i in range(len(result.sensors))
                 if result.sensor_status(i) == "unverified")
    why = ("an unpublished figure, or an axis a fitted profile's recording did not record, "
           "can decide them" if any(set(_PARTS) & set(result.sensor_unknown(i)) for i in
                                    range(len(result.sensors)))
           else "an unpublished figure can decide them: ask the vendor")
    tail = f", {n_open} unverified ({why})" if n_open else ""
    note = assumption_note(result)
    return (f"Requirement ({result.require}: {need} passes under every profile): {verdict}; "
            f"{n_pass} of {len(result.sensors)} sensor(s) pass{tail}."
            + (" " + note if note else ""))


def _heading(result: SelectionResult) -> str:
    return (f"Sensors against Δ* = {fmt(result.budget)} {result.unit}, method {result.method}, "
            f"criterion {result.criterion}: {_CRITERION[result.criterion]}")


#: What the bounds criterion can and cannot say (the help of --criterion says it too).
BOUNDS_NOTE = ("The bounds are sufficient, not necessary: a sensor within every bound meets "
               "the budget under this allocation, one outside a bound may still meet it; "
               "--criterion rms (Δ_V(RMS) ≤ Δ*, eq. 17) is the direct test.")


def _legend(result: SelectionResult) -> str:
    judged = CELL_MARGIN[result.criterion]
    spec = (" Under bounds a datasheet (spec-form) sensor's nonlinearity and VRE are "
            "checked against the allowable figures for its own range and NL definition."
            if "specs" in result.sources and result.criterion in ("bounds", "both") else "")
    text = (f"Cells: ✓ pass / ✗ fail under the criterion, with the margin of the test that "
            f"decides it, {judged} (> 1: within; ∞: nothing to bound).{spec} "
            f"{DISAGREE_MARK}rms, {DISAGREE_MARK}worst, {DISAGREE_MARK}bounds: that other "
            "test would decide the cell otherwise (rms: Δ_V(RMS) ≤ Δ*; worst: |Δ_V| ≤ Δ*; "
            "bounds: every coefficient, or datasheet figure, within its bound). Ranked by "
            f"the worst margin {ranking_margin(result)} over the profiles. Each sensor's "
            "bounds include its own frequency response where it acts at the input "
            "(`at: input`); an output filter earns no credit. Shares of Δ*"
            + (" (in brackets: under a profile with linear vibration, where the g² term "
               "takes α6)" if result.has_linear else "") + ": "
            + shares_text(result.allocation, linear=result.has_linear) + ". "
            + ("The vre check compares each sensor's effective VRE |Δ0(6)|/Σ⟨a_j²⟩ with "
               "its bound. " if result.has_linear else "")
            + BOUNDS_NOTE + unit_note(result))
    if result.unknown:
        text += (f" {UNVERIFIED_MARK} unverified: the sensor passes on its published figures, "
                 "but a figure its datasheet does not publish (named; g²: a coefficient-form "
                 "sensor's g² sensitivity, not given) can change the verdict "
                 "there; it is counted as not passing and not ranked (--assume-unknown zero "
                 "takes such figures as 0).")
    if result.yields is not None:
        text += " " + _yield_legend(result)
    if result.saturated is not None and result.saturated.any():
        text += (f" {SATURATED_MARK}: the sensor saturates (|Ω_K3| + Σ tone amplitudes + "
                 f"locked peaks + {result.peak_factor:g}σ3 at its nonlinear element exceeds "
                 "its range, docs/model.md section 9) and fails whatever the criterion.")
    return text


def _yield_legend(result: SelectionResult) -> str:
    y = result.yields
    assert y is not None
    how = ("exact: Δ_V ~ N(Δ_V at the mean, u(Δ_V)²)" if y.method == "exact" else
           f"Monte Carlo, {y.draws} draws (seed {y.seed}), 95 % Wilson interval in JSON/CSV")
    return (f"A production lot (lot:) shows its yield, the probability that a part drawn "
            f"from it passes the criterion ({how}; docs/model.md section 14); it passes where "
            f"the yield is at least {y.target:g}. Its margin and ranking are those of its "
            "mean.")


# ------------------------------------------------------------------ JSON, CSV


def _sat(result: SelectionResult, i: int, j: int) -> bool:
    return bool(result.saturated is not None and result.saturated[i, j])


#: Sensors per block of the streamed JSON: bounds the Python objects alive at once.
_BLOCK = 1024
#: Where the sensors go in the document's text (a string json writes as one token).
_SLOT = "\0sensors\0"


def to_json(result: SelectionResult) -> str:
    """``select --format json`` (docs/output.md) (sensors in catalogue order)."""
    return "".join(to_json_chunks(result))


def to_json_chunks(result: SelectionResult) -> Iterator[str]:
    """``select --format json`` as consecutive pieces of text: the document's other
    fields, then the sensors a block at a time, then its end.

    ``"".join(to_json_chunks(result))`` is the whole document; only one block of
    sensor entries (:func:`_sensor_entries`) exists as Python objects at a time.
    """
    document = header(result.method, result.unit)
    document["budget"] = result.budget
    document["profiles"] = json_of(profile_columns(result.profiles, result.rates,
                                                   result.profile_bounds, result.unit),
                                   range(len(result.profiles)))
    document["criterion"] = result.criterion
    document["require"] = result.require
    document["assume_unknown"] = result.assume_unknown
    if result.yields is not None:
        document["yield"] = {"target": result.yields.target, "seed": result.yields.seed}
    document["sensors"] = _SLOT
    before, after = dumps(document).split(json.dumps(_SLOT), 1)
    yield before + "["
    n = len(result.sensors)
    for start in range(0, n, _BLOCK):
        # a block is ~10^4 acyclic dicts: the cyclic collector would walk them
        # again and again as they are made; paused while one block is built
        collecting = gc.isenabled()
        gc.disable()
        try:
            text = json.dumps(_sensor_entries(result, start, min(start + _BLOCK, n)),
                              allow_nan=False)[1:-1]
        finally:
            if collecting:
                gc.enable()
        yield text if start == 0 else ", " + text
    yield "]" + after


def _sensor_entries(result: SelectionResult, start: int, stop: int) -> list[dict[str, Any]]:
    """The JSON entries of sensors ``start``..``stop`` (docs/output.md), one dict each:
    the one definition of a sensor's entry, whole document or streamed."""
    sensors = []
    for i, sensor in enumerate(result.sensors[start:stop], start):
        cells = []
        for j, profile in enumerate(result.profiles):
            spec = result.source(i) == "specs"
            checks = _spec_checks(result, i, j) if spec else {
                name: {"value": number(result.values[i, j, b]),
                       "bound": number(result.bounds[i, j, b]),
                       "pass": result.check(i, j, b)}
                for b, name in enumerate(BOUNDED)
            }
            if result.vre_pass is not None and not spec:
                value, bound = _vre(result, i, j)
                checks["vre"] = {"value": number(value), "bound": number(bound),
                                 "pass": result.vre_check(i, j)}
            cell = {"profile": profile, "pass": bool(result.passed[i, j]),
                    "status": result.status(i, j),
                    "unknown": list(result.unknown.get((i, j), ())),
                    "rms": number(result.rms[i, j]), "margin": number(result.margin[i, j]),
                    "criterion_margin": number(cell_margin(result, i, j)),
                    "disagrees": list(result.disagrees.get((i, j), ())),
                    "checks": checks}
            if result.total is not None:
                cell["total"] = number(result.total[i, j])
            if result.yields is not None and result.yields.is_lot(i):
                cell["yield"] = _yield_json(result, i, j)
            cell["saturated"] = _sat(result, i, j)
            cell["reason"] = reason(result, i, j)
            cells.append(cell)
        sensors.append({"sensor": sensor, "source": result.source(i),
                        "pass": bool(result.sensor_pass[i]),
                        "status": result.sensor_status(i),
                        "unknown": list(result.sensor_unknown(i)),
                        "questions": list(result.questions.get(i, ())),
                        "profiles": cells})
    return sensors


def _yield_json(result: SelectionResult, i: int, j: int) -> dict[str, Any]:
    """``{"value", "method", "interval": [lo, hi] | null, "draws"}`` (docs/output.md, select)."""
    y = result.yields
    assert y is not None
    interval = (None if y.method == "exact"
                else [number(y.low[i, j]), number(y.high[i, j])])
    return {"value": number(y.value[i, j]), "method": y.method, "interval": interval,
            "draws": y.draws}


def _spec_checks(result: SelectionResult, i: int, j: int) -> dict[str, Any]:
    """A datasheet sensor's checks: nonlinearity (%FS) and VRE against their spec bounds."""
    assert result.nl_value is not None and result.nl_bound is not None
    assert result.nl_pass is not None and result.vre_value is not None
    assert result.vre_bound is not None and result.vre_pass is not None
    vre = float(result.vre_value[i, j])
    return {
        "nonlinearity": {"value": number(result.nl_value[i, j]), "unit": "%FS",
                         "bound": number(result.nl_bound[i, j]),
                         "pass": result.nl_check(i, j)},
        "vre": {"value": None if math.isnan(vre) else vre,
                "bound": number(result.vre_bound[i, j]), "pass": result.vre_check(i, j)},
    }


def to_csv(result: SelectionResult) -> str:
    """One row per sensor × profile: the result's records
    (:func:`gyrovib.api.evaluation.records.selection_columns`, which the DataFrame shares); an
    unconstrained bound or margin is ``inf``.

    With datasheet (spec-form) sensors the rows gain ``source``, ``total`` and
    their checks (``value_nonlinearity``… in %FS, ``value_vre``… per g²; empty on
    coefficient rows, whose coefficient columns are empty on spec rows).
    """
    return csv_of(selection_columns(result), selection_cells(result),
                  title_flags=True)


# ------------------------------------------------------------------ human


#: The mark of a cell whose verdict hangs on an unpublished figure.
UNVERIFIED_MARK = "?"
#: Words of each status, as tables write a sensor's verdict.
VERDICT = {"pass": "PASS", "fail": "FAIL", "unverified": "UNVERIFIED"}
#: rich styles of each status.
STYLE = {"pass": "green", "fail": "bold red", "unverified": "bold yellow"}


def _cell(result: SelectionResult, i: int, j: int) -> str:
    if result.is_unverified(i, j):  # no margin: it hangs on the unknown figures
        return f"{UNVERIFIED_MARK} {' '.join(_unknown_names(result, i, j))} unknown"
    mark = "✓" if result.passed[i, j] else "✗"
    sat = f" {SATURATED_MARK}" if _sat(result, i, j) else ""
    if result.yields is not None and result.yields.is_lot(i):
        return f"{mark}{sat} yield {fmt(float(result.yields.value[i, j]), 4)}"
    assumed = "*" if result.unknown.get((i, j)) and result.passed[i, j] else ""
    other = result.disagrees.get((i, j))
    disagree = f" {DISAGREE_MARK}{','.join(other)}" if other else ""
    return f"{mark}{sat} {_margin(cell_margin(result, i, j))}{assumed}{disagree}"


def cell_margin(result: SelectionResult, i: int, j: int) -> float:
    """The margin a cell shows: that of the test deciding it (:attr:`criterion_margin`)."""
    if result.criterion_margin is None:
        return float(result.margin[i, j])
    return float(result.criterion_margin[i, j])


#: What each criterion's cell margin is.
CELL_MARGIN = {
    "bounds": "the least bound/value over the sensor's checks (a datasheet part: allowable "
              "NL/its NL and allowable VRE/its VRE)",
    "rms": "Δ*/Δ_V(RMS)",
    "worst": "Δ*/|Δ_V| (a datasheet part: over its envelope)",
    "both": "the smaller of the bounds margin (least bound/value) and Δ*/Δ_V(RMS)",
}
#: What the ranking's margin is: Δ*/Δ_V(RMS) (Δ*/|Δ_V| under ``worst``); a
#: datasheet part's is Δ*/its worst |Δ_V| over the envelope.
#: The mark of a cell that another test would decide otherwise, before their names.
DISAGREE_MARK = "≠"


def ranking_margin(result: SelectionResult) -> str:
    """The margin :attr:`~SelectionResult.ranking` orders by, in words."""
    base = "Δ*/|Δ_V|" if result.criterion == "worst" else "Δ*/Δ_V(RMS)"
    if "specs" in result.sources and result.criterion != "worst":
        return base + " (a spec-form part: Δ*/its worst |Δ_V|)"
    return base


def _unknown_names(result: SelectionResult, i: int, j: int) -> list[str]:
    """The unknown figures of a cell as written: VRE, m31, m32."""
    return [unknown_label(result, i, n) for n in result.unknown.get((i, j), ())]


def _unverified(result: SelectionResult) -> list[int]:
    """Unverified sensors, in the ranking's order."""
    return [i for i in result.ranking if result.sensor_status(i) == "unverified"]


def _asked(result: SelectionResult) -> tuple[Cell[int], ...]:
    """The unverified sensors' table: the questions for each one's vendor."""
    return (Cell("sensor", result.sensors.__getitem__, style="yellow"),
            Cell("ask for", lambda i: " | ".join(result.questions.get(i, ()))
                 or _ask(result, i), no_wrap=False))


_PARTS = ("x1", "x2", "x3", "acceleration")


def _ask(result: SelectionResult, i: int) -> str:
    """The unknown figures of an unverified sensor, and the parts a profile's recording
    did not record (a recording to make, not a question for the vendor)."""
    names = result.sensor_unknown(i)
    figures = [n for n in names if n not in _PARTS]
    parts = [n for n in names if n in _PARTS]
    out = ["the unknown figures " + ", ".join(figures)] if figures else []
    if parts:
        out.append("a recording of " + ", ".join(parts) + " (not recorded)")
    return " | ".join(out)


def assumption_note(result: SelectionResult) -> str:
    """What ``--assume-unknown zero`` took as 0, in one sentence ("" when nothing)."""
    if result.assume_unknown != "zero" or not result.unknown:
        return ""
    order = ("vre", "m31", "m32")
    cells = sorted({(i, n) for (i, _), names in result.unknown.items() for n in names},
                   key=lambda c: (result.sensors[c[0]], order.index(c[1])))
    by_sensor: dict[str, list[str]] = {}
    for i, name in cells:
        by_sensor.setdefault(result.sensors[i], []).append(unknown_label(result, i, name))
    return ("Assumed (--assume-unknown zero): unpublished figures taken as 0 -- "
            + "; ".join(f"{s}: {', '.join(n)}" for s, n in by_sensor.items())
            + "; cells marked * pass only under that assumption.")


def _passing(result: SelectionResult) -> list[int]:
    """Passing sensors, ranked by worst margin."""
    return [i for i in result.ranking if result.sensor_pass[i]]


def _ranked(result: SelectionResult) -> tuple[Cell[int], ...]:
    """The passing sensors' table: rank, worst margin and the profile of it."""
    rank = {i: str(k) for k, i in enumerate(_passing(result), 1)}

    def under(i: int) -> str:
        return result.profiles[int(result.margin[i].argmin())] if result.profiles else ""

    return (Cell("rank", rank.__getitem__, "right"),
            Cell("sensor", result.sensors.__getitem__),
            Cell("worst margin", lambda i: _margin(result.worst_margin[i]), "right"),
            Cell("under", under))


def _failing(result: SelectionResult) -> list[int]:
    """Failing sensors; with datasheet sensors, ranked by worst margin."""
    order = result.ranking if "specs" in result.sources else range(len(result.sensors))
    return [i for i in order if result.sensor_status(i) == "fail"]


def _limited(result: SelectionResult) -> tuple[Cell[int], ...]:
    """The failing sensors' table: what limits each."""
    return (Cell("sensor", result.sensors.__getitem__, style="red"),
            Cell("limited by", lambda i: limit_text(result, i), no_wrap=False))


def _matrix(result: SelectionResult) -> tuple[Cell[int], ...]:
    """The pass/fail matrix in Markdown: a row per sensor, a column per profile."""
    def profile(j: int) -> Cell[int]:
        return Cell(result.profiles[j], lambda i: _cell(result, i, j))

    return (Cell("sensor", result.sensors.__getitem__),
            *(profile(j) for j in range(len(result.profiles))),
            Cell("verdict", lambda i: f"**{VERDICT[result.sensor_status(i)]}**"))


def _under_matrix(result: SelectionResult) -> list[tuple[str, str, tuple[Cell[int], ...],
                                                          list[int]]]:
    """The tables under the matrix that have rows: their titles (terminal, Markdown),
    cells and rows (sensors)."""
    ranked = f"Passing sensors, ranked by worst margin {ranking_margin(result)}"
    asked = ("Unverified sensors: questions for the vendor (the figures that would decide "
             "each)")
    tables = [(ranked, ranked, _ranked(result), _passing(result)),
              ("Failing sensors: what limits each", "Failing sensors, and what limits each",
               _limited(result), _failing(result)),
              (asked, asked, _asked(result), _unverified(result))]
    return [table for table in tables if table[3]]


def to_markdown(result: SelectionResult) -> str:
    """The pass/fail matrix, the ranking and the limiting coefficients, in Markdown."""
    text = [_heading(result) + "\n", markdown_of(_matrix(result), range(len(result.sensors)))]
    text += [f"{title}:\n\n" + markdown_of(cells, rows)
             for _, title, cells, rows in _under_matrix(result)]
    text.append(_summary(result) + "\n\n" + _legend(result) + "\n")
    return "\n".join(text)


def to_table(result: SelectionResult, width: int | None = None, color: bool = False,
             ascii: bool = False) -> str:
    """Tables: pass/fail matrix (failing cells red), ranking, limiting coefficients."""

    out: list[Any] = [Text(_heading(result), style="bold")]
    matrix = Table(header_style="bold")
    longest = max((len(s) for s in result.sensors), default=6)
    matrix.add_column("sensor", no_wrap=True, min_width=longest)
    for profile in result.profiles:
        matrix.add_column(profile, justify="center", overflow="fold", min_width=8)
    matrix.add_column("verdict", justify="center", no_wrap=True, min_width=7)
    for i, sensor in enumerate(result.sensors):
        cells = [Text(_cell(result, i, j), style=STYLE[result.status(i, j)])
                 for j in range(len(result.profiles))]
        status = result.sensor_status(i)
        verdict = Text(VERDICT[status], style="bold " + STYLE[status].split()[-1])
        matrix.add_row(sensor, *cells, verdict)
    out.append(matrix)
    out += [table_of(cells, rows, title=title, title_justify="left")
            for title, _, cells, rows in _under_matrix(result)]
    out.append(Text(_summary(result), style="bold green" if result.requirement_met
                    else "bold red"))
    out.append(Text(_legend(result), style="dim"))
    return rich_text(out, width=width, color=color, ascii=ascii)
