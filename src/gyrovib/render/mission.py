"""Renderers of :class:`gyrovib.api.MissionResult`: table, json, csv, markdown, junit."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from rich.table import Table
from rich.text import Text

from gyrovib.api.missions.results import BUDGET_NOISE_TERMS, COLUMNS, TRIAD_COLUMNS
from gyrovib.reasons import unverified_text
from gyrovib.records import Column, names
from gyrovib.render.common import dumps, fmt, header, number, rich_text
from gyrovib.render.formats import Cell, csv_of, json_of, junit_of, known, markdown_of, table_of
from gyrovib.render.mission_answer import allowance_cells
from gyrovib.render.mission_segments import segments_csv, segments_markdown, segments_table

if TYPE_CHECKING:
    from gyrovib.api.missions.results import MissionResult, MissionRow
    from gyrovib.render.formats import Case


#: The verdict cell of each row status (None: no budget).
VERDICT = {None: "-", "pass": "pass", "fail": "FAIL", "unverified": "UNVERIFIED"}
#: How an unverified row's reason says to take its unpublished figures as 0: the
#: command line's option (mission's rows are worded for the command line).
ASSUME_ZERO = "--assume-unknown zero"


def _verdict(row: MissionRow) -> str:
    return VERDICT[row.status]


def _budget_text(result: MissionResult) -> str:
    if result.angle_budget is not None:
        return (f"angle budget: total |θ_V| + {fmt(result.coverage)}·RSS(noise) ≤ "
                f"{fmt(result.angle_budget)} {result.angle_unit}")
    if result.budget is not None:
        return f"budget Δ̄_RMS ≤ {fmt(result.budget)} {result.unit}"
    return "no budget"


def unverified_reason(row: MissionRow) -> str | None:
    """Why an unverified row is open (the unpublished figures that can decide it); None
    when the row is not unverified."""
    if not row.unverified:
        return None
    return unverified_text(row.unknown, spec=row.source == "specs", advice=ASSUME_ZERO)


def _reason(result: MissionResult, row: MissionRow) -> str:
    """Why a row fails, in one line ('' when it passes or has no budget)."""
    if row.passed is None or row.passed:
        return ""
    if row.unverified:
        return unverified_reason(row) or ""
    if row.saturated:
        bad = [str(k + 1) for k, s in enumerate(row.segments) if s.saturated]
        return f"saturated in segment {', '.join(bad)}"
    if result.angle_budget is not None and row.budget is not None:
        return (f"total {budget_total(row)} deg > {fmt(result.angle_budget)} "
                f"{result.angle_unit}")
    if result.angle_budget is not None:
        return (f"|θ_V| = {fmt(abs(row.angle))} {result.angle_unit} > "
                f"{fmt(result.angle_budget)} {result.angle_unit}")
    return f"Δ̄_RMS = {fmt(row.rms)} {result.unit} > {fmt(result.budget)} {result.unit}"


#: The headings of the budget's noise terms (:data:`BUDGET_NOISE_TERMS`) in the table.
_NOISE_HEAD = ("θ_ARW", "θ_B", "θ_RRW", "θ_R")


def budget_total(row: MissionRow) -> str:
    """The budget's total: '≥ x' when a noise figure is unknown (a lower bound)."""
    if row.budget is None:
        return "-"
    if math.isnan(row.budget.total):
        return "?"
    return ("≥ " if row.budget.lower_bound else "") + fmt(row.budget.total)


def _noise_cell(name: str) -> Callable[[MissionRow], str]:
    """A noise term in deg; '?' where the figure is unknown (never 0), '≤ x' where it is
    only an upper bound (the budget uses the bound), ' typ' where it is typical."""
    def text(row: MissionRow) -> str:
        if row.budget is None:
            return "-"
        if (v := getattr(row.budget, name)) is None:
            return "?"
        return (("≤ " if name in row.budget.bounds else "") + fmt(v)
                + (" typ" if name in row.budget.typical else ""))
    return text


def _axis(row: MissionRow) -> str:
    if row.axis is None:
        return "-"
    return row.axis + (" (worst)" if row.axis == row.worst_axis else "")


def _worst(row: MissionRow) -> str:
    w = row.segments[row.worst_index]
    worst = f"({fmt(w.total)})" if math.isfinite(row.worst_total) else "(?)"
    return f"{row.worst_index + 1} {w.profile} {worst}"


def _verdict_cell(row: MissionRow) -> str:
    return _verdict(row) + (" (saturated)" if row.saturated else "") + _on_typical(row)


def table_cells(result: MissionResult) -> tuple[Cell[MissionRow], ...]:
    """The columns of the rows' table, its Markdown and its terminal table alike: one
    row per sensor × mission × axis (the records they show: :data:`COLUMNS`)."""
    rate, angle = f" ({result.unit})", f" ({result.angle_unit})"
    return (Cell("sensor", of="sensor"), Cell("mission", of="mission"),
            Cell("axis", _axis, of="axis"),
            Cell(f"mean Δ̄_V{rate}", justify="right", of="mean"),
            Cell(f"angle θ_V{angle}", justify="right", of="angle"),
            Cell(f"mean RMS Δ̄_RMS{rate}", justify="right", of="rms"),
            *(Cell(f"{title} (deg)", _noise_cell(name), "right", of=f"theta_{name}")
              for title, name in zip(_NOISE_HEAD, BUDGET_NOISE_TERMS, strict=True)),
            Cell("total (deg)", budget_total, "right", of="budget_total"),
            Cell("worst segment", _worst, of="worst_segment"),
            Cell("verdict", _verdict_cell, of="status"))


def _on_typical(row: MissionRow) -> str:
    """' (on typ)' where a verdict rests on a figure the datasheet gives as typical."""
    typical = row.budget is not None and row.budget.typical and row.status is not None
    return " (on typ)" if typical else ""


def _unknown_notes(result: MissionResult) -> list[str]:
    """Why rows are unverified (once per sensor and reason), and what
    ``--assume-unknown zero`` took as 0."""
    notes: list[str] = []
    seen: dict[tuple[str, str], None] = {}
    for r in result.rows:
        reason = unverified_reason(r)
        if reason:
            seen[(r.sensor, reason)] = None
    notes.extend(f"{sensor}: {reason}." for sensor, reason in seen)
    if result.assume_unknown == "zero":
        taken: dict[str, dict[str, None]] = {}
        for r in result.rows:
            if r.unknown:
                taken.setdefault(r.sensor, {}).update(dict.fromkeys(r.unknown))
        if taken:
            notes.append("Assumed (--assume-unknown zero): unpublished figures taken as 0 -- "
                         + "; ".join(f"{s}: " + ", ".join("VRE" if n == "vre" else n
                                                          for n in names)
                                     for s, names in taken.items()) + ".")
    return notes


def _bound_note(result: MissionResult) -> list[str]:
    """The note on rows whose budget rests on a noise figure given only as a bound."""
    if not any(r.budget is not None and r.budget.bounds for r in result.rows):
        return []
    return ["'≤ x': a term whose noise figure is only an upper bound (a term the static "
            "log did not resolve); the total uses the bound, so it rests on a bound: the "
            "most the term can be, not a measured value."]


def _table_notes(result: MissionResult) -> list[str]:
    """The legend under the table: the definitions, then what applies to these rows."""
    notes = ["mean Δ̄_V = Σ T_s·Δ_V,s / Σ T_s; angle θ_V = Σ T_s·Δ_V,s; mean RMS = "
             "√(Σ T_s·Δ_V(RMS),s² / Σ T_s); worst segment: its number, profile and Δ_V,s "
             "(docs/model.md section 12). Budget over the mission's T hours (section 15): "
             f"θ_ARW = N·√T, θ_B = B·T, θ_RRW = K·T^1.5/√3, θ_R = R·T; total = |θ_V| + "
             f"{fmt(result.coverage)}·√(θ_ARW² + θ_B² + θ_RRW² + θ_R²) (coverage k = "
             f"{fmt(result.coverage)}); '?': a noise figure the catalogue does not give, "
             "unknown, so the total is a lower bound (≥)."]
    notes.extend(_bound_note(result))
    notes += _typical_note(result)
    if any(r.source == "specs" for r in result.rows):
        notes.append("A datasheet sensor's mean and angle are the worst case over its "
                     "envelope of the whole mission (one conversion function for every "
                     "segment).")
    if any(r.axis is not None for r in result.rows):
        notes.append("axis: the vehicle axis of the sensitive axis x3 in a triad; (worst): "
                     "the triad's largest |θ_V|.")
    if result.budget is not None or result.angle_budget is not None:
        n = sum(1 for p in result.sensor_pass if p)
        n_open = sum(1 for k in range(len(result.sensors))
                     if result.sensor_status(k) == "unverified")
        open_ = f", {n_open} unverified" if n_open else ""
        notes.append(f"{n} of {len(result.sensors)} sensors pass every mission{open_} "
                     f"(--require {result.require}: "
                     f"{'met' if result.requirement_met else 'NOT met'}).")
    notes += _rank_notes(result)
    return notes


def _typical_note(result: MissionResult) -> list[str]:
    """What 'typ' means, where a row's budget rests on a typical figure."""
    if not any(r.budget is not None and r.budget.typical for r in result.rows):
        return []
    return ["'typ': a figure the datasheet gives as typical, not guaranteed; '(on typ)': a "
            "verdict that rests on one."]


def _rank_notes(result: MissionResult) -> list[str]:
    """What the order of a ranked result means, and which sensors it does not rank."""
    if result.ranks is None:
        return []
    out = ["Sensors ranked by their largest budget total, smallest first."]
    left = [s for s, r in zip(result.sensors, result.ranks, strict=True) if r is None]
    if left:
        out.append(f"Not ranked (a total that is only a lower bound, or a verdict "
                   f"unverified), listed after the ranked ones: {', '.join(left)}.")
    return out


def to_table(result: MissionResult, width: int | None = None, color: bool = False,
             ascii: bool = False, segments: bool = False) -> str:
    """One row per sensor × mission × axis: mean, angle, mean RMS, worst segment, verdict;
    with ``segments``, the budget segment by segment under it
    (:func:`gyrovib.render.mission_segments.segments_table`)."""

    cells = table_cells(result)
    if len(result.missions) == 1:  # in the title
        cells = tuple(c for c in cells if c.of != "mission")
    table = table_of(cells, result.rows, COLUMNS, title=f"Missions: "
                     f"{', '.join(result.missions)} ({_budget_text(result)})",
                     title_justify="left")
    out: list[Any] = [table]
    if any(r.budget is not None and r.budget.allowed is not None for r in result.rows):
        out.append(_allowance_table(result))
    if segments:
        out.append(segments_table(result))
    notes = _table_notes(result)
    out.append(Text(" ".join(notes), style="dim"))
    out.extend(Text(note) for note in _unknown_notes(result))
    return rich_text(out, width=width, color=color, ascii=ascii)


def _allowance_table(result: MissionResult) -> Table:
    """Per row, the largest value of each figure that still meets the angle budget."""
    cells = (Cell("sensor", of="sensor"), Cell("axis", lambda r: r.axis or "-", of="axis"),
             *allowance_cells())
    return table_of(cells, result.rows, COLUMNS, title="Largest figure that meets the "
                    "budget, the others as given (none (X): X alone uses the allowance; *: "
                    "an upper limit, a figure being unknown)", title_justify="left")


def json_columns(result: MissionResult) -> tuple[Column[MissionRow], ...]:
    """The columns of the JSON's rows: the result's records (:data:`COLUMNS`) with,
    after ``unknown``, the words the library leaves to the renderer: why the row fails."""
    at = names(COLUMNS).index("unknown") + 1
    reason: Column[MissionRow] = Column("reason", None, lambda r: _reason(result, r) or None,
                                        skip=("csv", "frame"))
    return (*COLUMNS[:at], reason, *COLUMNS[at:])


def to_json(result: MissionResult) -> str:
    """The JSON document of docs/output.md (mission): one entry per sensor × mission
    (× axis), then each triad's summary and each sensor's verdict."""
    document = {
        **header("exact", result.unit), "angle_unit": result.angle_unit,
        "budget": None if result.budget is None else number(result.budget),
        "angle_budget": None if result.angle_budget is None else number(result.angle_budget),
        "require": result.require, "assume_unknown": result.assume_unknown,
        "mission": json_of(json_columns(result), result.rows),
        "triads": json_of(TRIAD_COLUMNS, result.triads()),
        "sensors": json_of(result.sensor_records(), range(len(result.sensors))),
        "requirement_met": result.requirement_met,
    }
    return dumps(document)


def to_csv(result: MissionResult, segments: bool = False) -> str:
    """One row per sensor × mission × axis: the result's records
    (:meth:`MissionResult.records`), as its DataFrame has them; with ``segments``, one
    row per segment instead (:func:`gyrovib.render.mission_segments.segments_csv`)."""
    if segments:
        return segments_csv(result)
    return csv_of(result.records(), result.rows)


def to_markdown(result: MissionResult, segments: bool = False) -> str:
    """The rows as a Markdown table with their notes; with ``segments``, the budget
    segment by segment under them (:func:`~gyrovib.render.mission_segments.segments_markdown`)."""
    text = markdown_of(table_cells(result), result.rows, COLUMNS)
    notes = _unknown_notes(result) + _rank_notes(result)
    text += "\n" + "\n\n".join(notes) + "\n" if notes else ""
    return text + ("\n" + segments_markdown(result) if segments else "")


def to_junit(result: MissionResult) -> str:
    """JUnit XML: one testcase per sensor × mission × axis (classname = sensor)."""
    return junit_of("gyrovib mission", f"gyrovib mission: {_budget_text(result)}",
                    [_case(result, r) for r in result.rows])


def _case(result: MissionResult, r: MissionRow) -> Case:
    """A row as a JUnit test case: its figures, and why it fails."""
    name = r.mission if r.axis is None else f"{r.mission} (x3 on {r.axis})"
    out = (f"θ_V = {known(r.angle)} {result.angle_unit}, budget total "
           f"{budget_total(r)} deg, mean RMS = {known(r.rms)} "
           f"{result.unit}, worst segment {r.worst_index + 1} ({r.worst_profile})"
           + (f"; the verdict rests on typical (typ) figures: "
              f"{', '.join(r.budget.typical)}"
              if r.budget is not None and _on_typical(r) else ""))
    if r.passed is not False:
        return r.sensor, name, out, None
    reason = _reason(result, r)
    return r.sensor, name, out, ("Unverified" if r.unverified else "BudgetExceeded", reason,
                                 reason)
