"""Renderers of ``gyrovib allan`` (docs/model.md section 15): a table per axis, JSON
(keys: docs/output.md), the log-log plot with error bars, and
Kalibr's ``imu.yaml`` (render/kalibr.py)."""

from __future__ import annotations

import os
import warnings
from typing import TYPE_CHECKING, Any

import numpy as np
from rich.table import Table
from rich.text import Text

from gyrovib import units
from gyrovib.render.common import dumps, fmt, header, number, png, pyplot, rich_text

if TYPE_CHECKING:
    from gyrovib.api.noise import AllanResult, AxisAllan, Figure

_FIGURES = (("quantization", "Q: quantization"), ("arw", "N: angle random walk"),
            ("bias_instability", "B: bias instability"), ("rrw", "K: rate random walk"),
            ("rate_ramp", "R: rate ramp"))


#: The accelerometer's names of the terms that differ from the gyro's.
_ACCEL_LABELS = {"arw": "N: velocity random walk", "rrw": "K: acceleration random walk"}


def figure_json(fig: Figure) -> dict[str, Any]:
    """``{value, unit, interval}`` or ``{bound, unit, confidence}`` (docs/output.md, allan)."""
    if fig.is_bound:
        return {"bound": number(fig.upper), "unit": fig.unit, "confidence": fig.confidence}
    assert fig.interval is not None
    return {"value": number(fig.upper), "unit": fig.unit,
            "interval": [number(fig.interval[0]), number(fig.interval[1])]}


def _axis_json(ax: AxisAllan) -> dict[str, Any]:
    entry: dict[str, Any] = {"axis": ax.axis, "tau": [number(t) for t in ax.tau],
                             "adev": [number(a) for a in ax.adev],
                             "ci": [[number(lo), number(hi)]
                                    for lo, hi in zip(ax.ci_lo, ax.ci_hi, strict=True)],
                             "edf": [number(v) for v in ax.edf]}
    for name, _ in _FIGURES:
        entry[name] = figure_json(ax.figures[name])
    gm = ax.gauss_markov
    entry["gauss_markov"] = None if gm is None else {
        "sigma": number(gm.sigma), "tau_c": number(gm.tau_c), "unit": gm.unit,
        "interval": None if gm.interval is None else [number(v) for v in gm.interval]}
    entry["misfit_tau"] = [number(t) for t in ax.misfit]
    entry["fitted_from_tau"] = number(ax.fitted_from)
    return entry


def to_json(result: AllanResult) -> str:
    """One object per axis: axis, tau (s), adev (rate unit), ci, the five terms and
    gauss_markov; the confidence of the intervals and the warnings at the top."""
    doc = header("allan", result.axes[0].unit if result.axes else "deg/h")
    doc |= {"recording": {"file": os.path.basename(result.file), "topic": result.topic,
                          "instance": result.instance, "sha256": result.sha256,
                          "samples": result.samples, "fs": result.fs,
                          "segments": result.segments},
            "confidence": result.confidence,
            "axes": [_axis_json(ax) for ax in result.axes],
            "warnings": list(result.warnings)}
    if result.accel:
        doc["accelerometer"] = [_axis_json(ax) for ax in result.accel]
    return dumps(doc)


def summary(result: AllanResult) -> str:
    """Which samples were used (the longest segment of a record with gaps)."""
    used = f"{result.samples} samples at {result.fs:.6g} Hz ({result.samples / result.fs:.6g} s)"
    if result.segments > 1:
        used += (f", only the longest of {result.segments} contiguous segments (a gap "
                 "breaks the record)")
    source = "" if result.source is None else f" ({result.source})"
    return f"recording {os.path.basename(result.file)}{source}: {used}"


def figure_text(fig: Figure) -> str:
    """'value [lo, hi]' or '≤ bound' (a bound, never a value)."""
    if fig.is_bound:
        return f"≤ {fmt(fig.upper)}"
    assert fig.interval is not None
    return f"{fmt(fig.upper)} [{fmt(fig.interval[0], 3)}, {fmt(fig.interval[1], 3)}]"


def _legend(result: AllanResult) -> str:
    pct = f"{100 * result.confidence:.4g} %"
    return ("Overlapping Allan deviation (IEEE Std 952, allantools' oadev). The five terms "
            "σ² = 3Q²/τ² + N²/τ + 0.664²B² + K²τ/3 + R²τ²/2 are fitted jointly, non-negatively, "
            "weighted by each point's equivalent degrees of freedom; [lo, hi]: the "
            f"{pct} interval from a parametric bootstrap of the fit. '≤ x': a term the "
            "record does not resolve (its slope region is absent or its 95 % interval "
            "reaches 0), given only as an upper bound at 95 % — use it as a maximum, never "
            "as a value (docs/error-budget.md).")


def to_table(result: AllanResult, width: int | None = None, color: bool = False,
             ascii: bool = False) -> str:
    """The figures per axis, then a short σ(τ) table per axis (one point a decade)."""

    items: list[Any] = [Text(summary(result))]
    pct = f"{100 * result.confidence:.4g} %"
    figures = Table(title="noise model", header_style="bold")
    for k, label in enumerate(("axis", "term", f"value [{pct}] or bound", "unit")):
        figures.add_column(label, justify="right" if k == 2 else "left")
    for prefix, group in (("", result.axes), ("accel ", result.accel)):
        for ax in group:
            for name, label in _FIGURES:
                fig = ax.figures[name]
                figures.add_row(prefix + ax.axis, _ACCEL_LABELS.get(name, label) if prefix
                                else label, figure_text(fig), fig.unit)
            if ax.gauss_markov is not None:
                gm = ax.gauss_markov
                figures.add_row(prefix + ax.axis, "Gauss–Markov σ, τ_c",
                                f"{fmt(gm.sigma)}, τ_c = {fmt(gm.tau_c)} s", gm.unit)
    items.append(figures)
    for ax in result.axes:
        items.append(_curve_table(ax, pct))
    items.append(Text(_legend(result), style="dim"))
    return rich_text(items, width=width, color=color, ascii=ascii)


def _decade_points(ax: AxisAllan) -> list[int]:
    """About one grid point a decade, and the curve's minimum."""

    logs = np.log10(ax.tau)
    marks = np.arange(np.ceil(logs[0]), np.floor(logs[-1]) + 1)
    picks = {int(np.argmin(abs(logs - m))) for m in marks}
    picks |= {0, ax.tau.size - 1, int(np.argmin(ax.adev))}
    return sorted(picks)


def _curve_table(ax: AxisAllan, pct: str) -> Any:

    table = Table(title=f"axis {ax.axis}: σ(τ), {ax.unit} ({ax.tau.size} points in the "
                        "JSON output)", header_style="bold")
    table.add_column("τ, s", justify="right")
    table.add_column(f"σ(τ), {ax.unit}", justify="right")
    table.add_column(f"{pct} interval", justify="right")
    table.add_column("EDF", justify="right")
    low = int(ax.adev.argmin())
    for i in _decade_points(ax):
        table.add_row(fmt(float(ax.tau[i])), fmt(float(ax.adev[i]))
                      + ("  (minimum)" if i == low else ""),
                      f"{fmt(float(ax.ci_lo[i]), 3)} … {fmt(float(ax.ci_hi[i]), 3)}",
                      fmt(float(ax.edf[i]), 3))
    return table


def plot(result: AllanResult) -> bytes:
    """The Allan deviation per axis, log-log, with its confidence error bars, the fitted
    model and each resolved term's line (PNG bytes)."""
    plt = pyplot()
    fig, axes = plt.subplots(len(result.axes), 1, figsize=(8, 3.4 * len(result.axes)),
                             squeeze=False)
    with warnings.catch_warnings():
        # a flat or one-point curve must not print the library's warnings with its paths
        warnings.simplefilter("ignore")
        for ax, panel in zip(result.axes, axes[:, 0], strict=True):
            _panel(panel, ax, result.confidence)
        axes[-1, 0].set_xlabel("τ, s")
        fig.suptitle(f"{os.path.basename(result.file)}: Allan deviation", fontsize=10)
        fig.tight_layout()
        data = png(fig, dpi=100)
    plt.close(fig)
    return data


def _panel(panel: Any, ax: AxisAllan, confidence: float) -> None:
    tau = ax.tau
    err = np.vstack([ax.adev - ax.ci_lo, ax.ci_hi - ax.adev])
    panel.errorbar(tau, ax.adev, yerr=err, fmt="k.", ms=3, lw=0.6, capsize=1.5,
                   label=f"overlapping Allan deviation, {100 * confidence:.4g} % intervals")
    panel.set_xscale("log")
    panel.set_yscale("log")
    to_unit = 1.0 / units.scale(ax.unit)  # deg/s → the plot's unit
    basis = {"quantization": (np.sqrt(3.0) / tau, 1.0),
             "arw": (1.0 / np.sqrt(tau), 1 / 60.0),
             "bias_instability": (np.full_like(tau, np.sqrt(2 * np.log(2) / np.pi)),
                                  1 / 3600.0),
             "rrw": (np.sqrt(tau / 3.0), 1 / 216_000.0),
             "rate_ramp": (tau / np.sqrt(2.0), 1 / 3600.0 ** 2)}
    for k, (name, label) in enumerate(_FIGURES):
        f = ax.figures[name]
        shape, factor = basis[name]
        style = ":" if f.is_bound else "--"
        text = f"{label.split(':')[0]} {'≤ ' if f.is_bound else '= '}{f.upper:.3g} {f.unit}"
        panel.plot(tau, shape * f.upper * factor * to_unit, style, color=f"C{k}", lw=0.9,
                   label=text)
    panel.plot(tau, ax.model, color="C6", lw=0.9, alpha=0.8, label="fitted model")
    low, high = float(np.min(ax.ci_lo)), float(np.max(ax.ci_hi))
    if low > 0 and high > low:
        panel.set_ylim(low / 3, high * 3)
    panel.set_title(f"axis {ax.axis}", fontsize=9)
    panel.set_ylabel(f"σ(τ), {ax.unit}")
    panel.grid(True, which="both", lw=0.3)
    panel.legend(fontsize=6, loc="best")
