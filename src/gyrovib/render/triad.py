"""A command's output under the triad (docs/model.md section 12): the three axes' outputs
in one document, each result tagged with its ``axis``, and the ``worst_axis`` summary.

``draw`` is the command's own renderer for the chosen format (result → text).
"""

from __future__ import annotations

import json
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from gyrovib.api.placement.triad import TriadResult

#: The formats a triad can be written in.
TRIAD_FORMATS = ("table", "json", "csv", "markdown")


def _summary(result: TriadResult) -> list[str]:
    lines = []
    for key, axis in result.worst_axis.items():
        if isinstance(axis, dict):
            shown = ", ".join(f"{c}: {a}" for c, a in axis.items())
            lines.append(f"worst axis for {key}: {shown}")
        else:
            lines.append(f"worst axis for {key}: {axis}")
    return lines


def to_text(result: TriadResult, draw: Callable[[Any], str], fmt: str) -> str:
    """Table or markdown: each axis's output under a heading, then the worst axes."""
    out: list[str] = []
    for axis, placement, one in zip(result.axes, result.placements, result.results,
                                    strict=True):
        heading = f"x3 on {axis} ({placement})"
        out.append(f"## {heading}\n\n" if fmt == "markdown" else f"{heading}\n")
        out.append(draw(one))
        out.append("\n")
    summary = _summary(result)
    out.append("\n".join(f"- {s}" if fmt == "markdown" else s for s in summary) + "\n")
    return "".join(out)


def to_json(result: TriadResult, draw: Callable[[Any], str]) -> str:
    """One document: the first axis's header keys, every list of results of the three
    axes concatenated with ``"axis"`` added to each entry, ``"placement": "triad"``,
    ``"axes"`` and ``"worst_axis"``."""
    docs = [json.loads(draw(one)) for one in result.results]
    merged: dict[str, Any] = {}
    for key, value in docs[0].items():
        if isinstance(value, list) and all(isinstance(v, dict) for v in value):
            merged[key] = [{**entry, "axis": axis}
                           for axis, doc in zip(result.axes, docs, strict=True)
                           for entry in doc[key]]
        else:
            merged[key] = value
    merged["placement"] = "triad"
    merged["axes"] = {axis: placement for axis, placement in
                      zip(result.axes, result.placements, strict=True)}
    merged["worst_axis"] = dict(result.worst_axis)
    if "require" in merged:  # select: a sensor passes when it passes on every axis
        merged["requirement_met"] = result.requirement_met
    return json.dumps(merged, allow_nan=False) + "\n"


def to_csv(result: TriadResult, draw: Callable[[Any], str]) -> str:
    """The three CSV tables as one, with a first column ``axis``."""
    out: list[str] = []
    for k, (axis, one) in enumerate(zip(result.axes, result.results, strict=True)):
        lines = draw(one).splitlines()
        if k == 0:
            out.append("axis," + lines[0])
        out.extend(f"{axis},{line}" for line in lines[1:])
    return "\n".join(out) + "\n"


def render(result: TriadResult, draw: Callable[[Any], str], fmt: str) -> str:
    """The triad in ``fmt`` (one of :data:`TRIAD_FORMATS`)."""
    if fmt == "json":
        return to_json(result, draw)
    if fmt == "csv":
        return to_csv(result, draw)
    return to_text(result, draw, fmt)
