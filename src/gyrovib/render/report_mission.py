"""The mission section of ``gyrovib report --mission`` (docs/model.md section 12): per mission
the accumulated angle |θ_V| of every sensor against the angle budget, and per sensor the
segments that make it up."""

from __future__ import annotations

import math
from html import escape
from typing import TYPE_CHECKING, Any

import numpy as np

from gyrovib import units
from gyrovib.core.mission import ANGLE_UNITS
from gyrovib.render.common import fmt, html_table
from gyrovib.render.formats import cell_texts, known
from gyrovib.render.mission import budget_total
from gyrovib.render.mission_answer import allowance_cells, answer_line
from gyrovib.render.svg import Marker, bar_chart, stacked_bar_chart

if TYPE_CHECKING:
    from gyrovib.api.missions.results import MissionResult, MissionRow
    from gyrovib.api.noise.results import Budget
    from gyrovib.core._types import FloatArray

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


#: Largest ratio of the budget totals drawn on one common axis; past it each bar is drawn
#: on its own scale (the parts as shares of its total), which a common axis would
#: flatten to nothing beside the largest.
COMMON_SCALE_SPREAD = 20.0


def _total_text(lengths: list[float]) -> str:
    """A budget bar's total in deg, '?' when a part of it is unknown."""
    if any(math.isnan(v) for v in lengths):
        return "?"
    return fmt(sum(v for v in lengths if v > 0))


def _own_scale(lengths: list[list[float]]) -> bool:
    """Whether the bars' totals span more than :data:`COMMON_SCALE_SPREAD`."""
    totals = [t for t in (sum(v for v in row if v > 0) for row in lengths) if t > 0]
    return bool(totals) and max(totals) > COMMON_SCALE_SPREAD * min(totals)


def _shares(row: list[float]) -> list[float]:
    """A bar's parts as percentages of its own total."""
    total = sum(v for v in row if v > 0)
    return [100.0 * v / total if total > 0 else 0.0 for v in row]


def budget_chart(result: MissionResult, mission: str) -> str:
    """The whole angle budget per sensor as a stacked bar: which term dominates. On one
    axis in deg when the totals are within :data:`COMMON_SCALE_SPREAD` of each other,
    else each bar as the shares of its own total; the tooltips give each part and its
    bar's total in deg either way."""
    rows = _shown(result, mission)
    names = [r.sensor + (f" ({r.axis})" if r.axis else "") for r in rows]
    lengths = [budget_lengths(r) for r in rows]
    tips = [[f"{known(v)} deg of {_total_text(row)} deg" for v in row] for row in lengths]
    title = f"Angle budget over {mission}: |θ_V| + {fmt(result.coverage)}·RSS(noise)"
    note = ("the noise part split by each term's share of the variance; ≥ ?: a noise "
            "figure unknown, the total a lower bound")
    open_end = [bool(r.budget and r.budget.lower_bound) for r in rows]
    if _own_scale(lengths):
        return stacked_bar_chart(
            title, f"% of each bar's own total, in its tooltips (the totals span over "
            f"{fmt(COMMON_SCALE_SPREAD)}×); {note}",
            names, BUDGET_PARTS, [_shares(row) for row in lengths], open_end, None, tips)
    marker = (None if result.angle_budget is None or result.angle_unit != "deg" else
              Marker(f"θ* = {fmt(result.angle_budget, 3)} deg", x=float(result.angle_budget)))
    return stacked_bar_chart(title, f"deg; {note}", names, BUDGET_PARTS, lengths, open_end,
                             marker, tips)


def _segments_table(result: MissionResult, row: MissionRow, rate_unit: str | None = None
                    ) -> str:
    """A row's segments; the carrier Ω_K3 in ``rate_unit`` (the unit the mission's file
    writes its rates in; default the result's), the errors in the result's unit."""
    rate_unit = rate_unit or result.unit
    to_rate = units.scale(result.unit) / units.scale(rate_unit)
    head = ["#", "profile", "T_s (s)", f"Ω_K3 ({rate_unit})", f"Δ_V,s ({result.unit})",
            f"T_s·Δ_V,s ({result.angle_unit})", f"Δ_V(RMS),s ({result.unit})", "saturated"]

    factor = ANGLE_UNITS[result.unit][1]
    body = []
    for k, s in enumerate(row.segments):
        cells = [str(k + 1), s.profile, fmt(s.duration), fmt(s.rate[2] * to_rate),
                 known(s.total), known(s.duration * s.total * factor), known(s.rms),
                 "yes" if s.saturated else ""]
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


#: Size of a θ(t) chart (px) and its margins.
_W, _H, _L, _B = 520, 200, 56, 28
#: Verdict words.
_WORDS = {None: "no budget", "pass": "passes", "fail": "FAILS", "unverified": "UNVERIFIED"}


def theta_chart(result: MissionResult, row: MissionRow) -> str:
    """θ(t) of one row as inline SVG: the vibration staircase θ_V(t) segment by segment,
    the ±k·σ(t) noise cone around it (σ(t)² = N²t + B²t² + K²t³/3 + R²t², the row's
    terms at T scaled by √(t/T), t/T, (t/T)^1.5, t/T) and ±θ*; each segment's point
    carries a tooltip with its θ values."""
    b = row.budget
    if b is None or not row.timeline:
        return ""
    if math.isnan(b.total):  # θ_V rests on an axis the recording did not record
        return (f"<p>{_e(row.sensor)}: θ(t) unknown, its vibration error resting on an axis "
                "the recording did not record (unknown, not 0).</p>")
    span = row.duration
    t, vib, upper, lower = _cone(row, b, span)
    top = max(float(np.max(np.abs(np.concatenate([upper, lower])))),
              result.angle_budget or 0.0, 1e-12) * 1.1

    def px(tt: float, th: float) -> str:
        return (f"{_L + (_W - _L - 8) * tt / span:.1f},"
                f"{(_H - _B) / 2 - (_H - _B) / 2 * th / top + 4:.1f}")

    cone = " ".join(px(a, c) for a, c in zip(t, upper, strict=True))
    cone += " " + " ".join(px(a, c) for a, c in zip(t[::-1], lower[::-1], strict=True))
    stairs = " ".join(px(a, c) for a, c in zip(t, vib, strict=True))
    ends = np.cumsum([s.duration for s in row.segments])
    dots = "".join(_dot(px(e, s.vibration), _tooltip(k, e, s))
                   for k, (e, s) in enumerate(zip(ends, row.timeline, strict=True)))
    limits = "" if result.angle_budget is None or result.angle_unit != "deg" else "".join(
        _hline(px(0.0, sign * result.angle_budget).split(",")[1]) for sign in (1.0, -1.0))
    axis = (f'<text x="4" y="12" font-size="10">±{_e(fmt(top / 1.1))} deg</text>'
            f'<text x="{_W - 90}" y="{_H - 6}" font-size="10">{_e(fmt(span / 3600.0))} h</text>'
            f'<text x="{_L}" y="{_H - 6}" font-size="10">0 h</text>')
    title = (f"{row.sensor}{f' (x3 on {row.axis})' if row.axis else ''}: θ(t), total "
             f"{'≥ ' if b.lower_bound else ''}{fmt(b.total)} deg, {_WORDS[row.status]}")
    return (f'<svg xmlns="http://www.w3.org/2000/svg" width="{_W}" height="{_H}" role="img">'
            f"<title>{_e(title)}</title>"
            f'<polygon points="{cone}" fill="#1f77b4" fill-opacity="0.2"/>'
            f'<polyline points="{stairs}" fill="none" stroke="#d62728" stroke-width="1.6"/>'
            f"{limits}{dots}{axis}</svg>")


def _cone(row: MissionRow, b: Budget, span: float
          ) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """t (s), θ_V(t) and the cone's edges θ_V ± k·σ(t) (deg) on 200 points."""
    t = np.linspace(0.0, span, 200)
    ends = np.cumsum([s.duration for s in row.segments])
    vib = np.interp(t, np.concatenate([[0.0], ends]),
                    [0.0] + [x.vibration for x in row.timeline])
    x = t / span
    var = np.zeros(t.size)
    for v, power in ((b.arw, 0.5), (b.bias_instability, 1.0), (b.rrw, 1.5),
                     (b.repeatability, 1.0)):
        if v is not None:
            var += (v * x**power) ** 2
    half = b.coverage * np.sqrt(var)
    return t, vib, vib + half, vib - half


def _hline(y: str) -> str:
    return (f'<line x1="{_L}" x2="{_W - 8}" y1="{y}" y2="{y}" stroke="#000" '
            'stroke-dasharray="4 3"/>')


def _dot(at: str, tip: str) -> str:
    x, y = at.split(",")
    return f'<circle cx="{x}" cy="{y}" r="2.5" fill="#d62728"><title>{_e(tip)}</title></circle>'


def _tooltip(k: int, end: float, b: Budget) -> str:
    """A segment end's θ values: the staircase, the cone's half-width, the total."""
    return (f"segment {k + 1} ends at {fmt(end / 3600.0)} h: θ_V = {fmt(b.vibration)} deg, "
            f"±{fmt(b.coverage)}·σ = ±{fmt(b.total - abs(b.vibration))} deg, total "
            f"{fmt(b.total)} deg")


def verdict_table(result: MissionResult, mission: str) -> str:
    """Every sensor's worst row: its total against the budget as a number and a word,
    and the largest figure of each kind that would meet the budget."""
    rows = _shown(result, mission)
    with_allowance = any(r.budget is not None and r.budget.allowed is not None for r in rows)
    allowance = allowance_cells() if with_allowance else ()
    head = ["sensor", "axis", "|θ_V| (deg)", "total (deg)", "budget", "verdict",
            *(c.title for c in allowance)]
    budget = ("-" if result.angle_budget is None else
              f"{fmt(result.angle_budget)} {result.angle_unit}")
    body = [[r.sensor, r.axis or "-", known(abs(r.angle)), budget_total(r), budget,
             _WORDS[r.status], *allowed]
            for r, allowed in zip(rows, cell_texts(allowance, rows), strict=True)]
    return html_table(head, body, caption="Each sensor's total and verdict (a triad: its "
                      "worst axis); the largest value of each figure that meets the budget, "
                      "the others as given (*: an upper limit, another figure being unknown)")


#: The noise figures of a ``noise:`` block, and their heading.
_FIGURES = (("arw", "N: angle random walk"), ("bias_instability", "B: bias instability"),
            ("rrw", "K: rate random walk"), ("bias_repeatability", "R: bias repeatability"))


def noise_table(noise: dict[str, dict[str, Any]]) -> str:
    """Each sensor's noise figures as its catalogue writes them — value, unit and the
    datasheet's qualifier (typ, max) — and '?' where a figure is not given (unknown,
    never 0). ``noise``: sensor → figure name → an object with ``value``, ``unit``,
    ``qualifier`` (or None)."""
    if not noise:
        return ""
    body = []
    for sensor, figures in noise.items():
        cells = [sensor]
        for name, _ in _FIGURES:
            fig = figures.get(name)
            cells.append("?" if fig is None else
                         f"{fmt(fig.value)} {fig.unit}"
                         + (f" {fig.qualifier}" if getattr(fig, "qualifier", None) else ""))
        body.append(cells)
    return html_table(("sensor", *(t for _, t in _FIGURES)), body, caption="The noise "
                      "figures of the budget, as the catalogue gives them (typ: typical, "
                      "max: guaranteed; ?: not given, unknown)")


def mission_section(result: MissionResult,
                    noise: dict[str, dict[str, Any]] | None = None,
                    rate_units: dict[str, str] | None = None) -> str:
    """The HTML of the report's mission section (``rate_units``: mission id → the rate
    unit of its file, in which its segments' carrier rates are shown)."""
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
    answer = answer_line(result)
    if answer is not None:
        parts.append(f'<p class="answer"><strong>{_e(answer)}</strong></p>')
    parts.append(noise_table(noise or {}))
    for mission in result.missions:
        parts.append(f'<section class="mission"><h3>{_e(mission)}</h3>')
        parts.append(verdict_table(result, mission))
        parts.append(f'<div class="charts"><figure>{angle_chart(result, mission)}</figure>'
                     f"<figure>{budget_chart(result, mission)}</figure></div>")
        parts.append('<div class="charts">' + "".join(
            f"<figure>{theta_chart(result, r)}</figure>" for r in _shown(result, mission))
            + "</div>")
        parts.extend(_segments_table(result, r, (rate_units or {}).get(mission))
                     for r in _shown(result, mission))
        parts.append("</section>")
    return "\n".join(parts)
