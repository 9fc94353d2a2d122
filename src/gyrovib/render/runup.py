"""Renderers of ``gyrovib runup`` (docs/model.md section 16): a table per step and the
estimates, JSON (keys: docs/output.md), CSV, Markdown and the plot.

An unknown figure is '?' in tables, null in JSON and empty in CSV.
"""

from __future__ import annotations

import math
import os
from typing import TYPE_CHECKING, Any

from rich.text import Text

from gyrovib.api.runup.results import ESTIMATE_RECORDS, STEP_RECORDS
from gyrovib.render.common import dumps, fmt, header, number, png, pyplot, rich_text
from gyrovib.render.formats import Cell, csv_of, json_of, markdown_of, table_of

if TYPE_CHECKING:
    from gyrovib.api.runup import Estimate, RunupResult, Step

UNIT = "deg/s"


def _c(value: float, digits: int = 4) -> str:
    """A table cell: '?' for an unknown figure."""
    return fmt(value, digits) if math.isfinite(value) else "?"


def _estimate_json(e: Estimate) -> dict[str, Any]:
    return {"value": number(e.value), "uncertainty": number(e.uncertainty), "unit": e.unit,
            "identifiable": e.identifiable, "status": e.status, "separate": e.separate,
            "catalogue": number(e.catalogue), "catalogue_bound": e.catalogue_bound,
            "ratio": number(e.ratio), "vif": number(e.vif)}


def to_json(result: RunupResult) -> str:
    """``steps``, ``estimates`` (by name), ``drift``, ``chi2`` and the recording."""
    doc = header("runup", UNIT)
    doc |= {
        "recording": {"file": os.path.basename(result.file), "topic": result.topic,
                      "instance": result.instance, "sha256": result.sha256,
                      "samples": result.samples, "fs": result.fs,
                      "crossover": result.crossover, "steps_given": result.steps_given},
        "sensor": result.sensor,
        "steps": json_of(STEP_RECORDS, result.steps),
        "estimates": {e.name: _estimate_json(e) for e in result.estimates},
        "drift": {"value": number(result.drift), "uncertainty": number(result.drift_uncertainty),
                  "unit": "deg/s/s", "estimated": math.isfinite(result.drift),
                  "vif": number(result.drift_vif)},
        "chi2": {"value": number(result.chi2), "dof": result.dof,
                 "reduced": number(result.reduced_chi2), "inflation": number(result.inflation)},
        "constant": number(result.constant),
        "requirement_met": result.requirement_met,
        "limits": list(result.limits),
        "notes": list(result.notes),
    }
    return dumps(doc)


def to_csv(result: RunupResult) -> str:
    """The steps (one row each), a blank line, then the estimates (one row each): the
    records :data:`~gyrovib.api.runup.results.STEP_RECORDS` and
    :data:`~gyrovib.api.runup.results.ESTIMATE_RECORDS` declare."""
    return (csv_of(STEP_RECORDS, result.steps, title_flags=True) + "\n"
            + csv_of(ESTIMATE_RECORDS, result.estimates, title_flags=True))


def _flags(s: Step) -> str:
    return ", ".join(w for w, on in (("baseline", s.baseline), ("> 3σ", s.outlier),
                                      ("moved", s.moved)) if on)


def _predicted(s: Step) -> str:
    return "" if s.status is None else ("≤ " if s.bound else "") + _c(s.predicted, 3)


def _step_table(result: RunupResult) -> tuple[Cell[Step], ...]:
    """The steps' table (Markdown and terminal): without a sensor, no prediction and no
    verdict."""
    compared = result.sensor is not None
    return tuple(c for c in (
        Cell("step", lambda s: str(s.index), "right", of="step"),
        Cell("time, s", lambda s: f"{s.start:.6g}–{s.end:.6g}"),
        Cell("T, s", lambda s: _c(s.duration, 4), "right", of="duration"),
        Cell("x3 rms, deg/s", lambda s: _c(s.x3_rms, 3), "right", of="x3_rms"),
        Cell("a rms, g", lambda s: _c(s.accel_rms, 3), "right", of="accel_rms"),
        Cell("shift ± u, deg/s", lambda s: f"{_c(s.shift, 3)} ± {_c(s.uncertainty, 2)}",
             "right", of="shift"),
        Cell("fit, deg/s", lambda s: _c(s.fitted, 3), "right", of="fitted"),
        Cell("predicted, deg/s", _predicted, "right", of="predicted") if compared else None,
        Cell("residual, deg/s", lambda s: _c(s.residual, 2), "right", of="residual"),
        Cell("verdict", lambda s: s.status or "", of="status") if compared else None,
        Cell("flags", _flags)) if c is not None)


def _catalogue(e: Estimate) -> str:
    if not math.isfinite(e.catalogue):
        return "?"
    return ("≤ " if e.catalogue_bound else "") + _c(e.catalogue, 3)


def _estimate_table(result: RunupResult) -> tuple[Cell[Estimate], ...]:
    """The estimates' table: the catalogue's figure only with a sensor, what would
    separate a term only when one is not identifiable."""
    compared = result.sensor is not None
    separate = any(e.separate for e in result.estimates)
    return tuple(c for c in (
        Cell("term", lambda e: e.name, of="name"),
        Cell("in-situ ± u", lambda e: f"{_c(e.value, 3)} ± {_c(e.uncertainty, 2)}", "right",
             of="value"),
        Cell("unit", lambda e: e.unit, of="unit"),
        Cell("status", lambda e: e.status, of="status"),
        Cell("catalogue", _catalogue, "right", of="catalogue") if compared else None,
        Cell("ratio", lambda e: _c(e.ratio, 3) if math.isfinite(e.ratio) else "", "right",
             of="ratio") if compared else None,
        Cell("what would separate it", lambda e: e.separate or "", of="separate")
        if separate else None) if c is not None)


def _summary(result: RunupResult) -> str:
    drift = ("not estimated (the steps' order does not separate it)"
             if not math.isfinite(result.drift)
             else f"{fmt(result.drift, 3)} ± {fmt(result.drift_uncertainty, 2)} deg/s/s")
    chi = (f"χ² = {fmt(result.chi2, 3)} on {result.dof} degrees of freedom"
           + (f" (uncertainties × {math.sqrt(result.inflation):.3g})"
              if result.inflation > 1 else ""))
    source = "given" if result.steps_given else "found from the running variance"
    read = "" if result.source is None else f" ({result.source})"
    return (f"recording {os.path.basename(result.file)}{read}: {result.samples} samples at "
            f"{result.fs:.6g} Hz, {len(result.steps)} steps ({source}), crossover "
            f"{result.crossover:g} Hz; drift {drift}; {chi}"
            + (f"; compared with sensor {result.sensor}" if result.sensor else ""))


def _verdict(result: RunupResult) -> str:
    if result.sensor is None:
        return ""
    outside = [s.index for s in result.steps if s.status == "outside"]
    unknown = [s.index for s in result.steps if s.status == "unverified"]
    if outside:
        return (f"verdict: step(s) {', '.join(map(str, outside))} outside the prediction of "
                f"{result.sensor} (measured shift more than 2 u from it)")
    if unknown:
        return (f"verdict: unverified — the prediction of {result.sensor} is unknown on "
                f"step(s) {', '.join(map(str, unknown))} (a figure it needs is not published)")
    return f"verdict: every step within the prediction of {result.sensor}"


def to_table(result: RunupResult, width: int | None = None, color: bool = False,
             ascii: bool = False) -> str:
    """The summary, a table of the steps, a table of the estimates, notes and limits."""
    items: list[Any] = [Text(_summary(result))]
    items.append(table_of(_step_table(result), result.steps, title="steps"))
    items.append(table_of(_estimate_table(result), result.estimates,
                          title="in-situ estimates (standard uncertainty u)"))
    verdict = _verdict(result)
    if verdict:
        items.append(Text(verdict, style="bold"))
    items += [Text(f"note: {n}") for n in result.notes]
    items += [Text(f"limit: {n}", style="dim") for n in result.limits]
    return rich_text(items, width=width, color=color, ascii=ascii)


def to_markdown(result: RunupResult) -> str:
    """The two tables as GitHub Markdown, with the summary, notes and limits."""
    parts = [_summary(result), "", markdown_of(_step_table(result), result.steps), "",
             markdown_of(_estimate_table(result), result.estimates)]
    verdict = _verdict(result)
    if verdict:
        parts += ["", verdict]
    parts += [""] + [f"- note: {n}" for n in result.notes] + [f"- limit: {n}"
                                                               for n in result.limits]
    return "\n".join(parts) + "\n"


#: The unit of each term's regressor (docs/model.md section 16); the G terms' is g².
_REGRESSOR_UNITS = {"A1": "deg/s", "k2": "(deg/s)^2", "k4": "(deg/s)^4", "m31": "(deg/s)^2",
                    "m32": "(deg/s)^2"}


def _leading(result: RunupResult) -> Estimate:
    """The estimate that moves the shifts most over these steps (|θ|·span of φ)."""
    def reach(e: Estimate) -> float:
        values = [dict(s.regressors)[e.name] for s in result.steps]
        span = max(values) - min(values)
        effect = abs(e.value) * span
        return effect if math.isfinite(effect) else -1.0

    return max(result.estimates, key=reach)


def plot(result: RunupResult) -> bytes:
    """Shift against the regressor of the term that moves it most (:func:`_leading`):
    measured with 2u error bars, the fit, and the catalogue sensor's prediction (PNG)."""
    plt = pyplot()
    first = _leading(result)
    x = [dict(s.regressors)[first.name] for s in result.steps]
    fig, ax = plt.subplots(figsize=(7, 4.2))
    ax.errorbar(x, [s.shift for s in result.steps],
                yerr=[2 * s.uncertainty for s in result.steps], fmt="o", color="k", ms=4,
                capsize=3, label="measured shift ± 2u")
    order = sorted(range(len(x)), key=lambda k: x[k])
    ax.plot([x[k] for k in order], [result.steps[k].fitted for k in order], "-", color="C0",
            label="fit")
    if result.sensor is not None:
        ax.plot(x, [s.predicted for s in result.steps], "s", mfc="none", color="C3",
                label=f"{result.sensor}: predicted" + (" (bound)" if result.steps[0].bound
                                                       else ""))
    for s, xv in zip(result.steps, x, strict=True):
        ax.annotate(str(s.index), (xv, s.shift), textcoords="offset points", xytext=(4, 4),
                    fontsize=7)
    ax.axhline(0.0, color="0.7", lw=0.8)
    ax.set_xlabel(f"{first.name} regressor, {_REGRESSOR_UNITS.get(first.name, 'g^2')}")
    ax.set_ylabel(f"shift from the baseline, {UNIT}")
    ax.set_title(f"{os.path.basename(result.file)}: run-up test", fontsize=10)
    ax.grid(True, lw=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    data = png(fig, dpi=100)
    plt.close(fig)
    return data


__all__ = ["plot", "to_csv", "to_json", "to_markdown", "to_table"]
