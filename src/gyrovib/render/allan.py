"""Renderers of ``gyrovib allan`` (docs/model.md section 15): a table per axis, JSON
(keys: INTERFACE.md, fourth round) and the log-log plot."""

from __future__ import annotations

import io
import os
from typing import TYPE_CHECKING, Any

import numpy as np
from rich.table import Table
from rich.text import Text

from gyrovib import units
from gyrovib.render.common import dumps, fmt, header, number, rich_text

if TYPE_CHECKING:
    from gyrovib.api.noise import AllanResult, AxisAllan, Figure

_FIGURES = (("arw", "N: angle random walk"), ("bias_instability", "B: bias instability"),
            ("rrw", "K: rate random walk"))


def _figure(fig: Figure) -> dict[str, Any]:
    return {"value": number(fig.value), "unit": fig.unit,
            "uncertainty": number(fig.uncertainty)}


def to_json(result: AllanResult) -> str:
    """One object per axis: axis, tau (s), adev (rate unit), arw, bias_instability, rrw."""
    axes = []
    for ax in result.axes:
        entry: dict[str, Any] = {"axis": ax.axis, "tau": [number(t) for t in ax.tau],
                                 "adev": [number(a) for a in ax.adev]}
        for name, _ in _FIGURES:
            fig = getattr(ax, name)
            entry[name] = _figure(fig) | {"tau_read": number(fig.tau)}
        axes.append(entry)
    doc = header("allan", result.axes[0].unit if result.axes else "deg/h")
    doc |= {"recording": {"file": os.path.basename(result.file), "topic": result.topic,
                          "instance": result.instance, "sha256": result.sha256,
                          "samples": result.samples, "fs": result.fs,
                          "segments": result.segments},
            "axes": axes}
    return dumps(doc)


def _summary(result: AllanResult) -> str:
    used = f"{result.samples} samples at {result.fs:.6g} Hz ({result.samples / result.fs:.6g} s)"
    if result.segments > 1:
        used += f", the longest of {result.segments} contiguous segments"
    source = "" if result.source is None else f" ({result.source})"
    return f"recording {os.path.basename(result.file)}{source}: {used}"


def _legend() -> str:
    return ("Overlapping Allan deviation (IEEE Std 952, allantools' oadev). Each figure is "
            "read on its line through the point of the curve where its standard "
            "uncertainty (u, from the equivalent degrees of freedom and the share of the "
            "other fitted terms there) is least; read at τ: that point; share: its own "
            "term's share of the fitted σ² there. N is the value of its slope −½ line at "
            "τ = 1 s, K of its slope +½ line at τ = 3 s, B = σ_min / 0.664 "
            "(docs/error-budget.md).")


def to_table(result: AllanResult, width: int | None = None, color: bool = False,
             ascii: bool = False) -> str:
    """The figures per axis, then a short σ(τ) table per axis (one point a decade)."""

    items: list[Any] = [Text(_summary(result))]
    figures = Table(title="noise figures", header_style="bold")
    for k, label in enumerate(("axis", "figure", "value ± u", "unit", "read at τ (s)",
                               "share")):
        figures.add_column(label, justify="right" if k in (2, 4, 5) else "left")
    for ax in result.axes:
        for name, label in _FIGURES:
            fig = getattr(ax, name)
            figures.add_row(ax.axis, label, f"{fmt(fig.value)} ± {fmt(fig.uncertainty, 2)}",
                            fig.unit, fmt(fig.tau), f"{100 * fig.share:.0f} %")
    items.append(figures)
    for ax in result.axes:
        items.append(_curve_table(ax))
    items.append(Text(_legend(), style="dim"))
    return rich_text(items, width=width, color=color, ascii=ascii)


def _decade_points(ax: AxisAllan) -> list[int]:
    """About one grid point a decade, and the curve's minimum."""

    logs = np.log10(ax.tau)
    marks = np.arange(np.ceil(logs[0]), np.floor(logs[-1]) + 1)
    picks = {int(np.argmin(abs(logs - m))) for m in marks}
    picks |= {0, ax.tau.size - 1, int(np.argmin(ax.adev))}
    return sorted(picks)


def _curve_table(ax: AxisAllan) -> Any:

    table = Table(title=f"axis {ax.axis}: σ(τ), {ax.unit} ({ax.tau.size} points in the "
                        "JSON output)", header_style="bold")
    table.add_column("τ, s", justify="right")
    table.add_column(f"σ(τ), {ax.unit}", justify="right")
    low = int(ax.adev.argmin())
    for i in _decade_points(ax):
        table.add_row(fmt(float(ax.tau[i])), fmt(float(ax.adev[i]))
                      + ("  (minimum)" if i == low else ""))
    return table


def plot(result: AllanResult) -> bytes:
    """The Allan deviation per axis, log-log, with the fitted terms' lines and the three
    figures' slope lines (PNG bytes)."""

    # lazy: matplotlib is optional, for --plot only
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(len(result.axes), 1, figsize=(8, 3.2 * len(result.axes)),
                             squeeze=False)
    for ax, panel in zip(result.axes, axes[:, 0], strict=True):
        tau = ax.tau
        panel.loglog(tau, ax.adev, "k.-", lw=0.8, ms=3, label="overlapping Allan deviation")
        to_unit = 1.0 / units.scale(ax.unit)  # deg/s → the plot's unit
        n, b, k = (ax.arw.value / 60.0, ax.bias_instability.value / 3600.0,
                   ax.rrw.value / 216_000.0)
        floor = np.sqrt(2 * np.log(2) / np.pi)
        lines = ((n / np.sqrt(tau), f"N = {ax.arw.value:.3g} {ax.arw.unit} (slope −½)", "C0"),
                 (np.full_like(tau, b * floor * 1.0),
                  f"B = {ax.bias_instability.value:.3g} {ax.bias_instability.unit}", "C1"),
                 (k * np.sqrt(tau / 3), f"K = {ax.rrw.value:.3g} {ax.rrw.unit} (slope +½)",
                  "C2"))
        for values, label, color in lines:
            panel.loglog(tau, values * to_unit, "--", color=color, lw=0.9, label=label)
        fn, fb, fk = (ax.fitted[0] / 60.0, ax.fitted[1] / 3600.0, ax.fitted[2] / 216_000.0)
        model = np.sqrt(fn**2 / tau + (floor * fb) ** 2 + fk**2 * tau / 3)
        panel.loglog(tau, model * to_unit, color="C3", lw=0.8, alpha=0.7,
                     label="fitted N²/τ + 0.664²B² + K²τ/3")
        panel.set_ylim(ax.adev.min() / 5, ax.adev.max() * 5)
        panel.set_title(f"axis {ax.axis}", fontsize=9)
        panel.set_ylabel(f"σ(τ), {ax.unit}")
        panel.grid(True, which="both", lw=0.3)
        panel.legend(fontsize=7, loc="best")
    axes[-1, 0].set_xlabel("τ, s")
    fig.suptitle(f"{os.path.basename(result.file)}: Allan deviation", fontsize=10)
    fig.tight_layout()
    out = io.BytesIO()
    fig.savefig(out, format="png", dpi=100)
    plt.close(fig)
    return out.getvalue()
