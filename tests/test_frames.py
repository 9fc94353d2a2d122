"""The notebook API: lazy top-level names, and ``to_frame()`` equal to the JSON output.

The reference for every frame is the command's own ``--format json`` (parsed):
each frame value must equal the JSON value at the key the column is named
after (``a.b`` = ``row["a"]["b"]``), exactly, since both come from the same
float64 arrays and JSON writes floats at full precision (repr). JSON writes
``null`` for a number that is not finite (docs/output.md); the frame keeps the
float there, so ``null`` must meet a non-finite frame value.
"""

from __future__ import annotations

import json
import math
import re
import subprocess
import sys
from typing import Any

import numpy as np
import pytest
from click.testing import CliRunner

import gyrovib
from gyrovib.cli.main import cli

pd = pytest.importorskip("pandas", reason="to_frame needs the pandas extra")


def cli_json(*args: str) -> Any:
    result = CliRunner().invoke(cli, [*args, "--format", "json"], catch_exceptions=False)
    assert result.exit_code in (0, 1), result.output
    return json.loads(result.stdout)


def same(frame_value: Any, json_value: Any) -> bool:
    if json_value is None:  # a missing text (a passing cell's reason) stays None
        return frame_value is None or (isinstance(frame_value, float)
                                       and not math.isfinite(frame_value))
    if isinstance(json_value, list):
        return list(frame_value) == json_value
    if isinstance(json_value, bool):
        return bool(frame_value) is json_value
    return frame_value == json_value


#: How docs/output.md ("DataFrames") names a frame column after its JSON key path, where
#: the name is not the path joined by ``_``: written out here, not read from the
#: declaration under test, so that a renamed column fails.
RENAMED = [
    (r"additive_terms\.(\w+)", r"additive_\1"),  # analyze
    (r"multiplicative_coefficients\.(\w+)", r"multiplicative_\1"),
    (r"pass", "passed"),  # select: `pass` is a Python keyword
    (r"checks\.(\w+)\.(value|bound|pass|unit)", r"\2_\1"),
    (r"spec_bounds\.nonlinearity\.value", "spec_nonlinearity"),  # bounds --range
    (r"spec_bounds\.(\w+)", r"spec_\1"),
    (r"spec_bounds\.nonlinearity\.(\w+)", r"spec_nonlinearity_\1"),
]


def namer(result: Any) -> Any:
    """The frame column of a JSON key path (docs/output.md), for ``result``'s command."""
    kind = type(result).__name__
    rules = list(RENAMED)
    if kind in ("BoundsResult", "SelectionResult"):
        rules.append((r"(bounds|parts)\.(\w+)", r"\2" if kind == "BoundsResult"
                      else r"profile_\1_\2"))

    def name(path: str) -> str:
        for pattern, repl in rules:
            if re.fullmatch(pattern, path):
                return re.sub(pattern, repl, path)
        return path.replace(".", "_")

    return name


def check_row(frame_row: Any, expected: dict[str, Any], name: Any) -> None:
    """Each JSON value (key path → value) in its column (``name``: :func:`namer`)."""
    for path, value in expected.items():
        column = name(path)
        got = frame_row[column]
        assert same(got, value), f"{column} ({path}): frame {got!r} != JSON {value!r}"


def columns(name: Any, paths: Any) -> set[str]:
    return {name(p) for p in paths}


def flatten(prefix: str, value: Any) -> dict[str, Any]:
    """JSON object → ``{"a.b": leaf}``; the rate list → ``rate.x1..x3``."""
    if isinstance(value, dict):
        out: dict[str, Any] = {}
        for k, v in value.items():
            out.update(flatten(f"{prefix}.{k}" if prefix else k, v))
        return out
    if prefix.endswith("rate") and isinstance(value, list):
        return {f"{prefix}.x{k + 1}": v for k, v in enumerate(value)}
    return {prefix: value}


@pytest.mark.parametrize("unit", ["deg/s", "deg/h"])
def test_analyze_frame_equals_json(unit):
    document = cli_json("analyze", "--unit", unit)
    result = gyrovib.analyze(unit=unit)
    frame, name = result.to_frame(), namer(result)
    rows = document["results"]
    assert len(frame) == len(rows) == 9 * 14  # bundled: 9 sensors × 14 profiles
    for k, row in enumerate(rows):
        expected = flatten("", row)
        expected["warnings"] = row["warnings"]
        check_row(frame.iloc[k], expected, name)
    # a spec-form row adds its envelope: the frame has the union of the rows' keys
    assert set(frame.columns) == columns(name, set().union(*(flatten("", row)
                                                                  for row in rows)))
    assert frame.attrs["method"] == document["method"] and frame.attrs["unit"] == unit


def test_analyze_numeric_frame_has_stderr_samples_and_seed():
    args = ["--method", "numeric", "--samples", "20000", "--seed", "3", "--sensor", "adxrs645",
            "--profile", "engine-harmonics"]
    document = cli_json("analyze", *args)
    result = gyrovib.analyze(sensors="adxrs645", profiles="engine-harmonics", method="numeric",
                             samples=20000, seed=3)
    frame = result.to_frame()
    check_row(frame.iloc[0], flatten("", document["results"][0]), namer(result))
    assert (frame.attrs["samples"], frame.attrs["seed"]) == (document["samples"],
                                                             document["seed"])


def test_bounds_frame_equals_json():
    document = cli_json("bounds", "--budget", "10deg/h", "--unit", "deg/h")
    result = gyrovib.bounds(budget="10deg/h", unit="deg/h")
    frame = result.to_frame()
    assert len(frame) == len(document["profiles"]) == 14
    for k, row in enumerate(document["profiles"]):
        check_row(frame.iloc[k], flatten("", row), namer(result))
    # An unconstrained bound (JSON null) is +inf: k3 of a still profile (Ω_K3 = 0 →
    # no Δ(1)·Ω term, eq. 25) is the bundled flat-random-hover's.
    hover = frame.set_index("profile").loc["flat-random-hover"]
    assert hover["k3"] == math.inf
    assert frame.attrs["budget"] == document["budget"]


def test_select_frame_equals_json():
    document = cli_json("select", "--budget", "10deg/h", "--criterion", "both")
    result = gyrovib.select(budget="10deg/h", criterion="both")
    frame, name = result.to_frame(), namer(result)
    profiles = {p["profile"]: p for p in document["profiles"]}
    k = 0
    for sensor in document["sensors"]:
        for cell in sensor["profiles"]:
            expected = flatten("", {key: v for key, v in cell.items()})
            expected["sensor"] = sensor["sensor"]
            expected["source"] = sensor["source"]
            expected["sensor_pass"] = sensor["pass"]
            entry = profiles[cell["profile"]]
            expected.update(flatten("", {"rate": entry["rate"]}))
            expected.update(flatten("profile_bounds", entry["bounds"]))
            expected.update(flatten("profile_parts", entry["parts"]))
            check_row(frame.iloc[k], expected, name)
            k += 1
    assert k == len(frame) == 9 * 14  # 9 sensors × 14 profiles
    assert "passed" in frame.columns  # the JSON's pass: a keyword df.query cannot use
    assert frame.attrs["criterion"] == "both" and frame.attrs["require"] == document["require"]


def test_sweep_frame_equals_json():
    document = cli_json("sweep", "--rate-range", "-10:10:5", "--profile", "engine-harmonics",
                        "--profile", "uav-blade-pass-tone")
    result = gyrovib.sweep(rates=(-10, 10), points=5,
                           profiles=["engine-harmonics", "uav-blade-pass-tone"])
    frame = result.to_frame()
    rates = document["rates"]
    k = 0
    for series in document["series"]:
        for r, rate in enumerate(rates):
            expected = {"sensor": series["sensor"], "profile": series["profile"],
                        "rate_x3": rate}
            for method in ("exact", "paper"):
                values = series[method]
                for name in ("total", "rms"):
                    # paper null: the paper's formulas do not cover engine-harmonics (3 tones)
                    expected[f"{method}.{name}"] = None if values is None else values[name][r]
            check_row(frame.iloc[k], expected, namer(result))
            k += 1
    assert k == len(frame) == 9 * 2 * 5
    assert frame["paper_rms"][frame["profile"] == "engine-harmonics"].isna().all()


def test_missing_pandas_names_the_extra(monkeypatch):
    from gyrovib.records import MissingDependency

    result = gyrovib.bounds(budget=0.01, profiles="flat-random-hover")
    monkeypatch.setitem(sys.modules, "pandas", None)  # import pandas → ImportError
    with pytest.raises(MissingDependency, match=r"pip install 'gyrovib\[pandas\]'"):
        result.to_frame()


def test_notebook_units_match_the_library():
    """A budget "36deg/h" is 36/3600 = 0.01 deg/s for :func:`gyrovib.api.select`; without
    ``unit`` the output follows the budget's unit (README, "Units": ``--unit``'s default)."""
    from gyrovib import api

    a = gyrovib.select(budget="36deg/h", rate=["1deg/s"])
    b = gyrovib.select(budget=36, unit="deg/h", rate=3600)
    c = api.select(api.load(), budget=0.01, rate=[1.0], unit="deg/h")
    d = gyrovib.select(budget="36deg/h", unit="deg/s", rate=["1deg/s"])
    assert a.unit == b.unit == "deg/h"
    assert a.budget == b.budget == c.budget == 36.0
    assert d.budget == 0.01
    assert (b.margin == c.margin).all() and (a.margin == c.margin).all()


def test_names_are_documented_and_listed():
    for name in ("load", "analyze", "bounds", "select", "sweep"):
        function = getattr(gyrovib, name)
        assert function.__module__ == "gyrovib.notebook"
        assert "Returns\n    -------" in (function.__doc__ or ""), name  # numpydoc
        assert name in dir(gyrovib) and name in gyrovib.__all__
    with pytest.raises(AttributeError, match="no attribute 'nope'"):
        _ = gyrovib.nope


def test_import_gyrovib_is_light():
    code = ("import sys, gyrovib, json; "
            "print(json.dumps(sorted({m.split('.')[0] for m in sys.modules})))")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          check=True, timeout=60)
    loaded = set(json.loads(done.stdout))
    assert "gyrovib" in loaded  # the probe works
    assert not loaded & {"numpy", "pandas", "pydantic", "pydantic_core", "rich", "yaml"}


def test_bounds_range_frame_equals_json():
    args = ["--budget", "10deg/h", "--unit", "deg/h", "--range", "360000", "--nl-fit",
            "minimax"]
    document = cli_json("bounds", *args)
    result = gyrovib.bounds(budget="10deg/h", unit="deg/h", range_=360000, nl_fit="minimax")
    frame, name = result.to_frame(), namer(result)
    for k, row in enumerate(document["profiles"]):
        assert "spec_bounds" in row
        check_row(frame.iloc[k], flatten("", row), name)
    assert set(frame.columns) == columns(name, flatten("", document["profiles"][0]))


@pytest.mark.parametrize("command", [
    ("analyze", "--profile", "cruise-hard-mounted", "--profile", "engine-harmonics"),
    ("select", "--budget", "10deg/h", "--profile", "cruise-hard-mounted"),
    ("bounds", "--budget", "10deg/h", "--range", "100"),
    ("sweep", "--rate-range", "-10:10:3", "--profile", "engine-harmonics"),
])
def test_csv_columns_are_frame_columns(command: tuple[str, ...]) -> None:
    # docs/output.md ("DataFrames"): DataFrame and CSV name their columns alike;
    # every CSV column is a frame column holding the same values, row for row
    import io

    done = CliRunner().invoke(cli, [*command, "--format", "csv"], catch_exceptions=False)
    assert done.exit_code in (0, 1), done.output
    table = pd.read_csv(io.StringIO(done.stdout), keep_default_na=False)
    kind = command[0]
    args = dict(zip(command[1::2], command[2::2], strict=False))
    if kind == "analyze":
        frame = gyrovib.analyze(profiles=["cruise-hard-mounted", "engine-harmonics"]).to_frame()
    elif kind == "select":
        frame = gyrovib.select(budget="10deg/h", profiles="cruise-hard-mounted").to_frame()
    elif kind == "bounds":
        frame = gyrovib.bounds(budget="10deg/h", range_=100).to_frame()
    else:
        frame = gyrovib.sweep(rates=(-10, 10), points=3, profiles="engine-harmonics").to_frame()
    assert args  # the command's options were read
    missing = [c for c in table.columns if c not in frame.columns]
    assert not missing, missing
    assert len(table) == len(frame)
    for column in table.columns:
        for got, want in zip(frame[column], table[column], strict=True):
            if isinstance(got, (bool, np.bool_)):
                assert str(bool(got)).lower() == str(want).lower(), column
            elif isinstance(got, (float, np.floating)):
                assert (math.isnan(got) and want in ("", "nan")) or got == float(want), column
            elif isinstance(got, (list, tuple)):
                assert " ".join(map(str, got)) == want or "; ".join(map(str, got)) == want
            elif got is None:
                assert want == "", column
            else:
                assert str(got) == str(want), column
