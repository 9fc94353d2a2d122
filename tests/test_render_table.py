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

from gyrovib import api
from gyrovib.catalog.loader import merge, parse_catalog
from gyrovib.formatting import fmt
from gyrovib.render import analysis as render
from gyrovib.render.common import Table, Text, rich_text, wrap
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
        cells = ["0" if math.isfinite(v) and abs(v) < 1e-12 * scale else fmt(v)
                 for v in values]
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
    # "small" (range 10 deg/h) saturates under the 20000 deg/h tone (MODEL.md section 9)
    result = results()[0]
    assert result.saturated is not None and result.saturated[0, 0]
    lines = [ln for ln in render.to_table(result, width=400, detail=True).splitlines()
             if ln.startswith("│")]
    marked = [ln.split("│")[1].strip() for ln in lines if render.SATURATED_MARK in ln]
    expected = [s for j in range(len(result.profiles)) for i, s in enumerate(result.sensors)
                if result.saturated[i, j]]
    assert [m.split()[0] for m in marked] == expected


def test_nan_and_infinite_values_print_as_fmt_writes_them() -> None:
    result = results()[0]
    e = result.error
    total = np.array(e.total)
    total[0, 0], total[1, 0] = np.nan, -np.inf
    odd = dataclasses.replace(result, error=dataclasses.replace(e, total=total))
    found = table_rows(render.to_table(odd, width=400, detail=True))
    assert found[0][0][-2] == "nan" and found[0][1][-2] == "-∞"


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
    # Without colour a row that fits is written from its plain texts; with colour every
    # row goes through the general path. Colour only adds SGR codes around texts, so
    # the coloured table without its codes is the reference for the plain one.
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


@settings(deadline=None, max_examples=1000)
@given(st.text(alphabet="ab Δ-.\t\n\r\x0b\x0c\xa0\u2003", max_size=40), st.integers(1, 45))
def test_wrap_is_textwrap(text: str, width: int) -> None:
    # render.common.wrap skips textwrap for a text that fits as it is; the reference
    # is textwrap itself (an empty result read as one empty line)
    import textwrap

    assert wrap(text, width) == (textwrap.wrap(text, width) or [""])
