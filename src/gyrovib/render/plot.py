"""Plots of :class:`gyrovib.api.SweepResult` as PNG bytes (optional matplotlib).

matplotlib is an optional extra (``pip install 'gyrovib[plot]'``). The figure
is built with :class:`matplotlib.figure.Figure` directly, never pyplot, so no
GUI backend or global figure state is involved.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from gyrovib.api import SweepResult
from gyrovib.api.datasheet.specs import worst_residual
from gyrovib.errors import GyrovibError
from gyrovib.render.common import png

MISSING_MATPLOTLIB = (
    "plotting needs matplotlib, which is not installed: pip install 'gyrovib[plot]'"
)


def _figure_class() -> Any:
    try:
        # lazy: matplotlib is optional, for --plot only
        from matplotlib.figure import Figure
    except ImportError:
        raise GyrovibError(MISSING_MATPLOTLIB) from None
    return Figure


def sweep_png(result: SweepResult, budget: float | None = None, *, log: bool = False,
              dpi: int = 100) -> bytes:
    """Δ_V and Δ_V(RMS) against Ω_K3: one row of two panels per profile.

    One colour per sensor; the exact method drawn solid, the paper's dashed
    (absent where the paper refuses the profile). ``budget`` (in the result's
    unit) is shaded: ±Δ*_V on the Δ_V panel, [0, Δ*_V] on the RMS panel.
    ``log``: symmetric-log Δ_V and logarithmic RMS axes, for sensors of very
    different sizes.
    """
    figure_class = _figure_class()
    n_rows = max(1, len(result.profiles))
    fig = figure_class(figsize=(10.0, 1.2 + 2.9 * n_rows), dpi=dpi, layout="constrained")
    axes = fig.subplots(n_rows, 2, squeeze=False, sharex=True)
    colours = [f"C{k % 10}" for k in range(len(result.sensors))]
    x = result.rates
    for j, profile in enumerate(result.profiles):
        ax_total, ax_rms = axes[j]
        refused = profile in result.paper_refused
        for i, sensor in enumerate(result.sensors):
            for ax, field in ((ax_total, "total"), (ax_rms, "rms")):
                ax.plot(x, getattr(result.exact, field)[i, j], color=colours[i], lw=1.6,
                        label=f"{sensor} exact")
                if not refused:
                    ax.plot(x, getattr(result.paper, field)[i, j], color=colours[i], lw=1.2,
                            ls="--", label=f"{sensor} paper")
        if budget is not None:
            ax_total.axhspan(-budget, budget, color="tab:green", alpha=0.12, lw=0,
                             label="budget ±Δ*")
            ax_rms.axhspan(0.0, budget, color="tab:green", alpha=0.12, lw=0, label="budget Δ*")
        note = " (paper: not covered)" if refused else ""
        ax_total.set_title(f"{profile}: Δ_V{note}", fontsize=10, loc="left")
        ax_rms.set_title(f"{profile}: Δ_V(RMS){note}", fontsize=10, loc="left")
        for ax in (ax_total, ax_rms):
            ax.grid(True, alpha=0.3)
            ax.set_ylabel(result.unit)
            ax.axhline(0.0, color="0.5", lw=0.6)
        if log:
            ax_total.set_yscale("symlog", linthresh=_linthresh(result, j))
            ax_rms.set_yscale("log")
    for ax in axes[-1]:
        ax.set_xlabel(f"Ω_K3 ({result.unit})")
    legend: dict[str, Any] = {}
    for ax in axes[:, 0]:
        for handle, label in zip(*ax.get_legend_handles_labels(), strict=True):
            legend.setdefault(label, handle)
    handles, labels = list(legend.values()), list(legend)
    if handles:
        fig.legend(handles, labels, loc="outside lower center", ncol=min(4, len(labels)),
                   fontsize=8, frameon=False)
    return png(fig, dpi=dpi)


def _linthresh(result: SweepResult, j: int) -> float:
    values = np.abs(result.exact.total[:, j])
    positive = values[values > 0]
    return float(positive.min()) if positive.size else 1.0


def envelope_png(result: SweepResult, *, dpi: int = 100) -> bytes | None:
    """The worst-case polynomials of the spec-form sensors against their NL envelope.

    One panel per spec-form sensor × profile: the residual r(ω) of the
    polynomial attaining the worst |Δ_V| (at the swept rate where it is
    largest) from its reference line, over the sensor's range [−R, R], with the
    band ±b the datasheet allows (docs/model.md section 11). None when the sweep has
    no spec-form sensor.
    """
    spec = [i for i in range(len(result.sensors)) if result.source(i) == "specs"]
    if not spec or result.worst_coefficients is None or not len(result.profiles):
        return None
    figure_class = _figure_class()
    n_rows, n_cols = len(spec), len(result.profiles)
    fig = figure_class(figsize=(3.6 * n_cols + 0.6, 1.0 + 2.6 * n_rows), dpi=dpi,
                       layout="constrained")
    axes = fig.subplots(n_rows, n_cols, squeeze=False)
    for row, i in enumerate(spec):
        for j, profile in enumerate(result.profiles):
            ax = axes[row, j]
            totals = np.abs(result.exact.total[i, j])
            if not np.any(np.isfinite(totals)):
                ax.set_axis_off()
                continue
            r = int(np.nanargmax(totals))
            w, resid, b = worst_residual(result, i, j, r)
            ax.axhspan(-b, b, color="tab:green", alpha=0.12, lw=0, label="±b (datasheet NL)")
            ax.plot(w, resid, color="C3", lw=1.4, label="worst polynomial's residual")
            ax.axhline(0.0, color="0.5", lw=0.6)
            ax.grid(True, alpha=0.3)
            ax.set_title(f"{result.sensors[i]} / {profile}\nΩ_K3 = {result.rates[r]:.4g}: "
                         f"|Δ_V| = {totals[r]:.3g} {result.unit}", fontsize=9, loc="left")
            ax.set_xlabel(f"ω ({result.unit})")
            ax.set_ylabel(f"r(ω) ({result.unit})")
    handles, labels = axes[0, 0].get_legend_handles_labels()
    if handles:
        fig.legend(handles, labels, loc="outside lower center", ncol=2, fontsize=8,
                   frameon=False)
    return png(fig, dpi=dpi)
