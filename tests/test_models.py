"""gyrovib.models in Python: a catalogue built as models (validated or
constructed) is analysed like the same catalogue read from a file; a loaded
catalogue exposes its models; the draft-07 step of the JSON Schema."""

from __future__ import annotations

import numpy as np
import pytest
from pydantic import ValidationError

import gyrovib
from gyrovib.errors import CatalogError
from gyrovib.models import Catalogue, Coefficients, Profile, Sensor, Tone
from gyrovib.models.schema import DRAFT_07, FLOAT_MAX, draft_07

TEXT = """\
gyrovib: 1
units: {rate: deg/h}
sensors:
  - id: a
    coefficients: {A1: 1.0e-3, k2: 2.0e-5, k4: 1.0e-9, m31: 1.0e-6}
  - id: b
    output_coefficients: {K1: 25, K2: 5.0e-4}
profiles:
  - id: tone
    rate: [0, 0, 36]
    harmonic: [{frequency: 100, amplitude: [0, 0, 7200]}]
  - id: rms
    random: {rms: [3600, 3600, 7200]}
"""

DATA = {
    "gyrovib": 1, "units": {"rate": "deg/h"},
    "sensors": [{"id": "a", "coefficients": {"A1": 1.0e-3, "k2": 2.0e-5, "k4": 1.0e-9,
                                             "m31": 1.0e-6}},
                {"id": "b", "output_coefficients": {"K1": 25, "K2": 5.0e-4}}],
    "profiles": [{"id": "tone", "rate": [0, 0, 36],
                  "harmonic": [{"frequency": 100, "amplitude": [0, 0, 7200]}]},
                 {"id": "rms", "random": {"rms": [3600, 3600, 7200]}}],
}


@pytest.fixture(scope="module")
def from_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("cat") / "c.gyrovib.yaml"
    path.write_text(TEXT, encoding="utf-8")
    return str(path)


def test_a_validated_model_analyses_as_its_file(from_file):
    model = Catalogue.model_validate(DATA)
    got = gyrovib.analyze(model, unit="deg/h")
    want = gyrovib.analyze(from_file, unit="deg/h")
    assert got.sensors == want.sensors == ("a", "b")
    # the same numbers, and not vacuously: every sensor has an error under the tone
    assert np.array_equal(got.error.total, want.error.total)
    assert np.all(np.abs(got.error.total[:, 0]) > 0)


def test_a_constructed_model_is_accepted_by_every_notebook_function(from_file):
    model = Catalogue(
        gyrovib=1, units={"rate": "deg/h"},
        sensors=[Sensor(id="a", coefficients=Coefficients(A1=1.0e-3, k2=2.0e-5, k4=1.0e-9,
                                                          m31=1.0e-6)),
                 Sensor(id="b", output_coefficients={"K1": 25, "K2": 5.0e-4})],
        profiles=[Profile(id="tone", rate=(0, 0, 36),
                          harmonic=[Tone(frequency=100, amplitude=(0, 0, 7200))]),
                  Profile(id="rms", random={"rms": (3600, 3600, 7200)})])
    assert model == Catalogue.model_validate(DATA)
    assert np.array_equal(gyrovib.analyze(model, unit="deg/h").error.total,
                          gyrovib.analyze(from_file, unit="deg/h").error.total)
    b = gyrovib.bounds(model, budget="10deg/h")
    assert b.profiles == ("tone", "rms")
    s = gyrovib.select(model, budget="10deg/h")
    assert set(s.sensors) == {"a", "b"}
    w = gyrovib.sweep(model, rates=[-100, 100], sensors="a", profiles="tone")
    assert w.sensors == ("a",)


def test_ids_repeated_across_python_catalogues_are_refused():
    one = Catalogue.model_validate({"gyrovib": 1, "sensors": [{"id": "a", "coefficients": {}}],
                                    "profiles": [{"id": "p"}]})
    with pytest.raises(CatalogError, match="duplicate sensor id 'a'"):
        gyrovib.analyze([one, one])


def test_a_loaded_catalogue_exposes_its_models(from_file):
    catalog = gyrovib.load(from_file)
    (model,) = catalog.models
    assert isinstance(model, Catalogue) and model.rate_unit == "deg/h"
    assert [type(s) for s in catalog.sensor_models] == [Sensor, Sensor]
    assert catalog.sensor_models[1].rate_coefficients.k2 == pytest.approx(5.0e-4 / 25)
    assert [p.id for p in catalog.profile_models] == ["tone", "rms"]
    assert model == Catalogue.model_validate(DATA)


@pytest.mark.parametrize("value", ["1e3", True, None, float("nan"), float("inf"), [1]])
def test_numbers_are_strict(value):
    with pytest.raises(ValidationError):
        Coefficients(k2=value)


def test_integers_are_numbers_and_models_are_frozen():
    c = Coefficients(k2=3)
    assert c.k2 == 3.0 and type(c.k2) is float
    with pytest.raises(ValidationError, match="frozen"):
        c.k2 = 1.0  # type: ignore[misc]
    with pytest.raises(ValidationError, match="give the conversion function once"):
        Sensor(id="s")
    with pytest.raises(ValidationError, match="extra"):
        Sensor(id="s", coefficients={}, mass=3)  # type: ignore[call-arg]


# ---------------------------------------------------------------- the draft-07 step


def test_draft_07_step():
    pydantic_schema = {
        "$defs": {"B": {"title": "B", "type": "object", "properties": {
            "t": {"title": "T", "type": "array", "maxItems": 2, "minItems": 2,
                  "prefixItems": [{"type": "number", "exclusiveMinimum": 0},
                                  {"type": "integer"}]},
            "c": {"$ref": "#/$defs/C", "description": "a C", "default": {"title": "kept"}},
        }}, "C": {"type": "object", "properties": {}}},
        "title": "A", "type": "object",
        "properties": {"b": {"anyOf": [{"$ref": "#/$defs/B"}, {"type": "null"}]},
                       "title": {"type": "string", "title": "Title"}},
    }
    assert draft_07(pydantic_schema) == {
        "type": "object",
        "properties": {"b": {"anyOf": [{"$ref": "#/definitions/B"}, {"type": "null"}]},
                       "title": {"type": "string"}},
        "definitions": {
            "B": {"type": "object", "properties": {
                "t": {"type": "array", "maxItems": 2, "minItems": 2, "additionalItems": False,
                      "items": [{"type": "number", "exclusiveMinimum": 0,
                                 "maximum": FLOAT_MAX},
                                {"type": "integer"}]},
                "c": {"allOf": [{"$ref": "#/definitions/C"}], "description": "a C",
                      "default": {"title": "kept"}},
            }},
            "C": {"type": "object", "properties": {}},
        },
    }


def test_gyrovib_schema_is_the_models_schema_in_draft_07_form():
    from gyrovib.models.schema import catalog_schema

    schema = catalog_schema()
    assert schema["$schema"] == DRAFT_07
    body = draft_07(Catalogue.model_json_schema())
    assert schema["definitions"] == body["definitions"]
    assert schema["properties"] == body["properties"]
    assert set(schema["definitions"]) >= {"Sensor", "Profile", "Allocation", "Units"}


# ---------------------------------------------------------------- messages of pydantic's errors


def _messages(text):
    from gyrovib.catalog.loader import parse_catalog

    with pytest.raises(CatalogError) as info:
        parse_catalog(text, "c.yaml")
    return [str(p) for p in info.value.problems]


def test_a_bad_value_in_a_list_of_five_or_six_is_not_a_wrong_count():
    # pydantic counts a tuple after dropping its bad values ("4 items"): not said
    assert _messages("gyrovib: 1\nallocation: {w: [1, 1, -1, 1, 1]}\n") == [
        "c.yaml:2:24: allocation.w[2]: must be positive (greater than 0), got -1"]
    assert _messages("gyrovib: 1\nallocation: {w: [1, 1, 1, 1]}\n") == [
        "c.yaml:2:17: allocation.w: too few values (4; expected 5 or 6)"]


def test_a_wrong_count_is_said_once_not_with_its_values():
    assert _messages("gyrovib: 1\nprofiles:\n  - {id: p, rate: [[1], 2, 3, 4]}\n") == [
        "c.yaml:3:19: profile 'p': rate: too many values (4; expected 3)"]


def test_the_one_of_rule_follows_the_mappings_other_problems():
    assert _messages("gyrovib: 1\nsensors:\n  - {name: n, x: 1}\n") == [
        "c.yaml:3:5: sensors[0]: missing required key 'id'",
        "c.yaml:3:5: sensors[0]: give the conversion function once: either 'coefficients' "
        "(eq. 2), 'output_coefficients' (eq. 1), 'specs' (the datasheet) or 'lot' (a "
        "production lot)",
        "c.yaml:3:15: sensors[0]: unknown key 'x'; allowed here: id, name, vendor, part, "
        "notes, range, coefficients, output_coefficients, specs, response, g2_sensitivity, vre, "
        "uncertainty, lot, noise",
    ]


def test_values_other_layers_hold_agree_with_the_models():
    """Where another layer must hold a value of the format without importing pydantic
    (the engine's paper allocation, the command line's --nl-* choices, read by
    `gyrovib --help`), it must agree with the models."""
    from typing import get_args

    from gyrovib.cli import spec_options
    from gyrovib.core import synthesis
    from gyrovib.models import Allocation, Nonlinearity

    a = Allocation()
    assert (a.r, a.w, a.v) == (synthesis.DEFAULT_R, synthesis.DEFAULT_W, synthesis.DEFAULT_V)
    fields = Nonlinearity.model_fields
    assert get_args(fields["fit"].annotation) == spec_options.NL_FITS
    assert get_args(fields["measure"].annotation) == spec_options.NL_MEASURES
    assert get_args(fields["of"].annotation) == spec_options.NL_OF


def test_two_broken_rules_of_one_mapping_are_both_said():
    assert _messages("gyrovib: 1\nsensors:\n  - {id: a, coefficients: {}, specs: {range: 1, "
                     "nonlinearity: {value: 1, unit: '%FS'}}, vre: 1, g2_sensitivity: {}}\n") == [
        "c.yaml:3:5: sensor 'a': give the conversion function once: either 'coefficients' "
        "(eq. 2), 'output_coefficients' (eq. 1), 'specs' (the datasheet) or 'lot' (a "
        "production lot)",
        "c.yaml:3:5: sensor 'a': give the g² sensitivity once: 'g2_sensitivity' or its "
        "shorthand 'vre' (G11 = G22 = G33), not both",
    ]


def test_the_schema_carries_units_and_descriptions_from_the_models():
    from gyrovib.models.schema import catalog_schema

    sensor = catalog_schema()["definitions"]["Sensor"]["properties"]
    assert sensor["range"]["unit"] == "rate"
    assert sensor["range"]["description"] == Sensor.model_fields["range"].description
    assert sensor["vre"]["unit"] == "rate/g^2"
