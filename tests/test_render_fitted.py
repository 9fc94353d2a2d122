"""The tables' fast path (render.common: cells laid out before rich draws them,
``padding=0``) against rich drawing the same table itself with its one space of
padding: the same characters, and in colour the same style on every character."""

from __future__ import annotations

import io

import pytest
from rich import box
from rich.console import Console
from rich.table import Table
from rich.text import Text

from gyrovib.render.common import rich_text

HEADERS = ("sensor", "Δ_VA", "Δ_V", "note", "flag")
JUSTIFY = ("default", "right", "right", "center", "left")
STYLES = (None, None, "bold", "dim", None)


def _cells() -> list[list[Text]]:
    name = Text("adxrs453")
    name.append(" ⚠1", style="yellow")
    odd = Text("x", style="red")  # a base style, no span
    underlined = Text("u", style="underline")  # a style that shows on spaces
    return [[name, Text("1.234e-05", style="green"), Text("−0.5"), Text("ok"), underlined],
            [Text("g", style="blue"), Text("12"), Text("3.14159"), odd, Text("yes")],
            [Text("mems-Ω"), Text("0"), Text("-"), Text("a longer note"), Text("")]]


def _ours(color: bool) -> str:
    table = Table()
    for h, j, s in zip(HEADERS, JUSTIFY, STYLES, strict=True):
        table.add_column(h, justify=j, style=s, no_wrap=True)  # type: ignore[arg-type]
    for row in _cells():
        table.add_row(*row)
    return rich_text([table], width=160, color=color)


def _riches(color: bool) -> str:
    """The same table drawn by rich alone, as render.common drew it before."""
    out = io.StringIO()
    console = Console(file=out, width=160, height=25,
                      color_system="standard" if color else None, force_terminal=color,
                      force_jupyter=False, force_interactive=False, no_color=False,
                      legacy_windows=False, markup=False, emoji=False, highlight=False,
                      soft_wrap=False, _environ={})
    cells = _cells()
    table = Table(box=box.HEAVY_HEAD, show_edge=True, pad_edge=True, collapse_padding=False,
                  header_style="bold", highlight=False)
    for k, (h, j, s) in enumerate(zip(HEADERS, JUSTIFY, STYLES, strict=True)):
        width = max(len(h), *(row[k].cell_len for row in cells))
        table.add_column(Text(h), justify=j, style=s, no_wrap=True,  # type: ignore[arg-type]
                         overflow="fold", width=width)
    for row in cells:
        table.add_row(*row)
    console.print(table)
    return out.getvalue()


def _styled_chars(ansi: str) -> list[tuple[str, str]]:
    console = Console(width=400, color_system="standard", force_terminal=True)
    chars = []
    for line in ansi.split("\n"):
        for seg in Text.from_ansi(line).render(console):
            chars.extend((c, str(seg.style or "")) for c in seg.text)
        chars.append(("\n", ""))
    return chars


def test_same_characters_as_rich_padding() -> None:
    assert _ours(color=False) == _riches(color=False)


@pytest.mark.parametrize("color", [True])
def test_same_style_on_every_character(color: bool) -> None:
    ours, riches = _ours(color), _riches(color)
    assert "\x1b[" in ours
    assert _styled_chars(ours) == _styled_chars(riches)
    # not vacuous: bold, dim, underline and colours were drawn
    assert len({style for _, style in _styled_chars(ours)}) >= 6
