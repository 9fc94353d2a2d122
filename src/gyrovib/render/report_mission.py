"""The mission section of ``gyrovib report --mission`` (docs/model.md section 12): per mission
the accumulated angle |θ_V| of every sensor against the angle budget, and per sensor the
segments that make it up."""

from __future__ import annotations

from html import escape
from typing import TYPE_CHECKING

from gyrovib.core.mission import ANGLE_UNITS
from gyrovib.render.common import fmt
from gyrovib.render.mission import known
from gyrovib.render.svg import Marker, bar_chart, stacked_bar_chart

if TYPE_CHECKING:
    from gyrovib.api.missions.results import MissionResult, MissionRow

PASS_FILL, FAIL_FILL, NO_BUDGET_FILL = "#2ca02c", "#d62728", "#1f77b4"
#: Unverified (hangs on an unpublished datasheet figure): its own colour, as in select.
OPEN_FILL = "#8c6bb1"


def _e(text: object) -> str:
    return escape(str(text), quote=True)


def _shown(result: MissionResult, mission: str) -> list[MissionRow]:
    """One row per sensor: its own, or the worst axis of a triad."""
    rows = [r for r in result.rows if r.mission == mission]
    return [r for r in rows if r.axis is None or r.axis == r.worst_axis]


def _fill(row: MissionRow) -> str:
    if row.unverified:
        return OPEN_FILL
    return NO_BUDGET_FILL if row.passed is None else PASS_FILL if row.passed else FAIL_FILL


def angle_chart(result: MissionResult, mission: str) -> str:
    rows = _shown(result, mission)
    names = [r.sensor + (f" ({r.axis})" if r.axis else "") for r in rows]
    marker = (None if result.angle_budget is None else
              Marker(f"θ* = {fmt(result.angle_budget, 3)} {result.angle_unit}",
                     x=float(result.angle_budget)))
    return bar_chart(f"Accumulated angle |θ_V| over {mission}",
                     f"|θ_V| ({result.angle_unit}, log); green: passes, red: fails"
                     + ("; purple: unverified (an unpublished datasheet figure can decide it)"
                        if any(r.unverified for r in rows) else "")
                     + ("; a triad shows its worst axis" if any(r.axis for r in rows) else ""),
                     names, [abs(r.angle) for r in rows], [_fill(r) for r in rows], marker)


#: The parts of a budget bar: |θ_V|, then k·RSS(noise) split by each term's share of RSS².
BUDGET_PARTS = ("vibration |θ_V|", "angle random walk", "bias instability", "rate random walk",
                "bias repeatability")
_NOISE = ("arw", "bias_instability", "rrw", "repeatability")


def budget_lengths(row: MissionRow) -> list[float]:
    """A row's budget bar in deg: |θ_V|, then the k·RSS of the noise terms divided among
    them in proportion to their squares (they add in quadrature, so each term's part of
    the noise is its share of the variance); an unknown term has no part."""
    b = row.budget
    if b is None:
        return [abs(row.angle)]
    terms = [getattr(b, n) or 0.0 for n in _NOISE]
    var = sum(t * t for t in terms)
    noise = b.total - abs(b.vibration)
    return [abs(b.vibration), *((noise * t * t / var) if var > 0 else 0.0 for t in terms)]


def budget_chart(result: MissionResult, mission: str) -> str:
    """The whole angle budget per sensor as a stacked bar: which term dominates."""
    rows = _shown(result, mission)
    names = [r.sensor + (f" ({r.axis})" if r.axis else "") for r in rows]
    marker = (None if result.angle_budget is None or result.angle_unit != "deg" else
              Marker(f"θ* = {fmt(result.angle_budget, 3)} deg", x=float(result.angle_budget)))
    return stacked_bar_chart(
        f"Angle budget over {mission}: |θ_V| + {fmt(result.coverage)}·RSS(noise)",
        "deg; the noise part split by each term's share of the variance; ≥ ?: a noise "
        "figure unknown, the total a lower bound", names, BUDGET_PARTS,
        [budget_lengths(r) for r in rows],
        [bool(r.budget and r.budget.lower_bound) for r in rows], marker)


def _segments_table(result: MissionResult, row: MissionRow) -> str:
    head = ["#", "profile", "T_s (s)", f"Ω_K3 ({result.unit})", f"Δ_V,s ({result.unit})",
            f"T_s·Δ_V,s ({result.angle_unit})", f"Δ_V(RMS),s ({result.unit})", "saturated"]

    factor = ANGLE_UNITS[result.unit][1]
    body = []
    for k, s in enumerate(row.segments):
        cells = [str(k + 1), s.profile, fmt(s.duration), fmt(s.rate[2]), fmt(s.total),
                 fmt(s.duration * s.total * factor), fmt(s.rms), "yes" if s.saturated else ""]
        style = ' class="worst"' if k == row.worst_index else ""
        body.append(f"<tr{style}>" + "".join(f"<td>{_e(c)}</td>" for c in cells) + "</tr>")
    where = f" with x3 on {row.axis}" if row.axis else ""
    note = (" A datasheet sensor's segments are each their own worst case; its θ_V is the "
            "worst case of the whole mission (one conversion function), at most their sum."
            if row.source == "specs" else "")
    caption = (f"{row.sensor}{where}: θ_V = {known(row.angle)} {result.angle_unit}, mean "
               f"Δ̄_V = {known(row.mean)} {result.unit}, mean RMS = {known(row.rms)} "
               f"{result.unit}; "
               f"worst segment {row.worst_index + 1} ({row.worst_profile}).{note}")
    return (f"<table><caption>{_e(caption)}</caption><thead><tr>"
            + "".join(f"<th>{_e(h)}</th>" for h in head) + "</tr></thead><tbody>"
            + "".join(body) + "</tbody></table>")


def mission_section(result: MissionResult) -> str:
    """The HTML of the report's mission section."""
    budget = ("no budget" if result.angle_budget is None and result.budget is None else
              f"angle budget |θ_V| ≤ {fmt(result.angle_budget)} {result.angle_unit}"
              if result.angle_budget is not None else
              f"budget Δ̄_RMS ≤ {fmt(result.budget)} {result.unit}")
    parts = ["<style>section.mission tr.worst td{font-weight:bold}</style>",
             "<h2>Missions</h2>",
             f"<p>Each sensor over each mission (docs/model.md section 12; {_e(budget)}): the "
             "accumulated angle θ_V = Σ T_s·Δ_V,s, and per sensor the segments that make "
             "it up (the worst segment highlighted); and the whole angle budget, |θ_V| plus "
             "the noise of each sensor's noise: figures over the mission (section 15).</p>"]
    for mission in result.missions:
        parts.append(f'<section class="mission"><h3>{_e(mission)}</h3>')
        parts.append(f'<div class="charts"><figure>{angle_chart(result, mission)}</figure>'
                     f"<figure>{budget_chart(result, mission)}</figure></div>")
        parts.extend(_segments_table(result, r) for r in _shown(result, mission))
        parts.append("</section>")
    return "\n".join(parts)
