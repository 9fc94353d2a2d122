"""A result that declares its records (gyrovib/records.py: Column) gets its CSV header and
cells (render/formats.py) and its DataFrame columns from that one declaration: they cannot
drift apart, and a column moved in the declaration moves in both; where the JSON rows are
written from it too (analyze, mission with its segments, its triads and sensors, a
recording, several recordings, bounds, runup), their key paths are the declaration's, in
its order. Every result with a CSV is checked here (analyze, mission, bounds, select,
sweep, fit, a recording, runup); the expected cells are the frame's own values, written as
docs/output.md says a CSV writes them. Likewise its human tables: their Markdown header is
the declared cells' titles (render/formats.py: Cell), each cell names a declared record and
shows its value, and JUnit has one case per verdict row."""

from __future__ import annotations

import csv
import io
from pathlib import Path

import numpy as np
import pytest

import gyrovib
from gyrovib.records import Column, frame_of, names
from gyrovib.render import mission as render_mission
from gyrovib.render.formats import csv_of
from tests.test_recording_unknown import SENSORS as UNKNOWN_SENSORS
from tests.test_yield_select import CATALOGUE as LOT

pd = pytest.importorskip("pandas")


@pytest.fixture(scope="module")
def mission_result() -> object:
    # the bundled catalogue's missions with an angle budget: budget columns filled in,
    # flags, unknowns (None) and every status among the rows
    return gyrovib.mission(angle_budget="0.5deg")


def _csv(text: str) -> list[list[str]]:
    return list(csv.reader(io.StringIO(text)))


#: The mission CSV's header as docs/output.md lists it (the frame's columns too).
MISSION_CSV = ("sensor", "mission", "placement", "axis", "mean", "angle", "rms",
               "worst_segment", "worst_profile", "worst_total", "duration", "saturated",
               "source", "passed", "status", "unknown", "theta_arw", "theta_bias_instability",
               "theta_rrw", "theta_repeatability", "budget_total", "coverage",
               "allowed_vibration", "allowed_arw", "allowed_bias_instability", "allowed_rrw",
               "allowed_repeatability", "typical", "lower_bound", "rests_on_bound", "bounds",
               "allowed_upper")


def test_mission_csv_header_and_frame_columns_are_the_declaration(mission_result) -> None:
    from gyrovib.records import written

    declared = names(written(mission_result.records(), "csv"))
    # the declaration is in the JSON's order; csv_after puts axis, source and typical
    # where the documented header has them, and the budget's marks (lower_bound,
    # rests_on_bound, bounds, allowed_upper) last
    assert declared == MISSION_CSV != names(mission_result.records())[:len(MISSION_CSV)]
    table = _csv(render_mission.to_csv(mission_result))
    assert tuple(table[0]) == declared
    assert tuple(mission_result.to_frame().columns) == declared == names(
        written(mission_result.records(), "frame"))
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
    from dataclasses import replace

    from gyrovib.records import written

    moved: tuple[Column, ...] = tuple(replace(c, csv_after=None) for c in
                                      reversed(written(mission_result.records(), "csv")))
    rows = mission_result.rows
    header = _csv(csv_of(moved, rows))[0]
    assert tuple(header) == names(moved) == tuple(frame_of(moved, rows).columns)
    assert header[0] == "allowed_upper" and header[-1] == "sensor"
    # a CSV place declared after a column moves with that column
    declared = mission_result.records()
    at = names(declared).index("unknown")
    shifted = (*declared[:at], replace(declared[at], csv_after="sensor"), *declared[at + 1:])
    assert _csv(csv_of(shifted, rows))[0][:2] == ["sensor", "unknown"]


def _check_entries(entries: list, columns, rows, frame) -> tuple[int, int]:
    """Each JSON entry has exactly the declared key paths of its row (``only``), in the
    declaration's order; each value is the frame's (null: unknown) or, where the JSON
    reads the row its own way (``json_value``), that reading; sub-records (``each``)
    are checked likewise. Returns how many values were compared and how many were null."""
    import math

    from gyrovib.records import written

    shown = written(columns, "json")
    by_path = {c.key or c.name: c for c in shown}
    compared = nulls = 0
    assert len(entries) == len(rows)
    for k, (entry, row) in enumerate(zip(entries, rows, strict=True)):
        found = _leaves(entry, set(by_path))
        assert [p for p, _ in found] == [c.key or c.name for c in shown
                                         if c.only is None or c.only(row)]
        for path, value in found:
            c = by_path[path]
            if c.each is not None:
                n, z = _check_entries(value, c.each, c.value(row), None)
                compared, nulls = compared + n, nulls + z
                continue
            if c.json_value is not None or frame is None or c.name not in frame.columns:
                want = (c.value if c.json_value is None else c.json_value)(row)
            else:
                want = frame[c.name].iloc[k]
                want = want.item() if hasattr(want, "item") else want
            if want is None or (isinstance(want, float) and not math.isfinite(want)):
                assert value is None, path
                nulls += 1
            else:
                assert value == (list(want) if isinstance(want, tuple) else want), path
            compared += 1
    return compared, nulls


@pytest.mark.parametrize("kwargs", [{"angle_budget": "0.5deg"}, {"budget": "36deg/h"},
                                    {"budget": "1deg/h", "placement": "x1=+Y,x2=+Z,x3=+X"}])
def test_mission_json_entries_are_the_declaration(kwargs: dict) -> None:
    # mission's JSON rows are written from the same declaration as its CSV and frame, in
    # the declaration's order: nested (its worst segment, its budget), with its segments
    # as sub-records; the renderer adds the one key in words (reason) after unknown
    import json

    from gyrovib.api.missions.results import COLUMNS

    result = gyrovib.mission(**kwargs)
    columns = render_mission.json_columns(result)
    assert [c for c in columns if c.name != "reason"] == list(COLUMNS)
    entries = json.loads(render_mission.to_json(result))["mission"]
    compared, nulls = _check_entries(entries, columns, result.rows, result.to_frame())
    assert compared > 20 * len(result.rows) and nulls  # the probe meets unknown figures
    # the JSON counts segments from 0, the CSV from 1; both read one declared column
    frame = result.to_frame()
    assert [e["worst_segment"]["index"] + 1 for e in entries] == list(frame["worst_segment"])
    assert [" ".join(e["unknown"]) for e in entries] == list(frame["unknown"])
    # the probes: every row has its budget; the bundled missions' triad has an axis on
    # each row, a rotation none
    assert all("budget" in e for e in entries)
    assert all(("axis" in e) == ("placement" not in kwargs) for e in entries)


#: The keys of mission's ``triads`` and ``sensors`` entries, in order, as its JSON writes
#: them (docs/output.md; ``rank`` only from ``select --mission``, which ranks).
TRIAD_KEYS = ("sensor", "mission", "worst_axis", "pass", "status")
SENSOR_KEYS = ("sensor", "pass", "status")


@pytest.mark.parametrize("kwargs", [{"angle_budget": "0.5deg"}, {},
                                    {"budget": "36deg/h", "placement": "x1=+Y,x2=+Z,x3=+X"}])
@pytest.mark.parametrize("rank", [False, True])
def test_mission_triads_and_sensors_are_their_declarations(kwargs: dict, rank: bool) -> None:
    # the triads' and the sensors' entries are written from their declarations in api
    # (TRIAD_COLUMNS, MissionResult.sensor_records): their keys are the literal tuples
    # above, and their values the rows' own: a triad passes when every axis does, its
    # status the worst of its axes' (fail, then unverified, then pass), None without a
    # budget; a rotation has no triad
    import json

    from gyrovib.api.missions.results import TRIAD_COLUMNS
    from gyrovib.api.noise import ranked

    result = gyrovib.mission(**kwargs)
    result = ranked(result) if rank else result
    document = json.loads(render_mission.to_json(result))
    assert names(TRIAD_COLUMNS) == TRIAD_KEYS
    assert names(result.sensor_records()) == SENSOR_KEYS + (("rank",) if rank else ())
    triad = "placement" not in kwargs
    assert len(document["triads"]) == (len(result.sensors) * len(result.missions) if triad
                                       else 0)
    for entry in document["triads"]:
        assert tuple(entry) == TRIAD_KEYS
        rows = [r for r in result.rows if (r.sensor, r.mission) == (entry["sensor"],
                                                                     entry["mission"])]
        assert [r.axis for r in rows] == ["X", "Y", "Z"]
        judged = bool(kwargs)
        assert entry["pass"] == (all(r.passed for r in rows) if judged else None)
        statuses = [r.status for r in rows]
        assert entry["status"] == (None if not judged else "fail" if "fail" in statuses
                                   else "unverified" if "unverified" in statuses else "pass")
        assert entry["worst_axis"] == rows[0].worst_axis in ("X", "Y", "Z")
    assert [e["sensor"] for e in document["sensors"]] == list(result.sensors)
    for k, entry in enumerate(document["sensors"]):
        assert tuple(entry) == SENSOR_KEYS + (("rank",) if rank else ())
        assert entry["pass"] == result.sensor_pass[k]
        assert entry["status"] == result.sensor_status(k)
        assert entry.get("rank") == (result.ranks[k] if rank else None)
    statuses = {e["status"] for e in document["triads"] + document["sensors"]}
    assert statuses >= ({"fail", "unverified"} if kwargs.get("angle_budget") else {None}
                        if not kwargs else {"fail"})  # the probes meet these verdicts


# analyze's cases: the bundled catalogues (spec-form sensors and their envelope, saturated
# rows, locked harmonics), the numeric method (stderr), a catalogue of a sensor with an
# uncertainty, a lot and a profile with phase: worst (keys that only some rows have),
# another unit, and a profile fitted from a recording without x1 and x2 (unknown: NaN)
LOT_AND_WORST = """\
gyrovib: 1
sensors:
  - id: unit-1
    coefficients: {A1: 1.2e-3, k2: 3.1e-5, k3: -2.0e-7, m31: 2.0e-6}
    uncertainty:
      sigma: {A1: 1.0e-4, k2: 2.0e-6, k3: 1.5e-8, m31: 1.0e-6}
  - id: plain
    coefficients: {A1: 1.2e-3, k2: 3.1e-5, k3: -2.0e-7, m31: 2.0e-6}
  - id: lot-1
    lot:
      units: 20
      mean: {A1: 1.2e-3, k2: 3.1e-5, k3: -2.0e-7, m31: 2.0e-6}
      sigma: {A1: 1.0e-4, k2: 2.0e-6, k3: 1.5e-8, m31: 1.0e-6}
profiles:
  - id: worst
    rate: [0, 0, 0.5]
    harmonics:
      fundamental: 20
      orders:
        - {order: 1, amplitude: [0.5, 0.0, 2.0], phase: [30, 0, 0]}
        - {order: 2, amplitude: [0.0, 0.3, 1.0], phase: worst}
  - id: hover
    rate: [0, 0, -5]
    harmonic:
      - {frequency: 80, amplitude: [2, 0, 25]}
"""

#: Only x3 and no accelerations recorded (as `gyrovib profile --rate-columns -,-,gz`
#: writes it): k2 depends on x3 alone, m31 also on x1, a g² term on the accelerations
#: A fitted profile without x1, x2 and the accelerations, and the sensors of
#: tests/test_recording_unknown.py: where a sensor needs what was not recorded, null.
UNRECORDED = """\
gyrovib: 1
units: {rate: deg/s, acceleration: g}
profiles:
  - id: fitted
    rate: [0, 0, 0.2]
    not_recorded: [x1, x2, acceleration]
    random:
      rms: [0, 0, 1.0]
""" + UNKNOWN_SENSORS[UNKNOWN_SENSORS.index("sensors:"):]

ANALYZE_CASES = {
    "bundled": {},
    "numeric": {"sensors": "adxrs453", "method": "numeric", "samples": 1000},
    "lot-and-worst": {"catalog": LOT_AND_WORST},
    "deg/h": {"unit": "deg/h", "profiles": ("uav-blade-pass-tone", "flat-random-hover")},
    "unrecorded": {"catalog": UNRECORDED},
}


def _analysis(case: str, tmp_path) -> object:
    kwargs = dict(ANALYZE_CASES[case])
    text = kwargs.pop("catalog", None)
    if text is None:
        return gyrovib.analyze(**kwargs)
    path = tmp_path / "catalogue.gyrovib.yaml"
    path.write_text(text, encoding="utf-8")
    return gyrovib.analyze(str(path), **kwargs)


def _leaves(value: object, keys: set[str], prefix: str = "") -> list[tuple[str, object]]:
    """The key paths of a JSON entry in order, each with its value: an object or a list is
    entered unless its path is itself a declared key (a row's warnings, its phases)."""
    if prefix[:-1] not in keys and isinstance(value, (dict, list)):
        items = value.items() if isinstance(value, dict) else enumerate(value)
        return [leaf for k, v in items for leaf in _leaves(v, keys, f"{prefix}{k}.")]
    return [(prefix[:-1], value)]


@pytest.mark.parametrize("case", list(ANALYZE_CASES))
def test_analyze_json_csv_and_frame_come_from_one_declaration(case: str, tmp_path) -> None:
    # analyze declares its records once (api.evaluation.records.analysis_columns): the CSV
    # takes the columns that do not skip it, the frame and the JSON every column, in one
    # order; a JSON entry has exactly the declared key paths of the columns on its row
    # (``only``), in the declared order, each holding the frame's value (NaN: null)
    import json
    import math

    from gyrovib.api.evaluation.records import analysis_cells, analysis_columns
    from gyrovib.records import written
    from gyrovib.render import analysis as render_analysis

    result = _analysis(case, tmp_path)
    columns = analysis_columns(result)
    rows = analysis_cells(result)
    table = _csv(render_analysis.to_csv(result))
    frame = result.to_frame()
    assert tuple(table[0]) == names(written(columns, "csv"))
    assert tuple(frame.columns) == names(written(columns, "frame")) == names(columns)
    # every record is in the JSON: a column added without a JSON key fails here
    assert written(columns, "json") == columns
    assert len(table) - 1 == len(frame) == len(rows) == len(result.sensors) * len(
        result.profiles)
    entries = json.loads(render_analysis.to_json(result))["results"]
    keys = {c.key or c.name: c for c in columns}
    assert len(keys) == len(columns)  # one key path per column
    seen_null = seen_only = 0
    for k, (row, entry) in enumerate(zip(rows, entries, strict=True)):
        found = _leaves(entry, set(keys))
        expected = [c.key or c.name for c in columns if c.only is None or c.only(row)]
        # no key outside the declaration, none of its keys missing, in its order
        assert [path for path, _ in found] == expected
        seen_only += len(expected) < len(columns)
        for path, value in found:
            want = frame[keys[path].name].iloc[k]
            want = want.item() if hasattr(want, "item") else want
            if isinstance(want, float) and math.isnan(want):
                assert value is None, path
                seen_null += 1
            elif isinstance(want, tuple):
                assert value == list(want), path
            else:
                assert value == want, path
    # the probes: the spec-form, lot, worst-phase and unrecorded cases have keys on some
    # rows only; the unrecorded case has unknown errors, written null, and so have the
    # bundled profiles with linear vibration for the sensors without a g² figure (the
    # bundled catalogue has such sensors, adxrs453 among them: 'bundled', 'numeric')
    from gyrovib.api.datasheet.specs import UNKNOWN_TERM_NOTES

    g2_unknown = any(w in UNKNOWN_TERM_NOTES for ws in result.warnings.values() for w in ws)
    assert g2_unknown == (case in ("bundled", "numeric"))
    assert bool(seen_only) == (case == "lot-and-worst" or "specs" in result.sources)
    assert bool(seen_null) == (case == "unrecorded" or g2_unknown)
    assert ("stderr" in table[0]) == (case == "numeric")


@pytest.mark.parametrize("case", list(ANALYZE_CASES))
def test_analyze_columns_read_alike_one_row_or_many(case: str, tmp_path) -> None:
    # a column that reads many rows at once (``many``, the fast writers' path) reads what
    # it reads one row at a time (``value``): the JSON, the CSV and the frame agree
    from gyrovib.api.evaluation.records import analysis_cells, analysis_columns

    result = _analysis(case, tmp_path)
    # the probe: the numbers of a row are read at once
    assert _read_alike(analysis_columns(result), analysis_cells(result)) > 15


def _read_alike(columns, rows, types: bool = False) -> int:
    """Each column that reads many rows at once (``many``) reads what ``value`` reads row
    by row, NaN for NaN; with ``types``, as the same Python types, and a column of flags
    as an array of flags. Returns how many such columns there are."""
    fast = 0
    for column in columns:
        if column.many is None:
            continue
        many = list(column.many(rows))
        one = [column.value(row) for row in rows]
        if types:
            assert list(map(type, np.asarray(many).tolist())) == list(map(type, one)), \
                column.name
            if all(type(v) is bool for v in one):  # flags: the frame's column is of flags
                assert np.asarray(column.many(rows)).dtype == bool, column.name
        assert np.array_equal(np.asarray(many, dtype=object), np.asarray(one, dtype=object)) \
            or np.allclose(np.asarray(many, float), np.asarray(one, float), rtol=0, atol=0,
                           equal_nan=True), column.name
        fast += 1
    return fast


def test_a_column_added_to_analyze_records_is_in_json_csv_and_frame() -> None:
    # one edit: a column appended to the declaration appears in every output alike, at
    # its key path in the JSON (here under an object that does not exist yet)
    import json
    from dataclasses import replace

    from gyrovib.api.evaluation.records import analysis_cells, analysis_columns
    from gyrovib.render.formats import json_text

    result = gyrovib.analyze(sensors="adxrs453")
    rows = analysis_cells(result)
    columns = analysis_columns(result)
    added = (*columns, Column("probe", None, lambda c: c[0] + 10 * c[1], key="extra.probe"))
    entries = json.loads(json_text(added, rows))
    assert [e["extra"]["probe"] for e in entries] == [i + 10 * j for i, j in rows]
    assert _csv(csv_of(added, rows))[0][-1] == "probe"
    assert tuple(frame_of(added, rows).columns)[-1] == "probe"
    # a key written on some rows only, declared so, is left out of the others
    some = (*columns, replace(added[-1], only=lambda c: c[1] == 0))
    entries = json.loads(json_text(some, rows))
    assert ["extra" in e for e in entries] == [j == 0 for _, j in rows]


# ---------------------------------------------------------------- every declared result

#: What a check that cannot bind holds in the frame: no figure, no bound, a pass.
_NOTHING = {"value_vre": lambda v: v == 0.0, "bound_vre": lambda v: v == np.inf,
            "pass_vre": lambda v: v is True or v is np.True_}


def _frame_and_csv_agree(columns, rows, frame, text: str) -> int:
    """The CSV's header is the declaration less its frame-only columns, the frame's
    columns the whole declaration, in order; each CSV cell is its frame value as the
    column writes it (a number as its repr, unknown empty, a flag true/false or
    True/False). Returns how many cells were compared."""
    from gyrovib.records import written

    table = _csv(text)
    assert tuple(table[0]) == names(written(columns, "csv"))
    assert tuple(frame.columns) == names(written(columns, "frame"))
    assert len(table) - 1 == len(rows) == len(frame)
    compared = 0
    for k, cells in enumerate(table[1:]):
        for column, cell in zip(written(columns, "csv"), cells, strict=True):
            value = frame[column.name].iloc[k]
            if column.blank is not None and column.blank(rows[k]):
                # a check the CSV does not make on this row (a coefficient row's VRE
                # check without linear vibration): it must decide nothing, never hide a
                # known figure behind an empty cell
                assert _NOTHING[column.name](value), (column.name, value)
                assert cell == "", column.name
                continue
            shown = column.cell(value) if column.cell is not None else value
            if shown is None or (isinstance(shown, float) and np.isnan(shown)):
                assert cell == "", column.name
            elif isinstance(shown, (bool, np.bool_)):
                assert cell.lower() == str(bool(shown)).lower(), column.name
            elif isinstance(shown, float):
                # a count with unknown rows is a float column in the frame: 0.0 for 0
                assert cell == repr(float(shown)) or (
                    shown.is_integer() and cell == str(int(shown))), column.name
            elif isinstance(shown, (list, tuple)):
                assert cell in (" ".join(shown), "; ".join(shown)), column.name
            else:
                assert cell == str(shown), column.name
            compared += 1
    return compared


def test_bounds_csv_and_frame_come_from_one_declaration() -> None:
    from gyrovib.api.evaluation.records import bounds_columns
    from gyrovib.render import bounds as render_bounds

    result = gyrovib.bounds(budget="10deg/h", range_=100)
    columns = bounds_columns(result)
    assert "spec_vre" in names(columns) and "vre" in names(columns)  # the --range probe
    assert _frame_and_csv_agree(columns, range(len(result.profiles)), result.to_frame(),
                                render_bounds.to_csv(result)) > 100


EXAMPLES = Path(__file__).resolve().parent.parent / "docs" / "examples"

# select's cases: the bundled catalogues (datasheet parts, linear vibration: the VRE check
# binds on every row), an unknown figure taken as 0, a profile without linear vibration
# (a coefficient row's VRE check is not in the CSV), lots judged by a Monte-Carlo and by
# an exact yield (its interval null), and a profile fitted from a recording without x1,
# x2 and the accelerations (unknown bounds: checks that decide nothing)
SELECT_CASES = {
    "both": {"budget": "10deg/h", "criterion": "both"},
    "assumed": {"budget": "1deg/h", "profiles": "engine-harmonics", "assume_unknown": "zero"},
    "no-linear": {"budget": "10deg/h", "profiles": "flat-random-hover"},
    "monte-carlo": {"catalog": LOT, "budget": 6e-3, "criterion": "rms", "yield_target": 0.9},
    "exact-yield": {"catalog": [str(EXAMPLES / "rate-table-gx100.gyrovib.yaml"),
                                str(EXAMPLES / "rotor-tone.gyrovib.yaml")],
                    "budget": "36deg/h", "criterion": "worst", "yield_target": 0.99},
    "unrecorded": {"catalog": UNRECORDED, "budget": 1.0},
}

def _selection(case: str, tmp_path) -> object:
    kwargs = dict(SELECT_CASES[case])
    text = kwargs.get("catalog")
    if isinstance(text, str) and "\n" in text:
        path = tmp_path / "catalogue.gyrovib.yaml"
        path.write_text(text, encoding="utf-8")
        kwargs["catalog"] = str(path)
    return gyrovib.select(**kwargs)


def _json_equal(value: object, want: object) -> bool:
    """A JSON value against the frame's: null where the frame's is None, NaN or an
    infinity (unknown, unbounded), a list where it is a list; else equal."""
    import math

    want = want.item() if hasattr(want, "item") else want
    if value is None:
        return want is None or (isinstance(want, float) and not math.isfinite(want))
    return value == want


@pytest.mark.parametrize("case", list(SELECT_CASES))
def test_select_json_csv_and_frame_come_from_one_declaration(case: str, tmp_path) -> None:
    # select declares its records once (api.evaluation.records.selection_records): a row
    # per sensor, its sensor × profile records listed in ``profiles`` (``each``). The JSON's
    # sensor entries are written from it (the text json.dumps writes of json_of's dicts:
    # key order included); the CSV and the frame are its flattened table, a line per
    # sensor × profile, the CSV without the frame-only columns, each cell the frame's
    # value as the column writes it (names joined, empty on its ``blank`` rows); every
    # JSON leaf holds the frame's value, or the JSON's own reading of the row
    import json

    from gyrovib.api.evaluation.records import (
        selection_cells,
        selection_columns,
        selection_records,
    )
    from gyrovib.records import flattened, written
    from gyrovib.render import select as render_select
    from gyrovib.render.formats import json_of

    result = _selection(case, tmp_path)
    records = selection_records(result)
    columns, rows = selection_columns(result), selection_cells(result)
    assert names(columns) == names(flattened(records))
    frame = result.to_frame()
    assert _frame_and_csv_agree(columns, rows, frame,
                                render_select.to_csv(result)) > 10 * len(rows)
    blank = sum(1 for c in written(columns, "csv") if c.blank is not None for row in rows
                if c.blank(row))
    # the probes: a coefficient row's VRE check the CSV makes only with linear vibration
    assert blank if case == "no-linear" else case != "both" or not blank
    document = json.loads(render_select.to_json(result))
    n = len(result.sensors)
    assert document["sensors"] == json.loads(json.dumps(json_of(records, range(n))))
    (listing,) = [c for c in records if c.each is not None]
    at = {row: k for k, row in enumerate(rows)}  # a sensor × profile's line in the frame
    compared = nulls = 0
    for i, entry in enumerate(document["sensors"]):
        lines = [at[row] for row in listing.value(i)]
        assert list(entry) == [c.key or c.name for c in written(records, "json")]
        for c in records:
            if c.each is None and "frame" not in c.skip:
                assert all(_json_equal(entry[c.key or c.name], frame[c.name].iloc[k])
                           for k in lines), c.name
        for row, k, cell in zip(listing.value(i), lines, entry["profiles"], strict=True):
            for c in written(listing.each, "json"):
                if c.only is not None and not c.only(row):
                    continue
                value = _at(cell, c.key or c.name)
                want = frame[c.name].iloc[k] if c.json_value is None else c.json_value(row)
                assert _json_equal(value, want), c.name
                compared += 1
                nulls += value is None
            for c in listing.each:  # the profile's figures: the document's profiles
                if "json" in c.skip and c.name.startswith("profile_"):
                    value = _at(document["profiles"][row[1]], c.key)
                    assert _json_equal(value, frame[c.name].iloc[k]), c.name
    # the probes: datasheet rows and lots have keys of their own; nulls are met
    assert compared > 10 * len(rows) and nulls
    assert tuple(frame.columns) == names(written(columns, "frame"))


@pytest.mark.parametrize("case", list(SELECT_CASES))
def test_select_columns_read_alike_one_row_or_many(case: str, tmp_path) -> None:
    # select's columns that read many rows at once (the JSON's and the frame's path) read
    # what they read one row at a time (the CSV's): empty on a datasheet row's coefficient
    # checks, None where a check decides nothing
    from gyrovib.api.evaluation.records import selection_cells, selection_columns

    result = _selection(case, tmp_path)
    # the probe: the numbers and checks of a row are read at once
    assert _read_alike(selection_columns(result), selection_cells(result), types=True) > 15


def _at(entry: object, key: str) -> object:
    """The value at a key path of a JSON entry."""
    for part in key.split("."):
        entry = entry[int(part)] if part.isdigit() else entry[part]  # type: ignore[index]
    return entry


def test_select_key_orders_are_declared_once() -> None:
    # the JSON's order is the declaration's; the CSV's and the frame's put a column after
    # the one it names (csv_after): moving a column in the declaration moves it in every
    # output, and a column placed after one it does not have is refused
    from dataclasses import replace

    from gyrovib.api.evaluation.records import selection_columns, selection_records
    from gyrovib.records import flattened, written

    result = gyrovib.select(budget="10deg/h", criterion="both")
    records = selection_records(result)
    head = names(written(selection_columns(result), "csv"))
    assert head[:4] == ("sensor", "profile", "passed", "sensor_pass")
    assert head[-6:] == ("saturated", "status", "unknown", "criterion_margin", "disagrees",
                         "reason")
    (listing,) = [c for c in records if c.each is not None]
    cells = listing.each
    assert names(written(cells, "json"))[:4] == ("profile", "passed", "status", "unknown")
    moved = replace(listing, each=tuple(replace(c, csv_after="profile")
                                        if c.name == "reason" else c for c in cells))
    again = tuple(moved if c is listing else c for c in records)
    assert names(written(flattened(again), "csv"))[:4] == ("sensor", "profile", "reason",
                                                           "passed")
    lost = replace(listing, each=tuple(replace(c, csv_after="nowhere") if c.name == "reason"
                                       else c for c in cells))
    with pytest.raises(ValueError):
        written(flattened(tuple(lost if c is listing else c for c in records)), "csv")


def test_sweep_csv_writer_and_frame_are_the_declaration() -> None:
    # sweep's CSV is written column by column for speed: it must equal the generic writer
    # over the declaration, byte for byte (the paper refuses engine-harmonics: empty cells)
    from gyrovib.api.evaluation.records import sweep_cells, sweep_columns
    from gyrovib.render import sweep as render_sweep

    result = gyrovib.sweep(rates=(-10, 10), points=5)
    assert result.paper_refused  # the probe has refused cells
    columns, rows = sweep_columns(result), sweep_cells(result)
    text = render_sweep.to_csv(result)
    assert text == csv_of(columns, rows, title_flags=True)
    assert _frame_and_csv_agree(columns, rows, result.to_frame(), text) > 100


def test_fit_csv_and_frame_come_from_one_declaration() -> None:
    from pathlib import Path

    from gyrovib.api.commands.fit import fit
    from gyrovib.render import fit as render_fit

    table = Path(__file__).resolve().parent.parent / "docs" / "examples" / "rate-table-gx100.csv"
    result = fit(table)
    assert len(result.units) > 1  # a lot: several units' rows
    assert _frame_and_csv_agree(result.records(), result.rows(), result.to_frame(),
                                render_fit.to_csv(result)) > 50


def test_recording_csv_and_frame_come_from_one_declaration(tmp_path) -> None:
    pytest.importorskip("scipy.signal")
    from gyrovib.api.recordings.analysis import analyze_recording
    from gyrovib.api.recordings.reading import read_recording
    from gyrovib.render import recording as render_recording

    # a synthetic rate log (noise and a 31.3 Hz tone on a slow carrier), no accelerometer:
    # the recorded terms are unknown, written empty
    fs, n = 250.0, 7500
    t = np.arange(n) / fs
    rate = np.random.default_rng(1).normal(0.0, 0.2, (n, 3))
    rate += np.outer(np.sin(2 * np.pi * 31.3 * t), (0.2, 0.2, 0.4))
    rate[:, 2] += 2.0 + np.sin(2 * np.pi * 0.05 * t)
    np.save(tmp_path / "log.npy", rate)
    result = analyze_recording(read_recording(str(tmp_path / "log.npy"), fs=fs),
                               gyrovib.load())
    assert _frame_and_csv_agree(result.records(), range(len(result.sensors)),
                                result.to_frame(), render_recording.to_csv(result)) > 50
    # the JSON's results come from the same declaration: the frame's values under their
    # key paths (unknown: null), and what only the JSON has (each row's source)
    import json

    rows = json.loads(render_recording.to_json(result))["results"]
    frame = result.to_frame()
    known = unknown = 0
    for k, row in enumerate(rows):
        for column in result.records():
            if "json" in column.skip or "frame" in column.skip:
                continue
            value: object = row
            for part in (column.key or column.name).split("."):
                value = value[part]  # type: ignore[index]
            expected = frame[column.name].iloc[k]
            if isinstance(expected, float) and np.isnan(expected):
                assert value is None, column.name
                unknown += 1
            else:
                assert value == expected, column.name
                known += isinstance(expected, float)
        assert row["source"] in ("specs", "coefficients") and "unit" not in row
    assert unknown  # the probe meets unknown figures (null) as well as numbers
    assert known  # the probe compares numbers, not only nulls
    # every key of an entry is declared, in the declaration's order: the profile at its
    # mean rate, one declaration, nested after the ratio in the JSON and last in the CSV
    compared, _ = _check_entries(rows, result.records(), range(len(result.sensors)), frame)
    assert compared >= 15 * len(rows)
    assert list(rows[0])[list(rows[0]).index("ratio") + 1] == "at_mean_rate"
    assert _csv(render_recording.to_csv(result))[0][-3:] == ["unit", "at_mean_rate",
                                                             "at_mean_ratio"]
    # and its Markdown is its declared cells, each the frame's value of its record
    assert _check_cells(render_recording.table_cells(result), result.records(),
                        range(len(result.sensors)), frame,
                        render_recording.to_markdown(result)) >= 2 * len(result.sensors)


def test_several_recordings_csv_and_json_are_the_recording_declaration(tmp_path) -> None:
    # analyze over several recordings writes each recording's rows from the one-recording
    # declaration: the CSV its header after ``recording``, the JSON each recording's
    # results and each sensor's worst row (then the recording, its index, saturations)
    pytest.importorskip("scipy.signal")
    import json

    from click.testing import CliRunner

    from gyrovib.api.recordings.analysis import analyze_recording
    from gyrovib.api.recordings.reading import read_recording
    from gyrovib.cli.main import cli
    from gyrovib.records import written

    fs, n = 250.0, 5000
    t = np.arange(n) / fs
    paths = []
    for k, carrier in enumerate((2.0, 6.0)):
        rate = np.random.default_rng(k).normal(0.0, 0.2, (n, 3))
        rate[:, 2] += carrier + np.sin(2 * np.pi * 31.3 * t)
        paths.append(str(tmp_path / f"log{k}.npy"))
        np.save(paths[-1], rate)
    args = ["analyze", "--recording", paths[0], "--recording", paths[1], "--fs", "250"]
    analyses = [analyze_recording(read_recording(p, fs=fs), gyrovib.load()) for p in paths]
    columns = analyses[0].records()
    table = _csv(CliRunner().invoke(cli, [*args, "--format", "csv"]).stdout)
    assert tuple(table[0]) == ("recording", *names(written(columns, "csv")))
    assert len(table) - 1 == sum(len(a.sensors) for a in analyses)
    document = json.loads(CliRunner().invoke(cli, [*args, "--format", "json"]).stdout)
    for analysis, entry in zip(analyses, document["recordings"], strict=True):
        rows = range(len(analysis.sensors))
        compared, _ = _check_entries(entry["results"], analysis.records(), rows,
                                     analysis.to_frame())
        assert compared >= 15 * len(rows)
    keys = [(c.key or c.name).split(".")[0] for c in written(columns, "json")]
    found = 0
    for worst in document["worst"]:
        # a sensor unknown on some recording has no worst row: its name only
        row = dict.fromkeys(keys) if worst["recording"] is not None else ["sensor"]
        assert list(worst) == [*row, "recording", "index", "saturated_on"]
        found += worst["recording"] is not None
    assert found  # the probe meets worst rows


def test_runup_csv_sections_are_the_declarations() -> None:
    from pathlib import Path

    from click.testing import CliRunner

    from gyrovib.api.runup.results import ESTIMATE_RECORDS, STEP_RECORDS
    from gyrovib.cli.main import cli
    from gyrovib.records import written

    example = Path(__file__).resolve().parent.parent / "docs" / "examples" / "runup-quad.npz"
    done = CliRunner().invoke(cli, ["runup", str(example), "--fs", "200", "--accel-columns",
                                    "ax,ay,az", "--estimate", "k2,vre", "--format", "csv"])
    assert done.exit_code in (0, 1), done.output
    steps, estimates = done.stdout.split("\n\n")
    assert tuple(_csv(steps)[0]) == names(written(STEP_RECORDS, "csv"))
    assert tuple(_csv(estimates)[0]) == names(ESTIMATE_RECORDS)
    assert len(_csv(estimates)) == 3  # k2 and vre
    # the JSON's steps are the same declaration: its keys in order, the CSV's values
    import json

    done = CliRunner().invoke(cli, ["runup", str(example), "--fs", "200", "--accel-columns",
                                    "ax,ay,az", "--estimate", "k2,vre", "--format", "json"])
    entries = json.loads(done.stdout)["steps"]
    keys = [c.key or c.name for c in written(STEP_RECORDS, "json")]
    assert [list(e) for e in entries] == [keys] * (len(_csv(steps)) - 1)
    for entry, row in zip(entries, _csv(steps)[1:], strict=True):
        line = dict(zip(_csv(steps)[0], row, strict=True))
        assert str(entry["index"]) == line["step"]
        assert repr(entry["shift"]) == line["shift"] and entry["predicted"] is None


def test_bounds_json_entries_are_the_declaration() -> None:
    # the JSON's profiles are written from the same declaration: their key paths are the
    # columns' keys, and each value the frame's (unbounded: null)
    import json
    import math

    from gyrovib.api.evaluation.records import bounds_columns
    from gyrovib.render import bounds as render_bounds

    result = gyrovib.bounds(budget="10deg/h", range_=100)
    columns = bounds_columns(result)
    document = json.loads(render_bounds.to_json(result))
    frame = result.to_frame()

    def leaves(prefix: str, value: object) -> list[tuple[str, object]]:
        if isinstance(value, dict):
            return [p for k, v in value.items() for p in leaves(f"{prefix}{k}.", v)]
        if isinstance(value, list):
            return [p for k, v in enumerate(value) for p in leaves(f"{prefix}{k}.", v)]
        return [(prefix[:-1], value)]

    keys = [c.key or c.name for c in columns]
    unbounded = 0
    for k, entry in enumerate(document["profiles"]):
        found = leaves("", entry)
        assert sorted(path for path, _ in found) == sorted(keys)
        for column in columns:
            value = dict(found)[column.key or column.name]
            expected = frame[column.name].iloc[k]
            if isinstance(expected, float) and math.isinf(expected):
                assert value is None
                unbounded += 1
            else:
                assert value == expected, column.name
    assert unbounded  # the probe meets an unconstrained bound


# ------------------------------------------------------------ the human tables and JUnit
#
# A human table (Markdown, and the terminal table drawn from the same declaration) is
# declared once as cells (render/formats.py: Cell), each naming the record it shows.
# Its Markdown header is the cells' titles, in order; a cell that names a record and has
# no text of its own writes that record's value, so it is the DataFrame's value; and no
# cell can name a record the result does not declare.

def _markdown(text: str) -> list[list[str]]:
    """The rows of the first Markdown table in ``text`` (header first, the rule left
    out), each cell unescaped."""
    import re

    lines = [line for line in text.splitlines() if line.startswith("|")]
    start = text.splitlines().index(lines[0])
    table = []
    for line in text.splitlines()[start:]:
        if not line.startswith("|"):
            break
        table.append([c.replace("\\|", "|") for c in re.split(r"(?<!\\) \| ", line[2:-2])])
    return [table[0], *table[2:]]


def _number_in(text: str) -> float | None:
    """The number a table cell shows ('≤ 0.5 typ' → 0.5), None when it shows none."""
    import re

    found = re.fullmatch(r"[≤≥]? ?(-?[0-9.]+(?:e[-+][0-9]+)?)(?: typ| ⚠[0-9,]+)?", text)
    return None if found is None else float(found.group(1))


def _check_cells(cells, records, rows, frame, text: str) -> int:
    """The Markdown in ``text`` has the cells' titles as its header and one line per row;
    every cell names a declared record (or none). A cell without its own text shows the
    frame's value of its record as the tables write a value ('?' unknown); a cell with
    its own text that shows a number shows that value to the digits it writes (2 to 4
    significant figures, or 0 for a value negligible beside its row's largest), and no
    number where the frame's value is unknown. Returns
    how many cells were compared with the frame."""
    import math

    from gyrovib.render.formats import known

    table = _markdown(text)
    assert table[0] == [c.title for c in cells]
    assert len(table) - 1 == len(rows)
    declared = names(records)
    assert all(c.of is None or c.of in declared for c in cells), \
        [c.of for c in cells if c.of not in declared]
    compared = 0
    for k, line in enumerate(table[1:]):
        assert len(line) == len(cells)
        for cell, shown in zip(cells, line, strict=True):
            if cell.of is None:
                continue
            value = frame[cell.of].iloc[k]
            value = value.item() if hasattr(value, "item") else value
            value = None if isinstance(value, float) and math.isnan(value) else value
            if cell.text is None:
                assert shown == known(value), cell.title
                compared += 1
            elif value is None:
                # unknown in the frame: the cell shows no number for it (never a 0)
                assert _number_in(shown) is None, (cell.title, shown)
                compared += 1
            elif (number := _number_in(shown)) is not None and isinstance(value, float):
                assert math.isclose(number, value, rel_tol=0.05) or (
                    number == 0 and abs(value) < 1e-9), (cell.title, shown, value)
                compared += 1
    return compared


def test_mission_markdown_and_terminal_table_are_one_declaration(mission_result) -> None:
    from gyrovib.api.missions.results import COLUMNS
    from gyrovib.render.formats import table_of

    cells = render_mission.table_cells(mission_result)
    text = render_mission.to_markdown(mission_result)
    assert _check_cells(cells, COLUMNS, mission_result.rows, mission_result.to_frame(),
                        text) >= 3 * len(mission_result.rows)  # mean, angle, rms, …
    # the header carries the records' units: the rate and angle units of the result
    assert f"mean Δ̄_V ({mission_result.unit})" in _markdown(text)[0]
    assert f"angle θ_V ({mission_result.angle_unit})" in _markdown(text)[0]
    # the terminal table draws the same columns under the same headings
    drawn = table_of(cells, mission_result.rows, COLUMNS)
    assert [c.header for c in drawn.columns] == [c.title for c in cells]
    # a cell moved in the declaration moves in the Markdown, its values with it
    from gyrovib.render.formats import markdown_of

    moved = _markdown(markdown_of(tuple(reversed(cells)), mission_result.rows, COLUMNS))
    original = _markdown(text)
    assert moved == [list(reversed(line)) for line in original]


def test_mission_segments_markdown_is_its_declaration(mission_result) -> None:
    from gyrovib.api.missions.results import SEGMENT_COLUMNS
    from gyrovib.render.mission_segments import _cells

    text = render_mission.to_markdown(mission_result, segments=True)
    segments = text[text.index("Segment by segment"):]
    rows = mission_result.segment_rows()
    assert _check_cells(_cells(mission_result), SEGMENT_COLUMNS, rows,
                        mission_result.segments_frame(), segments) >= len(rows)


@pytest.mark.parametrize("case", ["bundled", "numeric", "unrecorded"])
def test_analyze_markdown_names_its_records(case: str, tmp_path) -> None:
    # "unrecorded": the sensors that need x1 or the accelerations have unknown errors,
    # which the Markdown must show as '?', never as a number
    from gyrovib.api.evaluation.records import analysis_cells, analysis_columns
    from gyrovib.render import analysis as render_analysis

    result = _analysis(case, tmp_path)
    cells = render_analysis.markdown_cells(result)
    assert all(c.of is not None for c in cells)  # every column shows a record
    rows = analysis_cells(result)
    text = render_analysis.to_markdown(result)
    assert _check_cells(cells, analysis_columns(result), rows, result.to_frame(),
                        text) > 5 * len(rows)
    assert ("± stderr" in [c.title for c in cells]) == (case == "numeric")  # the probe
    assert case != "unrecorded" or "| ? |" in text


def test_fit_markdown_is_its_declaration() -> None:
    from pathlib import Path

    from gyrovib.api.commands.fit import fit
    from gyrovib.render import fit as render_fit

    table = Path(__file__).resolve().parent.parent / "docs" / "examples" / "rate-table-gx100.csv"
    result = fit(table)
    first = [r for r in result.rows() if r[0] == 0]
    frame = result.to_frame().iloc[:len(first)]
    assert _check_cells(render_fit._unit_cells(result), result.records(), first, frame,
                        render_fit.to_markdown(result)) >= 3 * len(first)


def test_runup_markdown_tables_are_their_declarations() -> None:
    from pathlib import Path

    from gyrovib.api.recordings.reading import read_recording
    from gyrovib.api.runup.results import ESTIMATE_RECORDS, STEP_RECORDS
    from gyrovib.api.runup.run import runup
    from gyrovib.records import frame_of
    from gyrovib.render import runup as render_runup

    example = Path(__file__).resolve().parent.parent / "docs" / "examples" / "runup-quad.npz"
    recording = read_recording(str(example), fs=200, accel_columns=("ax", "ay", "az"))
    result = runup(recording, gyrovib.load(), sensor="adis16460", estimate=("k2", "vre"))
    text = render_runup.to_markdown(result)
    steps, estimates = text.split("\n\n")[1:3]
    step_cells = render_runup._step_table(result)
    assert "predicted, deg/s" in [c.title for c in step_cells]  # the probe has a sensor
    assert _check_cells(step_cells, STEP_RECORDS, result.steps,
                        frame_of(STEP_RECORDS, result.steps), steps) >= 4 * len(result.steps)
    _check_cells(render_runup._estimate_table(result), ESTIMATE_RECORDS, result.estimates,
                 frame_of(ESTIMATE_RECORDS, result.estimates), estimates)


def test_junit_has_one_case_per_verdict_row(mission_result) -> None:
    # the generic JUnit writer over verdict rows: a test case per row, a failure exactly
    # where the row does not pass (an unverified one included), counted in the suite
    import xml.etree.ElementTree as ET

    from gyrovib.render import select_ci

    root = ET.fromstring(render_mission.to_junit(mission_result))
    cases = root.findall(".//testcase")
    assert len(cases) == len(mission_result.rows) == int(root.get("tests"))
    failed = [r.passed is False for r in mission_result.rows]
    assert [case.find("failure") is not None for case in cases] == failed
    assert int(root.get("failures")) == sum(failed) > 0  # the probe has failing rows
    result = gyrovib.select(budget="10deg/h", criterion="both")
    root = ET.fromstring(select_ci.to_junit(result))
    cases = root.findall(".//testcase")
    assert [(c.get("classname"), c.get("name")) for c in cases] == [
        (s, p) for s in result.sensors for p in result.profiles]
    assert [c.find("failure") is not None for c in cases] == [
        not bool(result.passed[i, j]) for i in range(len(result.sensors))
        for j in range(len(result.profiles))]


def test_select_and_bounds_markdown_headers_are_their_cells() -> None:
    # tables that are not one row per record (select's matrix: a column per profile;
    # bounds: a row per coefficient) still take their headers from their cells
    from gyrovib.render import bounds as render_bounds
    from gyrovib.render import select as render_select

    result = gyrovib.select(budget="10deg/h")
    table = _markdown(render_select.to_markdown(result))
    assert table[0] == [c.title for c in render_select._matrix(result)]
    assert table[0] == ["sensor", *result.profiles, "verdict"]
    assert [line[0] for line in table[1:]] == list(result.sensors)
    bounds = gyrovib.bounds(budget="10deg/h")
    table = _markdown(render_bounds.to_markdown(bounds))
    assert table[0] == [c.title for c in render_bounds._cells(bounds, 0)]
    assert [line[0] for line in table[1:]] == render_bounds._rows(bounds, 0)


#: mission's JSON key order as docs/output.md and docs/missions.md give it, written out
#: here (not read from the declaration under test): a row, its budget, what the budget
#: allows, its worst segment, a segment; each entry has these keys or some of them, in
#: this order. And the CSV header of ``mission --segments`` (docs/missions.md).
MISSION_JSON = {
    "row": ("sensor", "mission", "placement", "mean", "angle", "rms", "worst_segment",
            "segments", "saturated", "pass", "status", "unknown", "reason", "source",
            "budget", "axis", "worst_axis"),
    "budget": ("vibration", "arw", "bias_instability", "rrw", "repeatability", "total",
               "coverage", "unit", "lower_bound", "rests_on_bound", "bounds", "typical",
               "allowed"),
    "allowed": ("vibration", "arw", "bias_instability", "rrw", "repeatability", "unit",
                "limited_by", "upper"),
    "worst_segment": ("index", "profile", "total"),
    "segment": ("profile", "duration", "rate", "total", "rms", "saturated", "end", "budget"),
}
SEGMENTS_CSV = ("sensor", "mission", "placement", "axis", "segment", "profile", "start",
                "duration", "end", "rate_x1", "rate_x2", "rate_x3", "total", "rms",
                "saturated", "theta_vibration", "theta_arw", "theta_bias_instability",
                "theta_rrw", "theta_repeatability", "budget_total", "coverage", "lower_bound",
                "rests_on_bound", "bounds")


def _in_order(entry: dict, kind: str, always: tuple[str, ...] = ()) -> None:
    keys = list(entry)
    assert keys == [k for k in MISSION_JSON[kind] if k in entry], (kind, keys)
    assert set(always) <= set(keys), kind


@pytest.mark.parametrize("kwargs", [{"angle_budget": "0.5deg"}, {"budget": "36deg/h"},
                                    {"angle_budget": "0.5deg", "assume_unknown": "zero"}])
def test_mission_json_and_segments_csv_keep_their_documented_order(kwargs: dict) -> None:
    import json

    result = gyrovib.mission(**kwargs)
    rows = json.loads(render_mission.to_json(result))["mission"]
    budgets = 0
    for row in rows:
        _in_order(row, "row", ("sensor", "mission", "placement", "mean", "angle", "rms",
                               "segments", "pass", "status", "unknown", "source", "axis"))
        if isinstance(row.get("worst_segment"), dict):
            _in_order(row["worst_segment"], "worst_segment", MISSION_JSON["worst_segment"])
        for budget in [row.get("budget"), *(s.get("budget") for s in row["segments"])]:
            if isinstance(budget, dict):
                budgets += 1
                _in_order(budget, "budget", ("vibration", "total", "coverage"))
                if isinstance(budget.get("allowed"), dict):
                    _in_order(budget["allowed"], "allowed")
        for segment in row["segments"]:
            _in_order(segment, "segment", ("profile", "duration", "total", "rms"))
    assert budgets or "angle_budget" not in kwargs  # the probe: budgets were checked
    from gyrovib.render.mission_segments import segments_csv

    assert tuple(_csv(segments_csv(result))[0]) == SEGMENTS_CSV


#: select's JSON keys of a sensor and of a sensor × profile entry, in order, as
#: docs/output.md lists them (written out: not read from the declaration under test);
#: an entry has these or some of them (a spec-form part, a lot, a yield add theirs).
SELECT_SENSOR_KEYS = ("sensor", "source", "pass", "status", "unknown", "questions",
                      "profiles")
SELECT_ENTRY_KEYS = ("profile", "pass", "status", "unknown", "rms", "margin",
                     "criterion_margin", "disagrees", "checks", "total", "saturated", "reason")


def test_select_json_keys_are_the_documented_ones() -> None:
    import json

    from gyrovib.render import select as render_select

    document = json.loads(render_select.to_json(gyrovib.select(budget="10deg/h")))
    for sensor in document["sensors"]:
        assert tuple(sensor) == SELECT_SENSOR_KEYS
        for entry in sensor["profiles"]:
            assert tuple(entry) == SELECT_ENTRY_KEYS, tuple(entry)


def test_mission_csv_and_frame_carry_the_budget_marks_the_json_and_tables_have() -> None:
    # A total that is only a lower bound (a noise figure unknown), one that rests on a
    # figure given only as an upper bound (docs/examples/gx100-budget: its bias
    # instability and rate random walk are bounds from an Allan record), and an allowance
    # that is only an upper limit: the JSON's budget.lower_bound, rests_on_bound, bounds
    # and allowed.upper are the CSV's and the frame's lower_bound, rests_on_bound, bounds
    # and allowed_upper (names joined by spaces), row for row; the tables mark them '≥',
    # '≤' and '*'. They come last, so every other column keeps its place.
    import json

    from gyrovib.catalog.loader import bundled_paths
    from gyrovib.render.mission_segments import segments_csv

    root = Path(__file__).resolve().parents[1]
    files = [str(root / "docs" / "examples" / "gx100-budget.gyrovib.yaml"),
             *map(str, bundled_paths())]
    result = gyrovib.mission(files, angle_budget="0.5deg")
    rows = json.loads(render_mission.to_json(result))["mission"]
    table = _csv(render_mission.to_csv(result))
    frame = result.to_frame()
    marks = ("lower_bound", "rests_on_bound", "bounds", "allowed_upper")
    assert tuple(table[0][-4:]) == tuple(frame.columns[-4:]) == marks
    assert tuple(table[0][:-4]) == MISSION_CSV[:-4]
    seen = set()
    for k, (row, cells) in enumerate(zip(rows, table[1:], strict=True)):
        budget = row["budget"]
        want = (budget["lower_bound"], budget["rests_on_bound"], " ".join(budget["bounds"]),
                " ".join(budget["allowed"]["upper"]))
        assert tuple(cells[-4:]) == (str(want[0]).lower(), str(want[1]).lower(), *want[2:])
        assert tuple(frame[m].iloc[k] for m in marks) == want
        seen.add(want[:3])
    # the probe met each kind: a lower bound, a total resting on bounds (named)
    assert (True, False, "") in seen and (False, True, "bias_instability rrw") in seen
    # the segments' CSV and frame end with the same marks, as each segment's JSON budget
    segments = _csv(segments_csv(result))
    assert tuple(segments[0][-3:]) == marks[:3]
    flat = [s["budget"] for row in rows for s in row["segments"]]
    assert [tuple(line[-3:]) for line in segments[1:]] == [
        (str(b["lower_bound"]).lower(), str(b["rests_on_bound"]).lower(), " ".join(b["bounds"]))
        for b in flat]
    assert tuple(result.segments_frame().columns[-3:]) == marks[:3]
