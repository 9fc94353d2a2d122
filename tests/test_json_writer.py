"""The fast JSON writer over declared records (render/formats.json_text) against its plain
reference: ``json.dumps(json_of(...), allow_nan=False)``, one dict per row, which the
standard library encodes. Each case is built so that a shortcut of the fast writer would
show: values repeated across rows (encoded once), 0.0 beside -0.0 (equal, but written
apart), NaN (null), an infinity (null, or refused where the column says it overflowed),
texts with '%' and non-ASCII characters, keys on some rows only, lists and nested objects,
and blocks of rows."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from gyrovib.records import Column
from gyrovib.render import formats
from gyrovib.render.formats import json_of, json_text

ROWS = list(range(11))


def reference(columns, rows) -> str:
    return json.dumps(json_of(columns, rows), allow_nan=False)


def _value(k: int) -> float:
    # repeats (k % 4), signed zeros, NaN, and numbers that need all 17 digits
    return [0.0, -0.0, math.nan, 0.1 + 0.2, 1e-300, -2.5e16][k % 6] * (1 + (k % 4 == 3))


COLUMNS = (
    Column("name", None, lambda k: f"s-{k % 3} 50 % Δ"),
    Column("x", None, _value),
    Column("rate_x1", None, lambda k: float(k), key="rate.0"),
    Column("rate_x2", None, lambda k: -float(k), key="rate.1"),
    Column("a", None, lambda k: k * 0.5, key="terms.a"),
    Column("b", None, lambda k: math.inf if k == 4 else 1.0, key="terms.b"),
    Column("flag", None, lambda k: k % 2 == 0),
    Column("count", None, lambda k: k),
    Column("maybe", None, lambda k: None if k % 3 else "yes"),
    Column("lot", None, lambda k: True, only=lambda k: k % 5 == 0),
    Column("u", None, lambda k: k / 7, key="uncertainty.total", only=lambda k: k > 6),
    Column("phases", None, lambda k: [{"2": 90.0}], only=lambda k: k == 3),
    Column("warnings", None, lambda k: ("ω saturates",) * (k % 2)),
    # read one row at a time as numpy scalars (NaN and inf among them), and tuples that
    # hold a dict: json_of's text, not a refusal or an unhashable value
    Column("scalar", None, lambda k: np.float64(math.nan if k == 1 else math.inf if k == 2
                                                 else k / 3)),
    Column("parts", None, lambda k: ({"order": k},)),
)


def test_same_text_as_json_dumps_of_the_entries() -> None:
    text = json_text(COLUMNS, ROWS)
    assert text == reference(COLUMNS, ROWS)
    entries = json.loads(text)
    # the probes: a key on some rows only, -0.0 kept apart from 0.0, NaN and inf as null
    assert [("lot" in e) for e in entries] == [k % 5 == 0 for k in ROWS]
    assert text.count('"x": -0.0') == 2 and text.count('"x": 0.0,') == 2
    assert entries[2]["x"] is None and entries[4]["terms"]["b"] is None


@pytest.mark.parametrize("block", [1, 2, 5, 4096])
def test_same_text_in_any_block_of_rows(monkeypatch, block: int) -> None:
    monkeypatch.setattr(formats, "_BLOCK", block)
    assert json_text(COLUMNS, ROWS) == reference(COLUMNS, ROWS)


def test_an_overflow_is_refused_where_the_column_says_so() -> None:
    finite = (*COLUMNS[:5], Column("b", None, COLUMNS[5].value, key="terms.b", finite=True))
    with pytest.raises(ValueError, match="JSON compliant"):
        json_text(finite, ROWS)
    with pytest.raises(ValueError, match="JSON compliant"):
        reference(finite, ROWS)
    # NaN stays unknown (null) in such a column
    nan = (COLUMNS[0], Column("x", None, _value, finite=True))
    assert json_text(nan, ROWS) == reference(nan, ROWS)
    assert json.loads(json_text(nan, ROWS))[2]["x"] is None


def test_columns_read_many_rows_at_once() -> None:
    many = tuple(Column(c.name, c.unit, c.value, key=c.key, only=c.only,
                        many=lambda rows, read=c.value: [read(k) for k in rows])
                 for c in COLUMNS)
    assert json_text(many, ROWS) == reference(COLUMNS, ROWS)


def test_keys_on_some_rows_at_any_depth_and_in_any_place() -> None:
    # an object whose keys are on different rows (a coefficient row's checks beside a
    # datasheet row's), a first key on some rows only, an entry with no key at all:
    # each row has its own set of keys, its commas where json writes them
    split = (Column("u", None, float, key="u.a", only=lambda k: k > 2),
             Column("v", None, float, key="u.b"),
             Column("w", None, float, key="u.c", only=lambda k: k % 2 == 0),
             COLUMNS[0], COLUMNS[9])
    text = json_text(split, ROWS)
    assert text == reference(split, ROWS)
    entries = json.loads(text)
    assert list(entries[0]["u"]) == ["b", "c"] and list(entries[3]["u"]) == ["a", "b"]
    only = (Column("a", None, float, only=lambda k: k == 1),)
    assert json_text(only, ROWS) == reference(only, ROWS)
    assert json.loads(json_text(only, ROWS))[:2] == [{}, {"a": 1.0}]


def test_sub_records_and_the_json_reading_of_a_row() -> None:
    # a row lists its sub-records (each), some of them with keys on some of them only,
    # none for some rows; a column the JSON reads its own way (json_value: None or a list)
    sub = (Column("sensor", None, lambda r: r[0], skip=("json",)),
           Column("j", None, lambda r: r[1]),
           Column("x", None, lambda r: _value(r[1]), key="x.value"),
           Column("odd", None, lambda r: "%s", key="x.odd", only=lambda r: r[1] % 2 == 1))
    columns = (Column("name", None, lambda k: f"s{k}"),
               Column("low", None, lambda k: k / 3, key="interval",
                      json_value=lambda k: None if k % 3 else [k / 3, None]),
               Column("high", None, lambda k: k / 2, skip=("json",)),
               Column("cells", None, lambda k: [(k, j) for j in range(k % 4)], each=sub))
    for block in (1, 3, 4096):
        text = "[" + "".join(formats.json_blocks(columns, ROWS, block)) + "]"
        assert text == reference(columns, ROWS)
    entries = json.loads(text)
    assert entries[3]["interval"] == [1.0, None] and entries[1]["interval"] is None
    assert [len(e["cells"]) for e in entries] == [k % 4 for k in ROWS]
    assert entries[3]["cells"][1] == {"j": 1, "x": {"value": -0.0, "odd": "%s"}}


def test_no_rows() -> None:
    assert json_text(COLUMNS, []) == reference(COLUMNS, []) == "[]"


def test_a_column_that_repeats_its_values() -> None:
    # most rows share a few values (a profile's rate, a term many sensors lack): written
    # a distinct value at a time, still told apart by sign, NaN null, infinity null
    import numpy as np

    rows = list(range(1000))
    cycle = [0.0, -0.0, math.nan, 0.1, math.inf]
    array = np.array([cycle[k % 5] for k in rows])
    columns = (Column("k", None, lambda k: k),
               Column("v", None, lambda k: cycle[k % 5]),
               Column("w", None, lambda k: array[k].item(),
                      many=lambda chosen: array[np.asarray(chosen, dtype=int)]))
    text = json_text(columns, rows)
    assert text == reference(columns, rows)
    assert text.count('"v": -0.0') == text.count('"w": -0.0') == 200
    assert text.count('"w": null') == 400
    finite = (columns[0], Column("v", None, columns[1].value, finite=True))
    with pytest.raises(ValueError, match="JSON compliant"):
        json_text(finite, rows)
