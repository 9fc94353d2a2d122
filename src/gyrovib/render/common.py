"""Helpers shared by the renderers."""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from typing import Any

from gyrovib._version import __version__
from gyrovib.formatting import NEGLIGIBLE as NEGLIGIBLE
from gyrovib.formatting import fmt as fmt


def number(value: float) -> float | None:
    """A JSON-safe number: non-finite values become ``None`` (``null``)."""
    v = float(value)
    return v if math.isfinite(v) else None


def header(method: str, unit: str) -> dict[str, Any]:
    """The fields every JSON document opens with."""
    return {"tool": "gyrovib", "version": __version__, "method": method, "unit": unit}


def dumps(document: Any) -> str:
    """Serialise a JSON document; NaN/Infinity are never written."""
    import json  # not at import time: the tables do without it

    return json.dumps(document, allow_nan=False) + "\n"


def fmt_budget(value: float | None, budget: float | None, digits: int = 4) -> str:
    """:func:`fmt`, but ``0`` for |value| below :data:`NEGLIGIBLE` × the budget (tables only)."""
    if (value is not None and budget is not None and budget > 0 and math.isfinite(value)
            and abs(value) < NEGLIGIBLE * budget):
        return "0"
    return fmt(value, digits)


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


def csv_cell(text: str) -> str:
    """One text cell as :func:`csv_text` writes it (quoted only when it must be)."""
    if not text or not any(c in text for c in ',"\r\n'):
        return text
    import csv
    import io

    buffer = io.StringIO()
    csv.writer(buffer, lineterminator="\n").writerow([text, ""])
    return buffer.getvalue()[:-2]


def float_cells(values: Any) -> list[str]:
    """The cells of a float column (any array-like), each ``repr`` of the float as
    :func:`csv_text` writes it. A column of one value throughout (bit for bit: a
    sweep's exact zeros) is written once and its cell repeated."""
    import numpy as np

    a = np.ascontiguousarray(values, dtype=float).reshape(-1)
    if a.size > 1:
        bits = a.view(np.int64)
        if bits[0] == bits[-1] and bool(np.all(bits == bits[0])):
            return [repr(float(a[0]))] * a.size
    return list(map(float.__repr__, a.tolist()))


def csv_lines(columns: Sequence[Sequence[str]]) -> str:
    """CSV rows from columns of cells already written as text (:func:`csv_cell`,
    :func:`float_cells`, ``"True"``/``"False"``, ``""`` for none): the same text
    :func:`csv_text` makes row by row, at a fraction of its cost per value."""
    if not columns or not len(columns[0]):
        return ""
    return "\n".join(map(",".join, zip(*columns, strict=True))) + "\n"


def csv_head(header_row: Iterable[str]) -> str:
    """The header line of :func:`csv_text`."""
    return ",".join(csv_cell(h) for h in header_row) + "\n"


def markdown_table(header_row: list[str], rows: Iterable[list[str]]) -> str:
    """A GitHub-flavoured Markdown table."""

    def cell(text: str) -> str:
        return text.replace("|", "\\|").replace("\n", " ")

    lines = ["| " + " | ".join(cell(h) for h in header_row) + " |",
             "|" + "|".join("---" for _ in header_row) + "|"]
    lines += ["| " + " | ".join(cell(c) for c in row) + " |" for row in rows]
    return "\n".join(lines) + "\n"


#: ANSI SGR codes of the few styles the tables use.
_SGR = {"bold": "1", "dim": "2", "red": "31", "green": "32", "yellow": "33"}


def _styled(text: str, style: str | None, color: bool) -> str:
    if not color or not style or not text:
        return text
    codes = ";".join(_SGR[word] for word in style.split() if word in _SGR)
    return f"\x1b[{codes}m{text}\x1b[0m" if codes else text


class Text:
    """A line of text with one style per piece (a small subset of rich's ``Text``)."""

    def __init__(self, text: str = "", style: str | None = None) -> None:
        self.pieces: list[tuple[str, str | None]] = [(text, style)] if text else []

    def append(self, text: str, style: str | None = None) -> None:
        self.pieces.append((text, style))

    @property
    def plain(self) -> str:
        return "".join(text for text, _ in self.pieces)

    def render(self, color: bool, default: str | None = None) -> str:
        return "".join(_styled(text, style or default, color) for text, style in self.pieces)

    def __len__(self) -> int:
        return len(self.plain)


Cell = str | Text


class Table:
    """A box table rendered by hand: what rich's ``Table`` drew here, at a fraction of
    its import and per-row cost (< 10 µs a row instead of ~1 ms).

    A table wider than the page is cut into column groups stacked one under the
    other, each repeating the first (key) column; a column that is still too
    wide and may wrap has its cells wrapped.
    """

    def __init__(self, title: str | None = None, title_justify: str = "left",
                 header_style: str | None = "bold") -> None:
        self.title = title
        self.header_style = header_style
        self.columns: list[dict[str, Any]] = []
        self.rows: list[list[Cell]] = []

    def add_column(self, header: str, justify: str = "left", no_wrap: bool = False,
                   style: str | None = None, min_width: int = 0, overflow: str = "fold") -> None:
        self.columns.append({"header": header, "justify": justify, "wrap": not no_wrap,
                             "style": style, "min_width": min_width})

    def add_row(self, *cells: Cell) -> None:
        self.rows.append(list(cells))

    def render(self, width: int, color: bool) -> list[str]:
        # each cell's text and length once (a Text joins its pieces on every len())
        plain = [[c if isinstance(c, str) else c.plain for c in row] for row in self.rows]
        lengths = [[len(t) for t in row] for row in plain]
        widths = [max([len(c["header"]), c["min_width"], *(r[k] for r in lengths)])
                  for k, c in enumerate(self.columns)]
        groups = _column_groups(widths, width)
        lines: list[str] = []
        if self.title:
            lines.extend(_styled(part, "bold", color) for part in wrap(self.title, width))
        for group in groups:
            group_widths = _fit(self.columns, group, widths, width)
            lines.extend(self._render_group(group, group_widths, color, plain, lengths))
        return lines

    def _render_group(self, group: list[int], widths: dict[int, int], color: bool,
                      plain: list[list[str]], lengths: list[list[int]]) -> list[str]:
        def rule(left: str, fill: str, mid: str, right: str) -> str:
            return left + mid.join(fill * (widths[k] + 2) for k in group) + right

        columns = [self.columns[k] for k in group]

        def one_line(cells: list[Cell], edge: str, styles: list[str | None]) -> str:
            parts = []
            for k, column, style in zip(group, columns, styles, strict=True):
                cell = cells[k]
                if isinstance(cell, str):
                    pad = widths[k] - len(cell)
                    text = _styled(cell, style, color) if color else cell
                else:
                    pad = widths[k] - len(cell)
                    text = cell.render(color, style)
                justify = column["justify"]
                left = pad // 2 if justify == "center" else pad if justify == "right" else 0
                parts.append(" " * (left + 1) + text + " " * (pad - left + 1))
            return edge + edge.join(parts) + edge

        def body(cells: list[Cell], edge: str, styles: list[str | None]) -> list[str]:
            if all(len(cells[k]) <= widths[k] for k in group):
                return [one_line(cells, edge, styles)]
            split = [_wrap(cells[k], widths[k]) for k in group]
            height = max(len(v) for v in split)
            return [one_line({k: v[n] if n < len(v) else "" for k, v in
                              zip(group, split, strict=True)}, edge, styles)  # type: ignore[arg-type]
                    for n in range(height)]

        # where a row fits and takes no colour, its line from the plain texts (as one_line
        # writes it: a cell's render without colour is its plain text)
        justify = [column["justify"] for column in columns]
        width_of = [widths[k] for k in group]

        def plain_line(texts: list[str], lens: list[int]) -> str | None:
            parts = []
            for k, w, j in zip(group, width_of, justify, strict=True):
                pad = w - lens[k]
                if pad < 0:
                    return None  # wraps: the general path
                left = pad // 2 if j == "center" else pad if j == "right" else 0
                parts.append(" " * (left + 1) + texts[k] + " " * (pad - left + 1))
            return "│" + "│".join(parts) + "│"

        lines = [rule("┏", "━", "┳", "┓")]
        lines += body([c["header"] for c in self.columns], "┃",
                      [self.header_style] * len(group))
        lines.append(rule("┡", "━", "╇", "┩"))
        styles = [column["style"] for column in columns]
        for row, texts, lens in zip(self.rows, plain, lengths, strict=True):
            line = None if color else plain_line(texts, lens)
            if line is None:
                lines += body(row, "│", styles)
            else:
                lines.append(line)
        lines.append(rule("└", "─", "┴", "┘"))
        return lines


def _column_groups(widths: list[int], page: int) -> list[list[int]]:
    """Split columns 1.. into groups that fit ``page`` with column 0 repeated in each."""
    def span(ks: list[int]) -> int:
        return 1 + sum(widths[k] + 3 for k in ks)

    if span(list(range(len(widths)))) <= page or len(widths) <= 2:
        return [list(range(len(widths)))]
    groups: list[list[int]] = []
    current = [0]
    for k in range(1, len(widths)):
        if len(current) > 1 and span([*current, k]) > page:
            groups.append(current)
            current = [0]
        current.append(k)
    groups.append(current)
    return groups


def _fit(columns: list[dict[str, Any]], group: list[int], widths: list[int],
         page: int) -> dict[int, int]:
    """Column widths of one group, narrowed until it fits ``page``: the wrappable
    columns first, then, as a last resort, any but the key column (folded)."""
    fitted = {k: widths[k] for k in group}
    excess = 1 + sum(w + 3 for w in fitted.values()) - page
    for last_resort in (False, True):
        for k in sorted(group, key=lambda k: -fitted[k]):
            if excess <= 0:
                return fitted
            if columns[k]["wrap"] or (last_resort and k != group[0]):
                cut = min(excess, fitted[k] - max(8, columns[k]["min_width"]))
                if cut > 0:
                    fitted[k] -= cut
                    excess -= cut
    return fitted


def _wrap(cell: Cell, width: int) -> list[Text]:
    """``cell`` in lines of at most ``width`` characters (at spaces where it can)."""
    text = cell if isinstance(cell, Text) else Text(cell)
    if len(text) <= width:
        return [text]
    import textwrap

    style = text.pieces[0][1] if len(text.pieces) == 1 else None
    chunks = textwrap.wrap(text.plain, width, break_long_words=True) or [""]
    return [Text(chunk, style) for chunk in chunks]


def wrap(text: str, width: int) -> list[str]:
    """``textwrap.wrap(text, width) or [""]``; a text that fits as it is (no leading or
    trailing whitespace, no tab or line break) is its own single line without
    textwrap's splitting (~40 µs a call, every table title)."""
    if len(text) <= width and text.isprintable() and text == text.strip():
        return [text]
    import textwrap

    return textwrap.wrap(text, width) or [""]


def rich_text(renderables: Iterable[Table | Text], width: int | None = None,
              color: bool = False, ascii: bool = False) -> str:
    """Render tables and lines of text to a string ``width`` columns wide (160 unless
    given); a line of text longer than that is wrapped at spaces. ``ascii``: only
    ASCII characters (:func:`to_ascii`), laid out after the transliteration."""
    page = max(width or 160, 40)
    lines: list[str] = []
    for item in renderables:
        if ascii:
            item = _ascii_item(item)
        if isinstance(item, Table):
            lines.extend(item.render(page, color))
            continue
        if len(item) <= page:
            lines.append(item.render(color))
            continue
        style = item.pieces[0][1] if item.pieces else None
        lines.extend(_styled(chunk, style, color) for chunk in wrap(item.plain, page))
    text = "\n".join(lines) + "\n"
    return to_ascii(text) if ascii else text


def _ascii_item(item: Table | Text) -> Table | Text:
    def text(cell: Cell) -> Text:
        out = Text()
        for piece, style in (cell.pieces if isinstance(cell, Text) else [(cell, None)]):
            out.append(to_ascii(piece), style)
        return out

    if isinstance(item, Text):
        return text(item)
    table = Table(title=None if item.title is None else to_ascii(item.title),
                  header_style=item.header_style)
    table.columns = [{**c, "header": to_ascii(c["header"])} for c in item.columns]
    table.rows = [[text(c) for c in row] for row in item.rows]
    return table




#: What each non-ASCII character of the renderers becomes on a stream that
#: cannot encode it (PYTHONIOENCODING=ascii, old consoles).
_ASCII = str.maketrans({
    "Δ": "Delta", "Ω": "Omega", "σ": "sigma", "µ": "u", "μ": "u", "±": "+/-", "∞": "inf",
    "✓": "v", "✗": "x", "⚠": "!", "²": "^2", "³": "^3", "×": "x", "·": "*", "≤": "<=",
    "≥": ">=", "≈": "~", "—": "--", "–": "-", "…": "...", "→": "->", "’": "'", "‘": "'",
    "“": '"', "”": '"', "°": "deg", "√": "sqrt", "∫": "int", "π": "pi", "α": "alpha",
    "β": "beta", "₀": "0", "₁": "1", "₂": "2", "₃": "3", "₄": "4", "₅": "5",
    "┏": "+", "┳": "+", "┓": "+", "┡": "+", "╇": "+", "┩": "+", "└": "+", "┴": "+",
    "┘": "+", "┃": "|", "│": "|", "━": "=", "─": "-",
})


def to_ascii(text: str) -> str:
    """``text`` in ASCII: ``Δ_V`` → ``Delta_V``, box lines → ``+ - = |``, ticks → ``v``/``x``;
    any other character outside ASCII becomes ``?``."""
    return text.translate(_ASCII).encode("ascii", "replace").decode("ascii")
