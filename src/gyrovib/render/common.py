"""Helpers shared by the renderers."""

from __future__ import annotations

import json
import math
from collections.abc import Iterable
from typing import Any

from gyrovib._version import __version__


def number(value: float) -> float | None:
    """A JSON-safe number: non-finite values become ``None`` (``null``)."""
    v = float(value)
    return v if math.isfinite(v) else None


def header(method: str, unit: str) -> dict[str, Any]:
    """The fields every JSON document opens with."""
    return {"tool": "gyrovib", "version": __version__, "method": method, "unit": unit}


def dumps(document: Any) -> str:
    """Serialise a JSON document; NaN/Infinity are never written."""
    return json.dumps(document, allow_nan=False) + "\n"


def fmt(value: float | None, digits: int = 4) -> str:
    """A number for a human table: ``digits`` significant figures, '∞' for unbounded."""
    if value is None:
        return "∞"
    v = float(value)
    if math.isinf(v):
        return "∞" if v > 0 else "-∞"
    if math.isnan(v):
        return "nan"
    if v == 0:
        return "0"
    return f"{v:.{digits}g}"


def csv_text(header_row: Iterable[str], rows: Iterable[Iterable[Any]]) -> str:
    """CSV with a header row, numbers written with full precision."""
    import csv
    import io

    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(list(header_row))
    for row in rows:
        writer.writerow(["" if x is None else (repr(x) if isinstance(x, float) else x)
                         for x in row])
    return buffer.getvalue()


def markdown_table(header_row: list[str], rows: Iterable[list[str]]) -> str:
    """A GitHub-flavoured Markdown table."""

    def cell(text: str) -> str:
        return text.replace("|", "\\|").replace("\n", " ")

    lines = ["| " + " | ".join(cell(h) for h in header_row) + " |",
             "|" + "|".join("---" for _ in header_row) + "|"]
    lines += ["| " + " | ".join(cell(c) for c in row) + " |" for row in rows]
    return "\n".join(lines) + "\n"


def rich_text(renderables: Iterable[Any], width: int | None = None, color: bool = False) -> str:
    """Render rich objects to a string (no terminal needed)."""
    import io

    from rich.console import Console

    buffer = io.StringIO()
    console = Console(
        file=buffer, width=width or 160, force_terminal=color, color_system="standard" if color
        else None, highlight=False, soft_wrap=False,
    )
    for item in renderables:
        console.print(item)
    return buffer.getvalue()
