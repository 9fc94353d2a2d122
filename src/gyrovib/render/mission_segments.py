"""``mission --segments``: the budget segment by segment (docs/model.md sections 12, 15).

Per sensor × mission × axis, each segment's error and the angle budget at its end:
θ_V summed segment by segment so far, each noise term over the time flown so far, and
their total with the coverage factor — the numbers of the θ(t) plot and of each JSON
segment's ``budget``. As a table under the main one (terminal or Markdown) and as CSV
records, one line per segment (:data:`gyrovib.api.missions.results.SEGMENT_COLUMNS`).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

from gyrovib.api.missions.results import BUDGET_NOISE_TERMS, SEGMENT_COLUMNS
from gyrovib.render.common import fmt
from gyrovib.render.formats import Cell, csv_of, known, markdown_of, table_of

if TYPE_CHECKING:
    from rich.table import Table

    from gyrovib.api.missions import MissionResult
    from gyrovib.api.missions.results import Budget, SegmentRecord


def _total(b: Budget) -> str:
    """The total at a segment's end: '≥ x' when a noise figure is unknown."""
    return ("≥ " if b.lower_bound else "") + known(b.total)


def _budget(text: Callable[[Budget], str]) -> Callable[[SegmentRecord], str]:
    """A figure of the budget at a segment's end; '-' without a budget."""
    return lambda r: "-" if r.budget is None else text(r.budget)


def _cells(result: MissionResult) -> tuple[Cell[SegmentRecord], ...]:
    """The columns of the segments' table (terminal and Markdown alike)."""
    def noise(name: str) -> Callable[[Budget], str]:
        return lambda b: known(getattr(b, name))

    return (Cell("sensor", of="sensor"), Cell("axis", lambda r: r.row.axis or "-", of="axis"),
            Cell("segment", lambda r: str(r.index + 1), "right", of="segment"),
            Cell("profile", of="profile"), Cell("end (s)", justify="right", of="end"),
            Cell(f"Ω_K3 ({result.unit})", justify="right", of="rate_x3"),
            Cell(f"Δ_V ({result.unit})", lambda r: known(r.segment.total)
                 + (" (saturated)" if r.segment.saturated else ""), "right", of="total"),
            Cell("θ_V (deg)", _budget(lambda b: known(b.vibration)), "right",
                 of="theta_vibration"),
            *(Cell(f"{title} (deg)", _budget(noise(name)), "right", of=f"theta_{name}")
              for title, name in zip(("θ_ARW", "θ_B", "θ_RRW", "θ_R"), BUDGET_NOISE_TERMS,
                                     strict=True)),
            Cell("total (deg)", _budget(_total), "right", of="budget_total"))


def _title(result: MissionResult) -> str:
    return ("Segment by segment: Δ_V of each segment, and at its end θ_V summed so far, "
            "the noise terms over the time flown and the total"
            + (f" (k = {fmt(result.coverage)})" if result.coverage != 1.0 else ""))


def segments_markdown(result: MissionResult) -> str:
    """:func:`segments_table` as a Markdown table under its title."""
    return f"{_title(result)}:\n\n" + markdown_of(_cells(result), result.segment_rows(),
                                                   SEGMENT_COLUMNS)


def segments_table(result: MissionResult) -> Table:
    """One line per sensor × axis × segment: the segment's Δ_V and the budget at its end."""
    return table_of(_cells(result), result.segment_rows(), SEGMENT_COLUMNS, title=_title(result),
                    title_justify="left")


def segments_csv(result: MissionResult) -> str:
    """One line per sensor × mission × axis × segment: :data:`SEGMENT_COLUMNS`."""
    return csv_of(SEGMENT_COLUMNS, result.segment_rows())
