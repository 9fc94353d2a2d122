"""Renderers of recordings (docs/model.md section 13): the honesty table of a fit, and
``analyze --recording`` as table, JSON, CSV and markdown (keys: docs/output.md)."""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from html import escape
from typing import TYPE_CHECKING, Any

import numpy as np

from gyrovib import units
from gyrovib.render.common import dumps, header, html_table
from gyrovib.render.formats import Cell, cell_texts, csv_of, json_of, markdown_of
from gyrovib.render.svg import LineChart, Marker, Series, color

if TYPE_CHECKING:
    from gyrovib.api.recordings.analysis import RecordingAnalysis
    from gyrovib.api.recordings.results import AxisHonesty, RecordingFit
    from gyrovib.records import Column

AXES = ("X", "Y", "Z")


def _num(v: float) -> float | None:
    return float(v) if math.isfinite(v) else None


def _fmt(v: float, digits: int = 4) -> str:
    return "—" if not math.isfinite(v) else f"{v:.{digits}g}"


def _known(v: float) -> str:
    """An error that can be unknown (an axis not recorded): '?' then, never 0 or a dash."""
    return "?" if not math.isfinite(v) else f"{v:.4g}"


def _percent(v: float) -> str:
    return "—" if not math.isfinite(v) else f"{100 * v:.1f} %"


def _decibels(v: float) -> str:
    return "—" if math.isnan(v) else f"{v:.2f}"


def shape_text(h: AxisHonesty) -> str:
    """An axis's shape figures in words: "shape 0.42 dB, 1.2 % of power off > 3 dB"."""
    if math.isnan(h.shape_db):
        return "no random part fitted"
    return f"shape {_decibels(h.shape_db)} dB, {_percent(h.off_3db)} of power off > 3 dB"


def recording_info(fit: RecordingFit, scale: float = 1.0) -> dict[str, Any]:
    """The ``"recording"`` object of the JSON; variances in (output unit)²."""
    return {
        "file": os.path.basename(fit.file), "topic": fit.topic, "instance": fit.instance,
        "sha256": fit.sha256, "samples": fit.samples,
        "fs": fit.fs, "crossover": fit.crossover, "segments": fit.segments,
        "duration": fit.duration,
        "axes": {a: {"variance": _num(h.variance / scale**2), "held": _num(h.held),
                     "skewness": _num(h.skewness), "excess_kurtosis": _num(h.excess_kurtosis),
                     "shape_db": _num(h.shape_db), "off_3db": _num(h.off_3db)}
                 for a, h in zip(AXES, fit.honesty, strict=True)},
    }


def _named(fit: RecordingFit) -> str:
    """The file's name, and the topic and instance read from a log: ``a.ulg
    (sensor_gyro_fifo instance 1)``."""
    base = os.path.basename(fit.file)
    return base if fit.source is None else f"{base} ({fit.source})"


def rate_text(fit: RecordingFit) -> str:
    """The fit's mean rate Ω_K, deg/s, as the tables write it: '?' about an axis the
    recording did not record (unknown, never 0)."""
    return ", ".join(f"{v:.4g}" if on else "?"
                     for v, on in zip(fit.rate, fit.rate_axes, strict=True))


#: The line under a table with an axis not recorded.
NOT_RECORDED_NOTE = "?: an axis the recording did not record: unknown, never 0"


def _honesty_cells(h: AxisHonesty, recorded: bool) -> tuple[str, ...]:
    """An axis's honesty figures as the tables write them; '?' throughout for an axis the
    recording did not record."""
    if not recorded:
        return ("?",) * 6
    return (_fmt(h.variance), _percent(h.held), _fmt(h.skewness, 3),
            _fmt(h.excess_kurtosis, 3), _decibels(h.shape_db), _percent(h.off_3db))


def honesty_table(fit: RecordingFit) -> str:
    """The honesty of the fit (docs/model.md section 13), one row per axis, as plain text;
    an axis not recorded is '?' throughout ('—': a figure that does not apply, as the
    shape of a random part that was not fitted)."""
    lines = [f"recording {_named(fit)}: {fit.samples} samples, "
             f"fs {fit.fs:.6g} Hz, f_c {fit.crossover:g} Hz, {fit.segments} segment(s), "
             f"{fit.duration:.6g} s analysed",
             f"{'axis':<5} {'variance (deg/s)²':>18} {'held':>8} {'skewness':>9} "
             f"{'excess kurtosis':>16} {'shape dB':>9} {'off 3 dB':>9}"]
    for axis, h, on in zip(AXES, fit.honesty, fit.rate_axes, strict=True):
        cells = _honesty_cells(h, on)
        lines.append(f"{axis:<5} {cells[0]:>18} {cells[1]:>8} {cells[2]:>9} {cells[3]:>16} "
                     f"{cells[4]:>9} {cells[5]:>9}")
    tones = len(fit.angular.tones) + sum(len(h.orders) for h in fit.angular.harmonics)
    lines.append(f"fitted: {len(fit.angular.tones)} tone(s), {len(fit.angular.harmonics)} "
                 f"harmonic group(s) ({tones} lines in all), carrier {len(fit.mission_rates)} "
                 f"histogram bin(s), mean rate Ω_K = [{rate_text(fit)}] deg/s")
    if not all(fit.rate_axes):
        lines.append(NOT_RECORDED_NOTE)
    lines += [f"warning: {w}" for w in fit.warnings]
    return "\n".join(lines) + "\n"


def rows_json(result: RecordingAnalysis) -> list[dict[str, Any]]:
    """The JSON's ``results``: one object per sensor, the result's records."""
    return json_of(result.records(), range(len(result.sensors)))


def to_json(result: RecordingAnalysis) -> str:
    """``analyze --recording --format json``."""

    document = header("recording", result.unit)
    document["results"] = rows_json(result)
    document["recording"] = recording_info(result.fit, units.scale(result.unit))
    document["warnings"] = list(result.fit.warnings)
    return dumps(document)


def to_csv(result: RecordingAnalysis) -> str:
    """``analyze --recording --format csv``: one row per sensor, the result's records (the
    DataFrame's columns)."""
    return csv_of(result.records(), range(len(result.sensors)))


def table_cells(result: RecordingAnalysis) -> tuple[Cell[int], ...]:
    """The columns of the table (plain text, Markdown, HTML alike): one row per sensor
    (its index), the records (:meth:`RecordingAnalysis.records`) they show."""
    def ratio(i: int) -> str:  # '?' where either side is unknown ('—': one of them is 0)
        unknown = math.isnan(result.recorded[i]) or math.isnan(result.fitted[i])
        return "?" if unknown else _fmt(result.ratio[i], 3)

    return (Cell("sensor", of="sensor"),
            Cell("Δ_V,rec", lambda i: _known(result.recorded[i]), of="recorded"),
            Cell("fitted Δ̄_V", lambda i: _known(result.fitted[i]), of="fitted"),
            Cell("ratio", ratio, of="ratio"),
            Cell("peak |ω3|", lambda i: _fmt(result.peak_rate[i]), of="peak_rate"),
            Cell("saturated", lambda i: "yes" if result.saturated[i] else "no",
                 of="saturated"))


def plain_table(cells: Sequence[Cell[int]], rows: Sequence[int],
                records: Sequence[Column[int]] = (), left: Sequence[int] = (0,)) -> list[str]:
    """A plain-text table of ``cells``: the heading, a rule, one line per row; the
    columns ``left`` aligned left, the others right."""
    lines = [[c.title for c in cells], *cell_texts(cells, rows, records)]
    widths = [max(len(line[k]) for line in lines) for k in range(len(cells))]
    out = ["  ".join(c.ljust(widths[k]) if k in left else c.rjust(widths[k])
                     for k, c in enumerate(line)).rstrip() for line in lines]
    return [out[0], "  ".join("-" * w for w in widths), *out[1:]]


def to_table(result: RecordingAnalysis, width: int | None = None, color: bool = False,
             ascii: bool = False) -> str:
    """``analyze --recording`` as a plain-text table, the honesty table after it (plain
    text whatever the terminal: ``width``, ``color`` and ``ascii`` are the other tables'
    keywords, not used)."""
    out = [f"recorded error Δ_V,rec and the fitted mission's closed form, {result.unit}",
           *plain_table(table_cells(result), range(len(result.sensors)), result.records())]
    for i, messages in sorted(result.warnings.items()):
        out += [f"warning: {result.sensors[i]}: {m}" for m in messages]
    return "\n".join(out) + "\n\n" + honesty_table(result.fit)


def to_markdown(result: RecordingAnalysis) -> str:
    """``analyze --recording --format markdown``."""
    out = [f"Recorded error Δ_V,rec and the fitted mission's closed form ({result.unit}), "
           f"recording `{_named(result.fit)}`", "",
           markdown_of(table_cells(result), range(len(result.sensors)),
                       result.records())[:-1]]
    for i, messages in sorted(result.warnings.items()):
        out += ["", *[f"> **warning** `{result.sensors[i]}`: {m}" for m in messages]]
    return "\n".join(out) + "\n"


def plot_fit(fit: RecordingFit, path: str) -> None:
    """Measured PSD against the fitted breakpoints and tones, one panel per axis (PNG)."""
    # lazy: matplotlib is optional, for --plot only
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    part = fit.angular
    fig, axes = plt.subplots(3, 1, figsize=(8, 9), sharex=True)
    f = part.frequencies
    for j, ax in enumerate(axes):
        ax.set_title(f"axis {AXES[j]}: {shape_text(fit.honesty[j])}", fontsize=9)
        if not fit.rate_axes[j]:
            ax.text(0.5, 0.5, "not recorded", transform=ax.transAxes, ha="center")
            continue
        ok = f > 0
        ax.loglog(f[ok], np.maximum(part.measured[j, ok], 1e-30), lw=0.6, color="0.5",
                  label="measured PSD (Welch)")
        table = part.psd[j]
        if table is not None:
            # the fit as the profile means it: straight lines on log-log axes between breakpoints
            ax.loglog(table[0], table[1], "o-", color="C0", ms=3, label="fitted breakpoints")
        df = float(f[1] - f[0])
        lines = [(t.frequency, t.amplitude[j]) for t in part.tones]
        lines += [(h.fundamental * o, a[j]) for h in part.harmonics
                  for o, a in zip(h.orders, h.amplitude, strict=True)]
        for k, (freq, amp) in enumerate(lines):
            # a tone of amplitude a as the PSD level that holds its power a²/2 in one bin
            ax.plot([freq, freq], [1e-30, max(amp**2 / 2 / df, 1e-30)], color="C3",
                    label="fitted tones (a²/2 per bin)" if k == 0 else None)
        ax.set_ylim(bottom=max(1e-12, float(np.min(part.measured[j, ok][
            part.measured[j, ok] > 0], initial=1e-12)) / 10))
        ax.set_ylabel("(deg/s)²/Hz")
        ax.legend(fontsize=7, loc="lower left")
    axes[-1].set_xlabel("frequency, Hz")
    worst = max((h.shape_db for h in fit.honesty if not math.isnan(h.shape_db)), default=None)
    shape = "" if worst is None else f", worst shape {worst:.2f} dB"
    fig.suptitle(f"{_named(fit)}: measured and fitted (f_c {fit.crossover:g} Hz"
                 f"{shape})")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def _thin(f: Any, s: Any, points: int = 400) -> tuple[list[float], list[float]]:
    """At most ``points`` log-spaced bins of a PSD (f > 0), for a chart."""

    ok = np.flatnonzero((f > 0) & (s > 0))
    if ok.size <= points:
        return f[ok].tolist(), s[ok].tolist()
    idx = np.unique(np.geomspace(1, ok.size, points).astype(int) - 1)
    return f[ok[idx]].tolist(), s[ok[idx]].tolist()


def report_section(result: RecordingAnalysis) -> str:
    """The recording's part of ``gyrovib report --recording`` (HTML): its PSD against the
    fitted profile per axis, the honesty table, and Δ_V,rec beside the closed form."""

    fit = result.fit
    part = fit.angular
    charts = []
    for j, axis in enumerate(AXES):
        if not fit.rate_axes[j]:
            continue
        fx, sx = _thin(part.frequencies, part.measured[j])
        series = [Series(f"measured {axis}", fx, sx, color(0))]
        table = part.psd[j]
        if table is not None:
            series.append(Series("fitted breakpoints", table[0].tolist(), table[1].tolist(),
                                 color(1)))
        lines = [(t.frequency, t.amplitude[j]) for t in part.tones]
        lines += [(h.fundamental * o, a[j]) for h in part.harmonics
                  for o, a in zip(h.orders, h.amplitude, strict=True)]
        markers = [Marker(f"{freq:.4g} Hz, a = {amp:.3g}", x=freq, style="tone", row=k % 3)
                   for k, (freq, amp) in enumerate(lines)]
        charts.append(LineChart(f"Recording {escape(os.path.basename(fit.file))}: axis {axis}",
                                "frequency (Hz)", "PSD (deg/s)²/Hz", series, xlog=True,
                                ylog=True, markers=markers).svg())
    head = ["axis", "variance (deg/s)²", "held", "skewness", "excess kurtosis", "shape dB",
            "off 3 dB"]
    rows = [[a, *_honesty_cells(h, on)]
            for a, h, on in zip(AXES, fit.honesty, fit.rate_axes, strict=True)]
    honesty = html_table(head, rows)
    cells = table_cells(result)
    compare = html_table([c.title for c in cells],
                          list(cell_texts(cells, range(len(result.sensors)),
                                           result.records())))
    notes = "".join(f"<li>{escape(result.sensors[i])}: {escape(m)}</li>"
                    for i, ms in sorted(result.warnings.items()) for m in ms)
    notes += "".join(f"<li>{escape(w)}</li>" for w in fit.warnings)
    figures = "".join(f"<figure>{c}</figure>" for c in charts)
    return (
        '<section class="recording" id="recording"><h2>Recording</h2>'
        f"<p class=\"sub\">{escape(_named(fit))}, SHA-256 "
        f"<code>{fit.sha256}</code>: {fit.samples} samples at {fit.fs:.6g} Hz, crossover "
        f"f_c = {fit.crossover:g} Hz, {fit.segments} segment(s), {fit.duration:.6g} s "
        f"analysed. Its fitted profile <code>{escape(fit.profile_id)}</code> is among the "
        "profiles below.</p>"
        f"<h3>Recorded error Δ_V,rec and the fitted mission's closed form ({result.unit})</h3>"
        f"{compare}<p>Δ_V,rec is eq. (2) averaged over the recorded samples (docs/model.md section "
        "13); the ratio fitted/recorded outside [0.8, 1.25] means the recording is not "
        "Gaussian-plus-tones or not stationary, and Δ_V,rec is the number to trust.</p>"
        f"<h3>Honesty of the fit</h3>{honesty}"
        + (f"<ul class=\"warnings\">{notes}</ul>" if notes else "")
        + f'<div class="charts">{figures}</div></section>')
