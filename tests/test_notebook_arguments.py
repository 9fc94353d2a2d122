"""The notebook API checks its arguments at its face: a wrong type is an
ArgumentTypeError (a TypeError), a wrong value an ArgumentError (a ValueError), both
under gyrovib's one error root and naming the argument, raised before any work; and
the command line's caps (samples, sweep points, rates) hold there too.

Before, ``analyze(rate=nan)`` raised numpy's LinAlgError, ``unit=5`` an
AttributeError, ``samples=10**400`` an OverflowError, ``samples=10**10`` ran for
minutes, ``load(b'...')``, nested paths and ``sweep(points=2.5)`` failed deep inside
pathlib or numpy."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest

import gyrovib
from gyrovib import api
from gyrovib.errors import ArgumentError, ArgumentTypeError, GyrovibError, OptionError
from gyrovib.limits import MAX_SAMPLES

V, T = ArgumentError, ArgumentTypeError
NUMERIC: dict[str, Any] = {"method": "numeric"}

# (function, keyword arguments, error class, the argument named)
CASES: list[tuple[str, dict[str, Any], type[GyrovibError], str]] = [
    ("analyze", {"rate": float("nan")}, V, "rate"),
    ("analyze", {"rate": [0, 0, float("inf")]}, V, "rate"),
    ("analyze", {"rate": [1, 2]}, V, "rate"),
    ("analyze", {"rate": b"1"}, T, "rate"),
    ("analyze", {"rate": "1 furlong"}, V, "rate"),
    ("analyze", {"unit": 5}, T, "unit"),
    ("analyze", {"unit": "furlong/fortnight"}, V, "unit"),
    ("analyze", {**NUMERIC, "samples": 10**400}, V, "samples"),
    ("analyze", {**NUMERIC, "samples": 10**10}, V, "samples"),
    ("analyze", {**NUMERIC, "samples": MAX_SAMPLES + 1}, V, "samples"),
    ("analyze", {**NUMERIC, "samples": 31}, V, "samples"),
    ("analyze", {**NUMERIC, "samples": 1e5}, T, "samples"),
    ("analyze", {**NUMERIC, "samples": True}, T, "samples"),
    ("analyze", {**NUMERIC, "seed": -1}, V, "seed"),
    ("analyze", {**NUMERIC, "seed": 1.5}, T, "seed"),
    ("analyze", {"method": "magic"}, V, "method"),
    ("analyze", {"method": None}, T, "method"),
    ("analyze", {"sensors": [1]}, T, "sensors"),
    ("analyze", {"profiles": 5}, T, "profiles"),
    ("analyze", {"peak_factor": float("nan")}, V, "peak_factor"),
    ("analyze", {"peak_factor": -1}, V, "peak_factor"),
    ("analyze", {"peak_factor": "3"}, T, "peak_factor"),
    ("analyze", {"catalog": b"catalog.yaml"}, T, "catalog"),
    ("analyze", {"catalog": [["a.yaml"]]}, T, "catalog"),
    ("analyze", {"catalog": 5}, T, "catalog"),
    ("bounds", {"budget": float("nan")}, V, "budget"),
    ("bounds", {"budget": 0}, V, "budget"),
    ("bounds", {"budget": "-1deg/h"}, V, "budget"),
    ("bounds", {"budget": 1, "unit": 3}, T, "unit"),
    ("bounds", {"budget": 1, "range_": float("inf")}, V, "range_"),
    ("bounds", {"budget": 1, "allocation": "1.5"}, T, "allocation"),
    ("bounds", {"budget": 1, "allocation": [1, 2]}, V, "allocation"),
    ("bounds", {"budget": 1, "allocation": [float("nan")]}, V, "allocation"),
    ("bounds", {"budget": 1, "range_": 100, "nl_fit": "best"}, V, "nl_fit"),
    ("bounds", {"budget": 1, "range_": 100, "nl_measure": 2}, T, "nl_measure"),
    ("bounds", {"budget": 1, "range_": 100, "nl_of": "fs"}, V, "nl_of"),
    ("bounds", {"budget": 1, "spec_weights": (1,)}, V, "spec_weights"),
    ("bounds", {"budget": 1, "spec_weights": (1, -1)}, V, "spec_weights"),
    ("select", {"budget": 1, "criterion": "best"}, V, "criterion"),
    ("select", {"budget": 1, "require": "most"}, V, "require"),
    ("select", {"budget": 1, "method": "numeric"}, V, "method"),
    ("sweep", {"points": 2.5}, T, "points"),
    ("sweep", {"points": 0}, V, "points"),
    ("sweep", {"points": 10**6}, V, "points"),
    ("sweep", {"rates": list(range(api.MAX_SWEEP_POINTS + 1))}, V, "rates"),
    ("sweep", {"rates": []}, V, "rates"),
    ("sweep", {"rates": "0:1:3"}, T, "rates"),
    ("sweep", {"rates": (0, float("nan"))}, V, "rates"),
    ("sweep", {"rates": (0, 1e308), "unit": "rpm"}, V, "rates"),
    ("sweep", {"rates": [[0, 1], [2, 3]]}, T, "rates"),
]


@pytest.mark.parametrize(("function", "kwargs", "error", "name"), CASES,
                         ids=[f"{c[0]}-{c[3]}-{i}" for i, c in enumerate(CASES)])
def test_a_wrong_argument_is_refused_at_the_face_naming_it(
        function: str, kwargs: dict[str, Any], error: type[GyrovibError], name: str) -> None:
    with pytest.raises(error) as caught:
        getattr(gyrovib, function)(**kwargs)
    assert isinstance(caught.value, GyrovibError)
    assert isinstance(caught.value, ValueError if error is V else TypeError)
    assert str(caught.value).startswith(f"argument {name!r}: "), str(caught.value)


@pytest.mark.parametrize(("args", "error"), [
    ((b"catalog.yaml",), T), (([["a.yaml", "b.yaml"]],), T), ((5,), T), (("",), V),
    (([Path("a.yaml"), 3],), T),
])
def test_load_refuses_what_is_not_a_path(args: tuple[Any, ...],
                                         error: type[GyrovibError]) -> None:
    with pytest.raises(error, match=r"^argument 'paths': "):
        gyrovib.load(*args)


def test_the_cap_on_samples_is_the_command_lines_and_the_librarys() -> None:
    from gyrovib.cli.analyze import analyze as command

    option = next(p for p in command.params if p.name == "samples")
    assert option.type.max == MAX_SAMPLES == 10**8  # type: ignore[attr-defined]
    with pytest.raises(OptionError, match="at most 100,000,000"):  # the library itself
        api.analyze(api.load(), method="numeric", samples=MAX_SAMPLES + 1)


def test_numpy_scalars_and_arrays_are_accepted() -> None:
    tone = {"sensors": "adxrs645", "profiles": "flat-random-hover"}
    plain = gyrovib.analyze(**tone, method="numeric", samples=1000, rate=2.0, seed=3)
    numpy = gyrovib.analyze(**tone, method="numeric", samples=np.int64(1000),
                            rate=np.float64(2.0), seed=np.uint8(3))
    assert np.array_equal(plain.error.total, numpy.error.total)
    swept = gyrovib.sweep(rates=np.linspace(-1.0, 1.0, 5), **tone)
    assert np.allclose(swept.rates, np.linspace(-1.0, 1.0, 5))
    paired = gyrovib.sweep(rates=(np.float32(-1), 1), points=np.int16(5), **tone)
    assert np.array_equal(paired.rates, swept.rates)
