"""A result that declares its records (gyrovib/records.py: Column) gets its CSV header and
cells (render/formats.py) and its DataFrame columns from that one declaration: they cannot
drift apart, and a column moved in the declaration moves in both."""

from __future__ import annotations

import csv
import io

import numpy as np
import pytest

import gyrovib
from gyrovib.records import Column, frame_of, names
from gyrovib.render import mission as render_mission
from gyrovib.render.formats import csv_of

pd = pytest.importorskip("pandas")


@pytest.fixture(scope="module")
def mission_result() -> object:
    # the bundled catalogue's missions with an angle budget: budget columns filled in,
    # flags, unknowns (None) and every status among the rows
    return gyrovib.mission(angle_budget="0.5deg")


def _csv(text: str) -> list[list[str]]:
    return list(csv.reader(io.StringIO(text)))


def test_mission_csv_header_and_frame_columns_are_the_declaration(mission_result) -> None:
    declared = names(mission_result.records())
    assert len(declared) == 28  # the probe works: every column of docs/output.md
    table = _csv(render_mission.to_csv(mission_result))
    assert tuple(table[0]) == declared
    assert tuple(mission_result.to_frame().columns) == declared
    assert len(table) - 1 == len(mission_result.rows) == len(mission_result.to_frame())


def test_mission_csv_cells_are_the_frame_values(mission_result) -> None:
    # the same value under the same name, row for row: a float as its repr, a flag as
    # true/false, unknown (None) as an empty cell
    table = _csv(render_mission.to_csv(mission_result))
    frame = mission_result.to_frame()
    seen_none = seen_flag = False
    for k, cells in enumerate(table[1:]):
        for name, cell in zip(table[0], cells, strict=True):
            value = frame[name].iloc[k]
            if value is None or (isinstance(value, float) and np.isnan(value)):
                # unknown: None, which pandas keeps as NaN in a column of numbers
                seen_none = True
                assert cell in ("", "nan")
            elif isinstance(value, (bool, np.bool_)):
                seen_flag = True
                assert cell == str(bool(value)).lower()
            elif isinstance(value, float):
                assert cell == repr(float(value))
            else:
                assert cell == str(value)
    assert seen_none and seen_flag  # the probe met both kinds


def test_a_column_moved_in_the_declaration_moves_in_csv_and_frame(mission_result) -> None:
    moved: tuple[Column, ...] = tuple(reversed(mission_result.records()))
    rows = mission_result.rows
    header = _csv(csv_of(moved, rows))[0]
    assert tuple(header) == names(moved) == tuple(frame_of(moved, rows).columns)
    assert header[0] == names(mission_result.records())[-1] and header[-1] == "sensor"


@pytest.mark.parametrize("kwargs", [{}, {"sensors": "adxrs453", "method": "numeric",
                                         "samples": 1000}])
def test_analyze_csv_and_frame_come_from_one_declaration(kwargs: dict) -> None:
    # analyze declares its records once (presentation.frames.analysis_columns): the CSV
    # takes its columns, the frame the same ones plus the frame-only ones, in one order
    from gyrovib.presentation.frames import analysis_columns
    from gyrovib.render import analysis as render_analysis

    result = gyrovib.analyze(**kwargs)
    table = _csv(render_analysis.to_csv(result))
    frame = result.to_frame()
    assert tuple(table[0]) == names(analysis_columns(result, csv=True))
    assert tuple(frame.columns) == names(analysis_columns(result, csv=False))
    in_csv = [c for c in frame.columns if c in table[0]]
    assert in_csv == table[0]  # the CSV's columns are the frame's, in the frame's order
    assert len(table) - 1 == len(frame) == len(result.sensors) * len(result.profiles)
    assert ("stderr" in table[0]) == ("method" in kwargs)  # the probe sees the numeric case
