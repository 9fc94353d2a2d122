"""Results are immutable: frozen fields, read-only arrays and mappings, a one-line repr."""

from __future__ import annotations

import dataclasses
import pickle

import numpy as np
import pytest

from gyrovib import api


@pytest.fixture(scope="module")
def catalog() -> api.Catalog:
    return api.load()  # the bundled catalogues: 9 sensors, 7 profiles


@pytest.fixture(scope="module")
def results(catalog: api.Catalog) -> dict[str, object]:
    return {
        "analyze": api.analyze(catalog),
        "bounds": api.bounds(catalog, budget=0.01),
        "select": api.select(catalog, budget=0.01),
        "sweep": api.sweep(catalog, [0.0, 1.0, 2.0]),
    }


def _arrays(value: object) -> list[np.ndarray]:
    if isinstance(value, np.ndarray):
        return [value]
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return [a for f in dataclasses.fields(value) for a in _arrays(getattr(value, f.name))]
    return []


@pytest.mark.parametrize("kind", ["analyze", "bounds", "select", "sweep"])
def test_every_array_is_read_only(results: dict[str, object], kind: str) -> None:
    arrays = _arrays(results[kind])
    assert len(arrays) >= 3  # rates and the nested error/bounds arrays at least
    for array in arrays:
        assert not array.flags.writeable
        if array.size:
            with pytest.raises(ValueError, match="read-only"):
                array[(0,) * array.ndim] = 0


@pytest.mark.parametrize("kind", ["analyze", "bounds", "select", "sweep"])
def test_fields_cannot_be_reassigned(results: dict[str, object], kind: str) -> None:
    with pytest.raises(dataclasses.FrozenInstanceError):
        results[kind].unit = "rpm"  # type: ignore[attr-defined]


def test_mappings_are_read_only(results: dict[str, object]) -> None:
    select = results["select"]
    with pytest.raises(TypeError):
        select.limits[0] = None  # type: ignore[attr-defined,index]
    sweep = results["sweep"]
    with pytest.raises(TypeError):
        sweep.paper_refused["x"] = "y"  # type: ignore[attr-defined,index]
    analysis = results["analyze"]
    with pytest.raises(TypeError):
        analysis.warnings[(0, 0)] = ("x",)  # type: ignore[attr-defined,index]


def test_a_replaced_result_is_frozen_too(results: dict[str, object]) -> None:
    analysis = results["analyze"]
    stderr = np.zeros(analysis.error.total.shape)  # type: ignore[attr-defined]
    numeric = dataclasses.replace(analysis, method="numeric", stderr=stderr)  # type: ignore[type-var]
    assert not numeric.stderr.flags.writeable


@pytest.mark.parametrize("kind", ["analyze", "bounds", "select", "sweep"])
def test_results_pickle_and_stay_frozen(results: dict[str, object], kind: str) -> None:
    # results cross process boundaries (multiprocessing) unchanged, and read-only again
    original = results[kind]
    copy = pickle.loads(pickle.dumps(original))
    assert type(copy) is type(original) and repr(copy) == repr(original)
    for a, b in zip(_arrays(original), _arrays(copy), strict=True):
        np.testing.assert_array_equal(a, b)
        assert not b.flags.writeable


def test_repr_is_one_short_line(results: dict[str, object]) -> None:
    # kind, method, unit and shape (sensors, profiles[, rates]) of the bundled catalogues
    assert repr(results["analyze"]) == "AnalysisResult(method='exact', unit='deg/s', shape=(9, 14))"
    assert repr(results["bounds"]) == "BoundsResult(method='exact', unit='deg/s', shape=(14,))"
    assert repr(results["select"]) == ("SelectionResult(method='exact', unit='deg/s', "
                                       "shape=(9, 14))")
    assert repr(results["sweep"]) == ("SweepResult(method='exact+paper', unit='deg/s', "
                                      "shape=(9, 14, 3))")


def test_public_names_still_import_from_the_package() -> None:
    from gyrovib.api import (  # noqa: F401 - the names cli, render and users import
        AnalysisResult,
        BoundsResult,
        SelectionResult,
        SweepResult,
        analyze,
        bounds,
        load,
        profile_location,
        rate_range,
        select,
        sensor_location,
        sensor_locations,
        sweep,
    )

    assert set(api.__all__) <= set(dir(api))
    for name in api.__all__:
        assert getattr(api, name) is not None, name
    with pytest.raises(AttributeError):
        api.no_such_name  # noqa: B018
