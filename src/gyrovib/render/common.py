"""Helpers shared by the renderers."""

from __future__ import annotations

import csv
import io
import itertools
import math
from collections.abc import Callable, Iterable, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from gyrovib._version import __version__
from gyrovib.formatting import NEGLIGIBLE as NEGLIGIBLE
from gyrovib.formatting import fmt as fmt

if TYPE_CHECKING:  # at run time rich is imported inside the functions that draw
    from rich.console import Console, ConsoleOptions
    from rich.measure import Measurement
    from rich.segment import Segment
    from rich.table import Table as Table
    from rich.text import Text as Text


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
    """:func:`fmt`, but ``0`` for |value| below :data:`NEGLIGIBLE` × the budget, and '?' for
    NaN, an unknown value (tables only)."""
    if value is not None and value != value:
        return "?"
    if (value is not None and budget is not None and budget > 0 and math.isfinite(value)
            and abs(value) < NEGLIGIBLE * budget):
        return "0"
    return fmt(value, digits)


def csv_text(header_row: Iterable[str], rows: Iterable[Iterable[Any]]) -> str:
    """CSV with a header row, numbers written with full precision."""
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(list(header_row))
    for row in rows:
        # None and NaN (unknown) are empty cells, never 'nan' or 0
        writer.writerow(["" if x is None or x != x else (repr(x) if isinstance(x, float)
                                                          else x) for x in row])
    return buffer.getvalue()


def csv_cell(text: str) -> str:
    """One text cell as :func:`csv_text` writes it (quoted only when it must be)."""
    if not text or not any(c in text for c in ',"\r\n'):
        return text
    buffer = io.StringIO()
    csv.writer(buffer, lineterminator="\n").writerow([text, ""])
    return buffer.getvalue()[:-2]


def float_cells(values: Any) -> list[str]:
    """The cells of a float column (any array-like), each ``repr`` of the float as
    :func:`csv_text` writes it. A column of one value throughout (bit for bit: a
    sweep's exact zeros) is written once and its cell repeated."""
    a = np.ascontiguousarray(values, dtype=float).reshape(-1)
    if a.size > 1:
        bits = a.view(np.int64)
        if bits[0] == bits[-1] and bool(np.all(bits == bits[0])):
            return ["" if a[0] != a[0] else repr(float(a[0]))] * a.size
    cells = list(map(float.__repr__, a.tolist()))
    if np.isnan(a).any():  # unknown: an empty cell, as csv_text writes it
        cells = ["" if c == "nan" else c for c in cells]
    return cells


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


def html_table(head: Iterable[str], rows: Iterable[Sequence[str]], raw: bool = False,
               caption: str | None = None) -> str:
    """An HTML table under its ``caption``; cells are escaped unless ``raw`` (then each
    row's cells are HTML already)."""
    from html import escape

    # the caption is element text: quotes need no escaping there
    out = ["<table>", *([f"<caption>{escape(caption, quote=False)}</caption>"] if caption
                        else []),
           "<thead><tr>", *(f"<th>{escape(h)}</th>" for h in head), "</tr></thead><tbody>"]
    for row in rows:
        out.append("<tr>" + "".join(c if raw else f"<td>{escape(c)}</td>" for c in row)
                   + "</tr>")
    out.append("</tbody></table>")
    return "".join(out)


class _Page(io.StringIO):
    """A text buffer that tells rich which encoding its output is for (``ascii``:
    rich then draws ``box.ASCII`` instead of the heavy box)."""

    def __init__(self, encoding: str) -> None:
        super().__init__()
        self._encoding = encoding

    @property
    def encoding(self) -> str:  # type: ignore[override]  # StringIO's is None, read-only
        return self._encoding


def rich_text(renderables: Iterable[Table | Text], width: int | None = None,
              color: bool = False, ascii: bool = False) -> str:
    """Tables and lines of text drawn by rich into a string ``width`` columns wide
    (160 unless given; display columns, :func:`rich.cells.cell_len`).

    A table wider than the page is cut into column groups stacked one under the
    other, each repeating the first (key) column (:func:`column_groups`); rich draws
    each group, narrowing (folding) a column only when one group alone is wider
    than the page. A table's title is a bold line above its first group; a line of
    text longer than the page is wrapped at spaces. ``color``: ANSI styles (bold,
    dim, red, green, yellow), nothing else. ``ascii``: only ASCII characters: the
    texts transliterated (:func:`to_ascii`) before the layout, the box drawn by
    rich's ASCII fallback.
    """
    # lazy: rich only draws tables; csv and json output never load it
    from rich.console import Console
    from rich.table import Table

    page = max(width or 160, 40)
    out = _Page("ascii" if ascii else "utf-8")
    # every setting given, so that no environment variable (COLUMNS, NO_COLOR,
    # FORCE_COLOR, TERM) changes what the CLI's own rules decided
    console = Console(file=out, width=page, height=25, color_system="standard" if color else None,
                      force_terminal=color, force_jupyter=False, force_interactive=False,
                      no_color=False, legacy_windows=False, markup=False, emoji=False,
                      highlight=False, soft_wrap=False, _environ={})
    cell = _ascii_cell if ascii else _cell
    for item in renderables:
        if isinstance(item, Table):
            if item.title:
                _print_lines(console, _styled_title(cell(item.title)), page)
            for group in _groups(item, page, cell):
                console.print(group)
        else:
            _print_lines(console, cell(item), page)
    text = out.getvalue()
    return to_ascii(text) if ascii else text


def _cell(value: Any) -> Text:
    """A cell as rich ``Text`` (a ``str`` taken literally: no markup, no highlighting)."""
    # lazy: rich only draws tables; csv and json output never load it
    from rich.text import Text

    return value if isinstance(value, Text) else Text(str(value))


def _ascii_cell(value: Any) -> Text:
    """:func:`_cell` transliterated by :func:`to_ascii`, each styled piece keeping its style."""
    # lazy: rich only draws tables; csv and json output never load it
    from rich.text import Text

    text = _cell(value)
    plain = text.plain
    if plain.isascii():
        return text
    spans = text.spans
    cuts = sorted({0, len(plain), *(s.start for s in spans), *(s.end for s in spans)})
    out = Text(style=text.style, justify=text.justify, overflow=text.overflow,
               no_wrap=text.no_wrap, end=text.end)
    for a, b in itertools.pairwise(cuts):
        styles = [str(s.style) for s in spans if s.start <= a and b <= s.end]
        out.append(to_ascii(plain[a:b]), style=" ".join(styles) or None)
    return out


def _print_lines(console: Console, text: Text, page: int) -> None:
    """``text`` wrapped at spaces to ``page`` columns, no line ending in a space."""
    if text.cell_len <= page and "\n" not in text.plain:
        console.print(text)
        return
    for line in text.wrap(console, page, overflow="fold"):
        line.rstrip()
        console.print(line)


def _styled_title(title: Text) -> Text:
    title = title.copy()
    title.stylize("bold")
    return title


def _measured(table: Table, cell: Callable[[Any], Text]
              ) -> tuple[list[Text], list[list[Text]], list[int], bool]:
    """The headers and cells of ``table`` as texts, each column's width, and whether
    every cell is on one line (no line break, no tab)."""
    columns = table.columns
    headers = [cell(c.header) for c in columns]
    cells = [[cell(x) for x in c.cells] for c in columns]
    widths = [max([h.cell_len, c.min_width or 0, *(x.cell_len for x in column)])
              for h, c, column in zip(headers, columns, cells, strict=True)]
    one_line = all("\n" not in t.plain and "\t" not in t.plain
                   for t in itertools.chain(headers, *cells))
    return headers, cells, widths, one_line


def _wrapping(table: Table, group: list[int], headers: list[Text], cells: list[list[Text]],
              widths: list[int], squeezed: bool) -> Table:
    """The columns ``group`` of ``table`` as a rich table that may wrap its cells; a
    ``squeezed`` group (wider than the page) may wrap any column but the key."""
    # lazy: rich only draws tables; csv and json output never load it
    from rich import box
    from rich.table import Table

    part = Table(box=box.HEAVY_HEAD, show_edge=True, pad_edge=True, collapse_padding=False,
                 header_style=table.header_style or "bold", highlight=False)
    for k in group:
        c = table.columns[k]
        part.add_column(headers[k], justify=c.justify, style=c.style,
                        no_wrap=c.no_wrap and not (squeezed and k != group[0]),
                        overflow="fold", min_width=c.min_width,
                        # a group that fits: its widths measured here once, not by rich
                        width=None if squeezed else widths[k])
    for row in zip(*(cells[k] for k in group), strict=True):
        part.add_row(*row)
    return part


def _groups(table: Table, page: int, cell: Callable[[Any], Text]) -> list[Table]:
    """``table`` as rich tables of today's look, one per column group that fits ``page``."""
    headers, cells, widths, one_line = _measured(table, cell)
    drawn = []
    for group in column_groups(widths, page):
        # a group still wider than the page (the key and one wide column) may wrap any
        # column but the key, so that rich narrows those and crops no value
        squeezed = 1 + sum(widths[k] + 3 for k in group) > page
        # every cell on one line: the cells of a group that fits can be handed to rich
        # already padded (:func:`_fitted`)
        if one_line and not squeezed:
            drawn.append(_fitted(table, group, headers, cells, widths))
        else:
            drawn.append(_wrapping(table, group, headers, cells, widths, squeezed))
    return drawn


def _fitted(table: Table, group: list[int], headers: list[Text], cells: list[list[Text]],
            widths: list[int]) -> Table:
    """The columns ``group`` of ``table`` as a rich table whose cells are already
    ``widths`` wide and carry their one space of padding each side (``padding=0``).

    The same characters and styles as the table with rich's padding, drawn in about
    two thirds of the time: rich's ``Padding`` around every cell (a render of its
    own, with line splitting and cropping, per cell) is what is saved; rich still
    lays out the box, the rows and the styles. Only for single-line cells in a
    group that fits the page (nothing to wrap)."""
    # lazy: rich only draws tables; csv and json output never load it
    from rich import box
    from rich.table import Table

    part = Table(box=box.HEAVY_HEAD, show_edge=True, padding=0, collapse_padding=False,
                 header_style=table.header_style or "bold", highlight=False)
    columns = table.columns
    for k in group:
        c = columns[k]
        part.add_column(_Line(_pad(headers[k], widths[k], c.justify)), justify="left",
                        style=c.style, no_wrap=True, overflow="fold", width=widths[k] + 2)
    for row in zip(*([_Line(_pad(x, widths[k], columns[k].justify)) for x in cells[k]]
                     for k in group), strict=True):
        part.add_row(*row)
    return part


class _Line:
    """A cell already laid out (:func:`_pad`: one line, exactly its column's width),
    handed to rich through its console protocol: rich renders the text's styled
    segments (``Text.render``) without wrapping and justifying it again."""

    __slots__ = ("text",)

    def __init__(self, text: Text) -> None:
        self.text = text

    def __rich_console__(self, console: Console, options: ConsoleOptions) -> Iterable[Segment]:
        return self.text.render(console)

    def __rich_measure__(self, console: Console, options: ConsoleOptions) -> Measurement:
        # lazy: rich only draws tables; csv and json output never load it
        from rich.measure import Measurement

        width = self.text.cell_len
        return Measurement(width, width)


def _pad(text: Text, width: int, justify: str) -> Text:
    """``text`` justified in ``width`` cells with one space each side, as rich lays it
    out: the two spaces of padding unstyled, the text's spans kept, and its base style
    kept as a span, over the justification's fill too when rich's justify pads the
    text itself ("left", "right", "center"; "default" pads outside it)."""
    # lazy: rich only draws tables; csv and json output never load it
    from rich.text import Text

    gap = width - text.cell_len
    left = gap if justify == "right" else gap // 2 if justify == "center" else 0
    if not text.spans and not text.style:
        return Text(" " * (1 + left) + text.plain + " " * (1 + gap - left), end="")
    fill = text.style if justify in ("left", "right", "center") else None
    out = Text(" ", end="")
    out.append(" " * left, style=fill)
    out.append_text(text)
    out.append(" " * (gap - left), style=fill)
    out.append(" ")
    return out


def column_groups(widths: Sequence[int], page: int) -> list[list[int]]:
    """The column groups of a table whose columns are ``widths`` display columns wide:
    columns 1.. split, in order, into groups that fit ``page`` with column 0 (the key)
    repeated in each. A group of the key and one column is kept even when wider
    than the page (rich then narrows it). A table of a heavy box with cells padded
    by one space is ``1 + Σ (width + 3)`` wide."""
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


def png(fig: Any, **savefig: Any) -> bytes:
    """The PNG bytes of a matplotlib figure (``savefig``'s keywords)."""
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", **savefig)
    return buffer.getvalue()


def pyplot() -> Any:
    """matplotlib.pyplot on the Agg backend, imported only when a plot is asked for
    (matplotlib is optional: ``pip install 'gyrovib[plot]'``)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt
