"""``mission --segments``: the budget segment by segment (docs/model.md sections 12, 15).

Per sensor × mission × axis, each segment's error and the angle budget at its end:
θ_V summed segment by segment so far, each noise term over the time flown so far, and
their total with the coverage factor — the numbers of the θ(t) plot and of each JSON
segment's ``budget``. As a table under the main one (terminal or Markdown) and as CSV
records, one line per segment (:data:`gyrovib.api.missions.results.SEGMENT_COLUMNS`).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from rich.table import Table

from gyrovib.api.missions.results import SEGMENT_COLUMNS
from gyrovib.render.common import fmt, markdown_table
from gyrovib.render.formats import csv_of

if TYPE_CHECKING:
    from gyrovib.api.missions import MissionResult
    from gyrovib.api.missions.results import Budget, SegmentRecord

_NOISE = ("arw", "bias_instability", "rrw", "repeatability")


def _known(value: float | None) -> str:
    """A number, '?' where unknown (None or NaN: never shown as 0)."""
    return "?" if value is None or math.isnan(value) else fmt(value)


def _total(b: Budget) -> str:
    """The total at a segment's end: '≥ x' when a noise figure is unknown."""
    return ("≥ " if b.lower_bound else "") + _known(b.total)


def _cells(result: MissionResult, r: SegmentRecord) -> list[str]:
    s = r.segment
    head = [r.row.sensor, r.row.axis or "-", str(r.index + 1), s.profile,
            fmt(r.start + s.duration), _known(s.rate[2]), _known(s.total)
            + (" (saturated)" if s.saturated else "")]
    b = r.budget
    if b is None:
        return [*head, *["-"] * (len(_NOISE) + 2)]
    return [*head, _known(b.vibration), *(_known(getattr(b, n)) for n in _NOISE), _total(b)]


def _title(result: MissionResult) -> str:
    return ("Segment by segment: Δ_V of each segment, and at its end θ_V summed so far, "
            "the noise terms over the time flown and the total"
            + (f" (k = {fmt(result.coverage)})" if result.coverage != 1.0 else ""))


def _head(result: MissionResult) -> list[str]:
    return ["sensor", "axis", "segment", "profile", "end (s)", f"Ω_K3 ({result.unit})",
            f"Δ_V ({result.unit})", "θ_V (deg)", "θ_ARW (deg)", "θ_B (deg)", "θ_RRW (deg)",
            "θ_R (deg)", "total (deg)"]


def segments_markdown(result: MissionResult) -> str:
    """:func:`segments_table` as a Markdown table under its title."""
    return (f"{_title(result)}:\n\n"
            + markdown_table(_head(result), (_cells(result, r) for r in result.segment_rows())))


def segments_table(result: MissionResult) -> Table:
    """One line per sensor × axis × segment: the segment's Δ_V and the budget at its end."""
    table = Table(header_style="bold", title=_title(result), title_justify="left")
    head = _head(result)
    for k, name in enumerate(head):
        table.add_column(name, no_wrap=True, justify="left" if k in (0, 1, 3) else "right")
    for record in result.segment_rows():
        table.add_row(*_cells(result, record))
    return table


def segments_csv(result: MissionResult) -> str:
    """One line per sensor × mission × axis × segment: :data:`SEGMENT_COLUMNS`."""
    return csv_of(SEGMENT_COLUMNS, result.segment_rows())
