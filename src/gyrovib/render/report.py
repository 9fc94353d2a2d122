"""The trade-study report: one self-contained HTML page from a :class:`TradeStudy`.

Everything is inline: the stylesheet (with a print stylesheet, so a browser's
"Print to PDF" gives clean A4 pages) and the charts, hand-written SVG from
:mod:`gyrovib.render.svg` (why not matplotlib: see there). There is no
script and no external reference, so the page opens offline. Every piece of
catalogue text (ids, names, notes, file names) is HTML-escaped.

The term names come from the core's term tuples (:data:`ADDITIVE_TERMS`,
:data:`MULTIPLICATIVE_TERMS`) and the bound names from :data:`BOUNDED`, so
a new term shows up in the tables and charts without a change here.
"""

from __future__ import annotations

from collections.abc import Sequence
from html import escape
from typing import TYPE_CHECKING

import numpy as np

from gyrovib import units
from gyrovib.api.report.views import TradeStudy
from gyrovib.core.analysis import ADDITIVE_TERMS, EXTRA_TERMS, MULTIPLICATIVE_TERMS
from gyrovib.render.analysis_cells import cells_text, grouped_warnings
from gyrovib.render.analysis_table import worst_case_text
from gyrovib.render.bounds import shares_text
from gyrovib.render.common import fmt
from gyrovib.render.common import html_table as _table
from gyrovib.render.report_spectrum import spectrum_charts, spectrum_text
from gyrovib.render.select import (
    CELL_MARGIN,
    DISAGREE_MARK,
    assumption_note,
    cell_margin,
    limit_text,
    ranking_margin,
    unknown_label,
)
from gyrovib.render.svg import (
    SIZES,
    LineChart,
    Marker,
    Series,
    bar_chart,
    color,
    dash,
    share_chart,
)

if TYPE_CHECKING:
    from gyrovib.api.lots.yields import LotYields

PASS_FILL, FAIL_FILL, OPEN_FILL = "#2ca02c", "#d62728", "#7b5ea7"
#: Profile columns per pass/fail table: more are split into further tables.
MATRIX_PROFILES = 7
#: Words and matrix classes of each status (unverified: its own colour, never "✓ ∞").
STATUS_TEXT = {"pass": "✓ pass", "fail": "✗ fail", "unverified": "? unverified"}
FORM_TAGS = {"datasheet": "datasheet (spec form): worst case",
             "output coefficients": "from output coefficients (eq. 1)",
             "lot": "production lot: analysed at its mean"}
SUPERSCRIPT = {1: "", 2: "²", 3: "³", 4: "⁴", 5: "⁵"}

CSS = """
:root { --ink: #1a1a1a; --muted: #666; --line: #d0d0d0; --pass: #e3f4e1; --fail: #fbe3e1;
  --warn: #fff4d6; --open: #ebe4f7; }
* { box-sizing: border-box; }
body { font: 14px/1.45 system-ui, -apple-system, "Segoe UI", Roboto, sans-serif;
  color: var(--ink); margin: 0 auto; max-width: 1520px; padding: 24px; }
h1 { font-size: 24px; margin: 0 0 4px; } h2 { font-size: 19px; margin: 28px 0 8px;
  border-bottom: 2px solid var(--ink); padding-bottom: 3px; }
h3 { font-size: 16px; margin: 20px 0 6px; }
p.sub { color: var(--muted); margin: 0 0 12px; }
.verdict { display: inline-block; padding: 4px 10px; border-radius: 4px; font-weight: 600; }
.verdict.met { background: var(--pass); } .verdict.not { background: var(--fail); }
table { border-collapse: collapse; margin: 6px 0 12px; font-size: 13px; }
th, td { border: 1px solid var(--line); padding: 3px 7px; text-align: left;
  vertical-align: top; }
th { background: #f3f3f3; } td.num { text-align: right; font-variant-numeric: tabular-nums; }
td.pass { background: var(--pass); } td.fail { background: var(--fail); }
td.unverified { background: var(--open); }
td.warn { outline: 2px solid #e0a800; outline-offset: -2px; }
.small { font-size: 11px; color: var(--muted); } code, .hash { font-family: ui-monospace,
  "SFMono-Regular", Menlo, Consolas, monospace; font-size: 12px; }
.hash { word-break: break-all; }
.charts { display: grid; gap: 10px 18px;
  grid-template-columns: repeat(auto-fill, minmax(min(720px, 100%), 1fr)); }
figure { margin: 0; } figcaption { font-size: 12px; color: var(--muted); max-width: 720px; }
svg.chart { display: block; max-width: 100%; height: auto; font-family: inherit;
  background: #fff; }
svg .ct { font-weight: 600; } svg .tx { text-anchor: middle; } svg .ty { text-anchor: end; }
svg .xl, svg .yl { text-anchor: middle; } svg .ml { fill: #b00; }
svg .mr { fill: #b00; text-anchor: end; }
svg .frame { fill: none; stroke: #999; } svg .grid { stroke: #e8e8e8; }
svg .ref { stroke: #b00; stroke-width: 1.5; stroke-dasharray: 5 3; }
svg .tone { stroke: #555; stroke-width: 1.2; stroke-dasharray: 2 2; }
nav ol { columns: 3; font-size: 13px; margin: 4px 0; }
.notes { color: var(--muted); font-style: italic; }
.scroll { overflow-x: auto; }
table.matrix { font-size: 12px; } table.matrix th, table.matrix td { padding: 2px 4px; }
ul.warnings li { background: var(--warn); margin: 2px 0; padding: 2px 6px; list-style: none; }
@page { size: A4 landscape; margin: 10mm; }
@media print {
  body { max-width: none; padding: 0; font-size: 11px; }
  nav { display: none; }
  .scroll { overflow: visible; }
  * { -webkit-print-color-adjust: exact; print-color-adjust: exact; }
  h2 { break-after: avoid; } h3 { break-after: avoid; }
  figure, table, .profile-head { break-inside: avoid; }
  .charts { grid-template-columns: minmax(0, 720px); }
  table.matrix { font-size: 10px; width: 100%; table-layout: fixed; }
  table.matrix td, table.matrix th { overflow-wrap: anywhere; }
  section.profile { break-before: page; }
}
""" + "".join(f"svg .{k} {{ font-size: {v:g}px; }}\n" for k, v in SIZES.items())
# the chart text sizes are those svg.py places its text by, in the charts' own px:
# a chart is shown at its own width (never wider than the page), so as displayed


def _e(text: object) -> str:
    return escape(str(text), quote=True)


def term_names(linear: bool = False, locked: bool = False) -> list[str]:
    """Labels of the terms of eq. (16): the additive Δ0 terms, then Δ(q)·Ω^q.

    ``linear``: Δ0(6), the g² term of a linear vibration (docs/model.md section 8),
    follows the additive terms; ``locked``: then k3·M3 and k5·M5, the odd-moment
    terms of phase-locked harmonics (docs/model.md section 10).
    """
    powers = [int(q[1:]) if q[1:].isdigit() else k + 1
              for k, q in enumerate(MULTIPLICATIVE_TERMS)]
    additive = [*ADDITIVE_TERMS, *(t for t in EXTRA_TERMS
                                   if (t == "g2" and linear) or (t != "g2" and locked))]
    return [*additive, *(f"{q}·Ω{SUPERSCRIPT.get(p, f'^{p}')}"
                               for q, p in zip(MULTIPLICATIVE_TERMS, powers, strict=True))]


def term_squares(study: TradeStudy) -> np.ndarray:
    """Each term's square in eq. (16), shape (sensors, profiles, terms).

    Additive: Δ0² (with Δ0(6)² when some profile has a linear vibration, and
    (k3·M3)², (k5·M5)² when some profile has phase-locked harmonics, as
    :func:`term_names` with ``linear`` and ``locked``). Multiplicative:
    (Δ(q)·Ω_K3^q)². Their sum is Δ_V(RMS)².
    """
    a = study.analysis
    omega = np.asarray(a.rates)[:, 2]
    qs = np.asarray(a.error.multiplicative_coefficients)
    powers = np.arange(1, qs.shape[-1] + 1)
    multiplicative = qs * omega[None, :, None] ** powers[None, None, :]
    additive = np.asarray(a.error.additive_terms)
    extra = [k for k, t in enumerate(EXTRA_TERMS)
             if (t == "g2" and a.has_linear) or (t != "g2" and any(a.locked))]
    if extra:
        additive = np.concatenate([additive, np.asarray(a.error.extra_terms)[..., extra]],
                                  axis=-1)
    terms = np.concatenate([additive, multiplicative], axis=-1)
    out: np.ndarray = terms * terms
    return out


def _dominant(squares: np.ndarray, names: Sequence[str]) -> str:
    if np.isnan(squares).any():  # a term unknown (a g² figure not given or published)
        return "Δ_V unknown"
    total = float(np.sum(squares))
    if not total > 0:
        return "no error"
    k = int(np.argmax(squares))
    return f"{names[k]} {100 * squares[k] / total:.0f} %"


# ----------------------------------------------------------------- sections


def _inputs(study: TradeStudy) -> str:
    s = study.selection
    files = _table(["catalogue file", "SHA-256", "bytes"], (
        [f"<td><code>{_e(f.name)}</code></td>", f'<td class="hash">{_e(f.sha256)}</td>',
         f'<td class="num">{f.size}</td>'] for f in study.files), raw=True)
    rows = [
        ["budget Δ*_V", f"{fmt(s.budget)} {s.unit}"],
        ["output unit", s.unit],
        ["method", s.method],
        ["criterion", s.criterion],
        ["requirement", f"{s.require}: " + ("at least one sensor" if s.require == "any"
                                              else "every sensor") + " passes everywhere"],
        ["allocation (shares of Δ*)" + (
            "; in brackets: under a linear vibration, whose g² term takes α6 "
            "(docs/model.md section 8)" if s.has_linear else ""),
         shares_text(s.allocation, linear=s.has_linear)],
        *([["production lots", _yield_input(s.yields)]] if s.yields is not None else []),
        ["sensors × profiles", f"{len(s.sensors)} × {len(s.profiles)}"],
        ["gyrovib version", study.version],
        ["date", study.created],
    ]
    return files + _table(["input", "value"], rows)


def _yield_input(y: LotYields) -> str:
    how = ("exact" if y.method == "exact"
           else f"Monte Carlo, {y.draws} draws, seed {y.seed}, 95 % Wilson interval")
    return f"pass where the yield is at least {y.target:g} ({how}; docs/model.md section 14)"


def _sensor_cells(study: TradeStudy, i: int) -> list[str]:
    """The matrix row's first two cells: the sensor (with its form, unless given as
    coefficients) and its overall status."""
    overall = study.selection.sensor_status(i)
    form = study.sensor_forms[i]
    tag = f'<br><span class="small">{_e(FORM_TAGS.get(form, form))}</span>' if (
        form != "coefficients") else ""
    return [f"<td><b>{_e(study.selection.sensors[i])}</b>{tag}</td>",
            f'<td class="{overall}">{STATUS_TEXT[overall]}</td>']


def _unverified_cell(study: TradeStudy, i: int, j: int, klass: str,
                     notes: Sequence[str]) -> str:
    """An unverified cell: no margin, it hangs on figures not published (named)."""
    s = study.selection
    unknown = ", ".join(unknown_label(s, i, n) for n in s.unknown.get((i, j), ()))
    return (f'<td class="{klass}"{_tip(notes)}>? unverified<br>'
            f'<span class="small">{_e(unknown)} unknown</span></td>')


def _cell_value(study: TradeStudy, i: int, j: int) -> str:
    """The number a decided cell shows: a lot's yield, else the deciding margin."""
    s = study.selection
    if s.yields is not None and s.yields.is_lot(i):
        return f"yield {fmt(float(s.yields.value[i, j]), 4)}"
    return fmt(cell_margin(s, i, j), 3)


def _decided_cell(study: TradeStudy, i: int, j: int, klass: str, notes: Sequence[str],
                  dominant: str) -> str:
    """A pass or fail cell: the mark, the value, the tests that disagree, the dominant
    term, the uncertainty and whether the sensor saturates."""
    s = study.selection
    mark = " ⚠" if notes else ""
    saturates = ('<br><span class="small"><b>saturates</b></span>'
                 if s.saturated is not None and s.saturated[i, j] else "")
    other = s.disagrees.get((i, j))
    disagree = (f' <span class="small">{DISAGREE_MARK}{_e(",".join(other))}</span>'
                if other else "")
    return (f'<td class="num {klass}"{_tip(notes)}>{"✓" if s.passed[i, j] else "✗"} '
            f'{_e(_cell_value(study, i, j))}{disagree}'
            f'{mark}<br><span class="small">{_e(dominant)}</span>'
            f'{_uncertainty(study, i, j)}{saturates}</td>')


def _matrix_cell(study: TradeStudy, i: int, j: int, squares: np.ndarray,
                 names: Sequence[str]) -> str:
    """The cell of sensor ``i`` under profile ``j``."""
    notes = study.analysis.warnings.get((i, j), ())
    status = study.selection.status(i, j)
    klass = status + (" warn" if notes else "")
    if status == "unverified":
        return _unverified_cell(study, i, j, klass, notes)
    return _decided_cell(study, i, j, klass, notes, _dominant(squares[i, j], names))


def _split_matrix(head: list[str], rows: list[list[str]], n_profiles: int) -> str:
    """The matrix as tables of at most MATRIX_PROFILES profile columns, the sensor
    columns repeated in each."""
    # many profiles: a compact table that scrolls rather than widening the page
    # at most MATRIX_PROFILES profile columns per table, so that each fits a printed
    # A4 landscape page: more profiles make more tables, the sensor columns repeated
    tables = []
    for start in range(0, max(n_profiles, 1), MATRIX_PROFILES):
        stop = min(start + MATRIX_PROFILES, n_profiles)
        part_head = [*head[:2], *head[2 + start:2 + stop]]
        part_rows = [[*row[:2], *row[2 + start:2 + stop]] for row in rows]
        table = _table(part_head, part_rows, raw=True).replace(
            "<table>", '<table class="matrix">', 1)
        tables.append(f'<div class="scroll">{table}</div>')
    return "".join(tables)


def _matrix(study: TradeStudy, squares: np.ndarray, names: Sequence[str]) -> str:
    """The pass/fail matrix: a row per sensor, a column per profile."""
    s = study.selection
    rows = [[*_sensor_cells(study, i),
             *(_matrix_cell(study, i, j, squares, names) for j in range(len(s.profiles)))]
            for i in range(len(s.sensors))]
    return _split_matrix(["sensor", "overall", *s.profiles], rows, len(s.profiles))


def _tip(notes: Sequence[str]) -> str:
    return f' title="{_e(" ".join(notes))}"' if notes else ""


def _uncertainty(study: TradeStudy, i: int, j: int) -> str:
    """``Δ_V = m ± u`` (docs/model.md section 14) under a cell, for a sensor with uncertainty
    or a lot (then the spread over the lot, at its mean)."""
    a = study.analysis
    if (a.uncertainty is None or not np.isfinite(a.uncertainty[i, j])
            or not np.isfinite(a.error.total[i, j])):  # no number to give it to
        return ""
    what = "lot mean Δ_V" if a.is_lot(i) else "Δ_V"
    return (f'<br><span class="small">{what} = {_e(fmt(a.error.total[i, j]))} ± '
            f'{_e(fmt(a.uncertainty[i, j], 2))}</span>')


def _ranking(study: TradeStudy) -> str:
    s = study.selection
    passing = [i for i in s.ranking if s.sensor_pass[i]]
    if not passing:
        return "<p>No sensor passes under every profile.</p>"
    rows = []
    for rank, i in enumerate(passing, 1):
        j = int(np.argmin(s.margin[i])) if len(s.profiles) else 0
        name = study.sensor_names[i] or ""
        rows.append([str(rank), s.sensors[i], name, study.sensor_forms[i],
                     fmt(s.worst_margin[i], 3),
                     s.profiles[j] if len(s.profiles) else "",
                     f"{fmt(s.rms[i, j])} {s.unit}" if len(s.profiles) else ""])
    return _table(["rank", "sensor", "name", "given as", f"worst margin {ranking_margin(s)}",
                   "under profile", "Δ_V(RMS) there"], rows)


def _failing(study: TradeStudy) -> str:
    s = study.selection
    failing = [i for i in range(len(s.sensors)) if s.sensor_status(i) == "fail"]
    if not failing:
        return "<p>No sensor fails on its published figures.</p>"
    rows = [[s.sensors[i], limit_text(s, i),
             str(sum(1 for j in range(len(s.profiles)) if not s.passed[i, j]))]
            for i in failing]
    return _table(["sensor", "what limits it (largest value/bound ratio)",
                   "profiles failed"], rows)


def _questions(study: TradeStudy) -> str:
    """Unverified sensors: the figures their vendor should be asked for."""
    s = study.selection
    note = assumption_note(s)
    open_ = [i for i in s.ranking if s.sensor_status(i) == "unverified"]
    if not open_:
        return f"<p>{_e(note)}</p>" if note else ""
    items = "".join(
        f"<li><b>{_e(s.sensors[i])}</b><ul>"
        + "".join(f"<li>{_e(q)}</li>" for q in s.questions.get(i, ()))
        + "</ul></li>" for i in open_)
    return ("<h2>Unverified sensors: questions for the vendor</h2>"
            "<p>These pass on their published figures, but their datasheets leave out a "
            "figure (or their catalogue entry gives no g² sensitivity) that can decide the "
            "verdict under a chosen profile (unknown, not zero; "
            "docs/model.md section 11). Each line is a figure to ask for, with the largest value "
            f'that would still pass.</p><ul class="questions">{items}</ul>')


def _warnings(study: TradeStudy) -> str:
    a = study.analysis
    if not a.warnings:
        return ""

    items = "".join(f"<li>{_e(message)} <b>({_e(cells_text(a, cells))})</b></li>"
                    for message, cells in grouped_warnings(a))
    return ("<h3>Warnings</h3><p>Marked ⚠ in the matrix: a note below applies to that cell "
            "(the sensor saturates, so the static model does not hold there, or an "
            f"assumption was made for a datasheet sensor).</p><ul class=\"warnings\">{items}</ul>")


# ----------------------------------------------------------------- charts


def _fill(status: str) -> str:
    return {"pass": PASS_FILL, "fail": FAIL_FILL}.get(status, OPEN_FILL)


def margins_chart(study: TradeStudy, j: int) -> str:
    s = study.selection
    fills = [_fill(s.status(i, j)) for i in range(len(s.sensors))]
    if s.criterion == "worst" and s.total is not None:  # what the verdict compares
        return bar_chart(f"|Δ_V| against the budget: {s.profiles[j]}",
                         f"|Δ_V| ({s.unit}, log; a datasheet part: its worst case)",
                         s.sensors, [float(v) for v in s.total[:, j]], fills,
                         Marker(f"Δ* = {fmt(s.budget, 3)}", x=float(s.budget)))
    return bar_chart(f"Δ_V(RMS) against the budget: {s.profiles[j]}",
                     f"Δ_V(RMS) ({s.unit}, log)",
                     s.sensors, [float(v) for v in s.rms[:, j]], fills,
                     Marker(f"Δ* = {fmt(s.budget, 3)}", x=float(s.budget)))


#: The colours of the bar charts, said under them.
BAR_KEY = ("Green: passes the criterion, red: fails, purple: unverified (passes on its "
           "published figures only).")
WORST_KEY = ("Green: passes under every profile, red: fails under one, purple: unverified "
             "(passes on its published figures only).")


def worst_margin_chart(study: TradeStudy) -> str:
    s = study.selection
    fills = [_fill(s.sensor_status(i)) for i in range(len(s.sensors))]
    return bar_chart("Worst margin over the profiles, per sensor",
                     f"margin {ranking_margin(s)} (log)",
                     s.sensors, [float(v) for v in s.worst_margin], fills,
                     Marker("margin 1", x=1.0))


def breakdown_chart(study: TradeStudy, j: int, squares: np.ndarray, names: Sequence[str]) -> str:
    a = study.analysis
    return share_chart(f"Error by term (eq. 16): {a.profiles[j]}", a.sensors, names,
                       [[float(v) for v in squares[i, j]] for i in range(len(a.sensors))])


def sweep_chart(study: TradeStudy, j: int) -> str:
    sw, s = study.sweep, study.selection
    method = s.method if s.method in ("exact", "paper") else "exact"
    err = getattr(sw, method)
    rates = [float(r) for r in sw.rates]
    series = [Series(name, rates, [float(v) for v in err.rms[i, j]], color(i), dash(i))
              for i, name in enumerate(sw.sensors)]
    omega = float(s.rates[j, 2])
    note = " (not covered by the paper's formulas)" if (
        method == "paper" and sw.profiles[j] in sw.paper_refused) else ""
    return LineChart(
        f"Δ_V(RMS) over the rate envelope, {method}: {sw.profiles[j]}{note}",
        f"Ω_K3 ({sw.unit})", f"Δ_V(RMS) ({sw.unit})", series, ylog=True,
        markers=(Marker(f"Δ* = {fmt(s.budget, 3)}", y=float(s.budget)),
                 Marker(f"profile Ω_K3 = {fmt(omega, 3)}", x=omega, style="tone")),
    ).svg()


def _figure(svg: str, caption: str = "") -> str:
    tail = f"<figcaption>{_e(caption)}</figcaption>" if caption else ""
    return f"<figure>{svg}{tail}</figure>"


def _profile_section(study: TradeStudy, j: int, squares: np.ndarray,
                     names: Sequence[str]) -> str:
    s = study.selection
    spectrum = study.spectra[j]
    rate_unit = study.rate_unit or s.unit  # the vehicle in its own unit, errors in Δ*'s

    to_rate = units.scale(s.unit) / units.scale(rate_unit)
    rate = ", ".join(fmt(float(v) * to_rate, 4) for v in s.rates[j])
    title = spectrum.profile + (f" — {spectrum.name}" if spectrum.name else "")
    notes = f'<p class="notes">{_e(spectrum.notes)}</p>' if spectrum.notes else ""

    why = [w for w in (worst_case_text(study.analysis, i, j)
                       for i in range(len(study.analysis.sensors))) if w]
    if why:  # the datasheet parts' worst cases, explained
        notes += ('<ul class="small worst">' + "".join(f"<li>{_e(w)}</li>" for w in why)
                  + "</ul>")
    figures = [
        _figure(margins_chart(study, j), BAR_KEY),
        _figure(breakdown_chart(study, j, squares, names),
                "Which coefficient dominates: each term's share of Δ_V(RMS)²."),
        _figure(sweep_chart(study, j), "Ω_K1, Ω_K2 stay the profile's; the dotted line marks "
                                       "the profile's own Ω_K3."),
        *(_figure(c) for c in spectrum_charts(spectrum, rate_unit)),
    ]
    return (f'<section class="profile" id="p{j}"><div class="profile-head">'
            f"<h3>{_e(title)}</h3>{notes}"
            f'<p class="sub">Ω_K = ({_e(rate)}) {_e(rate_unit)}; '
            f"{_e(spectrum_text(spectrum, rate_unit))}</p></div>"
            f"<div class=\"charts\">{''.join(figures)}</div></section>")


def to_html(study: TradeStudy, recording: str = "") -> str:
    """The whole report as one HTML document (UTF-8 text); ``recording``: the HTML of
    ``report --recording`` (:func:`gyrovib.render.recording.report_section`), placed
    before the profiles."""
    s = study.selection
    names = term_names(study.analysis.has_linear, any(study.analysis.locked))
    squares = term_squares(study)
    met = s.requirement_met
    n_pass = int(np.sum(s.sensor_pass))
    n_open = sum(1 for i in range(len(s.sensors)) if s.sensor_status(i) == "unverified")
    verdict = (f'<span class="verdict {"met" if met else "not"}">Requirement '
               f'{"met" if met else "NOT met"}</span> {n_pass} of {len(s.sensors)} sensor(s) '
               f"pass under every profile"
               + (f", {n_open} unverified (see the questions for the vendor)" if n_open
                  else "") + ".")
    toc = "".join(f'<li><a href="#p{j}">{_e(p)}</a></li>' for j, p in enumerate(s.profiles))
    title = f"gyrovib trade study: Δ* = {fmt(s.budget)} {s.unit}"
    body = [
        f"<header><h1>{_e(title)}</h1>",
        f'<p class="sub">{len(s.sensors)} sensor(s) × {len(s.profiles)} profile(s), method '
        f"{_e(s.method)}, criterion {_e(s.criterion)}; gyrovib {_e(study.version)}, "
        f"{_e(study.created)}</p><p>{verdict}</p></header>",
        f'<nav><b>Profiles</b><ol>{toc}</ol></nav>',
        "<h2>Inputs</h2>", _inputs(study),
        "<h2>Pass/fail matrix</h2>",
        f"<p>Each cell: ✓ pass / ✗ fail under the criterion, the margin of the test that "
        f"decides it, {_e(CELL_MARGIN[s.criterion])} (above 1: within), "
        f"{DISAGREE_MARK} and the names of the other tests (rms: Δ_V(RMS) ≤ Δ*; worst: "
        "|Δ_V| ≤ Δ*; bounds: every coefficient or datasheet figure within its bound) that "
        "would decide it otherwise, and the term that dominates Δ_V(RMS)²; "
        "? unverified: passes on its published figures, but a figure its datasheet does "
        "not publish (named; g²: a coefficient-form sensor's g² sensitivity, not given) "
        "can change the verdict.</p>",
        _matrix(study, squares, names),
        f'<div class="charts">{_figure(worst_margin_chart(study), WORST_KEY)}</div>',
        _warnings(study),
        "<h2>Passing sensors, ranked</h2>", _ranking(study),
        "<h2>Failing sensors: what limits them</h2>", _failing(study),
        _questions(study),
        recording,
        "<h2>Profiles</h2>",
        *(_profile_section(study, j, squares, names) for j in range(len(s.profiles))),
    ]
    return ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            '<meta name="viewport" content="width=device-width, initial-scale=1">'
            f"<title>{_e(title)}</title><style>{CSS}</style></head><body>\n"
            + "\n".join(body) + "\n</body></html>\n")
