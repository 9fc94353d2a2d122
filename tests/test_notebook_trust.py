"""The notebook API as a new user meets it (README, "Notebooks and DataFrames"):
a ``passed`` column that ``DataFrame.query`` can use, a one-line ``Catalog``, and a
bound that constrains nothing written as unbounded, never as a huge number."""

from __future__ import annotations

import math

import pytest

import gyrovib
from gyrovib.render.bounds import bound_text
from tests.conftest import invoke

pytest.importorskip("pandas", reason="to_frame needs the pandas extra")


def test_the_verdict_column_is_passed_and_query_can_use_it() -> None:
    result = gyrovib.select(budget="10deg/h", profiles=["cruise-hard-mounted"])
    frame = result.to_frame()
    assert "passed" in frame.columns and "pass" not in frame.columns
    failing = frame.query("not passed")
    expected = [result.sensors[i] for i in range(len(result.sensors))
                if not result.passed[i, 0]]
    assert list(failing["sensor"]) == expected and expected  # some do fail here


def test_a_catalog_prints_in_one_line() -> None:
    text = repr(gyrovib.load())
    # the bundled files: 9 sensors, 14 profiles and one mission (src/gyrovib/catalogs/)
    assert text == ("Catalog(9 sensors, 14 profiles, 1 mission from missions.gyrovib.yaml, "
                    "profiles.gyrovib.yaml, sensors.gyrovib.yaml)")
    assert str(gyrovib.load()) == text


def test_an_unconstraining_bound_reads_unbounded() -> None:
    assert bound_text("k3", math.inf) == "unbounded"
    # |A1| < 2 for any rate sensor (k1(1 ± A1/2) > 0): a larger bound constrains nothing
    assert bound_text("A1", 9.187e175) == "unbounded" and bound_text("A1", 2.0) == "unbounded"
    assert bound_text("A1", 1.999) == "1.999" and bound_text("k2", 9.187e175) == "9.187e+175"
    # cruise-isolated at Ω_K3 = 20 deg/s: E(Ω̄) is ~0, so A1's bound is astronomically large
    out = invoke("bounds", "--profile", "cruise-isolated", "--budget", "10deg/h",
                 env={"COLUMNS": "160"}).stdout
    row = next(line for line in out.splitlines() if line.startswith("│ A1"))
    assert "unbounded" in row and "e+" not in row
    doc = gyrovib.bounds(budget="10deg/h", profiles="cruise-isolated")
    assert doc.bounds.A1[0] > 1e100  # the library keeps the number (JSON as well)
