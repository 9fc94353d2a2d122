"""`gyrovib schema`: a draft-07 JSON Schema; valid catalogues pass, broken ones fail."""

from __future__ import annotations

import json
from pathlib import Path

import jsonschema
import pytest

from gyrovib.catalog.loader import _parse, bundled_paths
from gyrovib.models.schema import DRAFT_07, catalog_schema
from tests.conftest import VALID, invoke

#: The bundled catalogues, as files of the source tree (one copy: package data).
REPO_CATALOGS = sorted(
    (Path(__file__).parent.parent / "src" / "gyrovib" / "catalogs").glob("*.gyrovib.yaml"))


@pytest.fixture(scope="module")
def schema() -> dict:
    result = invoke("schema")
    assert result.exit_code == 0, result.stderr
    return json.loads(result.stdout)


@pytest.fixture(scope="module")
def validator(schema: dict) -> jsonschema.Draft7Validator:
    jsonschema.Draft7Validator.check_schema(schema)
    return jsonschema.Draft7Validator(schema)


def errors(validator: jsonschema.Draft7Validator, text: str) -> list[str]:
    return [e.message for e in validator.iter_errors(_parse(text, "<test>"))]


def test_schema_is_draft_07_only(schema: dict) -> None:
    assert schema["$schema"] == DRAFT_07
    assert schema["title"]
    text = json.dumps(schema)
    for newer in ("$defs", "prefixItems", "unevaluated", "dependentRequired", "$anchor"):
        assert newer not in text
    assert "#/definitions/Sensor" in text
    assert schema["required"] == ["gyrovib"]


def test_every_object_is_closed_and_described(schema: dict) -> None:
    objects = [schema, *schema["definitions"].values()]
    for obj in objects:
        assert obj["additionalProperties"] is False
        for name, prop in obj["properties"].items():
            assert prop.get("description"), name
            assert "title" not in prop, name


def test_no_ref_with_siblings(schema: dict) -> None:
    def walk(node: object) -> None:
        if isinstance(node, dict):
            if "$ref" in node:
                assert list(node) == ["$ref"], node
            for key, value in node.items():
                if key not in ("default", "enum", "const"):
                    walk(value)
        elif isinstance(node, list):
            for item in node:
                walk(item)

    walk(schema)


def test_tuples_use_array_items(schema: dict) -> None:
    rate = schema["definitions"]["Profile"]["properties"]["rate"]
    assert isinstance(rate["items"], list) and len(rate["items"]) == 3
    assert rate["additionalItems"] is False


def test_defaults_kept_as_values(schema: dict) -> None:
    assert schema["properties"]["units"]["default"] == {"rate": "deg/s", "acceleration": "g"}


def test_valid_catalogue_accepted(validator: jsonschema.Draft7Validator) -> None:
    assert errors(validator, VALID) == []


@pytest.mark.parametrize("path", [*REPO_CATALOGS, *bundled_paths()], ids=lambda p: str(p))
def test_shipped_catalogues_accepted(validator: jsonschema.Draft7Validator, path: Path) -> None:
    assert errors(validator, path.read_text(encoding="utf-8")) == []


BROKEN = [
    ("gyrovib: 1", "gyrovib: 2"),
    ("gyrovib: 1\n", ""),
    ("k2: 2.0e-7", "k_2: 2.0e-7"),
    ("k2: 2.0e-7", "k2: abc"),
    ("rate: deg/s", "rate: deg/min"),
    ("id: fog-a", "id: fog a"),
    ("rate: [0, 0, 30]", "rate: [0, 30]"),
    ("amplitude: [0.5, 0.5, 0.8]", "amplitude: [0.5, -0.5, 0.8]"),
    ("frequency: 120", "frequency: 0"),
    ("coherence: [1.0, 1.0]", "coherence: [1.0, 1.5]"),
    ("K1: 25.0", "K1: 0"),
    ("    output_coefficients:\n", "    coefficients: {}\n    output_coefficients:\n"),
    ("      coherence: [1.0, 1.0]", "      rms: [1, 1, 1]"),
    ("      - [200, 0.3]", "      - [200, 0.3, 1]"),
    ("    output_coefficients:\n", "    coefficients: null\n    output_coefficients:\n"),
    ("K1: 25.0", "K1: .inf"),
    ("k2: 2.0e-7", "k2: -.inf"),
    ("rate: [0, 0, 30]", "rate: [0, 0, 1e400]"),
    ("x3: [[20, 1.0e-4], [2000, 1.0e-4]]", "x3: [[20, 1.0e-4]]"),
]


@pytest.mark.parametrize(("old", "new"), [b for b in BROKEN if "null" not in b[1]])
def test_broken_catalogue_rejected(validator: jsonschema.Draft7Validator, old: str,
                                   new: str) -> None:
    assert old in VALID
    assert errors(validator, VALID.replace(old, new, 1)), (old, new)


def test_schema_matches_library(schema: dict) -> None:
    assert schema == catalog_schema()


def test_schema_output_option(tmp_path: Path) -> None:
    out = tmp_path / "gyrovib.schema.json"
    result = invoke("schema", "--output", str(out))
    assert result.exit_code == 0
    assert json.loads(out.read_text())["$schema"] == DRAFT_07


# ---------------------------------------------------------------- validate and the schema agree


def _corpus() -> list[tuple[str, str]]:
    from tests.test_hostile import CASES
    from tests.test_loader import ERROR_TEXTS

    texts = [(case[0], case[1]) for case in CASES if isinstance(case[1], str)]
    texts += [(f"loader-{i}", text) for i, text in enumerate(ERROR_TEXTS)]
    texts += [(f"broken-{old}->{new}", VALID.replace(old, new, 1)) for old, new in BROKEN]
    texts += [("valid", VALID)] + [(p.name, p.read_text(encoding="utf-8"))
                                   for p in [*REPO_CATALOGS, *bundled_paths()]]
    return texts


#: What validate checks that a JSON Schema cannot say (NaN: JSON cannot write it, and
#: every comparison with it is false, so no bound refuses it).
INEXPRESSIBLE = ("NaN is not a number", "must increase", "more than twice",
                 "two different frequencies", "check the units of K1", "duplicate sensor id",
                 "duplicate profile id")


@pytest.mark.parametrize(("name", "text"), _corpus(), ids=lambda x: x[:40])
def test_validate_and_schema_agree_on_the_corpus(validator: jsonschema.Draft7Validator,
                                                 name: str, text: str) -> None:
    from gyrovib.catalog.loader import parse_catalog
    from gyrovib.errors import CatalogError

    try:
        data = _parse(text, "<test>")
    except CatalogError:
        return  # not YAML (or refused by the reader): neither gets to judge it
    if not isinstance(data, dict) or "gyrovib" not in data:
        assert not validator.is_valid(data)
        return
    try:
        parse_catalog(text, "<test>")
        problems: list[str] = []
    except CatalogError as exc:
        problems = [p.message for p in exc.problems]
    if not problems:
        assert validator.is_valid(data), name
    elif validator.is_valid(data):
        assert all(any(m in p for m in INEXPRESSIBLE) for p in problems), problems
