"""The fast validator (plain records) agrees with the pydantic schema.

It may leave data to pydantic (``Unsure``) but must never accept what the
schema rejects, and what it accepts must come out exactly as the schema's.
"""

from __future__ import annotations

import copy
import math
from pathlib import Path

import pytest
import yaml
from pydantic import ValidationError

from gyrovib.catalog import records, schema
from gyrovib.catalog.loader import _Loader, bundled_paths, parse_catalog

BASE = {
    "gyrovib": 1,
    "units": {"rate": "deg/h"},
    "sensors": [
        {"id": "s-1", "name": "S", "vendor": "V", "part": "P", "notes": "N", "range": 100,
         "coefficients": {"k0": 1, "k1": 1.0, "A1": 1e-4, "k2": -2e-7, "k3": 1e-9, "k4": 0.0,
                          "k5": 1e-12, "m1": 0.1, "m2": -0.1, "m31": 1e-6, "m32": 2e-6},
         "response": [[10, 1.0], [500, 0.7], [500, 0.5]]},
        {"id": "s.2", "output_coefficients": {"unit": "mV", "K1": 25, "K0": 2.0, "A1": 2e-3,
                                              "K2": 1e-4, "K3": 1, "K4": 0, "K5": 0, "M1": 0,
                                              "M2": 0, "M31": 1, "M32": -1}},
    ],
    "profiles": [
        {"id": "p", "name": "P", "notes": "n", "rate": [0, 0, 30],
         "harmonic": [{"frequency": 120, "amplitude": [0.5, 0.5, 0.8], "phase": [0, 90, 0]}],
         "random": {"psd": {"x1": [[20, 1e-4], [2000, 1e-4]], "x3": [[20, 1e-4], [40, 1e-4]]},
                    "coherence": [0.5, -1]},
         "mount": [[20, 1.0], [200, 0.3]]},
        {"id": "q", "random": {"rms": [0.1, 0.1, 0.2]}},
    ],
    "allocation": {"r": 2, "w": [1, 1, 1, 0.5, 0.5], "v": [1, 0.5, 0.5]},
}

VALUES = [None, 0, 1, -1, 0.5, -0.5, 2, 1.5, True, False, "x", "deg/h", "mV", "", [], {},
          [1, 2, 3], [1, 2], [0, 0, 0, 0, 0], [[1, 1]], [[1, 1], [0.5, 1]], [[1, -1]],
          [1, [2], 3], {"x": 1}, math.nan, math.inf, -math.inf, 10**400, 2**60, -(2**60),
          "a b", "a" * 201, "x" * 10_001, [[0, 1]], (1, 2, 3)]


def paths(node, prefix=()):
    yield prefix
    if isinstance(node, dict):
        for key, value in node.items():
            yield from paths(value, (*prefix, key))
        yield (*prefix, "extra")
    elif isinstance(node, list):
        for i, value in enumerate(node):
            yield from paths(value, (*prefix, i))


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


DELETE = object()


def outcome(data):
    try:
        fast = records.catalog_file(copy.deepcopy(data)).model_dump()
    except records.Unsure:
        fast = None
    try:
        slow = schema.CatalogFile.model_validate(copy.deepcopy(data)).model_dump()
    except ValidationError:
        slow = None
    return fast, slow


def same(a, b):
    """Equal, with NaN never expected (both sides refuse it)."""
    return a == b and type(a) is type(b) if not isinstance(a, dict | list | tuple) else (
        type(a) is type(b) and len(a) == len(b) and (
            all(same(a[k], b[k]) for k in a) if isinstance(a, dict)
            else all(same(x, y) for x, y in zip(a, b, strict=True))))


def test_base_document_is_built_fast_and_equal():
    fast, slow = outcome(BASE)
    assert fast is not None and slow is not None
    assert same(fast, slow)


@pytest.mark.parametrize("path", [p for p in paths(BASE) if p], ids=lambda p: ".".join(map(str, p)))
def test_mutations_agree_with_the_schema(path):
    for value in [*VALUES, DELETE]:
        data = mutated(path, value)
        fast, slow = outcome(data)
        if fast is not None:
            assert slow is not None, f"fast path accepted what the schema refuses: {value!r}"
            assert same(fast, slow), (value, fast, slow)


def test_the_fast_path_leaves_only_huge_integers_to_pydantic():
    accepted = 0
    left: set[object] = set()
    for path in [p for p in paths(BASE) if p]:
        for value in [*VALUES, DELETE]:
            fast, slow = outcome(mutated(path, value))
            if slow is not None:
                if fast is None:
                    left.add(value)
                else:
                    accepted += 1
    assert accepted > 200
    assert left <= {2**60, -(2**60)}


EXAMPLE = Path(__file__).parents[1] / "docs" / "examples" / "select-example.yaml"


@pytest.mark.parametrize("path", [*sorted(bundled_paths()), EXAMPLE], ids=lambda p: p.name)
def test_real_catalogues_are_built_fast_and_equal(path):
    if not path.exists():
        pytest.skip("no such example")
    data = yaml.load(path.read_text(encoding="utf-8"), Loader=_Loader)
    fast, slow = outcome(data)
    assert fast is not None, "a real catalogue fell back to pydantic"
    assert same(fast, slow)


def test_huge_integer_is_left_to_the_schema_and_still_loads():
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
    from gyrovib.catalog.loader import _build, _Unusual

    loader = _Loader(text)
    try:
        node = loader.get_single_node()
        expected = loader.construct_document(node)
    finally:
        loader.dispose()
    try:
        got = _build(yaml.compose(text, Loader=_Loader))
    except _Unusual:  # the slow path takes over: nothing to compare
        return
    assert repr(got) == repr(expected)
