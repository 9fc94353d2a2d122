"""Streamed output: documents written in pieces are the same text as written whole,
column-wise CSV is the csv module's text, and a refusal of the exact method in a
sweep is an error at the profile, not an empty column."""

from __future__ import annotations

import csv
import io
import json
import sys
import textwrap
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gyrovib import api
from gyrovib.catalog.loader import merge, parse_catalog
from gyrovib.cli.options import as_options
from gyrovib.errors import ModelError
from gyrovib.render import select as render_select
from gyrovib.render import sweep as render_sweep
from gyrovib.render.common import csv_cell, float_cells
from tests.conftest import invoke

# ---------------------------------------------------------------- references


def select_document(result: api.SelectionResult) -> str:
    """``select --format json`` built in one piece: every sensor's entry a dict made from
    the declared records (json_of, one dict per sensor and per sensor × profile) and
    json.dumps of the whole document."""
    from gyrovib.api.evaluation.records import selection_records
    from gyrovib.render.formats import json_of

    sensors = json_of(selection_records(result), range(len(result.sensors)))
    document = json.loads(render_select.to_json(result))  # the other fields, as written
    document["sensors"] = sensors
    return json.dumps(document, allow_nan=False) + "\n"


def csv_reference(head: list[str], rows: list[list[Any]]) -> str:
    """What the csv module writes: floats as repr, None and NaN (unknown) as an empty
    cell."""
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(head)
    for row in rows:
        writer.writerow(["" if x is None or x != x else repr(x) if isinstance(x, float)
                         else x for x in row])
    return buffer.getvalue()


# ---------------------------------------------------------------- select JSON


@pytest.mark.parametrize("criterion", ["bounds", "rms", "both"])
def test_select_json_in_blocks_is_the_whole_document(criterion: str,
                                                     monkeypatch: pytest.MonkeyPatch) -> None:
    # blocks of 2 sensors over the bundled catalogues: several blocks, the last short;
    # budgets that make some sensors pass and some fail, and some bounds unconstrained
    # (null in the text)
    monkeypatch.setattr(render_select, "_BLOCK", 2)
    catalog = api.load()
    for budget in (1e-4, 0.05):
        result = api.select(catalog, budget=budget, criterion=criterion)
        chunks = list(render_select.to_json_chunks(result))
        assert len(chunks) == 2 + -(-len(result.sensors) // 2)
        assert "".join(chunks) == render_select.to_json(result) == select_document(result)


# ---------------------------------------------------------------- CSV by columns


@settings(deadline=None, max_examples=200)
@given(st.text(alphabet=st.sampled_from('ab ,"\r\n;é\t'), max_size=8))
def test_csv_cell_quotes_as_the_csv_module(text: str) -> None:
    assert "x," + csv_cell(text) + ",y\n" == csv_reference(["x", text, "y"], [])


def csv_lines(columns: list[list[str]]) -> str:
    """CSV rows from columns of cells already written as text, column-wise."""
    return "\n".join(map(",".join, zip(*columns, strict=True))) + "\n"


@settings(deadline=None, max_examples=200)
@given(st.lists(st.floats(allow_nan=True, allow_infinity=True), min_size=1, max_size=20))
def test_float_cells_and_csv_lines_write_what_the_csv_module_writes(values: list[float]
                                                                   ) -> None:
    names = [f"s{k}" for k in range(len(values))]
    text = "h\n" + csv_lines([[csv_cell(n) for n in names], float_cells(np.array(values))])
    assert text == csv_reference(["h"], [[n, v] for n, v in zip(names, values, strict=True)])


def test_sweep_csv_is_the_csv_modules_text_row_by_row() -> None:
    # the bundled catalogues: two profiles the paper refuses (empty cells), 9 sensors
    result = api.sweep(api.load(), api.rate_range(-150.0, 150.0, 31))
    assert result.paper_refused
    # adis16460 (range 100 deg/s) saturates at the outer rates: a True column cell
    assert result.saturated is not None and result.saturated.any()
    rows = []
    for j, profile in enumerate(result.profiles):
        refused = profile in result.paper_refused
        for i, sensor in enumerate(result.sensors):
            for r, rate in enumerate(result.rates.tolist()):
                paper = ([None, None] if refused else
                         [float(result.paper.total[i, j, r]), float(result.paper.rms[i, j, r])])
                rows.append([sensor, profile, rate, float(result.exact.total[i, j, r]),
                             float(result.exact.rms[i, j, r]), *paper,
                             bool(result.saturated[i, j, r])])
    head = ["sensor", "profile", "rate_x3", "exact_total", "exact_rms", "paper_total",
            "paper_rms", "saturated"]
    assert render_sweep.to_csv(result) == csv_reference(head, rows)


# ---------------------------------------------------------------- writing pieces


def pieces() -> Iterator[str]:
    yield "first\n"
    yield "Δ second\n"
    yield "third\n"


def failing_pieces() -> Iterator[str]:
    yield "partial\n"
    raise ValueError("Out of range float values are not JSON compliant")


def test_pieces_are_written_to_a_file_in_order(tmp_path: Path) -> None:
    from gyrovib.cli.output import write_output

    target = tmp_path / "out.txt"
    write_output(pieces(), str(target))
    assert target.read_text(encoding="utf-8") == "first\nΔ second\nthird\n"


def test_a_renderer_failing_midway_leaves_the_file_as_it_was(tmp_path: Path) -> None:
    from gyrovib.cli.output import write_output

    target = tmp_path / "out.txt"
    target.write_text("old\n")
    with pytest.raises(ValueError, match="not JSON compliant"):
        write_output(failing_pieces(), str(target))
    assert target.read_text() == "old\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.txt"]


def test_pieces_on_standard_output_and_a_renderers_error_is_not_a_write_failure(
        monkeypatch: pytest.MonkeyPatch) -> None:
    from gyrovib.cli import output

    stream = io.TextIOWrapper(io.BytesIO(), encoding="ascii")
    monkeypatch.setattr(sys, "stdout", stream)
    output.write_output(pieces(), None)
    stream.flush()
    # an ASCII stream gets the fallback (Δ → Delta), piece by piece
    assert stream.buffer.getvalue() == b"first\nDelta second\nthird\n"  # type: ignore[attr-defined]
    with pytest.raises(ValueError, match="not JSON compliant"):
        output.write_output(failing_pieces(), None)


def test_select_json_through_the_command_line_is_the_document(tmp_path: Path) -> None:
    target = tmp_path / "select.json"
    result = invoke("select", "--budget", "0.01", "--format", "json", "-o", target)
    assert result.exit_code in (0, 1)
    # the command line's copy of the result (its reasons name the options)
    expected = render_select.to_json(as_options(api.select(api.load(), budget=0.01)))
    assert target.read_text(encoding="utf-8") == expected
    piped = invoke("select", "--budget", "0.01", "--format", "json")
    assert piped.stdout == expected


# ---------------------------------------------------------------- sweep refusals


SWEEP = textwrap.dedent("""\
    gyrovib: 1
    sensors:
      - id: s
        coefficients: {k2: 1.0e-3, k3: 1.0e-5}
    profiles:
      - id: tone
        harmonic: [{frequency: 100, amplitude: [0, 0, 1.0]}]
      - id: four-tones-on-a-whisper
        harmonic:
          - {frequency: 100, amplitude: [0, 0, 1.0]}
          - {frequency: 170, amplitude: [0, 0, 0.7]}
          - {frequency: 230, amplitude: [0, 0, 0.5]}
          - {frequency: 310, amplitude: [0, 0, 0.3]}
        random: {rms: [0, 0, 1.0e-6]}
    """)


def test_a_sweep_refused_by_the_exact_method_is_an_error_at_the_profile(
        monkeypatch: pytest.MonkeyPatch) -> None:
    # four tones on a random part of RMS 1e-6 need a contour longer than the cap on
    # Bessel values (test_mixtures.py lowers the cap the same way to reach it): the
    # exact method refuses; before, sweep turned that into NaN and a "paper" note
    from gyrovib.core import mixtures

    monkeypatch.setattr(mixtures, "_MAX_CONTOUR_VALUES", 1000)
    catalog = merge([parse_catalog(SWEEP, "sweep.yaml")])
    with pytest.raises(ModelError) as caught:
        api.sweep(catalog, api.rate_range(-1.0, 1.0, 5))
    problem = caught.value.problems[0]
    assert "four-tones-on-a-whisper" in problem.message
    assert "merge the smallest tones" in problem.message
    assert "--method exact" not in problem.message  # no advice to use what refused
    assert problem.line == 8  # the profile's `- id:` line in SWEEP
    assert caught.value.profile == 1


def test_a_sweep_the_paper_refuses_keeps_its_exact_values() -> None:
    # several tones alone: the paper's formulas do not cover them (docs/model.md), the
    # exact method does; the paper column is empty, nothing is an error
    catalog = merge([parse_catalog(SWEEP, "sweep.yaml")])
    result = api.sweep(catalog, api.rate_range(-1.0, 1.0, 5), profiles=["tone"])
    assert not result.paper_refused
    several = merge([parse_catalog(SWEEP.replace("random: {rms: [0, 0, 1.0e-6]}", ""),
                                   "sweep.yaml")])
    result = api.sweep(several, api.rate_range(-1.0, 1.0, 5))
    assert list(result.paper_refused) == ["four-tones-on-a-whisper"]
    assert np.all(np.isfinite(result.exact.total))
