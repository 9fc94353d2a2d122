"""An Allan result as a ``noise:`` block to paste into a sensor of a catalogue."""

from __future__ import annotations

import os

from gyrovib.api.noise.results import AllanResult, AxisAllan, Figure

#: The figures a ``noise:`` block holds (the others are written as comments).
BLOCK_FIGURES = ("arw", "bias_instability", "rrw")


def _number(x: float) -> str:
    return f"{x:.4g}"


def _line(name: str, fig: Figure, indent: str) -> str:
    if fig.is_bound:
        return (f'{indent}{name}: "≤ {_number(fig.upper)} {fig.unit}"    '
                f"# not resolved by the record: an upper bound at "
                f"{100 * fig.confidence:.4g} %")
    assert fig.interval is not None
    return (f"{indent}{name}: {_number(fig.upper)} {fig.unit}    # "
            f"{100 * fig.confidence:.4g} % interval {_number(fig.interval[0])} … "
            f"{_number(fig.interval[1])}")


def _axis_lines(ax: AxisAllan, indent: str) -> list[str]:
    lines = [_line(name, ax.figures[name], indent) for name in BLOCK_FIGURES]
    for name in ("quantization", "rate_ramp"):
        fig = ax.figures[name]
        text = (f"≤ {_number(fig.upper)}" if fig.is_bound else _number(fig.upper))
        lines.append(f"{indent}# {name}: {text} {fig.unit} (not a field of the block)")
    if ax.gauss_markov is not None:
        gm = ax.gauss_markov
        lines.append(f"{indent}# Gauss–Markov: σ {_number(gm.sigma)} deg/h, τ_c "
                     f"{_number(gm.tau_c)} s (not a field of the block)")
    return lines


def noise_yaml(result: AllanResult) -> str:
    """One ``noise:`` block, ready to indent under a sensor: the figures of a single
    recorded axis, or one sub-block per axis (``x:``, ``y:``, ``z:``), with commented
    provenance, each value's interval as a comment and each unresolved figure as a
    bound (``"≤ 0.8 deg/h/sqrt(h)"``)."""
    source = "" if result.source is None else f", {result.source}"
    lines = [f"# from gyrovib allan {os.path.basename(result.file)}{source} "
             f"(sha256 {result.sha256[:16]}…, {result.samples} samples at {result.fs:.6g} Hz)"]
    if result.segments > 1:
        lines.append(f"# only the longest of {result.segments} contiguous segments was used "
                     "(the record has gaps)")
    lines.append("# intervals from a bootstrap of the noise model; a '≤' figure is a bound "
                 "(docs/error-budget.md)")
    lines.append("noise:")
    if len(result.axes) == 1:
        lines.append(f"  # axis {result.axes[0].axis}")
        lines.extend(_axis_lines(result.axes[0], "  "))
    else:
        for ax in result.axes:
            lines.append(f"  {ax.axis.lower()}:")
            lines.extend(_axis_lines(ax, "    "))
    return "\n".join(lines) + "\n"
