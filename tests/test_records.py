"""The format is defined once (gyrovib.models): validation, the models, the
JSON Schema, the messages and the locator all follow it.

``validate`` and the JSON Schema must agree on every rule a JSON Schema can
express; the only rules left to ``validate`` are those it cannot (breakpoint
order, a PSD's band, a K1 so small a division overflows; NaN, which JSON
cannot write).
"""

from __future__ import annotations

import copy
import math
from pathlib import Path
from typing import Annotated

import jsonschema
import pytest
import yaml
from pydantic import AllowInfNan, Field, Strict, ValidationError

from gyrovib import models
from gyrovib.catalog import messages
from gyrovib.catalog.dialect import Loader
from gyrovib.catalog.loader import bundled_paths, parse_catalog
from gyrovib.errors import CatalogError
from gyrovib.models.schema import catalog_schema

BASE = {
    "gyrovib": 1,
    "units": {"rate": "deg/h", "acceleration": "m/s^2"},
    "sensors": [
        {"id": "s-1", "name": "S", "vendor": "V", "part": "P", "notes": "N", "range": 100,
         "coefficients": {"k0": 1, "k1": 1.0, "A1": 1e-4, "k2": -2e-7, "k3": 1e-9, "k4": 0.0,
                          "k5": 1e-12, "m1": 0.1, "m2": -0.1, "m31": 1e-6, "m32": 2e-6},
         "response": [[10, 1.0], [500, 0.7], [500, 0.5]]},
        {"id": "s.2", "output_coefficients": {"unit": "mV", "K1": 25, "K0": 2.0, "A1": 2e-3,
                                              "K2": 1e-4, "K3": 1, "K4": 0, "K5": 0, "M1": 0,
                                              "M2": 0, "M31": 1, "M32": -1},
         # the file's accelerations are in m/s²: a g² sensitivity carries its unit
         "g2_sensitivity": {"G11": "1.0e-4 deg/h/g^2",
                            "G22": {"value": 1e-4, "unit": "deg/h/(m/s^2)^2"},
                            "G33": "2.0e-4 deg/h/(m/s²)²", "G12": 0, "G13": "-1e-5 rpm/g²",
                            "G23": 0}},
        {"id": "s3", "specs": {"range": 100, "nonlinearity": {
            "value": 0.5, "unit": "%FS", "fit": "endpoint", "measure": "rms", "of": "span"},
            "asymmetry": {"value": 500, "unit": "ppm"},
            "vre": {"value": 4e-4, "unit": "deg/h/g^2"}},
         "vre": "1e-4 deg/h/g^2", "response": {"at": "input", "table": [[10, 1.0], [500, 0.7]]}},
    ],
    "profiles": [
        {"id": "p", "name": "P", "notes": "n", "rate": [0, 0, 30],
         "harmonic": [{"frequency": 120, "amplitude": [0.5, 0.5, 0.8], "phase": [0, 90, 0]}],
         "random": {"psd": {"x1": [[20, 1e-4], [2000, 1e-4]], "x3": [[20, 1e-4], [40, 1e-4]]},
                    "coherence": [0.5, -1]},
         "mount": [[20, 1.0], [200, 0.3]]},
        {"id": "q", "random": {"rms": [0.1, 0.1, 0.2]},
         "harmonics": [{"fundamental": 40, "orders": [
             {"order": 1, "amplitude": [0.1, 0.1, 0.5], "phase": [0, 0, 0]},
             {"order": 2, "amplitude": [0, 0, 0.3], "phase": "worst"}]}],
         "acceleration": {"harmonic": [{"frequency": 120, "amplitude": [0.5, 0.5, 2],
                                        "phase": [0, 0, 0]}],
                          "random": {"psd": {"x1": [[20, 0.04], [2000, 0.04]]},
                                     "coherence": [0, 0.5, 0]},
                          "mount": [[20, 1.0], [200, 0.3]]}},
    ],
    "allocation": {"r": 2, "w": [1, 1, 1, 0.5, 0.5], "v": [1, 0.5, 0.5]},
}

VALUES = [None, 0, 1, -1, 0.5, -0.5, 2, 1.5, True, False, "x", "deg/h", "mV", "", [], {},
          "worst", "%FS", "input", "rms", "minimax", 2.0,
          [1, 2, 3], [1, 2], [0, 0, 0, 0, 0], [[1, 1]], [[1, 1], [0.5, 1]], [[1, -1]],
          [1, [2], 3], {"x": 1}, math.inf, -math.inf, 10**400, 2**60, -(2**60),
          "a b", "a" * 201, "x" * 10_001, [[0, 1]], [[1, 1], [1, 2], [1, 3]]]

#: Messages of the rules a JSON Schema cannot express.
INEXPRESSIBLE = ("breakpoint frequencies must increase", "appears more than twice", "given twice",
                 "two different frequencies", "overflows; check the units of K1",
                 "not a valid correlation", "integrates to a variance", "is more than the range")


def paths(node, prefix=()):
    yield prefix
    if isinstance(node, dict):
        for key, value in node.items():
            yield from paths(value, (*prefix, key))
        yield (*prefix, "extra")
    elif isinstance(node, list):
        for i, value in enumerate(node):
            yield from paths(value, (*prefix, i))


DELETE = object()


def mutated(base, path, value):
    doc = copy.deepcopy(base)
    target = doc
    for part in path[:-1]:
        target = target[part]
    if value is DELETE:
        if isinstance(target, dict):
            target.pop(path[-1], None)
        else:
            del target[path[-1]]
    else:
        target[path[-1]] = value
    return doc


@pytest.fixture(scope="module")
def schema_validator() -> jsonschema.Draft7Validator:
    schema = catalog_schema()
    jsonschema.Draft7Validator.check_schema(schema)
    return jsonschema.Draft7Validator(schema)


def verdicts(data, schema_validator):
    """(validate's errors or None when valid, whether the JSON Schema accepts)."""
    try:
        models.validate_document(copy.deepcopy(data))
        errors = None
    except ValidationError as exc:
        errors = messages.errors(exc, data)
    return errors, schema_validator.is_valid(data)


def alone(path):
    """(document, path in it) for a mutation at ``path``: inside a sensor or a profile, BASE
    with that one item in its list and the other list empty, else BASE itself.

    Both verdicts are the conjunction of the items' verdicts: the schema checks each item
    by its own subschema, and validate's rules are per item (the catalogue-level rules read
    one sensor and the file's units, kept here; uniqueness of ids is the loader's, across
    files). The untouched items are valid for both (test_base_document_is_valid_for_both),
    so the mutated item alone gets the verdicts the whole BASE would, and every path and
    value is still tried: the same agreement checked at a fifth of the schema's cost."""
    if len(path) < 3 or path[0] not in ("sensors", "profiles"):
        return BASE, path
    doc = {key: value for key, value in BASE.items() if key not in ("sensors", "profiles")}
    doc["sensors" if path[0] == "profiles" else "profiles"] = []
    doc[path[0]] = [BASE[path[0]][path[1]]]
    return doc, (path[0], 0, *path[2:])


def test_base_document_is_valid_for_both(schema_validator):
    assert verdicts(BASE, schema_validator) == (None, True)
    for key in ("sensors", "profiles"):  # and each item alone, as alone() uses them
        for i in range(len(BASE[key])):
            assert verdicts(alone((key, i, "id"))[0], schema_validator) == (None, True)


@pytest.mark.parametrize("path", [p for p in paths(BASE) if p], ids=lambda p: ".".join(map(str, p)))
def test_validate_and_schema_agree(path, schema_validator):
    base, path = alone(path)
    for value in [*VALUES, DELETE]:
        data = mutated(base, path, value)
        errors, schema_ok = verdicts(data, schema_validator)
        if errors is None:
            assert schema_ok, f"the schema refuses what validate accepts: {value!r}"
        elif schema_ok:  # only a rule the schema cannot say may tell them apart
            texts = [messages.message(e, data) for e in errors]
            assert all(any(m in t for m in INEXPRESSIBLE) for t in texts), (value, texts)


@pytest.mark.parametrize(("edit", "valid"), [
    # a null conversion function is "not given" for both
    ({"coefficients": None}, True),
    ({"output_coefficients": None}, False),
    ({"coefficients": None, "output_coefficients": None}, False),
    ({"coefficients": {}, "output_coefficients": {"K1": 1}}, False),
])
def test_null_next_to_the_other_form(edit, valid, schema_validator):
    doc = copy.deepcopy(BASE)
    doc["sensors"][1].update(edit)  # s.2 has output_coefficients
    errors, schema_ok = verdicts(doc, schema_validator)
    assert (errors is None) is valid
    assert schema_ok is valid


@pytest.mark.parametrize("value", [[[20, 1e-4]], [[20, math.inf], [40, 1]]])
def test_schema_refuses_one_point_psd_and_infinities(value, schema_validator):
    doc = copy.deepcopy(BASE)
    doc["profiles"][0]["random"]["psd"]["x1"] = value
    assert verdicts(doc, schema_validator)[0] is not None
    assert not schema_validator.is_valid(doc)


@pytest.mark.parametrize("where", [("sensors", 0, "coefficients", "k2"),
                                   ("profiles", 0, "rate", 1)])
def test_schema_refuses_infinite_coefficients_and_rates(where, schema_validator):
    for value in (math.inf, -math.inf, 10**400):
        doc = mutated(BASE, where, value)
        assert verdicts(doc, schema_validator)[0] is not None
        assert not schema_validator.is_valid(doc)


def test_validation_accepts_many_mutations():
    # each mutation in its item alone (alone()): validate accepts it there iff in BASE
    accepted = sum(1 for path in paths(BASE) if path for value in [*VALUES, DELETE]
                   if _valid(mutated(*alone(path), value)))
    assert accepted > 200


def _valid(data):
    try:
        models.validate_document(data)
    except ValidationError:
        return False
    return True


def test_defaults_of_the_models_are_their_fields_defaults():
    built = models.validate_document({"gyrovib": 1, "profiles": [{"id": "p"}]})
    assert built.profiles[0].rate == models.Profile.model_fields["rate"].default
    assert built.units == models.Units(rate="deg/s")
    assert built.units.acceleration == models.Units.model_fields["acceleration"].default
    assert models.Allocation().w == models.Allocation.model_fields["w"].default
    assert models.Tone(frequency=1, amplitude=[0, 0, 0]).phase == (0.0, 0.0, 0.0)


# ---------------------------------------------------------------- the models drive everything


CHANGED = """\
gyrovib: 1
sensors:
  - id: s
    range: 2.0e+6
    coefficients: {}
  - id: t
    range: 12.5
    coefficients: {}
  - id: u
    ranges: 1
    coefficients: {}
"""


@pytest.fixture
def capped_range(monkeypatch):
    """Sensor.range bounded above by 1e6 as well: the field's constraint changed in
    the model and the models rebuilt (undone afterwards)."""
    from annotated_types import Le

    field = models.Sensor.model_fields["range"]
    changed = copy.copy(field)
    changed.annotation = Annotated[float, Strict(), AllowInfNan(False), Field(gt=0),
                                   Le(1e6)] | None
    monkeypatch.setitem(models.Sensor.model_fields, "range", changed)
    models.Sensor.model_rebuild(force=True)
    models.Catalogue.model_rebuild(force=True)
    yield
    monkeypatch.undo()
    models.Sensor.model_rebuild(force=True)
    models.Catalogue.model_rebuild(force=True)


def _problems(text):
    try:
        parse_catalog(text, "c.yaml")
    except CatalogError as exc:
        return [str(p) for p in exc.problems]
    return []


def test_a_changed_bound_changes_validate_schema_and_messages(capped_range):
    # validate and its located message follow the model
    assert _problems(CHANGED) == [
        "c.yaml:4:12: sensor 's': range: must not be greater than 1000000, got 2000000.0",
        "c.yaml:10:5: sensor 'u': unknown key 'ranges'; did you mean 'range'?",
    ]
    assert parse_catalog(CHANGED.split("  - id: u")[0].replace("2.0e+6", "9"),
                         "c.yaml").model.sensors[0].range == 9.0
    # the JSON Schema follows
    schema = catalog_schema()
    sensor = schema["definitions"]["Sensor"]["properties"]
    assert sensor["range"]["anyOf"][0]["maximum"] == 1e6
    check = jsonschema.Draft7Validator(schema)
    assert not check.is_valid({"gyrovib": 1, "sensors": [{"id": "s", "range": 2e6,
                                                          "coefficients": {}}]})


def test_the_shipped_bound_is_back_after_the_change():
    assert _problems(CHANGED) == [
        "c.yaml:10:5: sensor 'u': unknown key 'ranges'; did you mean 'range'?"]
    sensor = catalog_schema()["definitions"]["Sensor"]["properties"]
    assert sensor["range"]["anyOf"][0]["maximum"] > 1e300


def test_no_bound_or_default_is_written_outside_the_models():
    """The old constants of the hand-written format are gone; the numbers of the
    format (bounds, most tones, table sizes) are named only in gyrovib.models."""
    src = Path(models.__file__).parents[1]
    outside = [p for p in src.rglob("*.py") if "models" not in p.relative_to(src).parts]
    for name in ("MAX_TONES", "MAX_TABLE", "MAX_TEXT", "MAX_ID", "ID_PATTERN",
                 "NONLINEARITY_UNITS", "ASYMMETRY_UNITS", "RESPONSE_AT", "FLOAT_MAX",
                 "_RATE_FORM", "spec.FORMAT", "catalog.spec", "catalog.kinds",
                 "catalog.records", "catalog.validate", "catalog.jsonschema"):
        users = [p.name for p in outside if name in p.read_text(encoding="utf-8")]
        assert not users, (name, users)


EXAMPLE = Path(__file__).parents[1] / "docs" / "examples" / "select-example.yaml"


@pytest.mark.parametrize("path", [*sorted(bundled_paths()), EXAMPLE], ids=lambda p: p.name)
def test_real_catalogues_are_valid_for_both(path, schema_validator):
    if not path.exists():
        pytest.skip("no such example")
    data = yaml.load(path.read_text(encoding="utf-8"), Loader=Loader)
    assert verdicts(data, schema_validator) == (None, True)


def test_huge_integer_still_loads():
    src = parse_catalog("gyrovib: 1\nsensors:\n  - id: s\n"
                        "    coefficients: {k2: 1180591620717411303424}\n")
    assert isinstance(src.model, models.Catalogue)
    assert src.model.sensors[0].rate_coefficients.k2 == 2.0**70


def test_records_are_immutable():
    src = parse_catalog("gyrovib: 1\nsensors:\n  - id: s\n    coefficients: {k2: 1}\n")
    with pytest.raises(ValidationError, match="frozen"):
        src.model.sensors[0].id = "t"  # type: ignore[misc]


@pytest.mark.parametrize("text", [
    "gyrovib: 1\nsensors:\n  - &a {id: s, coefficients: {}}\n",
    "gyrovib: 1\nsensors:\n  - id: !!str s\n    coefficients: {}\n",
    "gyrovib: 1\nbase: &b {k2: 1}\n",
    "gyrovib: 1\nprofiles:\n  - id: p\n    rate: [0, 0, -.inf]\n",
    "gyrovib: 1\nprofiles:\n  - {id: p, rate: [+1, -0, 1.5e3], notes: ~}\n",
    "gyrovib: 1\nprofiles:\n  - {id: p, name: 'true', notes: True}\n",
    "gyrovib: 1\n1: x\n",
])
def test_fast_yaml_construction_equals_pyyaml(text):
    from gyrovib.catalog.dialect import _stream, _Unusual

    loader = Loader(text)
    try:
        node = loader.get_single_node()
        expected = loader.construct_document(node)
    finally:
        loader.dispose()
    loader = Loader(text)
    try:
        got = _stream(loader)
    except _Unusual:  # the slow path takes over: nothing to compare
        return
    finally:
        loader.dispose()
    assert repr(got) == repr(expected)


def test_columns_declared_after_one_column_keep_their_order_and_a_missing_one_is_named() -> None:
    """``csv_after``: two columns placed after the same one follow it in the declaration's
    order; one placed after a column the output lacks (absent, or skipped there) is a
    ValueError naming both."""
    from dataclasses import replace

    from gyrovib.records import Column, names, written

    a, x = Column("a", None, str), Column("x", None, str)
    b, c = Column("b", None, str, csv_after="a"), Column("c", None, str, csv_after="a")
    assert names(written((a, x, b, c), "csv")) == ("a", "b", "c", "x")
    assert names(written((a, x, b, c), "json")) == ("a", "x", "b", "c")
    with pytest.raises(ValueError, match="'b' is declared after 'a', which the csv"):
        written((replace(a, skip=("csv",)), x, b), "csv")
    assert names(written((replace(a, skip=("csv",)), x, b), "frame")) == ("a", "b", "x")
