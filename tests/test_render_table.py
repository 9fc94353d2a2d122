"""The analyze table's cells are the per-element values of the result, formatted.

``to_table`` reads its numbers from nested lists (one ``tolist`` per array, for
speed); the reference here indexes the numpy arrays of the result one element at
a time, as the renderer did before, and formats each with :func:`fmt`.
"""

from __future__ import annotations

import dataclasses
import math
import re

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from rich.table import Table
from rich.text import Text

from gyrovib import api
from gyrovib.catalog.loader import merge, parse_catalog
from gyrovib.formatting import fmt
from gyrovib.render import analysis as render
from gyrovib.render.common import column_groups, rich_text
from tests.conftest import MIXED_FORMS

# the renderers' catalogue and a locked group (its odd-moment columns)
CATALOG = MIXED_FORMS + """  - id: shaft
    rate: [0, 0, 1]
    harmonics:
      fundamental: 50
      orders:
        - {order: 1, amplitude: [0.5, 0.3, 1.5], phase: [0, 90, 0]}
        - {order: 2, amplitude: [0.2, 0.2, 0.8], phase: [0, 0, 270]}
"""


def expected_rows(result: api.AnalysisResult, j: int) -> list[list[str]]:
    """Per sensor, the cells after the name: shown terms, Δ_VA, Δ_VM, Δ_V, [stderr], RMS."""
    e = result.error
    odd = bool(result.locked[j]) if result.locked else False
    rows = []
    for i in range(len(result.sensors)):
        values = [*render._terms(result, i, j, odd), float(e.additive[i, j]),
                  float(e.multiplicative[i, j]), float(e.total[i, j]), float(e.rms[i, j])]
        # a value below 1e-12 of the row's largest finite one is rounding noise: "0"
        scale = max((abs(v) for v in values if math.isfinite(v)), default=0.0)
        # NaN, unknown, reads "?" (never 'nan' or 0)
        cells = ["?" if v != v else "0" if math.isfinite(v) and abs(v) < 1e-12 * scale
                 else fmt(v) for v in values]
        if render.unknown_term(result, i, j):
            # the g² term of a sensor whose g² figure is unknown reads "?", not 0 (the
            # unknown-figure notes of gyrovib.api.datasheet.specs), and so do Δ_VA, Δ_V
            # and Δ_V(RMS), which hold it
            at = [t for k, t in enumerate(render.JSON_TERMS)
                  if k in render._shown(bool(result.has_linear), odd)].index("g2")
            assert [cells[k] for k in (at, -4, -2, -1)] == ["?"] * 4
        if result.stderr is not None:
            cells.insert(-1, fmt(result.stderr[i, j], 2))
        rows.append(cells)
    return rows


def table_rows(text: str) -> list[list[list[str]]]:
    """Per table, per body row, the cells after the name column."""
    tables: list[list[list[str]]] = []
    for line in text.splitlines():
        if line.startswith("┡"):
            tables.append([])
        elif line.startswith("│"):
            tables[-1].append([c.strip() for c in line.strip("│").split("│")][1:])
    return tables


def results() -> list[api.AnalysisResult]:
    catalog = merge([parse_catalog(CATALOG, "cat.yaml")])
    exact = api.analyze(catalog, unit="deg/s")
    numeric = api.analyze(catalog, method="numeric", samples=2000, unit="deg/h")
    return [exact, numeric, api.analyze(api.load())]


@pytest.mark.parametrize("index", [0, 1, 2], ids=["exact", "numeric", "bundled"])
def test_cells_are_the_formatted_values(index: int) -> None:
    result = results()[index]
    text = render.to_table(result, width=400, detail=True)
    found = table_rows(text)
    assert len(found) == len(result.profiles)
    for j in range(len(result.profiles)):
        assert found[j] == expected_rows(result, j)


def test_saturated_rows_are_marked() -> None:
    # "small" (range 10 deg/h) saturates under the 20000 deg/h tone (docs/model.md section 9)
    result = results()[0]
    assert result.saturated is not None and result.saturated[0, 0]
    lines = [ln for ln in render.to_table(result, width=400, detail=True).splitlines()
             if ln.startswith("│")]
    marked = [ln.split("│")[1].strip() for ln in lines if render.SATURATED_MARK in ln]
    expected = [s for j in range(len(result.profiles)) for i, s in enumerate(result.sensors)
                if result.saturated[i, j]]
    assert [m.split()[0] for m in marked] == expected


def test_nan_and_infinite_values_print_as_unknown_and_as_fmt_writes_them() -> None:
    # NaN is an unknown error (a profile fitted from a recording without an axis the
    # sensor needs, docs/model.md section 13): '?', never 'nan' or 0; -inf as fmt writes it
    result = results()[0]
    e = result.error
    total = np.array(e.total)
    total[0, 0], total[1, 0] = np.nan, -np.inf
    odd = dataclasses.replace(result, error=dataclasses.replace(e, total=total))
    found = table_rows(render.to_table(odd, width=400, detail=True))
    assert found[0][0][-2] == "?" and found[0][1][-2] == "-∞"


# ---------------------------------------------------------------- the Table itself

_SGR = re.compile("\x1b\\[[0-9;]*m")
WORDS = st.text(alphabet="abc Δ±1.-", min_size=0, max_size=14)


@st.composite
def tables(draw: st.DrawFn) -> Table:
    n_columns = draw(st.integers(1, 5))
    table = Table(title=draw(st.one_of(st.none(), WORDS)))
    for _ in range(n_columns):
        table.add_column(draw(WORDS), justify=draw(st.sampled_from(["left", "right", "center"])),
                         no_wrap=draw(st.booleans()), style=draw(st.sampled_from([None, "bold"])),
                         min_width=draw(st.integers(0, 6)))
    for _ in range(draw(st.integers(0, 6))):
        cells: list[str | Text] = []
        for _ in range(n_columns):
            if draw(st.booleans()):
                cells.append(draw(WORDS))
            else:
                text = Text(draw(WORDS))
                text.append(draw(WORDS), style=draw(st.sampled_from([None, "yellow", "bold red"])))
                cells.append(text)
        table.add_row(*cells)
    return table


@settings(deadline=None, max_examples=300)
@given(tables(), st.integers(40, 120))
def test_plain_rows_are_the_coloured_rows_without_colour(table: Table, width: int) -> None:
    # Colour only adds SGR codes around texts (rich's "standard" colour system), never
    # moves a character: the coloured table without its codes is the plain one.
    plain = rich_text([table], width=width, color=False)
    coloured = rich_text([table], width=width, color=True)
    assert "\x1b" not in plain
    assert _SGR.sub("", coloured) == plain


@settings(deadline=None, max_examples=500)
@given(st.floats(allow_nan=True, allow_infinity=True), st.integers(1, 20))
def test_fmt_is_its_definition(value: float, digits: int) -> None:
    # the definition of gyrovib.formatting.fmt: `digits` significant figures,
    # ∞/-∞ for infinities, nan, and 0 for either zero
    if math.isinf(value):
        expected = "∞" if value > 0 else "-∞"
    elif math.isnan(value):
        expected = "nan"
    elif value == 0:
        expected = "0"
    else:
        expected = f"{value:.{digits}g}"
    assert fmt(value, digits) == expected
    assert fmt(np.float64(value), digits) == expected


# ---------------------------------------------------------------- drawn by rich


def test_ascii_table_is_richs_ascii_box() -> None:
    # rich.box.ASCII, as rich/box.py defines it ("+--+", "| ||", "|-+|", ... "+--+"):
    # no column divider on the top and bottom lines, "|-+|" under the header. The
    # texts are transliterated first (Δ -> Delta, ± -> +/-), so the widths are theirs.
    table = Table()
    table.add_column("a")
    table.add_column("Δ")
    table.add_row("x", Text("±", style="red"))
    assert rich_text([table], ascii=True) == (
        "+-----------+\n"
        "| a | Delta |\n"
        "|---+-------|\n"
        "| x | +/-   |\n"
        "+-----------+\n")
    # and the heavy head (rich.box.HEAVY_HEAD) on a UTF-8 stream, as README.md shows
    assert rich_text([table]) == (
        "┏━━━┳━━━┓\n"
        "┃ a ┃ Δ ┃\n"
        "┡━━━╇━━━┩\n"
        "│ x │ ± │\n"
        "└───┴───┘\n")


def test_ascii_keeps_each_pieces_style() -> None:
    # "⚠1" becomes "!1" and keeps its yellow (SGR 33); "Δ" becomes "Delta", unstyled
    name = Text("Δ")
    name.append(" ⚠1", style="yellow")
    table = Table()
    table.add_column("sensor")
    table.add_row(name)
    text = rich_text([table], ascii=True, color=True)
    assert text.isascii()
    assert "Delta\x1b[33m !1\x1b[0m" in text


def test_color_ignores_the_environment(monkeypatch: pytest.MonkeyPatch) -> None:
    # the CLI decides (resolve_color: --color beats NO_COLOR/FORCE_COLOR, TERM=dumb plain);
    # rich must not second-guess it from the same variables, nor take COLUMNS as width
    table = Table()
    table.add_column("h", style="bold")
    table.add_row("v")
    for env in ({"NO_COLOR": "1", "TERM": "dumb", "COLUMNS": "50"},
                {"FORCE_COLOR": "1", "TERM": "xterm-256color", "COLUMNS": "50"}):
        with monkeypatch.context() as m:
            for key, value in env.items():
                m.setenv(key, value)
            coloured = rich_text([table, Text("w " * 40)], width=60, color=True)
            plain = rich_text([table, Text("w " * 40)], width=60, color=False)
        # the column's bold: SGR 1 (the cell's padding spaces are bold too, drawn in the
        # same escape as the value or apart)
        assert re.search(r"\x1b\[1m ?v ?\x1b\[0m", coloured)
        assert "\x1b" not in plain
        assert max(len(line) for line in plain.splitlines()) == 59  # 60, not COLUMNS=50
        assert _SGR.sub("", coloured) == plain


def test_column_groups_by_hand() -> None:
    # a heavy box with one space of padding is 1 + Σ (width + 3) wide: the key (6) and
    # ten columns of 9 fit 80 five at a time (1 + 9 + 5·12 = 70; six: 82)
    widths = [6] + [9] * 10
    assert column_groups(widths, 80) == [[0, 1, 2, 3, 4, 5], [0, 6, 7, 8, 9, 10]]
    assert column_groups(widths, 1 + 9 + 10 * 12) == [list(range(11))]
    # a key and one column wider than the page stay a group (rich narrows it)
    assert column_groups([6, 100, 3], 80) == [[0, 1], [0, 2]]
    assert column_groups([6, 100], 80) == [[0, 1]]


def test_wide_table_is_sliced_at_80_columns() -> None:
    table = Table(title="wide")
    table.add_column("sensor", no_wrap=True)
    for k in range(10):
        table.add_column(f"c{k}", justify="right", no_wrap=True)
    table.add_row("s1", *(f"{k}.000e-05" for k in range(10)))  # 9 wide, as by hand above
    table.add_row("s2", *(f"-{k}.00e-05" for k in range(10)))
    lines = rich_text([table], width=80).splitlines()
    assert lines[0] == "wide"
    heads = [line for line in lines if line.startswith("┃ sensor")]
    assert len(heads) == 2  # [0, 1..5] and [0, 6..10]
    assert heads[0].split("┃")[2:-1] == [f"        c{k} " for k in range(5)]
    assert heads[1].split("┃")[2:-1] == [f"        c{k} " for k in range(5, 10)]
    assert max(len(line) for line in lines) == 1 + 9 + 5 * 12 == 70
    body = [line for line in lines if line.startswith("│")]
    assert [line.split("│")[1] for line in body] == [" s1     ", " s2     "] * 2
    for k in range(10):  # every value whole, in its group
        assert f" {k}.000e-05 " in body[k // 5 * 2] and f" -{k}.00e-05 " in body[k // 5 * 2 + 1]


def test_display_width_not_len() -> None:
    from rich.cells import cell_len

    # 日本語: 3 characters, 6 columns (East Asian Wide); "e" + U+0301 (combining acute):
    # 2 characters, 1 column. A table laid out by len() would be ragged.
    table = Table()
    table.add_column("名前")
    table.add_column("x", justify="right")
    for name in ("日本語", "e\u0301", "abc"):
        table.add_row(name, "1")
    lines = rich_text([table]).splitlines()
    assert {cell_len(line) for line in lines} == {1 + (6 + 3) + (1 + 3)}
    assert len({len(line) for line in lines}) > 1  # the characters differ, the columns not
    assert "│ e\u0301      │ 1 │" in lines and "│ 日本語 │ 1 │" in lines
    # and the slicing measures display columns too: ten columns of 漢字漢字 (8 wide,
    # 4 long) do not fit 80 together (1 + 4 + 10·11 = 115; by len() 1 + 4 + 10·7 = 75
    # would fit), six at a time do (1 + 4 + 6·11 = 71; seven: 82)
    wide = Table()
    wide.add_column("k")
    for k in range(10):
        wide.add_column(f"h{k}")
    wide.add_row("r", *["漢字漢字"] * 10)
    lines = rich_text([wide], width=80).splitlines()
    assert sum(1 for line in lines if line.startswith("┃ k")) == 2
    assert max(cell_len(line) for line in lines) == 1 + 4 + 6 * 11
    assert [line.count("漢字漢字") for line in lines if line.startswith("│ r")] == [6, 4]
