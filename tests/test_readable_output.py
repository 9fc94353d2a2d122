"""Output that follows the question: the budget's unit, readable coefficient bounds, the
β1/2 share label, negligible values as 0, and sweep's rate range in another unit."""

from __future__ import annotations

import json
import re
import textwrap
from pathlib import Path

import pytest

from gyrovib.render.common import NEGLIGIBLE, fmt_budget
from tests.conftest import invoke as run

# one tone a3 = 2 deg/s at Ω̄ = 0.5 deg/s: M2 = 2, M4 = 3·16/8 = 6 (deg/s)^n
CATALOG = """
units: {rate: deg/s}
profiles:
  - id: tone
    rate: [0, 0, 0.5]
    harmonic:
      - {frequency: 100, amplitude: [0, 0, 2.0]}
sensors:
  - id: s
    coefficients: {k3: 1.0e-3, k5: 1.0e-3}
"""


@pytest.fixture
def catalog(tmp_path: Path) -> str:
    path = tmp_path / "cat.yaml"
    path.write_text("gyrovib: 1\n" + textwrap.dedent(CATALOG))
    return str(path)


def test_tables_write_coefficient_bounds_in_the_catalogue_unit(catalog: str) -> None:
    # exact k3 bound (β1/2)·Δ*/(|Ω̄|·3M2) = 0.22646·0.01/(0.5·3·2) = 7.549e-4 (deg/s)^-2;
    # in deg/h (the budget's unit, so the JSON's) it is 7.549e-4/3600² = 5.825e-11
    table = run("bounds", catalog, "--budget", "36deg/h").stdout
    assert re.search(r"│ k3 +│ +0\.000754\d +│ \(deg/s\)\^-2 +│ β1/2 = 0\.2265", table)
    assert "Δ* = 36 deg/h" in table and "catalogue's rate unit, deg/s" in table
    doc = json.loads(run("bounds", catalog, "--budget", "36deg/h", "--format", "json").stdout)
    assert doc["unit"] == "deg/h"
    k3_deg_s = 0.4529108136578382 / 2 * 0.01 / (0.5 * 3 * 2)  # β1 = c_M/√1.5, c_M = 1/√3.25
    assert doc["profiles"][0]["bounds"]["k3"] == pytest.approx(k3_deg_s / 3600**2, rel=1e-12)
    # with --unit given the tables keep the catalogue's unit too, and say so only if it differs
    same = run("bounds", catalog, "--budget", "0.01", "--unit", "deg/s").stdout
    assert "catalogue's rate unit" not in same


def test_select_failure_text_uses_the_catalogue_unit(catalog: str) -> None:
    # k5 = 1e-3 (deg/s)^-4 far beyond its bound: written in (deg/s)^-4, not (deg/h)^-4
    table = run("select", catalog, "--budget", "36deg/h").stdout
    assert "(deg/s)^-4" in table and "(deg/h)^-4" not in table
    assert "sufficient, not necessary" in table and "--criterion rms" in table


def test_paper_share_label_is_its_own_constant(catalog: str) -> None:
    table = run("bounds", catalog, "--budget", "0.01", "--method", "paper").stdout
    assert "0.35 (paper)" in table and "β1/2" not in table


def test_negligible_values_print_as_zero() -> None:
    # below 1e-12 of the budget: rounding residue, printed 0 in tables only
    assert fmt_budget(0.5 * NEGLIGIBLE * 10.0, 10.0) == "0"
    assert fmt_budget(2.0 * NEGLIGIBLE * 10.0, 10.0) != "0"
    assert fmt_budget(1e-20, None) != "0"


def test_sweep_rate_range_in_another_unit_is_converted(catalog: str) -> None:
    # -1deg/s:1deg/s:3 with --unit deg/h: -3600, 0, 3600 deg/h
    doc = json.loads(run("sweep", catalog, "--unit", "deg/h", "--rate-range=-1deg/s:1deg/s:3",
                         "--format", "json").stdout)
    assert doc["rates"] == [-3600.0, 0.0, 3600.0]
    # and a budget with a unit sets the unit when --unit is not given
    doc = json.loads(run("sweep", catalog, "--budget", "36deg/h", "--rate-range=-1:1:3",
                         "--format", "json").stdout)
    assert doc["unit"] == "deg/h" and doc["rates"] == [-1.0, 0.0, 1.0]
