"""The format is defined once (catalog/spec.py): the validator, the records,
the JSON Schema, the messages and the locator all follow it.

``validate`` and the JSON Schema must agree on every rule a JSON Schema can
express; the only rules left to ``validate`` are those it cannot (breakpoint
order, a PSD's band, a K1 so small a division overflows; NaN, which JSON
cannot write).
"""

from __future__ import annotations

import copy
import math
from pathlib import Path

import jsonschema
import pytest
import yaml

from gyrovib.catalog import kinds, messages, records, spec
from gyrovib.catalog.jsonschema import catalog_schema
from gyrovib.catalog.loader import _Loader, bundled_paths, parse_catalog
from gyrovib.catalog.locate import Index
from gyrovib.catalog.validate import Invalid, Validator

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
         "g2_sensitivity": {"G11": 1e-4, "G22": 1e-4, "G33": 2e-4, "G12": 0, "G13": -1e-5,
                            "G23": 0}},
        {"id": "s3", "specs": {"range": 100, "nonlinearity": {
            "value": 0.5, "unit": "%FS", "fit": "endpoint", "measure": "rms", "of": "span"},
            "asymmetry": {"value": 500, "unit": "ppm"}, "vre": 4e-4},
         "vre": 1e-4, "response": {"at": "input", "table": [[10, 1.0], [500, 0.7]]}},
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
                 "two different frequencies", "overflows; check the units of K1")


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


def mutated(path, value):
    doc = copy.deepcopy(BASE)
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
        records.catalog_file(copy.deepcopy(data))
        errors = None
    except Invalid as exc:
        errors = exc.errors
    return errors, schema_validator.is_valid(data)


def test_base_document_is_valid_for_both(schema_validator):
    assert verdicts(BASE, schema_validator) == (None, True)


@pytest.mark.parametrize("path", [p for p in paths(BASE) if p], ids=lambda p: ".".join(map(str, p)))
def test_validate_and_schema_agree(path, schema_validator):
    for value in [*VALUES, DELETE]:
        data = mutated(path, value)
        errors, schema_ok = verdicts(data, schema_validator)
        if errors is None:
            assert schema_ok, f"the schema refuses what validate accepts: {value!r}"
        elif schema_ok:  # only a rule the schema cannot say may tell them apart
            texts = [messages.message(e, data) for e in errors]
            assert all(any(m in t for m in INEXPRESSIBLE) for t in texts), (value, texts)


@pytest.mark.parametrize(("edit", "valid"), [
    # issue 15: a null conversion function is "not given" for both
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
        doc = mutated(where, value)
        assert verdicts(doc, schema_validator)[0] is not None
        assert not schema_validator.is_valid(doc)


def test_validation_accepts_many_mutations():
    accepted = sum(1 for path in paths(BASE) if path for value in [*VALUES, DELETE]
                   if _valid(mutated(path, value)))
    assert accepted > 200


def _valid(data):
    try:
        records.catalog_file(data)
    except Invalid:
        return False
    return True


def test_defaults_of_the_records_come_from_the_spec():
    assert records.Allocation._defaults == spec.defaults("Allocation")
    assert records.Tone._defaults["phase"] == (0.0, 0.0, 0.0)
    built = records.catalog_file({"gyrovib": 1, "profiles": [{"id": "p"}]})
    assert built.profiles[0].rate == spec.FORMAT["Profile"].field("rate").default
    assert built.units == records.Units(rate="deg/s")


# ---------------------------------------------------------------- the spec drives everything


def _changed_format():
    """The format with Sensor.range bounded by 1e6 and a new sensor field 'mass'."""
    fmt = dict(spec.FORMAT)
    sensor = fmt["Sensor"]
    fields = []
    for f in sensor.fields:
        if f.name == "range":
            f = f._replace(type=f.type._replace(maximum=1e6))
        fields.append(f)
    fields.append(kinds.Field("mass", kinds.Number(minimum=0), None, nullable=True,
                             description="Mass in grams.", unit="g"))
    fmt["Sensor"] = sensor._replace(fields=tuple(fields))
    return fmt


CHANGED = """\
gyrovib: 1
sensors:
  - id: s
    range: 2.0e+6
    mass: -3
    coefficients: {}
  - id: t
    mass: 12.5
    coefficients: {}
  - id: u
    masse: 1
    coefficients: {}
"""


def test_a_changed_spec_changes_validate_schema_messages_and_locator():
    fmt = _changed_format()
    data = yaml.load(CHANGED, Loader=_Loader)
    # the validator (the only path: the same code builds records for valid files)
    with pytest.raises(Invalid) as info:
        Validator(fmt)(data)
    errors = info.value.errors
    index = Index(CHANGED)
    found = {}
    for e in errors:
        place = index.place(e.loc, want_key=e.kind == "unknown_key")
        found[messages.message(e, data)] = place
    assert found == {
        "sensor 's': range: must not be greater than 1000000, got 2000000.0": (4, 12),
        "sensor 's': mass: must not be negative, got -3": (5, 11),
        "sensor 'u': unknown key 'masse'; did you mean 'mass'?": (11, 5),
    }
    # valid data with the new field: built, with the field
    valid = {"gyrovib": 1, "sensors": [{"id": "t", "mass": 12.5, "coefficients": {}}]}
    assert Validator(fmt)(valid)["sensors"][0]["mass"] == 12.5
    # the JSON Schema follows: the new field is known and bounded, range is capped
    schema = catalog_schema(fmt)
    sensor = schema["definitions"]["Sensor"]["properties"]
    assert sensor["mass"]["description"] == "Mass in grams."
    assert sensor["range"]["anyOf"][0]["maximum"] == 1e6
    check = jsonschema.Draft7Validator(schema)
    assert check.is_valid(valid)
    assert not check.is_valid({"gyrovib": 1, "sensors": [{"id": "s", "range": 2e6,
                                                          "coefficients": {}}]})
    assert not check.is_valid({"gyrovib": 1, "sensors": [{"id": "s", "mass": -3,
                                                          "coefficients": {}}]})
    # and the shipped format is untouched: 'mass' is still unknown there
    assert not jsonschema.Draft7Validator(catalog_schema()).is_valid(valid)
    assert not _valid(copy.deepcopy(valid))


EXAMPLE = Path(__file__).parents[1] / "docs" / "examples" / "select-example.yaml"


@pytest.mark.parametrize("path", [*sorted(bundled_paths()), EXAMPLE], ids=lambda p: p.name)
def test_real_catalogues_are_valid_for_both(path, schema_validator):
    if not path.exists():
        pytest.skip("no such example")
    data = yaml.load(path.read_text(encoding="utf-8"), Loader=_Loader)
    assert verdicts(data, schema_validator) == (None, True)


def test_huge_integer_still_loads():
    src = parse_catalog("gyrovib: 1\nsensors:\n  - id: s\n    range: 1180591620717411303424\n"
                        "    coefficients: {}\n")
    assert isinstance(src.model, records.CatalogFile)
    assert src.model.sensors[0].range == 2.0**70


def test_records_are_immutable():
    src = parse_catalog("gyrovib: 1\nsensors:\n  - id: s\n    coefficients: {k2: 1}\n")
    with pytest.raises(AttributeError):
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

    loader = _Loader(text)
    try:
        node = loader.get_single_node()
        expected = loader.construct_document(node)
    finally:
        loader.dispose()
    loader = _Loader(text)
    try:
        got = _stream(loader)
    except _Unusual:  # the slow path takes over: nothing to compare
        return
    finally:
        loader.dispose()
    assert repr(got) == repr(expected)
