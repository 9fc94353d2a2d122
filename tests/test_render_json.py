"""analyze's JSON writer (render/formats.json_text over analyze's declared records) writes
exactly what json.dumps gives for the document of one dict per row (render/formats.json_of
over the same records): the fast text and the plain reference agree byte for byte."""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest

from gyrovib import api
from gyrovib.api.evaluation.records import analysis_cells, analysis_columns
from gyrovib.catalog.loader import merge, parse_catalog
from gyrovib.render import analysis as render
from gyrovib.render import formats
from gyrovib.render.common import dumps
from tests.conftest import MIXED_FORMS

CATALOG = MIXED_FORMS


def reference(result) -> str:
    """The document built one dict per row (json_of) and written by json.dumps."""
    rows = formats.json_of(analysis_columns(result), analysis_cells(result))
    return dumps({**render._head(result), "results": rows})


@pytest.fixture
def result():
    catalog = merge([parse_catalog(CATALOG, "cat.yaml")])
    return api.analyze(catalog, unit="deg/s")


def test_same_text_as_the_row_by_row_document(result):
    assert result.warnings  # a warning with non-ASCII text is part of the check
    text = render.to_json(result)
    assert text == reference(result)
    assert json.loads(text)["results"][0]["warnings"]


def test_same_text_in_blocks(result, monkeypatch):
    monkeypatch.setattr(formats, "_BLOCK", 2)
    assert render.to_json(result) == reference(result)


def test_bundled_catalogues_same_text():
    result = api.analyze(api.load())
    assert render.to_json(result) == reference(result)


def test_stderr_column_with_non_finite_values(result):
    stderr = np.arange(result.error.total.size, dtype=float).reshape(result.error.total.shape)
    stderr[0, 0] = np.inf
    numeric = dataclasses.replace(result, method="numeric", stderr=stderr, samples=64, seed=0)
    text = render.to_json(numeric)
    assert text == reference(numeric)
    assert json.loads(text)["results"][0]["stderr"] is None


def test_infinite_values_are_refused_as_json_refuses_them(result):
    error = dataclasses.replace(result.error, total=result.error.total * np.inf)
    with pytest.raises(ValueError, match="JSON compliant"):
        render.to_json(dataclasses.replace(result, error=error))


def test_nan_is_unknown_and_written_null(result):
    # NaN is an error that is unknown (a profile fitted from a recording without an axis
    # the sensor needs, docs/model.md section 13): null, never a number
    total = np.array(result.error.total)
    total[0, 0] = np.nan
    error = dataclasses.replace(result.error, total=total)
    rows = json.loads(render.to_json(dataclasses.replace(result, error=error)))["results"]
    assert rows[0]["total"] is None and rows[1]["total"] == float(total[1, 0])


def test_no_sensors():
    result = api.analyze(api.load(), sensors=(), profiles=())
    empty = dataclasses.replace(result, sensors=(), error=dataclasses.replace(
        result.error, **{f.name: getattr(result.error, f.name)[:0]
                         for f in dataclasses.fields(result.error)}), warnings={})
    assert render.to_json(empty) == reference(empty)
    assert json.loads(render.to_json(empty))["results"] == []
