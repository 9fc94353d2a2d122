"""θ(t) of a mission as PNG bytes (optional matplotlib): per sensor, the heading error
that vibration rectification accumulates segment by segment (a staircase of slopes:
θ_V(t) grows at Δ_V,s through segment s) inside the noise cone ±k·σ(t), where over t
hours σ(t)² = N²t + B²t² + K²t³/3 + R²t² (docs/model.md section 15; the row's budget
terms at T scale as √(t/T), t/T, (t/T)^1.5 and t/T), and the angle budget ±θ*."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from gyrovib.render.common import png
from gyrovib.render.plot import _figure_class

if TYPE_CHECKING:
    from gyrovib.api.missions.results import MissionResult, MissionRow
    from gyrovib.core._types import FloatArray

#: Points of the cone per segment.
_PER_SEGMENT = 24


def sigma_at(row: MissionRow, hours: FloatArray) -> FloatArray:
    """σ(t) in deg at ``hours`` from the row's budget over T (unknown terms left out:
    the cone is then a lower bound, as the total)."""
    b = row.budget
    assert b is not None
    span = row.duration / 3600.0
    x = np.asarray(hours, dtype=float) / span
    total = np.zeros(x.shape)
    for value, power in ((b.arw, 0.5), (b.bias_instability, 1.0), (b.rrw, 1.5),
                         (b.repeatability, 1.0)):
        if value is not None:
            total += (value * x**power) ** 2
    out: FloatArray = np.sqrt(total)
    return out


def staircase(row: MissionRow) -> tuple[FloatArray, FloatArray]:
    """(t in h, θ_V in deg) at the start and end of every segment."""
    ends = np.cumsum([s.duration for s in row.segments]) / 3600.0
    theta = [0.0] + [b.vibration for b in row.timeline]
    return np.concatenate([[0.0], ends]), np.asarray(theta)


def _rows_to_draw(result: MissionResult) -> list[MissionRow]:
    """One row per sensor and mission: a triad's worst axis, else the row itself."""
    out = []
    for r in result.rows:
        if r.budget is not None and r.timeline and (r.axis is None or r.axis == r.worst_axis):
            out.append(r)
    return out


def theta_png(result: MissionResult, *, dpi: int = 100) -> bytes:
    """θ(t) per sensor (and mission): one panel each, the staircase and its cone."""
    figure_class = _figure_class()
    rows = _rows_to_draw(result)
    n = max(1, len(rows))
    fig = figure_class(figsize=(9.0, 1.0 + 2.4 * n), dpi=dpi, layout="constrained")
    axes = fig.subplots(n, 1, squeeze=False)[:, 0]
    for ax, row in zip(axes, rows, strict=False):
        b = row.budget
        assert b is not None
        axis = f", x3 on {row.axis}" if row.axis else ""
        if np.isnan(b.total):  # θ_V rests on an axis the recording did not record
            ax.set_title(f"{row.sensor} — {row.mission}{axis}: total unknown "
                         f"({row.status or 'no budget'})", fontsize=10, loc="left")
            ax.text(0.5, 0.5, "θ(t) unknown: the vibration error rests on an axis the "
                    "recording did not record (unknown, not 0)", ha="center", va="center",
                    transform=ax.transAxes, fontsize=9)
            ax.set_axis_off()
            continue
        t, theta = staircase(row)
        dense = np.linspace(0.0, t[-1], max(2, _PER_SEGMENT * len(row.segments)))
        vib = np.interp(dense, t, theta)
        cone = b.coverage * sigma_at(row, dense)
        ax.fill_between(dense, vib - cone, vib + cone, color="C0", alpha=0.2, lw=0,
                        label=f"±{b.coverage:g}·σ(t) noise" + (" (≥: figures unknown)"
                                                               if b.lower_bound else ""))
        ax.plot(t, theta, color="C3", lw=1.6, marker=".", label="θ_V(t) vibration")
        if result.angle_budget is not None:
            for sign in (1.0, -1.0):
                ax.axhline(sign * result.angle_budget, color="k", ls="--", lw=0.9)
        ax.set_title(f"{row.sensor} — {row.mission}{axis}: total "
                     f"{'≥ ' if b.lower_bound else ''}{b.total:.4g} deg "
                     f"({row.status or 'no budget'})", fontsize=10, loc="left")
        ax.set_ylabel("heading error (deg)")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8, loc="upper left")
    axes[-1].set_xlabel("time (h)")
    return png(fig)
