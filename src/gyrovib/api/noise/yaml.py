"""An Allan result as a ``noise:`` block to paste into a sensor of a catalogue."""

from __future__ import annotations

import os

from gyrovib.api.noise.results import AllanResult


def _number(x: float) -> str:
    return f"{x:.4g}" if x != 0 else "0"


def noise_yaml(result: AllanResult) -> str:
    """One ``noise:`` block per axis, each its own YAML document (``---`` between them),
    with commented provenance and each figure's uncertainty as a comment: in the
    default units, ready to indent under a sensor."""
    source = "" if result.source is None else f", {result.source}"
    lines = [f"# from gyrovib allan {os.path.basename(result.file)}{source} "
             f"(sha256 {result.sha256[:16]}…, {result.samples} samples at {result.fs:.6g} Hz)",
             "# one document per recorded axis: keep the sensor's own, indent it under the",
             "# sensor; ± values are standard uncertainties of the reads (docs/error-budget.md)"]
    for k, ax in enumerate(result.axes):
        if k:
            lines.append("---")
        lines.append(f"# axis {ax.axis}")
        lines.append("noise:")
        for name, fig in (("arw", ax.arw), ("bias_instability", ax.bias_instability),
                          ("rrw", ax.rrw)):
            lines.append(f"  {name}: {_number(fig.value)} {fig.unit}    "
                         f"# ± {_number(fig.uncertainty)}, read at τ = {fig.tau:.4g} s")
    return "\n".join(lines) + "\n"
